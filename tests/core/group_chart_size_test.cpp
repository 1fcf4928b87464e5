// What Version 1 watches for divergence (GroupChart::size): ||z^-1 y||_F, true of every group. It is constant on
// a compact group (sqrt(3) on SO(3), whatever y), and grows with the translation on SE(3) and R^k, where an
// iterate can run away: the globalised iteration then stops as diverged, naming it.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "core/groups/mechanics_groups.hpp"
#include "core/groups/se3_group.hpp"
#include "core/groups/so3_group.hpp"
#include "core/solvers/charts.hpp"
#include "core/solvers/run_method.hpp"
#include "rn_group.hpp"

namespace lienewton {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

template <class G>
Equation<G> equation_at(const G& g, const typename G::Element& z) {
  return Equation<G>::general(g, z, [&g](const typename G::Element&) { return zero_vector(g); });
}

TEST(GroupChartSize, ConstantOnSO3) {
  const SO3Group g;
  const auto eq = equation_at(g, g.random(1));
  const GroupChart<SO3Group> chart(eq, Differential::finite_difference);
  for (std::uint64_t seed = 2; seed < 12; ++seed)
    EXPECT_NEAR(chart.size(chart.at(g.random(seed))), std::sqrt(3.0), 8 * kEps);
}

// On SE(3) x R^6 a translation t of either factor adds t^2 to ||z^-1 y||_F^2 (identity blocks: 11).
TEST(GroupChartSize, GrowsWithTheTranslationOnSE3xR6) {
  const SE3xR6Group g;
  const auto z = g.random(3);
  const auto eq = equation_at(g, z);
  const GroupChart<SE3xR6Group> chart(eq, Differential::finite_difference);
  EXPECT_NEAR(chart.size(chart.at(z)), std::sqrt(11.0), 64 * kEps);
  for (double t : {1.0, 1e4, 1e9}) {
    SE3xR6Group::Vector v = SE3xR6Group::Vector::Zero();
    v(3) = t;   // SE(3)'s translation
    v(11) = t;  // R^6's
    const double size = chart.size(chart.at(g.times_exp(z, v)));
    EXPECT_NEAR(size, std::sqrt(11.0 + 2 * t * t), 64 * kEps * std::sqrt(11.0 + 2 * t * t)) << t;
    EXPECT_EQ(size > kDivergenceBound, t > kDivergenceBound) << t;
  }
}

// f(y) = 1 / y on R has no root: Newton's step y -> 2 y, which the line search takes whole (the merit falls to a
// quarter). The run stops as diverged when an iterate has |y - z| > 1e8 (y = 2^27), naming ||z^-1 y||_F, and
// returns the last iterate it recorded, y = 2^26 (the step check sees the runaway one iterate later, when the
// step 2^27 exceeds 1e8).
TEST(GroupChartSize, RunawayOnRIsDiverged) {
  const RnGroup g(1);
  const auto eq = Equation<RnGroup>::general(
      g, Eigen::VectorXd::Constant(1, 1.0), [](const Eigen::VectorXd& y) { return Eigen::VectorXd(y.cwiseInverse()); },
      [](const Eigen::VectorXd& y, const Eigen::VectorXd& u) {
        return Eigen::VectorXd(-u.cwiseQuotient(y.cwiseAbs2()));
      });
  SolverOptions opt;
  opt.differential = Differential::exact;
  opt.globalization = Globalization::line_search;
  const SolveResult r = newton_group(eq, opt);
  ASSERT_EQ(r.status, Status::diverged) << r.reason;
  EXPECT_EQ(Eigen::VectorXd(r.y)(0), std::ldexp(1.0, 26)) << r.reason;
  EXPECT_NE(r.reason.find("||z^-1 y||_F"), std::string::npos) << r.reason;
}

}  // namespace
}  // namespace lienewton
