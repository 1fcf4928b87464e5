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
    case ProblemKind::rigid_body: return kEnergy;
    case ProblemKind::heavy_top: return kAllInvariants;
    case ProblemKind::paper_linear:
    case ProblemKind::paper_sine: break;
  }
  return {};
}

bool has_invariants(const ProblemSpec& problem) { return !problem.g && !invariants_of(problem.kind).empty(); }

InvariantValues invariants_at(const ProblemSpec& problem, const Eigen::MatrixXd& y) {
  InvariantValues out;
  if (problem.is(ProblemKind::rigid_body)) {
    out[Invariant::energy] = RigidBody{problem.rigid_body}.energy(Eigen::Matrix3d(y));
  } else if (problem.is(ProblemKind::heavy_top)) {
    const HeavyTop top{problem.heavy_top};
    out[Invariant::energy] = top.energy(y);
    out[Invariant::vertical_momentum] = top.vertical_momentum(y);
  }
  return out;
}

InvariantDrift::InvariantDrift(const InvariantValues& initial) : initial_(initial) {
  for (Invariant i : kAllInvariants)
    if (initial_[i]) drift_[i] = 0.0;
}

void InvariantDrift::add(const InvariantValues& values) {
  for (Invariant i : kAllInvariants) {
    if (!initial_[i] || !values[i]) continue;
    const double scale = *initial_[i] == 0.0 ? 1.0 : std::abs(*initial_[i]);
    const double d = std::abs(*values[i] - *initial_[i]) / scale;
    // A non-finite value is the largest drift there is (std::max would keep the old one against NaN).
    drift_[i] = std::isfinite(d) ? std::max(*drift_[i], d) : std::numeric_limits<double>::infinity();
  }
}

}  // namespace lienewton
