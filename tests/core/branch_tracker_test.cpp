// The tests' own judges, checked against closed forms before they judge the solver: the branch tracker of
// branch_tracker.hpp (a constant field's root is an exponential for every h; a field on SO(2) whose branch folds
// at a known h*) and the matrix-ODE reference of matrix_ode_reference.hpp (its error by step doubling).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "branch_tracker.hpp"
#include "core/problems.hpp"
#include "matrix_ode_reference.hpp"

namespace lienewton::test {
namespace {

// The Q factor of a uniformly random matrix, as in the paper's experiment (an element of O(N)).
Eigen::MatrixXd random_orthogonal(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = uniform(rng);
  return Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ() * Eigen::MatrixXd::Identity(n, n);
}

Eigen::Matrix3d hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0.0, -w(2), w(1), w(2), 0.0, -w(0), -w(1), w(0), 0.0;
  return m;
}

// Rodrigues' formula, written here so the check does not go through the tracker's exponential.
Eigen::Matrix3d rodrigues(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  const Eigen::Matrix3d k = hat(w / angle);
  return Eigen::Matrix3d::Identity() + std::sin(angle) * k + (1.0 - std::cos(angle)) * k * k;
}

double rotation_angle(const Eigen::MatrixXd& v) { return Eigen::JacobiSVD<Eigen::MatrixXd>(v).singularValues()(0); }

TEST(BranchTracker, ConstantFieldOnSO3GivesTheExponentialForEveryH) {
  const Eigen::Vector3d w(0.3, -0.5, 0.8);
  const Eigen::MatrixXd a = hat(w), z = random_orthogonal(3, 1);
  const MatrixField g = [&a](const Eigen::MatrixXd&) { return a; };
  for (const double h : {0.1, 1.0, 3.0, 40.0}) {  // 40 |w| is far past log's cut at pi
    SCOPED_TRACE(h);
    const TrackedBranch r = track_branch(g, z, h);
    ASSERT_TRUE(r.reached);
    EXPECT_EQ(r.h_stop, h);
    EXPECT_LE((r.y - z * rodrigues(h * w)).norm(), 1e-10);
    EXPECT_LE((r.v - h * a).norm(), 1e-12 * (1.0 + h));
    EXPECT_GT(r.sigma_min, 0.99);  // D_v F = I
  }
}

// On SO(2) with y = z rot(theta) and g(y) = gamma(theta) K (K the generator), the implicit Euler equation is the
// scalar theta = tau gamma(theta). With gamma(t) = 1 + 5 (1 - cos t) the branch from theta = 0 is
// tau(theta) = theta / gamma(theta), increasing up to its maximum tau* where gamma(t) = t gamma'(t): a fold.
constexpr double kTheta0 = 0.7;
double fold_gamma(double t) { return 1.0 + 5.0 * (1.0 - std::cos(t)); }
double fold_gamma_slope(double t) { return 5.0 * std::sin(t); }

Eigen::MatrixXd rotation2(double angle) {
  Eigen::MatrixXd r(2, 2);
  r << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return r;
}

double angle_of(const Eigen::MatrixXd& r) { return std::atan2(r(1, 0), r(0, 0)); }

MatrixField folding_field() {
  return [](const Eigen::MatrixXd& y) {
    Eigen::MatrixXd k(2, 2);
    k << 0.0, -1.0, 1.0, 0.0;
    return Eigen::MatrixXd(fold_gamma(angle_of(y) - kTheta0) * k);
  };
}

// Bisection of f on [lo, hi] where f(lo) > 0 > f(hi).
template <class F>
double bisect(F f, double lo, double hi) {
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (f(mid) > 0.0 ? lo : hi) = mid;
  }
  return lo;
}

double fold_theta() { return bisect([](double t) { return fold_gamma(t) - t * fold_gamma_slope(t); }, 0.5, 1.0); }
double fold_tau() { return fold_theta() / fold_gamma(fold_theta()); }

TEST(BranchTracker, StopsAtTheFoldOfAnSO2Branch) {
  const double tau_star = fold_tau();
  const TrackedBranch r = track_branch(folding_field(), rotation2(kTheta0), 2.0 * tau_star);
  EXPECT_FALSE(r.reached);
  EXPECT_LE(r.h_stop, tau_star * (1.0 + 1e-12));
  EXPECT_GE(r.h_stop, 0.99 * tau_star);
  EXPECT_LE(r.sigma_min, 1e-3);
  EXPECT_NEAR(angle_of(r.y) - kTheta0, fold_theta(), 1e-2);
}

TEST(BranchTracker, ReachesHBelowTheFoldOnTheContinuedRoot) {
  const double tau_star = fold_tau(), theta_star = fold_theta();
  for (const double fraction : {0.2, 0.9}) {
    const double h = fraction * tau_star;
    SCOPED_TRACE(h);
    const TrackedBranch r = track_branch(folding_field(), rotation2(kTheta0), h);
    ASSERT_TRUE(r.reached);
    // The continued root is the one below theta*, where tau(theta) increases and the root is unique.
    const double expected = bisect([h](double t) { return h * fold_gamma(t) - t; }, 0.0, theta_star);
    const double theta = angle_of(r.y) - kTheta0;
    EXPECT_NEAR(theta, expected, 1e-10);
    EXPECT_LE(std::abs(theta - h * fold_gamma(theta)), 1e-12);
    EXPECT_GT(r.sigma_min, 1e-3);
  }
}

