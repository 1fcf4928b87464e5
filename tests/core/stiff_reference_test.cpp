// A stiff user field (a rigid body on SO(3) x R^3 pulled toward the identity attitude by a torsional spring and
// damper, k = c = 1e4, linearisation's fastest eigenvalue -1e4, with a smooth forcing torque):
//   R' = R hat(w),  J w' = (J w) x w - k vee(skew(R)) - c w + f(t),  f(t) = (0.5 sin 2t, 0.3 cos t, 0.2),
// J = diag(1, 2, 3), R(0) = exp(hat(0.5, -0.3, 0.8)), w(0) = (1, -2, 0.5), t in [0, 1]. The library's reference
// (core/reference_solution.hpp) must give a finite global_error there; it is checked against an independent
// reference computed here: classical RK4 on the 7 x 7 matrix ODE's entries (matrix_ode_reference.hpp, R a free 3 x 3
// matrix), at a step inside RK4's stability interval (h |lambda| = 0.31), its accuracy bounded by its distance
// from half the steps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/groups/so3_group.hpp"
#include "core/integrate.hpp"
#include "core/work_precision.hpp"
#include "matrix_ode_reference.hpp"

namespace lienewton {
namespace {

constexpr double kStiffness = 1e4;
constexpr const char* kSpringDamper =
    "R = y(1:3,1:3); w = y(4:6,7); J = [1; 2; 3]; S = (R - R')/2; s = [S(3,2); S(1,3); S(2,1)]; "
    "f = [0.5*sin(2*t); 0.3*cos(t); 0.2]; dw = (cross(J .* w, w) - k*s - c*w + f) ./ J; "
    "W = [0 -w(3) w(2); w(3) 0 -w(1); -w(2) w(1) 0]; g = [W zeros(3,4); zeros(4,3) [zeros(3) dw; zeros(1,4)]]";

Eigen::Matrix3d start_rotation() { return SO3Group{}.exp(Eigen::Vector3d(0.5, -0.3, 0.8)); }

Eigen::MatrixXd start() {
  Eigen::MatrixXd y = Eigen::MatrixXd::Identity(7, 7);
  y.topLeftCorner(3, 3) = start_rotation();
  y.block(3, 6, 3, 1) = Eigen::Vector3d(1, -2, 0.5);
  return y;
}

// The field as the 7 x 7 algebra element [[hat(w), 0], [0, [[0, dw], [0, 0]]]]: y' = y g(t, y) is R' = R hat(w),
// w' = dw on the matrix's entries, R free (not kept orthogonal).
Eigen::MatrixXd field(double t, const Eigen::MatrixXd& y) {
  const Eigen::Vector3d j(1, 2, 3), w = y.block(3, 6, 3, 1);
  const Eigen::Matrix3d r = y.topLeftCorner(3, 3), skew = (r - r.transpose()) / 2;
  const Eigen::Vector3d v(skew(2, 1), skew(0, 2), skew(1, 0));
  const Eigen::Vector3d f(0.5 * std::sin(2 * t), 0.3 * std::cos(t), 0.2);
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(7, 7);
  g.topLeftCorner(3, 3) << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  g.block(3, 6, 3, 1) = (j.cwiseProduct(w).cross(w) - kStiffness * v - kStiffness * w + f).cwiseQuotient(j);
  return g;
}

IntegrateRequest stiff_request(Integrator integrator, double h) {
  IntegrateRequest req;
  req.problem.group = "SOxR";
  req.problem.g = kSpringDamper;
  req.problem.parameters["k"] = Eigen::MatrixXd::Constant(1, 1, kStiffness);
  req.problem.parameters["c"] = Eigen::MatrixXd::Constant(1, 1, kStiffness);
  req.problem.z = start();
  req.integrator = integrator;
  req.h = h;
  req.t_end = 1.0;
  return req;
}

TEST(StiffReference, GlobalErrorIsFiniteAndMatchesAnIndependentReference) {
  const Eigen::MatrixXd fine = test::matrix_ode_reference_at(field, start(), 1.0, 1 << 15);
  const Eigen::MatrixXd coarse = test::matrix_ode_reference_at(field, start(), 1.0, 1 << 14);
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
