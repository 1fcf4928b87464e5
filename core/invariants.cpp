#include "invariants.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "problems.hpp"

namespace lienewton {

bool InvariantValues::any() const {
  return std::any_of(values.begin(), values.end(), [](const auto& v) { return v.has_value(); });
}

std::span<const Invariant> invariants_of(ProblemKind kind) {
  static constexpr Invariant kEnergy[] = {Invariant::energy};
  switch (kind) {
    case ProblemKind::rigid_body:
    case ProblemKind::chain: return kEnergy;  // the chain's at damping 0 only (has_invariants)
    case ProblemKind::heavy_top: return kAllInvariants;
    case ProblemKind::paper_linear:
    case ProblemKind::paper_sine:
    case ProblemKind::stiff_body: break;  // forced and damped: nothing is conserved
  }
  return {};
}

// A damped chain loses energy (dE/dt = -c sum |d_j'|^2): nothing it reports would be conserved.
bool has_invariants(const ProblemSpec& problem) {
  if (problem.is(ProblemKind::chain) && problem.chain.damping != 0.0) return false;
  return !problem.g && !invariants_of(problem.kind).empty();
}

InvariantValues invariants_at(const ProblemSpec& problem, const Eigen::MatrixXd& y) {
  InvariantValues out;
  if (problem.is(ProblemKind::rigid_body)) {
    out[Invariant::energy] = RigidBody{problem.rigid_body}.energy(Eigen::Matrix3d(y));
  } else if (problem.is(ProblemKind::heavy_top)) {
    const HeavyTop top{problem.heavy_top};
    out[Invariant::energy] = top.energy(y);
    out[Invariant::vertical_momentum] = top.vertical_momentum(y);
    if (const auto k = top.symmetry_axis()) out[Invariant::axial_spin] = so3xr3::omega(y)(*k);
  } else if (problem.is(ProblemKind::chain)) {
    out[Invariant::energy] = Chain{problem.chain}.energy(Chain::Group(problem.n).element(y));
  }
  return out;
}

InvariantValues invariant_scales(const ProblemSpec& problem, const Eigen::MatrixXd& y) {
  InvariantValues out = invariants_at(problem, y);
  if (problem.is(ProblemKind::rigid_body)) {
    out[Invariant::energy] = std::abs(*out[Invariant::energy]);  // kinetic alone: positive wherever M != 0
  } else if (problem.is(ProblemKind::heavy_top)) {
    const HeavyTop top{problem.heavy_top};
    out[Invariant::energy] = top.energy_scale(y);
    out[Invariant::vertical_momentum] = top.momentum_scale(y);
    if (out[Invariant::axial_spin]) out[Invariant::axial_spin] = so3xr3::omega(y).norm();
  } else if (problem.is(ProblemKind::chain)) {
    out[Invariant::energy] = Chain{problem.chain}.energy_scale(Chain::Group(problem.n).element(y));
  }
  return out;
}

InvariantDrift::InvariantDrift(const InvariantValues& initial, const InvariantValues& scales)
    : initial_(initial), scales_(scales) {
  for (Invariant i : kAllInvariants)
    if (initial_[i]) {
      drift_[i] = 0.0;
      if (!scales_[i] || !(*scales_[i] > 0.0)) scales_[i] = 1.0;  // nothing to compare with: absolute
    }
}

void InvariantDrift::add(const InvariantValues& values) {
  for (Invariant i : kAllInvariants) {
    if (!initial_[i] || !values[i]) continue;
    const double d = std::abs(*values[i] - *initial_[i]) / *scales_[i];
    // A non-finite value is the largest drift there is (std::max would keep the old one against NaN).
    drift_[i] = std::isfinite(d) ? std::max(*drift_[i], d) : std::numeric_limits<double>::infinity();
  }
}

}  // namespace lienewton
