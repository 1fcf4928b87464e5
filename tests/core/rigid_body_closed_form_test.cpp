// The built-in rigid-body pinned to a solution it did not compute: the torque-free rigid body's closed form in
// Jacobi elliptic functions (Landau & Lifshitz, Mechanics, section 37, eq. 37.10). For principal moments
// I1 < I2 < I3, energy E and |M|^2 > 2 E I2, with Omega_2(0) = 0, Omega_1(0) > 0, Omega_3(0) > 0:
//   Omega_1 = sqrt((2 E I3 - M^2) / (I1 (I3 - I1))) cn(tau),  Omega_2 = sqrt((2 E I3 - M^2) / (I2 (I3 - I2))) sn(tau),
//   Omega_3 = sqrt((M^2 - 2 E I1) / (I3 (I3 - I1))) dn(tau),
//   tau = t sqrt((I3 - I2)(M^2 - 2 E I1) / (I1 I2 I3)),  k^2 = (I2 - I1)(2 E I3 - M^2) / ((I3 - I2)(M^2 - 2 E I1)).
// The problem's body momentum M(t) = y(t)^T m = I Omega(t) is compared with it; sn, cn, dn come from the
// arithmetic-geometric mean (Abramowitz & Stegun 16.4), written here independently of the library.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "core/integrate.hpp"
#include "core/integrators/methods.hpp"

namespace lienewton {
namespace {

struct Jacobi {
  double sn, cn, dn;
};

// sn, cn, dn of u at parameter m = k^2 (0 <= m < 1) by the descending AGM sequence (A&S 16.4.2-16.4.4).
Jacobi jacobi(double u, double m) {
  std::vector<double> a{1.0}, c{std::sqrt(m)};
  double b = std::sqrt(1.0 - m);
  while (std::abs(c.back()) > 1e-16 && a.size() < 40) {
    const double an = (a.back() + b) / 2;
    c.push_back((a.back() - b) / 2);
    b = std::sqrt(a.back() * b);
    a.push_back(an);
  }
  const std::size_t n = a.size() - 1;
  double phi = std::ldexp(1.0, static_cast<int>(n)) * a[n] * u, previous = phi;
  for (std::size_t j = n; j >= 1; --j) {
    previous = phi;
    phi = (phi + std::asin(c[j] / a[j] * std::sin(phi))) / 2;
  }
  return {std::sin(phi), std::cos(phi), std::cos(phi) / std::cos(previous - phi)};
}

// The problem's defaults (I = diag(1, 2, 3), m = (0.6, 0.8, 0.5)) from y(0) = r0, which takes m0 = (0.5, 0, 1) to m,
// and the body momentum M(t) = y(t)^T m of that motion in closed form.
struct ClosedForm {
  Eigen::Vector3d inertia{1.0, 2.0, 3.0}, m{0.6, 0.8, 0.5};
  Eigen::Vector3d m0{0.5, 0.0, 1.0};  // |m0| = |m|, so y(0) m0 = m for a rotation
  Eigen::Matrix3d r0 = Eigen::Quaterniond::FromTwoVectors(m0, m).toRotationMatrix();
  double e = 0.5 * m0.dot(m0.cwiseQuotient(inertia)), l2 = m0.squaredNorm();
  double i1 = inertia(0), i2 = inertia(1), i3 = inertia(2);
  double rate = std::sqrt((i3 - i2) * (l2 - 2 * e * i1) / (i1 * i2 * i3));
  double k2 = (i2 - i1) * (2 * e * i3 - l2) / ((i3 - i2) * (l2 - 2 * e * i1));

