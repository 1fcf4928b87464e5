#pragma once
// An independent high-accuracy solution of the matrix ODE y' = y g(y) for judging global errors: the classical
// Runge-Kutta method of order 4 on the n x n entries, with no Lie-group structure and nothing shared with the
// project's reference_solution (an RKMK method). Its error at kMatrixOdeStepsPerUnit steps per unit of time is
// checked by step doubling in branch_tracker_test.cpp.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>

namespace lienewton::test {

inline constexpr int kMatrixOdeStepsPerUnit = 16384;

// y(t_end) of y' = y g(t, y) from y(0) = y0, with ceil(steps_per_unit |t_end|) equal steps (at least one).
inline Eigen::MatrixXd matrix_ode_reference_at(
    const std::function<Eigen::MatrixXd(double, const Eigen::MatrixXd&)>& g, const Eigen::MatrixXd& y0,
    double t_end, int steps_per_unit = kMatrixOdeStepsPerUnit) {
  const int steps = std::max(1, static_cast<int>(std::ceil(steps_per_unit * std::abs(t_end))));
  const double dt = t_end / steps;
  const auto f = [&g](double t, const Eigen::MatrixXd& y) -> Eigen::MatrixXd { return y * g(t, y); };
  Eigen::MatrixXd y = y0;
  for (int i = 0; i < steps; ++i) {
    const double t = i * dt;
    const Eigen::MatrixXd k1 = f(t, y);
    const Eigen::MatrixXd k2 = f(t + 0.5 * dt, y + (0.5 * dt) * k1);
    const Eigen::MatrixXd k3 = f(t + 0.5 * dt, y + (0.5 * dt) * k2);
    const Eigen::MatrixXd k4 = f(t + dt, y + dt * k3);
    y += (dt / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return y;
}

// The same for an autonomous g(y).
inline Eigen::MatrixXd matrix_ode_reference(const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& g,
                                            const Eigen::MatrixXd& y0, double t_end,
                                            int steps_per_unit = kMatrixOdeStepsPerUnit) {
  return matrix_ode_reference_at([&g](double, const Eigen::MatrixXd& y) { return g(y); }, y0, t_end, steps_per_unit);
}

}  // namespace lienewton::test
