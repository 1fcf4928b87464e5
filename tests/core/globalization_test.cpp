// Issue 14, section 2: the globalised Newton iteration (line search, trust region) on both versions.
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

// Every converged result of the globalised methods is true of the y it returns, over a spread of (N, h).
TEST(GlobalizedNewton, ConvergedMeansTheOracleResidualIsBelowTol) {
  int converged = 0;
  for (Method m : {Method::newton_group, Method::newton_algebra})
    for (Globalization g : {Globalization::line_search, Globalization::trust_region})
      for (int n : {2, 4, 6})
        for (double h : {0.25, 4.0, 64.0, 1024.0}) {
          const SolveResult r = solve(paper_request(ProblemKind::paper_sine, n, h, m, Differential::exact, g));
          const Oracle o = oracle(ProblemKind::paper_sine, h, start_point(n, 1), r.y);
          EXPECT_NEAR(o.residual, r.residual, 1e-9 * (1.0 + o.residual)) << n << " " << h << " " << r.reason;
          if (r.status != Status::converged) continue;
          ++converged;
          // The oracle's log rounds differently: agreement to tol plus the result's own rounding floor.
          EXPECT_LE(o.residual, 1e-13 + r.floor) << n << " " << h << " " << r.reason;
        }
  EXPECT_GE(converged, 16);
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

// The watchdog (solvers/watchdog.hpp). paper-linear N = 7, h = 64 from z: the monotone line search runs out of
// iterations; with the watchdog it takes full steps through iterates where 1/2 ||f||^2 grows ("watchdog" steps)
// and converges (in 14 iterations when measured).
TEST(Watchdog, TakesTheFullStepsAMonotoneSearchRefuses) {
  SolveRequest req = paper_request(ProblemKind::paper_linear, 7, 64, Method::newton_group, Differential::exact,
                                   Globalization::line_search);
  req.solver.watchdog = true;
  const SolveResult r = solve(req);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  int relaxed = 0;
  for (const TraceRecord& t : r.trace) relaxed += t.step_kind == "watchdog";
  EXPECT_GE(relaxed, 1);
  const Oracle o = oracle(ProblemKind::paper_linear, 64, start_point(7, 1), r.y);
  EXPECT_LE(o.residual, 1e-13 + r.floor) << "converged means ||f(y)|| <= tol for the returned y";
  EXPECT_LE(o.angle, std::numbers::pi);

  req.solver.watchdog = false;
  const SolveResult monotone = solve(req);
  EXPECT_NE(monotone.status, Status::converged) << "the case must need the watchdog: " << monotone.reason;
  for (const TraceRecord& t : monotone.trace) EXPECT_NE(t.step_kind, "watchdog");
}

// An episode that does not pay off: paper-linear N = 6, h = 8. The 32 full steps after the reference iterate all
// stay above its Armijo bound, so the iteration goes back and takes the line search's step from the reference:
// that record names the reference (step_from_iterate), its step is the distance from the reference's y (checked
// with Eigen's log, not the production one) and its residual lies below the reference's.
TEST(Watchdog, GoesBackToTheReferenceWhenTheEpisodeDoesNotPayOff) {
  SolveRequest req = paper_request(ProblemKind::paper_linear, 6, 8, Method::newton_group, Differential::exact,
                                   Globalization::line_search);
  req.solver.include_iterates = true;
  req.solver.watchdog = true;
  const SolveResult r = solve(req);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  int back = -1;
  for (int k = 0; k <= r.iterations; ++k)
    if (r.trace[k].step_from_iterate) {
      back = k;
      break;
    }
  ASSERT_GT(back, 0) << "the case must go back";
  const int ref = *r.trace[back].step_from_iterate;
  ASSERT_EQ(back - ref - 1, kWatchdogSteps);
  const double bound = std::sqrt(1.0 - 2.0 * kArmijoC1) * r.trace[ref].residual;  // phi = 1/2 ||f||^2
  for (int k = ref + 1; k < back; ++k) {
    EXPECT_EQ(r.trace[k].step_kind, "watchdog") << "record " << k;
    EXPECT_GT(r.trace[k].residual, bound) << "record " << k << ": the episode would have paid off";
  }
  EXPECT_LT(r.trace[back].residual, r.trace[ref].residual);
  const Eigen::MatrixXd s = oracle_log(r.trace[ref].y.transpose() * r.trace[back].y);
  EXPECT_NEAR(s.norm() / std::sqrt(2.0), r.trace[back].step, 1e-10);
  const Oracle o = oracle(ProblemKind::paper_linear, 8, start_point(6, 1), r.y);
  EXPECT_LE(o.residual, 1e-13 + r.floor);
}

}  // namespace
}  // namespace lienewton
