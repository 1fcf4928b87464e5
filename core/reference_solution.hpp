#pragma once
// The reference solution of y' = y g(y): the explicit Runge-Kutta-Munthe-Kaas method of order 4 with the
// exact dexpinv, at a step far below the integrators' (kReferenceStepsPerUnit steps per unit of time).
#include <Eigen/Dense>

#include "options.hpp"
#include "rigid_body_params.hpp"

namespace lienewton {

inline constexpr int kReferenceStepsPerUnit = 1024;

Eigen::MatrixXd reference_solution(ProblemKind problem, const RigidBodyParams& rb, const Eigen::MatrixXd& y0,
                                   double t_end);

}  // namespace lienewton
