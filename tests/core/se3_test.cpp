// SE(3)'s closed forms against 50-digit references (se3_reference_values.hpp, written by se3_reference.py from
// the power series of exp and ad, not from the closed forms): exp, log, dexp (2.10) and dexpinv (3.9) for rotation
// angles from 1e-300 to 1e-3, across (0, pi), within 1e-12 of pi and beyond it, and the new coefficient slopes
// E, F, H on both sides of their series limits. Errors are in units of eps = 2^-52, block by block of the matrices
// (rotation and translation of exp; the diagonal and the Q block of the Jacobians) and, where a block is I plus a
// small part, for that part alone (its off-diagonal entries), so that rounding the 1s cannot hide a wrong small part.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <numbers>

#include "core/groups/log_domain.hpp"
#include "core/groups/se3_group.hpp"
#include "se3_reference_values.hpp"

namespace lienewton {
namespace {

using MatL = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
constexpr double kEps = std::numeric_limits<double>::epsilon();
// Every block's normwise relative error, and every small part's, in eps.
constexpr double kBlockTolerance = 4.0;
// The slopes E, F, H: relative error in eps, entry by entry.
constexpr double kSlopeTolerance = 4.0;

template <int R, int C>
MatL rows_of(const long double (&a)[R * C]) {
  MatL m(R, C);
  for (int i = 0; i < R; ++i)
    for (int j = 0; j < C; ++j) m(i, j) = a[i * C + j];
  return m;
}

// ||c - r||_F / ||r||_F in eps (0 when both vanish).
double relative_error(const Eigen::MatrixXd& c, const MatL& r) {
  const long double err = (c.cast<long double>() - r).norm(), size = r.norm();
  if (size == 0) return err == 0 ? 0.0 : std::numeric_limits<double>::infinity();
  return static_cast<double>(err / size) / kEps;
}

// The same for the off-diagonal entries of a square block (the part beside its identity).
double off_diagonal_error(const Eigen::MatrixXd& c, const MatL& r) {
  Eigen::MatrixXd co = c;
  MatL ro = r;
  co.diagonal().setZero();
  ro.diagonal().setZero();
  return relative_error(co, ro);
}

// Checks each error against the tolerance and prints the largest (the figures the documentation quotes).
class Worst {
 public:
  Worst(const char* what, double tolerance) : what_(what), tolerance_(tolerance) {}
  ~Worst() { std::printf("%s: largest error %.2f eps (tolerance %.0f)\n", what_, worst_, tolerance_); }
  void operator()(double error, const std::string& where) {
    EXPECT_LE(error, tolerance_) << what_ << " at " << where;
    worst_ = std::max(worst_, error);
  }