struct PaperCase {
  bool sine;
  int n;
  double h;
};

MatrixField paper_field(bool sine) {
  if (sine) return [](const Eigen::MatrixXd& y) { return PaperSine{}.g(y); };
  return [](const Eigen::MatrixXd& y) { return PaperLinear{}.g(y); };
}

TEST(BranchTracker, PaperProblemsReachHWithARoundingLevelResidual) {
  const std::vector<PaperCase> cases = {{true, 3, 1.0 / 16},  {true, 3, 1.0},  {true, 3, 16.0}, {true, 5, 1.0 / 16},
                                        {true, 5, 0.5},       {true, 5, 2.0},  {false, 3, 0.5}, {false, 3, 16.0},
                                        {false, 5, 1.0 / 16}, {false, 5, 2.0}};
  for (const PaperCase& c : cases) {
    for (const std::uint64_t seed : {1u, 2u}) {
      SCOPED_TRACE(testing::Message() << (c.sine ? "paper-sine" : "paper-linear") << " n " << c.n << " h " << c.h
                                      << " seed " << seed);
      const MatrixField g = paper_field(c.sine);
      const Eigen::MatrixXd z = random_orthogonal(c.n, seed);
      const TrackedBranch r = track_branch(g, z, c.h);
      ASSERT_TRUE(r.reached);
      EXPECT_GT(r.steps, 0);
      EXPECT_LE((r.y.transpose() * r.y - Eigen::MatrixXd::Identity(c.n, c.n)).norm(), 1e-13);
      EXPECT_LE((r.v - c.h * g(r.y)).norm() / std::sqrt(2.0), 1e-12);
      ASSERT_LT(rotation_angle(r.v), 3.0);  // so the principal logarithm recovers V
      EXPECT_LE(implicit_euler_residual(g, z, c.h, r.y), 1e-12);
      if (c.n == 3) {
        const MatrixField3ld g_long = [s = c.sine](const Matrix3ld& y) -> Matrix3ld {
          return s ? PaperSine{}.g(y) : PaperLinear{}.g(y);
        };
        EXPECT_LE(implicit_euler_residual_so3_long(g_long, z, c.h, r.y), 1e-12);
      }
    }
  }
}

TEST(BranchTracker, LongDoubleRodriguesLogarithmInvertsTheExponentialUpToPi) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.48, -0.6, 0.64).normalized();
  for (const double angle : {1e-9, 0.3, 2.0, 2.5, std::numbers::pi - 1e-6, std::numbers::pi - 1e-12}) {
    SCOPED_TRACE(angle);
    const Eigen::Matrix<long double, 3, 1> w = (angle * axis).cast<long double>();
    const long double t = w.norm();
    Matrix3ld k;
    k << 0.0L, -w(2) / t, w(1) / t, w(2) / t, 0.0L, -w(0) / t, -w(1) / t, w(0) / t, 0.0L;
    const Matrix3ld r = Matrix3ld::Identity() + std::sin(t) * k + (1.0L - std::cos(t)) * k * k;
    EXPECT_LE(static_cast<double>((so3_log_long(r) - w).norm()), 1e-14);
  }
}

TEST(BranchTracker, ResidualsInDoubleAndLongDoubleAgreeOffTheRoot) {
  const Eigen::MatrixXd z = random_orthogonal(3, 3);
  const Eigen::MatrixXd y = z * rodrigues(Eigen::Vector3d(0.2, 0.1, -0.4));
  const MatrixField g = paper_field(true);
  const MatrixField3ld g_long = [](const Matrix3ld& m) -> Matrix3ld { return PaperSine{}.g(m); };
  const double in_double = implicit_euler_residual(g, z, 0.5, y);
  EXPECT_GT(in_double, 0.1);
  EXPECT_NEAR(static_cast<double>(implicit_euler_residual_so3_long(g_long, z, 0.5, y)), in_double,
              1e-13 * in_double);
}

// RK4's error is c dt^4, so with half as many steps the difference is 15 times the default's error (Richardson).
TEST(BranchTracker, MatrixOdeReferenceIsAccurateToTenToTheMinusTwelve) {
  const Eigen::MatrixXd y0 = random_orthogonal(5, 1);
  const MatrixField g = paper_field(true);
  const Eigen::MatrixXd y = matrix_ode_reference(g, y0, 1.0);
  const Eigen::MatrixXd coarser = matrix_ode_reference(g, y0, 1.0, kMatrixOdeStepsPerUnit / 2);
  EXPECT_LE((y - coarser).norm() / 15.0, 1e-12);
  EXPECT_LE((y.transpose() * y - Eigen::MatrixXd::Identity(5, 5)).norm(), 1e-12);
}

TEST(BranchTracker, MatrixOdeReferenceOfAConstantFieldIsTheExponential) {
  const Eigen::Vector3d w(-0.7, 0.2, 0.9);
  const Eigen::MatrixXd a = hat(w), y0 = random_orthogonal(3, 2);
  const Eigen::MatrixXd y = matrix_ode_reference([&a](const Eigen::MatrixXd&) { return a; }, y0, 2.0);
  EXPECT_LE((y - y0 * rodrigues(2.0 * w)).norm(), 1e-12);
}

}  // namespace
}  // namespace lienewton::test
