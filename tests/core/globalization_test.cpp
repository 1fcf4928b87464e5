// The globalised Newton iteration (line search, trust region) on both versions.
// Truth: the paper's rate r read off the trace (quadratic near a root), an oracle residual recomputed from the
// returned y with Eigen's matrix logarithm (residual_oracle.hpp), and a constructed f whose merit has a
// stationary point with no root, located in closed form.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "core/groups/so3.hpp"
#include "core/groups/so3_group.hpp"
#include "core/solve.hpp"
#include "core/solvers/run_method.hpp"
#include "core/start_point.hpp"
#include "paper_request.hpp"
#include "residual_oracle.hpp"
#include "rn_group.hpp"
#include "gtest_printers.hpp"

namespace lienewton {
namespace {

struct Case {
  Method method;
  Globalization globalization;
  Differential differential;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << to_string(c.method) << " " << to_string(c.globalization) << " " << to_string(c.differential);
}

class GlobalizedNewton : public ::testing::TestWithParam<Case> {};

// Far from the root the first steps are damped (alpha < 1, or not Newton's step); the last ones are full Newton
// steps and converge quadratically: once ||f_k|| <= 1e-2, ||f_{k+1}|| <= 0.5 ||f_k||^2 (or is below tol), a
// bound no linearly converging sequence keeps.
TEST_P(GlobalizedNewton, DampsFarAwayAndConvergesQuadraticallyNearTheRoot) {
  const Case c = GetParam();
  const SolveResult r = solve(paper_request(ProblemKind::paper_linear, 3, 64, c.method, c.differential, c.globalization));
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  bool damped = false;
  for (const TraceRecord& t : r.trace)
    damped |= t.step_kind != "" && (t.step_kind != "newton" || t.step_length.value_or(1.0) < 1.0);
  EXPECT_TRUE(damped) << "the test case must exercise the globalisation";
  ASSERT_GE(r.iterations, 3);
  for (int k = r.iterations - 2; k <= r.iterations; ++k) {
    EXPECT_EQ(r.trace[k].step_kind, "newton") << "record " << k;
    if (c.globalization == Globalization::line_search) { EXPECT_EQ(r.trace[k].step_length, 1.0) << "record " << k; }
  }
  int quadratic_steps = 0;
  for (int k = 1; k <= r.iterations; ++k) {
    const double before = r.trace[k - 1].residual, after = r.trace[k].residual;
    if (before > 1e-2) continue;
    EXPECT_LE(after, std::max(0.5 * before * before, 1e-13)) << "record " << k;
    quadratic_steps += after > 1e-13;
  }
  EXPECT_GE(quadratic_steps, 1);
  const Oracle o = oracle(ProblemKind::paper_linear, 64, start_point(3, 1), r.y);
  EXPECT_LE(o.residual, 1.05e-13) << "converged means ||f(y)|| <= tol for the returned y";
  EXPECT_NEAR(o.residual, r.residual, 1e-14);
}

INSTANTIATE_TEST_SUITE_P(
    BothVersionsBothStrategies, GlobalizedNewton,
    ::testing::Values(Case{Method::newton_group, Globalization::line_search, Differential::exact},
                      Case{Method::newton_group, Globalization::trust_region, Differential::exact},
                      Case{Method::newton_group, Globalization::line_search, Differential::finite_difference},
                      Case{Method::newton_algebra, Globalization::line_search, Differential::exact},
                      Case{Method::newton_algebra, Globalization::trust_region, Differential::finite_difference}));

TEST(GlobalizedNewton, NoneIsThePaperIteration) {
  for (Method m : {Method::newton_group, Method::newton_algebra}) {
    const SolveResult r = solve(paper_request(ProblemKind::paper_linear, 5, 8, m, Differential::exact, Globalization::none));
    for (const TraceRecord& t : r.trace) {
      EXPECT_EQ(t.step_kind, "");
      EXPECT_FALSE(t.step_length.has_value());
      EXPECT_FALSE(t.trust_radius.has_value());
    }
  }
}

// Every converged result of the globalised methods is true of the y it returns, over a spread of (N, h). Which
// cells at large h converge is rounding's to decide (22 to 25 of the 48 in three builds); the well-conditioned
// ones, h = 1/4 at N <= 4 (2 to 4 iterations), converge under any, so the check is never vacuous.
TEST(GlobalizedNewton, ConvergedMeansTheOracleResidualIsBelowTol) {
  for (Method m : {Method::newton_group, Method::newton_algebra})
    for (Globalization g : {Globalization::line_search, Globalization::trust_region})
      for (int n : {2, 4, 6})
        for (double h : {0.25, 4.0, 64.0, 1024.0}) {
          const SolveResult r = solve(paper_request(ProblemKind::paper_sine, n, h, m, Differential::exact, g));
          const Oracle o = oracle(ProblemKind::paper_sine, h, start_point(n, 1), r.y);
          EXPECT_NEAR(o.residual, r.residual, 1e-9 * (1.0 + o.residual)) << n << " " << h << " " << r.reason;
          if (h == 0.25 && n <= 4) { EXPECT_EQ(r.status, Status::converged) << n << " " << h << " " << r.reason; }
          if (r.status != Status::converged) continue;
          // The oracle's log rounds differently: agreement to tol plus the result's own rounding floor.
          EXPECT_LE(o.residual, 1e-13 + r.floor) << n << " " << h << " " << r.reason;
        }
}

// f(y) = vee((y - y^T) / 2) + a on SO(3) is sin(theta) n + a for y = exp(theta n^): with ||a|| > 1 it has no
// root, and 1/2 ||f||^2 is least, = 1/2 (||a|| - 1)^2, at theta = pi/2, n = -a / ||a|| (a non-degenerate
// minimum: second derivative ||a|| - 1 along theta). df_y(u) = vee((y u^ + u^ y^T) / 2).
class LocalMinimum : public ::testing::TestWithParam<std::pair<Globalization, Differential>> {};

TEST_P(LocalMinimum, StationaryPointWithoutRootIsReportedWithItsNumbers) {
  const auto [globalization, differential] = GetParam();
  const Eigen::Vector3d a(0.9, -0.6, 0.8);
  const SO3Group so3g;
  auto f = [a](const Eigen::Matrix3d& y) -> Eigen::Vector3d {
    const Eigen::Matrix3d s = 0.5 * (y - y.transpose());
    return Eigen::Vector3d(s(2, 1), s(0, 2), s(1, 0)) + a;
  };
  auto df = [](const Eigen::Matrix3d& y, const Eigen::Vector3d& u) -> Eigen::Vector3d {
    const Eigen::Matrix3d s = 0.5 * (y * so3::hat(u) + so3::hat(u) * y.transpose());
    return Eigen::Vector3d(s(2, 1), s(0, 2), s(1, 0));
  };
  const auto eq = Equation<SO3Group>::general(so3g, Eigen::Matrix3d::Identity(), f, df);
  SolverOptions opt;
  opt.differential = differential;
  opt.globalization = globalization;
  const SolveResult r = newton_group(eq, opt);
  ASSERT_EQ(r.status, Status::local_minimum) << r.reason;
  EXPECT_NE(r.reason.find("||D^T f||"), std::string::npos) << r.reason;
  const double least = a.norm() - 1.0;
  const Eigen::Matrix3d y = r.y;
  EXPECT_NEAR(f(y).norm(), least, 1e-9);
  EXPECT_NEAR(r.residual, f(y).norm(), 1e-15);
  const Eigen::Matrix3d at_min = so3::exp(Eigen::Vector3d(-std::numbers::pi / 2 * a.normalized()));
  EXPECT_LE((y - at_min).norm(), 1e-5);
  EXPECT_NE(r.reason.find(format_number(least).substr(0, 4)), std::string::npos) << r.reason;
}

// f(y) = log(y) - b on SO(3) with ||b|| = 4 > pi has no root: along b's axis ||f|| = ||b|| - theta falls towards
// the cut at theta = pi, where log jumps to the other side and ||f|| to ||b|| + pi. 1/2 ||f||^2 has no stationary
// point there (||D^T f|| stays near ||b|| - pi), yet no step decreases it past the cut: the trust region shrinks
// its radius to nothing at the cut and ends as no_descent (or left_log_domain, once within the log's margin of pi),
// not as stagnated (which it reported before no_descent existed) or local_minimum, with the numbers true of the
// returned y. (The line search creeps towards the cut with ever shorter steps until max_iterations.) With the
// watchdog (parameter true) the full steps run past the cut; the episode goes back to its reference, and when
// the trust region finds no step from there, the solve ends at that reference, so the same numbers hold.
class NoDescent : public ::testing::TestWithParam<bool> {};

TEST_P(NoDescent, CutOfLogEndsTheSearchAsWhatItIs) {
  const Eigen::Vector3d b = 4.0 * Eigen::Vector3d(0.6, 0.0, 0.8);
  const SO3Group so3g;
  auto f = [b](const Eigen::Matrix3d& y) -> Eigen::Vector3d { return so3::log(y) - b; };
  auto df = [](const Eigen::Matrix3d& y, const Eigen::Vector3d& u) -> Eigen::Vector3d {
    return so3::dexpinv(so3::log(y), u);  // d/dt log(y exp(t u)) at t = 0
  };
  const auto eq = Equation<SO3Group>::general(so3g, Eigen::Matrix3d::Identity(), f, df);
  SolverOptions opt;
  opt.globalization = Globalization::trust_region;
  opt.watchdog = GetParam();
  const SolveResult r = newton_group(eq, opt);
  if (opt.watchdog) {
    int relaxed = 0;
    for (const TraceRecord& t : r.trace) relaxed += t.step_kind == "watchdog";
    EXPECT_GE(relaxed, 1) << "the case must exercise the watchdog";
  }
  ASSERT_TRUE(r.status == Status::no_descent || r.status == Status::left_log_domain) << r.reason;
  const Eigen::Matrix3d y = r.y;
  EXPECT_NEAR(r.residual, f(y).norm(), 1e-12);
  EXPECT_NEAR(r.residual, b.norm() - std::numbers::pi, 1e-6);  // at the cut, from inside
  EXPECT_GE(r.residual, 1e6 * r.floor);
  EXPECT_NEAR(so3::angle(y), std::numbers::pi, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(TrustRegionWithAndWithoutWatchdog, NoDescent, ::testing::Bool());

INSTANTIATE_TEST_SUITE_P(
    StrategiesAndDifferentials, LocalMinimum,
    ::testing::Values(std::pair{Globalization::line_search, Differential::exact},
                      std::pair{Globalization::line_search, Differential::finite_difference},
                      std::pair{Globalization::trust_region, Differential::exact},
                      std::pair{Globalization::trust_region, Differential::finite_difference}));

}  // namespace
}  // namespace lienewton

namespace lienewton {
namespace {

// The watchdog (solvers/watchdog.hpp) on the classical case R^1 (Version 1 is Newton's method there, Corollary
// 3.3): f(x) = x^3 - 2x + 2 has one root, x* = -1.7693, and 1/2 f^2 a local minimum without root at
// x = sqrt(2/3), f = 0.911, between it and x_0 = 0.9. Newton's full steps from x_0 (f' = 0.43) jump over the hump
// to -1.26 and -2.17, where f is 2.5 and -3.9, then to -1.85 below the start's Armijo bound, and on to x*
// quadratically. The monotone line search refuses those steps.
RnGroup::Element cubic(const RnGroup::Element& x) { return RnGroup::Element(x.array().cube() - 2.0 * x.array() + 2.0); }
RnGroup::Element cubic_df(const RnGroup::Element& x, const RnGroup::Element& u) {
  return RnGroup::Element((3.0 * x.array().square() - 2.0) * u.array());
}

// Why: the watchdog exists to take the full steps that raise 1/2 ||f||^2 on the way to a root, which a monotone
// search refuses. Every step of this case is well-conditioned (f' is far from 0 along it), so no rounding turns it.
TEST(Watchdog, TakesTheFullStepsAMonotoneSearchRefuses) {
  const RnGroup r1(1);
  const auto eq = Equation<RnGroup>::general(r1, RnGroup::Element::Constant(1, 0.9), cubic, cubic_df);
  SolverOptions opt;
  opt.globalization = Globalization::line_search;
  opt.watchdog = true;
  const SolveResult r = newton_group(eq, opt);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  EXPECT_LE(std::abs(cubic(r.y)(0)), opt.tol);
  EXPECT_NEAR(r.y(0), -1.769292354238631, 1e-12);  // the real root, by Cardano's formula
  ASSERT_GE(r.iterations, 3);
  for (int k : {1, 2}) {
    EXPECT_EQ(r.trace[k].step_kind, "watchdog") << "record " << k;
    EXPECT_GT(r.trace[k].residual, r.trace[0].residual) << "record " << k;
  }

  // Without the watchdog no accepted step raises ||f||; where the search ends (the hump's minimum, or the root
  // when a long enough step clears the hump) depends on how far it may step, which R^1 does not bound.
  opt.watchdog = false;
  const SolveResult monotone = newton_group(eq, opt);
  if (monotone.status == Status::converged) {
    EXPECT_LE(std::abs(cubic(monotone.y)(0)), opt.tol);
  }
  for (std::size_t k = 1; k < monotone.trace.size(); ++k) {
    EXPECT_NE(monotone.trace[k].step_kind, "watchdog");
    EXPECT_LE(monotone.trace[k].residual, monotone.trace[k - 1].residual) << "record " << k;
  }
}

// Why: on the paper's problem the watchdog's answers are as honest as the monotone search's, whichever path
// rounding sends it along (paper-linear N = 7, h = 4 ... 64: the monotone search wandered for 100 iterations where
// the watchdog converged, after 14 to 82 iterations, when measured; such paths are rounding's to decide), and the
// monotone search never lets ||f|| grow.
TEST(Watchdog, AnswersOnThePaperProblemAreHonest) {
  for (double h : {4.0, 16.0, 64.0}) {
    SolveRequest req = paper_request(ProblemKind::paper_linear, 7, h, Method::newton_group, Differential::exact,
                                     Globalization::line_search);
    for (bool watchdog : {true, false}) {
      req.solver.watchdog = watchdog;
      const SolveResult r = solve(req);
      const Oracle o = oracle(ProblemKind::paper_linear, h, start_point(7, 1), r.y);
      EXPECT_NEAR(o.residual, r.residual, 1e-9 * (1.0 + o.residual)) << h << " " << r.reason;
      if (r.status == Status::converged) {
        EXPECT_LE(o.residual, 1e-13 + r.floor) << "converged means ||f(y)|| <= tol for the returned y";
        EXPECT_LE(o.angle, std::numbers::pi);
      }
      if (watchdog) continue;
      for (std::size_t k = 1; k < r.trace.size(); ++k) {
        EXPECT_NE(r.trace[k].step_kind, "watchdog");
        EXPECT_LE(r.trace[k].residual, r.trace[k - 1].residual) << "h = " << h << " record " << k;
      }
    }
  }
}

// Why: an episode that does not pay off must cost nothing but its iterations: the iteration goes back to the
// reference and goes on from there as the strategy alone would. f(y) = log(y) - b on SO(3), ||b|| = 4 > pi, from
// y_0 = exp(1.5 b / ||b||) (||f|| = 2.5, a Newton step shorter than pi: no search step is capped onto the cut): the
// full step lands across log's cut, where ||f|| = 2 pi, and every full step from there stays there (an episode
// that can never reach the Armijo bound, whatever the rounding). Each episode that went back: its records
// are kWatchdogSteps watchdog steps above the reference's bound; the record that went back names the
// reference (step_from_iterate), its step is the distance from the reference's y (by Eigen's log, not the
// production one) and its residual is not above the reference's; where the strategy finds no step from the
// reference (as the trust region at the cut in NoDescent), the step is 0 and the iterate is the reference's y.
class WatchdogBack : public ::testing::TestWithParam<Globalization> {};

TEST_P(WatchdogBack, GoesBackToTheReferenceWhenTheEpisodeDoesNotPayOff) {
  const Eigen::Vector3d b = 4.0 * Eigen::Vector3d(0.6, 0.0, 0.8);
  const SO3Group so3g;
  auto f = [b](const Eigen::Matrix3d& y) -> Eigen::Vector3d { return so3::log(y) - b; };
  auto df = [](const Eigen::Matrix3d& y, const Eigen::Vector3d& u) -> Eigen::Vector3d {
    return so3::dexpinv(so3::log(y), u);  // d/dt log(y exp(t u)) at t = 0
  };
  const auto eq = Equation<SO3Group>::general(so3g, so3::exp(Eigen::Vector3d(1.5 * b.normalized())), f, df);
  SolverOptions opt;
  opt.globalization = GetParam();
  opt.watchdog = true;
  opt.include_iterates = true;
  const SolveResult r = newton_group(eq, opt);
  const Eigen::Matrix3d y = r.y;
  EXPECT_NEAR(r.residual, f(y).norm(), 1e-12) << r.reason;
  int backs = 0;
  for (std::size_t k = 0; k < r.trace.size(); ++k) {
    if (!r.trace[k].step_from_iterate) continue;
    ++backs;
    const std::size_t ref = static_cast<std::size_t>(*r.trace[k].step_from_iterate);
    ASSERT_LT(ref, k);
    EXPECT_EQ(k - ref - 1, static_cast<std::size_t>(kWatchdogSteps));
    const double bound = std::sqrt(1.0 - 2.0 * kArmijoC1) * r.trace[ref].residual;  // phi = 1/2 ||f||^2
    for (std::size_t i = ref + 1; i < k; ++i) {
      EXPECT_EQ(r.trace[i].step_kind, "watchdog") << "record " << i;
      EXPECT_GT(r.trace[i].residual, bound) << "record " << i << ": the episode would have paid off";
    }
    const Eigen::MatrixXd s = oracle_log(r.trace[ref].y.transpose() * r.trace[k].y);
    EXPECT_NEAR(s.norm() / std::sqrt(2.0), r.trace[k].step, 1e-10) << "record " << k;
    EXPECT_LE(r.trace[k].residual, r.trace[ref].residual) << "record " << k;
    if (r.trace[k].step == 0.0) {
      EXPECT_EQ(r.trace[k].y, r.trace[ref].y);
      EXPECT_EQ(r.trace[k].residual, r.trace[ref].residual);
    }
  }
  EXPECT_GE(backs, 1) << "the case must go back";
}

INSTANTIATE_TEST_SUITE_P(BothStrategies, WatchdogBack,
                         ::testing::Values(Globalization::line_search, Globalization::trust_region),
                         [](const ::testing::TestParamInfo<Globalization>& info) {
                           return info.param == Globalization::line_search ? "LineSearch" : "TrustRegion";
                         });

}  // namespace
}  // namespace lienewton
