// The observed-order fit: exact on power laws, robust to points it must skip.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/order_fit.hpp"

namespace lienewton {
namespace {

TEST(OrderFit, RecoversTheExponentOfAPowerLaw) {
  for (double p : {0.5, 1.0, 2.0, 4.0}) {
    std::vector<double> h, error;
    for (int k = 1; k <= 6; ++k) {
      h.push_back(std::ldexp(1.0, -k));
      error.push_back(3.7 * std::pow(h.back(), p));
    }
    EXPECT_NEAR(fitted_order(h, error).value(), p, 1e-12) << p;
  }
}

TEST(OrderFit, IsTheLeastSquaresSlope) {
  // log error = {0, 1, 3} at log h = {0, 1, 2} (natural logs): slope 3/2 by the normal equations.
  const std::vector<double> h = {1.0, std::exp(1.0), std::exp(2.0)};
  const std::vector<double> error = {1.0, std::exp(1.0), std::exp(3.0)};
  EXPECT_NEAR(fitted_order(h, error).value(), 1.5, 1e-12);
}

TEST(OrderFit, SkipsPointsWithoutALogarithm) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> h = {0.5, 0.25, 0.125, 0.0625, -1.0};
  const std::vector<double> error = {0.25, 0.0625, 0.0, nan, 1.0};  // only the first two count: slope 2
  EXPECT_NEAR(fitted_order(h, error).value(), 2.0, 1e-12);
}

TEST(OrderFit, NothingWithoutTwoDistinctSteps) {
  EXPECT_FALSE(fitted_order({}, {}));
  EXPECT_FALSE(fitted_order({0.5}, {0.1}));
  EXPECT_FALSE(fitted_order({0.5, 0.5}, {0.1, 0.2}));
  EXPECT_FALSE(fitted_order({0.5, 0.25}, {0.0, 0.1}));
}

// The asymptotic range: error = h^2 for the small h, a pre-asymptotic regime above (a distant root's error, or a
// wrong one): the range is the small-h points whose local slopes agree, and the order is theirs.
TEST(OrderFit, AsymptoticRangeIsTheSmallStepsThatAgree) {
  const std::vector<double> h = {0.25, 0.125, 0.0625, 0.03125, 0.015625, 0.0078125};
  std::vector<double> error;
  for (double x : h) error.push_back(x * x);
  error[0] = 2.0;  // h = 1/4: pre-asymptotic
  error[1] = 0.5;
  const AsymptoticRange r = asymptotic_range(h, error);
  EXPECT_EQ(r.indices, (std::vector<std::size_t>{5, 4, 3, 2}));
  EXPECT_NEAR(r.order.value(), 2.0, 1e-12);
  EXPECT_FALSE(r.contains(0));
  EXPECT_TRUE(r.contains(2));
  // Fewer than three points: all of them; none: no order.
  EXPECT_EQ(asymptotic_range({0.5, 0.25}, {1.0, 0.1}).indices.size(), 2u);
  EXPECT_FALSE(asymptotic_range({}, {}).order);
}

}  // namespace
}  // namespace lienewton
