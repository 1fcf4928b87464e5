#pragma once
// The conserved quantities of the built-in problems (Invariant, core/options.hpp), evaluated from a state y (the
// group's matrix) with the problem's parameters alone: what a result reports about them is true of the y it
// returns, whichever integrator produced it.
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <iterator>
#include <optional>
#include <span>

#include "options.hpp"
#include "problem_spec.hpp"

namespace lienewton {

// One value per Invariant, absent where the problem has no such invariant.
struct InvariantValues {
  std::array<std::optional<double>, std::size(kAllInvariants)> values{};
  std::optional<double>& operator[](Invariant i) { return values[static_cast<std::size_t>(i)]; }
  const std::optional<double>& operator[](Invariant i) const { return values[static_cast<std::size_t>(i)]; }
  bool any() const;
};

// The invariants a built-in problem reports: rigid-body its energy; heavy-top its energy, vertical angular
// momentum and (a Lagrange top) its axial spin; chain its energy when undamped (c = 0; has_invariants says so for a
// request); the paper's problems and stiff-body none (nor does a user's g).
std::span<const Invariant> invariants_of(ProblemKind kind);
bool has_invariants(const ProblemSpec& problem);
InvariantValues invariants_at(const ProblemSpec& problem, const Eigen::MatrixXd& y);

// The size each invariant's drift is relative to, at the start y: one that means something even where the
// invariant itself is near 0 (a heavy top's vertical momentum): the rigid body's energy; the heavy top's kinetic
// plus potential energy size, its whole angular momentum |J w|, and |w| for the axial spin; the chain's kinetic,
// springs' and gravity's sizes summed (Chain::energy_scale) (words(Invariant)).
InvariantValues invariant_scales(const ProblemSpec& problem, const Eigen::MatrixXd& y);

// The drift of each invariant along a run: max_k |I(y_k) - I(y_0)| / scale (invariant_scales; 1 where it is 0).
class InvariantDrift {
 public:
  InvariantDrift(const InvariantValues& initial, const InvariantValues& scales);
  void add(const InvariantValues& values);
  const InvariantValues& initial() const { return initial_; }
  const InvariantValues& scales() const { return scales_; }
  const InvariantValues& drift() const { return drift_; }

 private:
  InvariantValues initial_, scales_, drift_;
};

}  // namespace lienewton
