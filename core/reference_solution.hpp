#pragma once
// The reference solution of y' = y g(y): the explicit Runge-Kutta-Munthe-Kaas method of order 4 with the
// exact dexpinv, at a step far below the integrators' (from kReferenceStepsPerUnit steps per unit of time, doubled
// until two successive solutions agree to kReferenceTolerance relative, at most kMaxReferenceSteps). On a stiff
// field RKMK4 overflows at the first step counts (h |lambda| beyond its stability interval): those runs are skipped,
// and the doubling goes on until the step is inside it. Where even kMaxReferenceSteps does not settle, the
// L-stable Radau IIA method rkmk-radau3 is refined the same way (kImplicitReferenceTolerance); where that fails too
// there is no reference, and the note says why.
#include <Eigen/Dense>
#include <optional>
#include <string>

#include "problem_spec.hpp"

namespace lienewton {

inline constexpr int kReferenceStepsPerUnit = 1024;
inline constexpr double kReferenceTolerance = 1e-11;
inline constexpr long long kMaxReferenceSteps = 1LL << 22;
inline constexpr double kImplicitReferenceTolerance = 1e-9;
inline constexpr long long kMaxImplicitReferenceSteps = 1LL << 14;
// A global error within this factor of the reference's estimated error is not the run's own.
inline constexpr double kReferenceErrorFactor = 10;

struct ReferenceSolution {
  std::optional<Eigen::MatrixXd> y{};  // none where no method settled
  // Its estimated error: the distance between its last two refinements over 2^p - 1, p the method's order
  // (Richardson: the finer's error when both are in the asymptotic regime).
  double error = 0;
  std::string note;                    // how it was computed, or why there is none
};

// The problem's flow on its group from y0 (an element of it) to t_end.
ReferenceSolution reference_solution(const ProblemSpec& problem, const Eigen::MatrixXd& y0, double t_end);

}  // namespace lienewton
