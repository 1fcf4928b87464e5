// SO(3) closed forms: the coefficient functions against long-double references on a log-spaced sweep of
// t in [1e-12, pi - 1e-12], the closed forms against the SO(N) spectral path at N = 3, and SO(3)-specific
// edges of log (near and at pi). The group properties shared with SO(N) are in group_properties_test.cpp.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <numbers>

#include "core/groups/so3.hpp"
#include "core/groups/so3_group.hpp"
#include "core/groups/son_group.hpp"

namespace lienewton {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;
constexpr long double kPiL = 3.141592653589793238462643383279502884L;

// ---------------------------------------------------------------------------------------------------------
// Long-double references (x87 extended: 64-bit mantissa, eps ~ 1.1e-19, 2^11 times finer than double).
// A and B from sinl without cancellation; C and D as power series, which have no cancellation for t <= pi
// (the first term dominates: at t = pi the terms of C sum to 0.101 from 1/6 - 0.082 + 0.019 - ..., a loss of
// < 2 bits; D's numerator sin x - x cos x, x = t/2, is summed as sum_k>=1 (-1)^(k+1) 2k x^(2k+1)/(2k+1)!).

long double ref_sinc(long double t) { return sinl(t) / t; }
long double ref_one_minus_cos_over_t2(long double t) {
  const long double s = sinl(0.5L * t);
  return 2.0L * s * s / (t * t);
}
long double ref_t_minus_sin_over_t3(long double t) {  // sum_k (-1)^k t^2k / (2k+3)!
  long double term = 1.0L / 6.0L, sum = 0.0L;
  for (int k = 0; k < 40; ++k) {
    sum += term;
    term *= -t * t / ((2.0L * k + 4.0L) * (2.0L * k + 5.0L));
  }
  return sum;
}
long double ref_dexpinv_coefficient(long double t) {  // (sin x - x cos x) / (sin x t^2), x = t/2
  const long double x = 0.5L * t;
  long double power = x * x * x, fact = 6.0L, sum = 0.0L;  // x^(2k+1), (2k+1)!, k = 1
  for (int k = 1; k < 40; ++k) {
    sum += ((k % 2 == 1) ? 1.0L : -1.0L) * 2.0L * k * power / fact;
    power *= x * x;
    fact *= (2.0L * k + 2.0L) * (2.0L * k + 3.0L);
  }
  return sum / (sinl(x) * t * t);
}

// Error in units of the last place of the (double-rounded) reference.
double ulps(double value, long double reference) {
  const double r = static_cast<double>(reference);
  const double ulp = std::nextafter(std::abs(r), std::numeric_limits<double>::infinity()) - std::abs(r);
  return static_cast<double>(std::fabs(static_cast<long double>(value) - reference) / ulp);
}

std::vector<double> sweep_points() {
  std::vector<double> t;
  const double lo = std::log(1e-12), hi = std::log(kPi - 1e-12);
  constexpr int kPoints = 4000;
  for (int i = 0; i <= kPoints; ++i) t.push_back(std::exp(lo + (hi - lo) * i / kPoints));
  t.front() = 1e-12;
  t.back() = kPi - 1e-12;
  // Both sides of the implementation's branch switches (1e-4 and 2) and the pi end.
  for (double edge : {1e-4, 2.0})
    for (int k = -8; k <= 8; ++k) t.push_back(edge * (1.0 + k * 1e-3));
  for (double d : {1e-3, 1e-6, 1e-9}) t.push_back(kPi - d);
  return t;
}

struct Coefficient {
  const char* name;
  double (*f)(double);
  long double (*ref)(long double);
};

// Each coefficient within 4 ulp of the long-double reference on the whole sweep (so3.hpp promises ~2).
TEST(SO3Coefficients, WithinFourUlpOfLongDoubleReference) {
  constexpr double kMaxUlps = 4.0;
  const Coefficient coefficients[] = {
      {"one_minus_cos_over_t2", so3::one_minus_cos_over_t2, ref_one_minus_cos_over_t2},
      {"t_minus_sin_over_t3", so3::t_minus_sin_over_t3, ref_t_minus_sin_over_t3},
      {"dexpinv_coefficient", so3::dexpinv_coefficient, ref_dexpinv_coefficient},
      {"rodrigues.a", [](double t) { return so3::rodrigues(t).a; }, ref_sinc},
      {"rodrigues.b", [](double t) { return so3::rodrigues(t).b; }, ref_one_minus_cos_over_t2},
  };
  const auto ts = sweep_points();
  for (const auto& c : coefficients) {
    double worst = 0.0, worst_t = 0.0;
    for (double t : ts) {
      const double e = ulps(c.f(t), c.ref(static_cast<long double>(t)));
      if (!(e <= worst)) worst = e, worst_t = t;
    }
    EXPECT_LE(worst, kMaxUlps) << c.name << ": worst error " << worst << " ulp at t = " << worst_t;
  }
}

// The references themselves against the direct formulas in long double where those have no cancellation.
TEST(SO3Coefficients, ReferencesAreConsistent) {
  for (long double t : {0.5L, 1.0L, 2.0L, 3.0L, kPiL - 1e-6L}) {
    const long double c_direct = (t - sinl(t)) / (t * t * t);
    const long double d_direct = (1.0L - 0.5L * t * cosl(0.5L * t) / sinl(0.5L * t)) / (t * t);
    EXPECT_LE(fabsl(ref_t_minus_sin_over_t3(t) - c_direct) / c_direct, 1e-17L) << static_cast<double>(t);
    EXPECT_LE(fabsl(ref_dexpinv_coefficient(t) - d_direct) / d_direct, 1e-17L) << static_cast<double>(t);
  }
  EXPECT_NEAR(static_cast<double>(ref_t_minus_sin_over_t3(0.0L)), 1.0 / 6.0, kEps);
  EXPECT_NEAR(static_cast<double>(ref_dexpinv_coefficient(1e-9L)), 1.0 / 12.0, kEps);
}

// safe_norm takes the fast sqrt(|v|^2) only where |v|^2 neither under- nor overflows: at every scale it
// is within 2 eps of the exact norm of a direction whose norm is 1 in exact arithmetic (0.48^2+0.6^2+0.64^2).
TEST(SO3Norm, SafeAtEveryScale) {
  for (double scale : {1e-305, 1e-200, 1e-141, 1e-139, 1e-5, 1.0, 3.0, 1e139, 1e141, 1e200, 1e305}) {
    const Eigen::Vector3d v = scale * Eigen::Vector3d(0.48, -0.6, 0.64);
    EXPECT_LE(std::abs(so3::safe_norm(v) - scale) / scale, 2 * kEps) << "scale " << scale;
  }
  EXPECT_EQ(so3::safe_norm(Eigen::Vector3d::Zero()), 0.0);
}

// The coefficients at t = 0 itself (a zero rotation vector is a common input).
TEST(SO3Coefficients, LimitsAtZero) {
  EXPECT_EQ(so3::rodrigues(0.0).a, 1.0);
  EXPECT_EQ(so3::rodrigues(0.0).b, 0.5);
  EXPECT_EQ(so3::one_minus_cos_over_t2(0.0), 0.5);
  EXPECT_DOUBLE_EQ(so3::t_minus_sin_over_t3(0.0), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(so3::dexpinv_coefficient(0.0), 1.0 / 12.0);
}

// ---------------------------------------------------------------------------------------------------------
// Closed forms vs the SO(N) spectral path at N = 3: alpha = (-w3, w2, -w1); hat matrices are identical.

Eigen::VectorXd alpha_of(const Eigen::Vector3d& w) { return Eigen::Vector3d(-w.z(), w.y(), -w.x()); }

TEST(SO3VsSON, HatAndCoordinatesAgree) {
  const Eigen::Vector3d w(0.3, -1.1, 2.2);
  EXPECT_EQ((so3::hat(w) - son::hat(alpha_of(w), 3)).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((son::vee(so3::hat(w)) - alpha_of(w)).cwiseAbs().maxCoeff(), 0.0);
}

// exp, log, dexp, dexpinv agree to <= 1e-14 relative on random inputs with |w| in (1e-3, pi - 1e-3) and at
// the moderate edges pi/2, 2, 3 about random axes.
TEST(SO3VsSON, ClosedFormsAgreeWithSpectralPath) {
  constexpr double kTol = 1e-14;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> angle(1e-3, kPi - 1e-3);
  const SO3Group g3;
  const SONGroup gn(3);
  std::vector<Eigen::Vector3d> ws;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    ws.push_back(angle(rng) * d.normalized());
  }
  for (double t : {kPi / 2, 2.0, 3.0}) ws.push_back(t * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  for (const auto& w : ws) {
    const Eigen::Vector3d u(normal(rng), normal(rng), normal(rng));
    const Eigen::Matrix3d r3 = so3::exp(w);
    const Eigen::MatrixXd rn = son::exp(son::hat(alpha_of(w), 3));
    EXPECT_LE((r3 - rn).norm() / r3.norm(), kTol) << "exp, |w| = " << w.norm();
    EXPECT_LE((alpha_of(so3::log(r3)) - son::vee(son::log(r3))).norm() / w.norm(), kTol) << "log, |w| = " << w.norm();
    const Eigen::VectorXd di3 = alpha_of(so3::dexpinv(w, u));
    const Eigen::VectorXd din = gn.dexpinv(gn.spectral(alpha_of(w)), alpha_of(u));
    EXPECT_LE((di3 - din).norm() / di3.norm(), kTol) << "dexpinv, |w| = " << w.norm();
    const Eigen::VectorXd d3 = alpha_of(so3::dexp(w, u));
    const Eigen::VectorXd dn = gn.dexp(gn.spectral(alpha_of(w)), alpha_of(u));
    EXPECT_LE((d3 - dn).norm() / d3.norm(), kTol) << "dexp, |w| = " << w.norm();
    // The matrix forms used by the solvers agree with the vector forms.
    EXPECT_LE((so3::dexpinv_matrix(w) * u - so3::dexpinv(w, u)).norm() / u.norm(), 4 * kEps * (1 + w.norm()));
    EXPECT_LE((so3::dexp_matrix(w) * u - so3::dexp(w, u)).norm() / u.norm(), 4 * kEps * (1 + w.norm()));
    (void)g3;
  }
}

// ---------------------------------------------------------------------------------------------------------
// SO(3)-specific edges of log.

// Near pi the well-known failure is losing digits: the rotation vector must stay accurate to <= 1e-14 relative
// for pi - d, d from 1e-3 down to 1e-15, about random axes (the closed form refuses nothing: |w| <= pi).
TEST(SO3Log, AccurateApproachingPi) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    for (double d = 1e-3; d >= 1e-15; d /= 10) {
      const Eigen::Vector3d w = (kPi - d) * axis;
      const Eigen::Vector3d back = so3::log(so3::exp(w));
      // At distance d from pi, exp(w) = exp(w') for w' = w - 2pi axis is only 2d away: accept either branch
      // there is no rounding-free way to tell them apart below d ~ eps.
      const double err = std::min((back - w).norm(), (back - (w - 2 * kPi * axis)).norm());
      EXPECT_LE(err / kPi, 1e-14) << "d = " << d;
      EXPECT_LE(back.norm(), kPi);
    }
  }
}

// Exactly pi about the coordinate axes: R = diag with two -1: |log R| = pi about the right axis.
TEST(SO3Log, ExactlyPiAboutCoordinateAxes) {
  for (int k = 0; k < 3; ++k) {
    Eigen::Matrix3d r = -Eigen::Matrix3d::Identity();
    r(k, k) = 1.0;
    const Eigen::Vector3d w = so3::log(r);
    EXPECT_DOUBLE_EQ(w.norm(), kPi);
    EXPECT_DOUBLE_EQ(std::abs(w(k)), kPi);
    EXPECT_LE((so3::exp(w) - r).norm(), 4 * kEps);
  }
}

// The group's log domain (inside_log_domain): within kLogDomainMargin of pi the closed form's result is not used.
TEST(SO3Log, GroupRefusesAnglesAtPiThroughItsLogDomain) {
  const SO3Group g;
  EXPECT_TRUE(inside_log_domain<SO3Group>(g.angle(g.log(so3::exp(Eigen::Vector3d(0, 0, kPi - 1e-9))))));
  EXPECT_FALSE(inside_log_domain<SO3Group>(g.angle(g.log(Eigen::Vector3d(1, -1, -1).asDiagonal()))));
}

// Small angles: exp is I + hat(w) to the last bit of the off-diagonals, and log returns w to <= 2 eps relative.
TEST(SO3Log, SmallAnglesKeepRelativeAccuracy) {
  for (double t : {1e-300, 1e-200, 1e-150, 1e-100, 1e-20, 1e-12, 1e-8}) {
    const Eigen::Vector3d w = t * Eigen::Vector3d(0.48, -0.6, 0.64);
    const Eigen::Vector3d back = so3::log(so3::exp(w));
    EXPECT_LE((back - w).stableNorm() / w.stableNorm(), 2 * kEps) << "t = " << t;
  }
}

}  // namespace
}  // namespace lienewton
