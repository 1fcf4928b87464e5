#pragma once
// The reference solution of y' = y g(y): the explicit Runge-Kutta-Munthe-Kaas method of order 4 with the
// exact dexpinv, at a step far below the integrators' (from kReferenceStepsPerUnit steps per unit of time, doubled
// until two successive solutions agree to kReferenceTolerance relative, at most kMaxReferenceSteps).
#include <Eigen/Dense>

#include "problem_spec.hpp"

namespace lienewton {

inline constexpr int kReferenceStepsPerUnit = 1024;
inline constexpr double kReferenceTolerance = 1e-11;
inline constexpr long long kMaxReferenceSteps = 1LL << 22;

// The problem's flow on its group from y0 (an element of it) to t_end.
Eigen::MatrixXd reference_solution(const ProblemSpec& problem, const Eigen::MatrixXd& y0, double t_end);

}  // namespace lienewton