 private:
  const char* what_;
  double tolerance_, worst_ = 0;
};

se3::Vec6 xi_of(const test::Se3Case& c) { return Eigen::Map<const se3::Vec6>(c.xi); }
std::string theta_of(const test::Se3Case& c) {
  char s[32];
  std::snprintf(s, sizeof s, "theta = %.17g", xi_of(c).head<3>().norm());
  return s;
}

// exp: the rotation block R, its part beside I (through expm1, which keeps it unrounded), and the translation V r.
TEST(Se3ClosedForms, ExpMatchesTheReference) {
  Worst check("exp", kBlockTolerance);
  for (const auto& c : test::kSe3Cases) {
    const MatL ref_m1 = rows_of<4, 4>(c.expm1), ref = ref_m1 + MatL::Identity(4, 4);
    const Eigen::Matrix4d t = se3::exp(xi_of(c)), m1 = se3::expm1(xi_of(c));
    check(relative_error(t.topLeftCorner<3, 3>(), ref.topLeftCorner(3, 3)), "R, " + theta_of(c));
    check(relative_error(m1.topLeftCorner<3, 3>(), ref_m1.topLeftCorner(3, 3)), "R - I, " + theta_of(c));
    check(relative_error(t.topRightCorner<3, 1>(), ref.topRightCorner(3, 1)), "V r, " + theta_of(c));
    EXPECT_EQ(t.row(3), Eigen::RowVector4d(0, 0, 0, 1));
  }
}

// log(round(exp xi)) = xi: the rotation vector and the translation part, each relative to its own size. The
// input's rounding is part of the error; log is well conditioned at every case (theta is not within rounding of pi,
// where the branch is decided by the rounding of sin theta ~ 1e-16).
TEST(Se3ClosedForms, LogMatchesTheReference) {
  Worst check("log", kBlockTolerance);
  for (const auto& c : test::kSe3Cases) {
    if (!c.log) continue;
    const MatL ref = rows_of<4, 4>(c.expm1) + MatL::Identity(4, 4);
    const Eigen::Matrix4d t = ref.cast<double>();
    const se3::Vec6 xi = se3::checked_log(t), exact = xi_of(c);
    const MatL w = exact.head<3>().cast<long double>(), r = exact.tail<3>().cast<long double>();
    check(relative_error(xi.head<3>(), w), "w, " + theta_of(c));
    check(relative_error(xi.tail<3>(), r), "r, " + theta_of(c));
  }
}

// dexp's and dexpinv's matrices: the upper right block is exactly 0, the diagonal blocks equal, each and its part
// beside I within tolerance, and the Q block within tolerance; their actions dexp(xi, u), dexpinv(xi, u) too.
TEST(Se3ClosedForms, JacobiansMatchTheReference) {
  const se3::Vec6 u = (se3::Vec6() << 0.4, -0.1, 0.9, -0.6, 0.2, 0.3).finished();
  Worst check("dexp and dexpinv", kBlockTolerance);
  for (const auto& c : test::kSe3Cases) {
    const se3::Vec6 xi = xi_of(c);
    struct Pair {
      const char* name;
      se3::Mat6 computed;
      MatL ref;
      se3::Vec6 action;
    };
    for (const Pair& p : {Pair{"dexp", se3::dexp_matrix(xi), rows_of<6, 6>(c.dexp), se3::dexp(xi, u)},
                          Pair{"dexpinv", se3::dexpinv_matrix(xi), rows_of<6, 6>(c.dexpinv), se3::dexpinv(xi, u)}}) {
      const Eigen::Matrix3d j = p.computed.topLeftCorner(3, 3), q = p.computed.bottomLeftCorner(3, 3);
      EXPECT_TRUE(p.computed.topRightCorner(3, 3).isZero(0.0)) << p.name;
      EXPECT_EQ(j, Eigen::Matrix3d(p.computed.bottomRightCorner(3, 3))) << p.name;
      const std::string at = std::string(p.name) + ", " + theta_of(c);
      check(relative_error(j, p.ref.topLeftCorner(3, 3)), "diagonal block of " + at);
      check(off_diagonal_error(j, p.ref.topLeftCorner(3, 3)), "diagonal block's part beside I of " + at);
      check(relative_error(q, p.ref.bottomLeftCorner(3, 3)), "Q block of " + at);
      const MatL action = p.ref * u.cast<long double>();
      check(relative_error(p.action.head<3>(), action.topRows(3)), "action (rotation) of " + at);
      check(relative_error(p.action.tail<3>(), action.bottomRows(3)), "action (translation) of " + at);
    }
  }
}

// E = B'/t, F = C'/t, H = D'/t, entry by entry, on both sides of their series limits (2.75, 3.6).
TEST(Se3ClosedForms, CoefficientSlopesMatchTheReference) {
  Worst check("slopes E, F, H", kSlopeTolerance);
  for (const auto& c : test::kSlopeCases) {
    const auto ulps = [](double value, long double ref) {
      return static_cast<double>(std::fabs((static_cast<long double>(value) - ref) / ref)) / kEps;
    };
    const std::string at = " at t = " + std::to_string(c.t);
    check(ulps(se3::one_minus_cos_over_t2_slope(c.t), c.e), "E" + at);
    check(ulps(se3::t_minus_sin_over_t3_slope(c.t), c.f), "F" + at);
    check(ulps(se3::dexpinv_coefficient_slope(c.t), c.h), "H" + at);
  }
}

// log refuses what is not in SE(3), in the group's words; the group refuses a request's matrix likewise.
TEST(Se3ClosedForms, LogAndMembershipRefuseNonElements) {
  const SE3Group g;
  Eigen::Matrix4d t = g.exp((se3::Vec6() << 0.1, 0.2, 0.3, 1, 2, 3).finished());
  EXPECT_EQ(g.not_an_element(t, "z"), "");
  Eigen::Matrix4d bad_row = t;
  bad_row(3, 0) = 1e-3;
  EXPECT_THROW(g.log(bad_row), LogDomainError);
  EXPECT_NE(g.not_an_element(bad_row, "z").find("last row of z"), std::string::npos);
  Eigen::Matrix4d sheared = t;
  sheared(0, 1) += 1e-3;
  EXPECT_THROW(g.log(sheared), LogDomainError);
  EXPECT_NE(g.not_an_element(sheared, "z").find("orthogonal"), std::string::npos);
  Eigen::Matrix4d reflected = t;
  reflected.topLeftCorner<3, 3>() *= -1.0;
  EXPECT_THROW(g.log(reflected), LogDomainError);
  EXPECT_NE(g.not_an_element(reflected, "z").find("det R = +1"), std::string::npos);
  Eigen::Matrix4d infinite = t;
  infinite(1, 3) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(g.log(infinite), LogDomainError);
}

}  // namespace
}  // namespace lienewton
