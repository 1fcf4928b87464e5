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
#include <vector>

#include "core/integrate.hpp"

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

TEST(RigidBodyClosedForm, BodyMomentumFollowsTheJacobiEllipticSolution) {
  const Eigen::Vector3d inertia(1.0, 2.0, 3.0), m(0.6, 0.8, 0.5);  // the built-in's defaults
  const Eigen::Vector3d m0(0.5, 0.0, 1.0);                           // |m0| = |m|, so y(0) m0 = m for a rotation
  ASSERT_NEAR(m0.norm(), m.norm(), 1e-15);
  const Eigen::Matrix3d r0 = Eigen::Quaterniond::FromTwoVectors(m0, m).toRotationMatrix();
  const double e = 0.5 * m0.dot(m0.cwiseQuotient(inertia)), l2 = m0.squaredNorm();
  const double i1 = inertia(0), i2 = inertia(1), i3 = inertia(2);
  ASSERT_GT(l2, 2 * e * i2);
  const double rate = std::sqrt((i3 - i2) * (l2 - 2 * e * i1) / (i1 * i2 * i3));
  const double k2 = (i2 - i1) * (2 * e * i3 - l2) / ((i3 - i2) * (l2 - 2 * e * i1));
  const auto closed_form = [&](double t) {
    const Jacobi f = jacobi(rate * t, k2);
    const Eigen::Vector3d omega(std::sqrt((2 * e * i3 - l2) / (i1 * (i3 - i1))) * f.cn,
                                std::sqrt((2 * e * i3 - l2) / (i2 * (i3 - i2))) * f.sn,
                                std::sqrt((l2 - 2 * e * i1) / (i3 * (i3 - i1))) * f.dn);
    return Eigen::Vector3d(inertia.cwiseProduct(omega));
  };
  EXPECT_LE((closed_form(0.0) - m0).norm(), 1e-14) << "the closed form starts at M(0)";
  EXPECT_GT((closed_form(3.0) - m0).norm(), 0.3) << "and moves far from it by t = 3";
  for (double t_end : {1.0, 3.0}) {
    IntegrateRequest req;
    req.problem.kind = ProblemKind::rigid_body;
    req.problem.n = 3;
    req.problem.z = r0;
    req.integrator = Integrator::rkmk_gauss3;
    req.h = 1.0 / 32;
    req.t_end = t_end;
    req.reference = false;
    const IntegrateResult r = integrate(req);
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    const Eigen::Vector3d body = Eigen::Matrix3d(r.y).transpose() * m;
    const double error = (body - closed_form(t_end)).norm();
    std::printf("t = %.0f: |M(t) - closed form| = %.2e\n", t_end, error);
    EXPECT_LE(error, 1e-8) << "t = " << t_end;
  }
}

}  // namespace
}  // namespace lienewton