  Eigen::Vector3d operator()(double t) const {
    const Jacobi f = jacobi(rate * t, k2);
    const Eigen::Vector3d omega(std::sqrt((2 * e * i3 - l2) / (i1 * (i3 - i1))) * f.cn,
                                std::sqrt((2 * e * i3 - l2) / (i2 * (i3 - i2))) * f.sn,
                                std::sqrt((l2 - 2 * e * i1) / (i3 * (i3 - i1))) * f.dn);
    return Eigen::Vector3d(inertia.cwiseProduct(omega));
  }
  // |M(t_end) - closed form| of an integration from r0 with the integrator's equal steps h.
  double error(Integrator integrator, double h, double t_end) const {
    IntegrateRequest req;
    req.problem.kind = ProblemKind::rigid_body;
    req.problem.n = 3;
    req.problem.z = r0;
    req.integrator = integrator;
    req.h = h;
    req.t_end = t_end;
    req.reference = false;
    const IntegrateResult r = integrate(req);
    EXPECT_EQ(r.status, Status::converged) << to_string(integrator) << " h = " << h << ": " << r.reason;
    return ((Eigen::Matrix3d(r.y).transpose() * m) - (*this)(t_end)).norm();
  }
};

TEST(RigidBodyClosedForm, BodyMomentumFollowsTheJacobiEllipticSolution) {
  const ClosedForm closed_form;
  const Eigen::Vector3d& m0 = closed_form.m0;
  ASSERT_NEAR(m0.norm(), closed_form.m.norm(), 1e-15);
  ASSERT_GT(closed_form.l2, 2 * closed_form.e * closed_form.i2);
  EXPECT_LE((closed_form(0.0) - m0).norm(), 1e-14) << "the closed form starts at M(0)";
  EXPECT_GT((closed_form(3.0) - m0).norm(), 0.3) << "and moves far from it by t = 3";
  for (double t_end : {1.0, 3.0}) {
    const double error = closed_form.error(Integrator::rkmk_gauss3, 1.0 / 32, t_end);
    std::printf("t = %.0f: |M(t) - closed form| = %.2e\n", t_end, error);
    EXPECT_LE(error, 1e-8) << "t = " << t_end;
  }
}

// The implicit RKMK stages are solved to the step's own scale, so a method's error falls with h^p until it meets
// the rounding of the steps themselves, whose sum stays below 10 eps |M| per step (a bound rounding cannot break:
// a few eps per step at most, and the errors of single steps partly cancel). With a stage test absolute in tol, the
// stages kept an error of about tol (1e-13) per step once h was small, and the error grew as h fell below 2^-12. The
// line C h^p is fitted at h = 1/8, far above rounding, with a margin of 4.
TEST(RigidBodyClosedForm, ImplicitRkmkKeepsItsOrderDownToRounding) {
  const ClosedForm closed_form;
  const double h0 = 1.0 / 8;
#ifdef LIENEWTON_SANITIZED
  const std::vector<int> halvings{12};  // 2^-14 and 2^-16 take 16384 and 65536 steps a method: the Release suite's
#else
  const std::vector<int> halvings{12, 14, 16};
#endif
  for (Integrator integrator : {Integrator::rkmk_gauss2, Integrator::rkmk_gauss3, Integrator::rkmk_radau2,
                                Integrator::rkmk_radau3, Integrator::rkmk_lobatto3c}) {
    const int p = order_of(integrator);
    const double c = 4.0 * closed_form.error(integrator, h0, 1.0) / std::pow(h0, p);
    for (int halving : halvings) {
      const double h = std::ldexp(1.0, -halving), steps = 1.0 / h;
      const double error = closed_form.error(integrator, h, 1.0);
      const double rounding = 10.0 * std::numeric_limits<double>::epsilon() * steps * closed_form.m.norm();
      const double bound = c * std::pow(h, p) + rounding;
      std::printf("%s h = 2^-%d: error %.2e (bound %.2e)\n", std::string(to_string(integrator)).c_str(), halving, error,
                  bound);
      EXPECT_LE(error, bound) << to_string(integrator) << " at h = 2^-" << halving;
    }
  }
}

}  // namespace
}  // namespace lienewton
