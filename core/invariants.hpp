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

// The invariants a built-in problem reports: rigid-body its energy; heavy-top its energy and vertical angular
// momentum; the paper's problems none (nor does a user's g).
std::span<const Invariant> invariants_of(ProblemKind kind);
bool has_invariants(const ProblemSpec& problem);
InvariantValues invariants_at(const ProblemSpec& problem, const Eigen::MatrixXd& y);

// The drift of each invariant along a run: max_k |I(y_k) - I(y_0)| / |I(y_0)| (not divided where I(y_0) = 0).
class InvariantDrift {
 public:
  explicit InvariantDrift(const InvariantValues& initial);
  void add(const InvariantValues& values);
  const InvariantValues& initial() const { return initial_; }
  const InvariantValues& drift() const { return drift_; }

 private:
  InvariantValues initial_, drift_;
};

}  // namespace lienewton
