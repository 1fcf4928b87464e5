#pragma once
// Adaptive step sizes by step doubling (Richardson extrapolation), as in Hairer, Norsett & Wanner, "Solving
// Ordinary Differential Equations I", 2nd ed., section II.4: a step of size h from y0 gives y1, two steps of h/2
// give y2, and for a method of order p the local error of y2 is (y2 - y1) / (2^p - 1) up to O(h^(p+2)) (II.4,
// "Richardson extrapolation"). Its size is measured in the scaled root-mean-square norm (4.11) over the entries
// of the group's matrices, sc_ij = atol + rtol max(|y0_ij|, |y2_ij|), and the next step is
//   h_new = h min(facmax, max(facmin, fac err^(-1/(p+1))))                                       (4.13)
// with the safety factor fac; after a rejected step facmax = 1 (II.4: do not grow right after a rejection).
// The step is accepted when err <= 1 and y2 (not the extrapolated value) is kept, so the result is the method's
// own. On a stiff step an implicit RKMK method gives its embedded estimate instead (integrators/embedded_estimate.hpp),
// measured in the same norm, and the next step takes the exponent of that estimate's order. docs/integrators.md.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace lienewton {

struct StepSizeControl {
  double rtol;
  double atol;
  int order;  // p of the integrator (order_of)

  static constexpr double kSafety = 0.9;
  static constexpr double kMinFactor = 0.2;
  static constexpr double kMaxFactor = 5.0;
  // A step whose stages cannot be solved on the solution's branch (or is not finite) is tried again at half size.
  static constexpr double kFailureFactor = 0.5;
  // The smallest step, as a fraction of t_end: below it the integration ends with status min_step.
  static constexpr double kMinStepFraction = 1e-10;

  // The scaled error estimate of y2 (two half steps) against y1 (one whole step), both from y0.
  double error(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& y1, const Eigen::MatrixXd& y2) const {
    const double richardson = std::ldexp(1.0, order) - 1.0;
    return scaled(y0, y2, (y2 - y1) / richardson);
  }

  // The scaled root-mean-square size of an error e of y1, a step from y0.
  double scaled(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& y1, const Eigen::MatrixXd& e) const {
    const Eigen::ArrayXXd scale = atol + rtol * y0.array().abs().max(y1.array().abs());
    return std::sqrt((e.array() / scale).square().mean());
  }

  // The factor of the next step from the error estimate err of the last try (4.13), an estimate of order
  // estimate_order (step doubling's: p).
  double factor(double err, bool after_rejection, int estimate_order) const {
    const double max_factor = after_rejection ? 1.0 : kMaxFactor;
    if (!(err > 0.0)) return max_factor;  // an exact step (err = 0)
    return std::min(max_factor, std::max(kMinFactor, kSafety * std::pow(err, -1.0 / (estimate_order + 1))));
  }
};

}  // namespace lienewton
