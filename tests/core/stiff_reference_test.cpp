// A stiff user field (a rigid body on SO(3) x R^3 pulled toward the identity attitude by a torsional spring and
// damper, k = c = 1e4, linearisation's fastest eigenvalue -1e4, with a smooth forcing torque):
//   R' = R hat(w),  J w' = (J w) x w - k vee(skew(R)) - c w + f(t),  f(t) = (0.5 sin 2t, 0.3 cos t, 0.2),
// J = diag(1, 2, 3), R(0) = exp(hat(0.5, -0.3, 0.8)), w(0) = (1, -2, 0.5), t in [0, 1]. The library's reference
// (core/reference_solution.hpp) must give a finite global_error there; it is checked against an independent
// reference computed here: classical RK4 on the ODE in R^9 x R^3 (R a free 3 x 3 matrix), at a step inside RK4's
// stability interval (h |lambda| = 0.31), its accuracy bounded by its distance from half the steps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/groups/so3_group.hpp"
#include "core/integrate.hpp"
#include "core/work_precision.hpp"

namespace lienewton {
namespace {

constexpr double kStiffness = 1e4;
constexpr const char* kSpringDamper =
    "R = y(1:3,1:3); w = y(4:6,7); J = [1; 2; 3]; S = (R - R')/2; s = [S(3,2); S(1,3); S(2,1)]; "
    "f = [0.5*sin(2*t); 0.3*cos(t); 0.2]; dw = (cross(J .* w, w) - k*s - c*w + f) ./ J; "
    "W = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]; g = [W zeros(3,4); zeros(4,3) [zeros(3) dw; zeros(1,4)]]";

struct State {
  Eigen::Matrix3d r;
  Eigen::Vector3d w;
};

Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

State rate(const State& s, double t) {
  const Eigen::Vector3d j(1, 2, 3);
  const Eigen::Matrix3d skew = (s.r - s.r.transpose()) / 2;
  const Eigen::Vector3d v(skew(2, 1), skew(0, 2), skew(1, 0));
  const Eigen::Vector3d f(0.5 * std::sin(2 * t), 0.3 * std::cos(t), 0.2);
  return {s.r * hat(s.w), (j.cwiseProduct(s.w).cross(s.w) - kStiffness * v - kStiffness * s.w + f).cwiseQuotient(j)};
}

State axpy(const State& s, double a, const State& d) { return {s.r + a * d.r, s.w + a * d.w}; }

Eigen::Matrix3d start_rotation() { return SO3Group{}.exp(Eigen::Vector3d(0.5, -0.3, 0.8)); }

Eigen::MatrixXd as_matrix(const State& s) {
  Eigen::MatrixXd y = Eigen::MatrixXd::Identity(7, 7);
  y.topLeftCorner(3, 3) = s.r;
  y.block(3, 6, 3, 1) = s.w;
  return y;
}

Eigen::MatrixXd rk4(int steps) {
  const double h = 1.0 / steps;
  State s{start_rotation(), Eigen::Vector3d(1, -2, 0.5)};
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    const State k1 = rate(s, t), k2 = rate(axpy(s, h / 2, k1), t + h / 2), k3 = rate(axpy(s, h / 2, k2), t + h / 2),
                k4 = rate(axpy(s, h, k3), t + h);
    s.r += h / 6 * (k1.r + 2 * k2.r + 2 * k3.r + k4.r);
    s.w += h / 6 * (k1.w + 2 * k2.w + 2 * k3.w + k4.w);
  }
  return as_matrix(s);
}

IntegrateRequest stiff_request(Integrator integrator, double h) {
  IntegrateRequest req;
  req.problem.group = "SOxR";
  req.problem.g = kSpringDamper;
  req.problem.parameters["k"] = Eigen::MatrixXd::Constant(1, 1, kStiffness);
  req.problem.parameters["c"] = Eigen::MatrixXd::Constant(1, 1, kStiffness);
  req.problem.z = as_matrix({start_rotation(), Eigen::Vector3d(1, -2, 0.5)});
  req.integrator = integrator;
  req.h = h;
  req.t_end = 1.0;
  return req;
}

TEST(StiffReference, GlobalErrorIsFiniteAndMatchesAnIndependentReference) {
  const Eigen::MatrixXd fine = rk4(1 << 15), coarse = rk4(1 << 14);
  const double reference_error = (fine - coarse).norm();
  std::printf("independent RK4 reference: 2^15 and 2^14 steps differ by %.1e\n", reference_error);
  ASSERT_LE(reference_error, 1e-9);
  for (const double h : {1.0 / 16, 1.0 / 64}) {
    const IntegrateResult r = integrate(stiff_request(Integrator::rkmk_gauss2, h));
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    ASSERT_TRUE(r.global_error.has_value()) << r.reason;
    const double independent = (r.y - fine).norm();
    std::printf("rkmk-gauss2 h = %g: global_error %.6e, against the independent reference %.6e\n", h,
                *r.global_error, independent);
    EXPECT_GT(independent, 1e3 * reference_error) << "the error must be the method's, not the references'";
    EXPECT_NEAR(*r.global_error, independent, 1e-6 * independent + 1e2 * reference_error);
  }
}

// An explicit step that overflows on the stiff field says so; it never claims to have left a branch it never had.
TEST(StiffReference, OverflowingExplicitStepSaysItOverflowed) {
  IntegrateRequest req = stiff_request(Integrator::rkmk4, 1.0 / 16);
  req.reference = false;
  const IntegrateResult r = integrate(req);
  EXPECT_EQ(r.status, Status::non_finite) << r.reason;
  EXPECT_NE(r.reason.find("overflowed"), std::string::npos) << r.reason;
  EXPECT_EQ(r.reason.find("branch"), std::string::npos) << r.reason;
}

// Work-precision on the stiff field: every point has a finite error and none is called rounding.
TEST(StiffReference, WorkPrecisionPointsAreNeverCalledRounding) {
  WorkPrecisionRequest req;
  const IntegrateRequest base = stiff_request(Integrator::rkmk_gauss2, 1.0 / 16);
  req.problem = base.problem;
  req.choices = {{.integrator = Integrator::dirk_cg2}};
  req.h = {1.0 / 16, 1.0 / 32, 1.0 / 64};
  const WorkPrecisionResult res = work_precision(req);
  for (const WorkPrecisionPoint& p : res.series.front().points) {
    EXPECT_TRUE(std::isfinite(p.error)) << "h = " << p.h;
    EXPECT_GT(p.error, 1e-12) << "h = " << p.h;
    EXPECT_EQ(p.excluded.find("rounding"), std::string::npos) << p.excluded;
  }
}

}  // namespace
}  // namespace lienewton
