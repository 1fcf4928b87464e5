// SO(N) specifics of son.hpp: coordinates in the paper's basis, the log domain check and its typed errors,
// the spectral form, and the exact differentials against their Bernoulli / exponential series.
// Shared group properties (round trips, orthogonality, FD and BCH checks) are in group_properties_test.cpp.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <algorithm>
#include <random>
#include <vector>

#include "core/groups/son.hpp"

namespace lienewton::son {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

Mat random_rotation(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Mat a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = normal(rng);
  Mat q = Eigen::HouseholderQR<Mat>(a).householderQ();
  if (q.determinant() < 0) q.col(0) = -q.col(0);
  return q;
}

// Coordinates in row-major order (1,2), (1,3), ..., (1,N), (2,3), ..., (N-1,N); q = N(N-1)/2.
TEST(SONCoordinates, PaperBasisOrder) {
  EXPECT_EQ(algebra_dim(2), 1);
  EXPECT_EQ(algebra_dim(15), 105);
  const int n = 4;
  Vec alpha(6);
  alpha << 1, 2, 3, 4, 5, 6;
  Mat expected(4, 4);
  expected << 0, 1, 2, 3,  //
      -1, 0, 4, 5,         //
      -2, -4, 0, 6,        //
      -3, -5, -6, 0;
  EXPECT_EQ(hat(alpha, n), expected);
  EXPECT_EQ(vee(expected), alpha);
  // vee takes the skew part of a general matrix.
  Mat m = expected;
  m += Mat::Constant(4, 4, 0.5);
  EXPECT_EQ(vee(m), alpha);
}

// Non-orthogonal, det -1, NaN, Inf, non-square: all LogDomainError with angle() NaN (no angle was found).
TEST(SONLog, RefusesMatricesOutsideSONWithTypedError) {
  std::mt19937_64 rng(3);
  for (int n : {2, 3, 7}) {
    const Mat r = random_rotation(n, rng);
    Mat reflection = Mat::Identity(n, n);
    reflection(n - 1, n - 1) = -1;
    Mat householder = Mat::Identity(n, n) - 2.0 * Vec::Ones(n) * Vec::Ones(n).transpose() / n;
    Mat nan = r;
    nan(0, 0) = std::numeric_limits<double>::quiet_NaN();
    Mat inf = r;
    inf(n - 1, 0) = -std::numeric_limits<double>::infinity();
    const Mat cases[] = {2.0 * r, r + 1e-6 * Mat::Ones(n, n), r * reflection, householder, nan, inf,
                         Mat::Zero(n, n)};
    for (const Mat& m : cases) {
      try {
        (void)log(m);
        ADD_FAILURE() << "accepted, n = " << n << "\n" << m;
      } catch (const LogDomainError& e) {
        EXPECT_TRUE(std::isnan(e.angle())) << e.what();
      }
    }
  }
  EXPECT_THROW((void)log(Mat::Identity(3, 4)), LogDomainError);
  EXPECT_THROW((void)log(Mat::Identity(1, 1)), LogDomainError);
  // And LogDomainError is a std::domain_error (callers may catch the standard type).
  EXPECT_THROW((void)log(2.0 * Mat::Identity(3, 3)), std::domain_error);
}

// Orthogonality tolerance: 1e-8 on ||R^T R - I||_F by default; a rotation perturbed by 1e-12 is still accepted.
TEST(SONLog, AcceptsRotationsWithRoundingErrors) {
  std::mt19937_64 rng(5);
  const Mat r = random_rotation(7, rng);
  EXPECT_NO_THROW((void)log(r + 1e-12 * Mat::Ones(7, 7)));
}

// The domain check at pi: angles above pi - kLogDomainMargin are refused with angle() reporting them; below
// accepted. Checked with a rotation by pi - d in a random plane of SO(7) that also rotates by 1 in another plane.
TEST(SONLog, DomainMarginAtPi) {
  std::mt19937_64 rng(9);
  const Mat q = random_rotation(7, rng);
  auto rotation = [&](double theta) {
    Mat d = Mat::Identity(7, 7);
    d.block<2, 2>(0, 0) << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
    d.block<2, 2>(3, 3) << std::cos(1.0), -std::sin(1.0), std::sin(1.0), std::cos(1.0);
    return Mat(q * d * q.transpose());
  };
  for (double d : {1e-2, 1e-5, 1e-8, 5e-10}) {
    SpectralForm s;
    ASSERT_NO_THROW(s = spectral_form_of_rotation(rotation(kPi - d))) << "pi - " << d;
    EXPECT_NEAR(s.max_angle(), kPi - d, 1e-14 * kPi) << "pi - " << d;
  }
  for (double d : {5e-11, 1e-13, 0.0}) {
    try {
      (void)spectral_form_of_rotation(rotation(kPi - d));
      ADD_FAILURE() << "pi - " << d << " accepted";
    } catch (const LogDomainError& e) {
      EXPECT_GE(e.angle(), kPi - kLogDomainMargin) << e.what();
      EXPECT_LE(e.angle(), kPi) << e.what();
    }
  }
  // Two planes at exactly pi (det +1: eigenvalue -1 four times), e.g. -I in SO(4).
  EXPECT_THROW((void)log(-Mat::Identity(4, 4)), LogDomainError);
}

// blockdiag(rot theta_k, 1) and blockdiag(theta_k J, 0), J = [0 -1; 1 0]: a rotation with known angles and its log.
struct KnownAngles {
  Mat rotation, generator;
};
KnownAngles known_angles(int n, const std::vector<double>& angles) {
  KnownAngles k{Mat::Identity(n, n), Mat::Zero(n, n)};
  for (std::size_t p = 0; p < angles.size(); ++p) {
    const int i = 2 * static_cast<int>(p);
    const double t = angles[p];
    k.rotation.block<2, 2>(i, i) << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
    k.generator(i, i + 1) = -t;
    k.generator(i + 1, i) = t;
  }
  return k;
}

// log from one symmetric eigensolve with the planes beyond 3pi/4 logged on their own invariant block (son.cpp):
// against R = Q blockdiag(rot theta_k, 1) Q^T with known angles, log R = Q blockdiag(theta_k J, 0) Q^T, to
// 4e-14 relative, and the largest angle to 1e-14 absolute. One far plane, two (distinct and equal angles, a
// 4-dimensional eigenspace of S), a plane at pi - 1e-8, next to a small and a tiny angle; and det -1 with a
// far plane still refused.
TEST(SONLog, FarPlanesOnTheirInvariantBlock) {
  std::mt19937_64 rng(21);
  const std::vector<std::vector<double>> angle_sets = {
      {2.5}, {3.0, 2.8}, {3.1, 3.1}, {kPi - 1e-8, 0.3}, {2.9, 1e-9, 0.7}, {2.4, 2.3561944901923448}};
  for (int n : {2, 4, 7, 15})
    for (const auto& angles : angle_sets) {
      if (2 * static_cast<int>(angles.size()) > n) continue;
      const Mat q = random_rotation(n, rng);
      const KnownAngles k = known_angles(n, angles);
      const Mat &d = k.rotation, &l = k.generator;
      const Mat r = q * d * q.transpose(), expected = q * l * q.transpose();
      double angle = 0;
      const Mat got = log(r, &angle);
      // 4e-14: forming R = Q D Q^T already rounds by ~n eps, and log near angle pi amplifies it (without FMA,
      // as the sanitizer build compiles, n = 7 with two planes at 3.1 measured 1.31e-14).
      EXPECT_LE((got - expected).norm() / expected.norm(), 4e-14) << "n = " << n << ", angle " << angles[0];
      EXPECT_NEAR(angle, *std::max_element(angles.begin(), angles.end()), 1e-14) << "n = " << n;
      if (n > 2 * static_cast<int>(angles.size())) {  // a reflection in a fixed direction: det -1
        Mat flip = Mat::Identity(n, n);
        flip(n - 1, n - 1) = -1;
        EXPECT_THROW((void)log(Mat(q * d * flip * q.transpose())), LogDomainError) << "n = " << n;
      }
    }
}

// exp by Pade scaling and squaring with one orthogonality step (son.cpp) against exp(v) = Q blockdiag(rot theta_k, 1)
// Q^T for v = Q blockdiag(theta_k J, 0) Q^T with known angles, from 1e-9 to 1000 (up to 2^8 squarings):
// error <= 4 eps (1 + theta_max) sqrt(N) in Frobenius norm (the angles' own rounding, eps theta, is what any exp
// inherits), orthogonality ||X^T X - I||_max <= 1e-15, and a tiny v keeps its relative accuracy in expm1.
TEST(SONExp, PadeAgainstKnownAngles) {
  std::mt19937_64 rng(23);
  const std::vector<std::vector<double>> angle_sets = {{1e-9}, {0.3, 1e-9}, {3.0, 2.0}, {3.2, 0.5}, {10.0, 100.0}, {1000.0}};
  for (int n : {2, 3, 8, 15, 64})
    for (const auto& angles : angle_sets) {
      if (2 * static_cast<int>(angles.size()) > n) continue;
      const Mat q = random_rotation(n, rng);
      const KnownAngles k = known_angles(n, angles);
      const Mat &d = k.rotation, &l = k.generator;
      const Mat v = q * l * q.transpose(), expected = q * d * q.transpose();
      const Mat x = exp(0.5 * (v - v.transpose()));
      const double theta = *std::max_element(angles.begin(), angles.end());
      EXPECT_LE((x - expected).norm(), 4 * kEps * (1 + theta) * std::sqrt(double(n))) << "n = " << n << ", " << theta;
      EXPECT_LE((x.transpose() * x - Mat::Identity(n, n)).cwiseAbs().maxCoeff(), 1e-15) << "n = " << n << ", " << theta;
    }
  const Mat tiny = hat(Vec::LinSpaced(28, 1e-20, 3e-20), 8);
  EXPECT_LE((expm1(tiny) - tiny).norm() / tiny.norm(), 4 * kEps);
}

// max_angle (no domain check) and SpectralForm::max_angle agree, and the spectral form rebuilds R and v.
TEST(SONSpectralForm, RebuildsRotationAndSkew) {
  std::mt19937_64 rng(13);
  for (int n : {2, 3, 5, 8, 15}) {
    const Mat r = random_rotation(n, rng);
    const SpectralForm s = spectral_form_of_rotation(r);
    EXPECT_LE((s.q.transpose() * s.q - Mat::Identity(n, n)).norm(), 8 * n * kEps);
    EXPECT_LE((s.rotation() - r).norm(), 1e-14 * std::sqrt(double(n)));
    EXPECT_NEAR(s.max_angle(), max_angle(r), 1e-12);
    const SpectralForm sv = spectral_form_of_skew(s.skew());
    EXPECT_NEAR(sv.max_angle(), s.max_angle(), 1e-13);
    EXPECT_LE((sv.rotation() - r).norm(), 1e-14 * std::sqrt(double(n)));
  }
}

// The exact dexp against its defining series (2.10) summed to convergence (|v| = 0.7, 40 terms, ratio < 0.2
// per term), and dexpinv against (3.9) at p = 11: <= 8 N eps relative in the Frobenius norm.
TEST(SONDifferentials, ExactAgreesWithSeries) {
  std::mt19937_64 rng(17);
  std::normal_distribution<double> normal;
  for (int n : {2, 3, 4, 7, 15}) {
    const int q = algebra_dim(n);
    Vec a(q), b(q);
    for (int i = 0; i < q; ++i) a(i) = normal(rng), b(i) = normal(rng);
    const Mat v = hat(0.7 * a / a.norm(), n), u = hat(b / b.norm(), n);
    const SpectralForm s = spectral_form_of_skew(v);
    Mat series = Mat::Zero(n, n), term = u;
    double factorial = 1.0;
    for (int k = 0; k < 40; ++k) {  // (-1)^k / (k+1)! ad_v^k
      factorial *= (k + 1);
      series += ((k % 2 == 0) ? 1.0 : -1.0) / factorial * term;
      term = bracket(v, term);
    }
    EXPECT_LE((dexp(s, u) - series).norm() / series.norm(), 8 * n * kEps) << "dexp, n = " << n;
    const Mat exact = dexpinv(s, u);
    EXPECT_LE((exact - dexpinv_series(v, u, 11)).norm() / exact.norm(), 8 * n * kEps) << "dexpinv, n = " << n;
    // Both results are exactly skew.
    EXPECT_EQ((exact + exact.transpose()).cwiseAbs().maxCoeff(), 0.0);
  }
}

// dexpinv_series(p) is (3.9) truncated after ad^(2p): p = 0 is (3.11)'s u + [v,u]/2 exactly.
TEST(SONDifferentials, SeriesOrderZeroIsTruncation311) {
  std::mt19937_64 rng(19);
  const Mat v = log(random_rotation(5, rng)), u = log(random_rotation(5, rng));
  EXPECT_LE((dexpinv_series(v, u, 0) - (u + 0.5 * bracket(v, u))).norm(), 4 * kEps * u.norm() * (1 + v.norm()));
  EXPECT_THROW((void)dexpinv_series(v, u, -1), std::invalid_argument);
  EXPECT_THROW((void)dexpinv_series(v, u, 12), std::invalid_argument);
}

// ad_v has eigenvalue 0 on the centraliser: dexpinv_v(v) = v and dexp_v(v) = v exactly up to rounding.
TEST(SONDifferentials, FixVOnItsOwnDirection) {
  std::mt19937_64 rng(23);
  for (int n : {3, 6, 15}) {
    const Mat v = log(random_rotation(n, rng));
    const SpectralForm s = spectral_form_of_skew(v);
    EXPECT_LE((dexpinv(s, v) - v).norm() / v.norm(), 8 * n * kEps) << n;
    EXPECT_LE((dexp(s, v) - v).norm() / v.norm(), 8 * n * kEps) << n;
  }
}

}  // namespace
}  // namespace lienewton::son
