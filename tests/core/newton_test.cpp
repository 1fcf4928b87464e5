// The solvers against the paper's claims and against independent truth: convergence rates (section 5),
// classical Newton on R^n (Corollary 3.3), one-step convergence for homomorphisms (Remark 3.1), Version 2 as
// the linearisation of Version 1 (Theorem 3.2), and the stopping rule.
#include <gtest/gtest.h>

#include <cmath>

#include "core/cpu_clock.hpp"
#include "core/solvers/run_method.hpp"
#include "core/solve.hpp"
#include "core/start_point.hpp"
#include "rn_group.hpp"
#include "gtest_printers.hpp"

namespace lienewton {
namespace {

SolveRequest paper_linear(int n, Method m, Differential d) {
  return SolveRequest{.problem = {.kind = ProblemKind::paper_linear, .n = n},
                      .solver = {.method = m, .differential = d}, .h = 0.5};
}

class QuadraticConvergence
    : public ::testing::TestWithParam<std::tuple<int, Method, Differential>> {};

TEST_P(QuadraticConvergence, NewtonRateIsTwoOnPaperLinear) {
  const auto [n, method, differential] = GetParam();
  const SolveResult r = solve(paper_linear(n, method, differential));
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  ASSERT_TRUE(r.rate.has_value());
  EXPECT_GE(*r.rate, 1.7);
  EXPECT_LE(*r.rate, 2.3);
  EXPECT_LE(r.residual, 1e-13);
}

INSTANTIATE_TEST_SUITE_P(
    Paper, QuadraticConvergence,
    ::testing::Combine(::testing::Values(3, 10), ::testing::Values(Method::newton_group, Method::newton_algebra),
                       ::testing::Values(Differential::exact, Differential::finite_difference)));

TEST(FixedPoint, ConvergesLinearlyOnPaperLinear) {
  for (int n : {3, 10}) {
    const SolveResult r = solve(paper_linear(n, Method::fixed_point, Differential::exact));
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    ASSERT_TRUE(r.rate.has_value());
    EXPECT_GE(*r.rate, 0.8) << "n = " << n;
    EXPECT_LE(*r.rate, 1.2) << "n = " << n;
  }
}

TEST(Solve, TraceHasOneRecordPerIterateAndIterationsIsTheConvergedIndex) {
  SolveRequest req = paper_linear(5, Method::newton_group, Differential::exact);
  req.solver.include_iterates = true;
  const SolveResult r = solve(req);
  ASSERT_EQ(r.status, Status::converged);
  ASSERT_EQ(static_cast<int>(r.trace.size()), r.iterations + 1);
  for (int i = 0; i < static_cast<int>(r.trace.size()); ++i) {
    EXPECT_EQ(r.trace[i].iteration, i);
    EXPECT_EQ(r.trace[i].y.rows(), 5);
  }
  EXPECT_GT(r.trace[r.iterations - 1].residual, req.solver.tol);  // converged at the first n below tol
  EXPECT_LE(r.trace.back().residual, req.solver.tol);
  // step n is |u_{n-1}|, and y_n = y_{n-1} exp(u_{n-1}) (3.5)
  EXPECT_EQ(r.trace[0].step, 0.0);
  for (int i = 1; i <= r.iterations; ++i) {
    const Eigen::MatrixXd rel = r.trace[i - 1].y.transpose() * r.trace[i].y;
    EXPECT_NEAR(son::vee(son::log(rel)).norm(), r.trace[i].step, 1e-13) << "n = " << i;
  }
  EXPECT_TRUE(r.trace[0].y.isApprox(start_point(5, req.problem.seed), 0.0));  // y_0 = z
  EXPECT_LT(r.orthogonality_error, 1e-13);
}

// cpu_seconds is the solver's own CPU time: it grows along the trace, ends at the result's, and leaves out
// what the callback spends (a callback that burns 50 ms of CPU per record does not show up in it; the solve itself
// takes ~3 ms in Release and 12 ms under ASan, so a 5 ms burn was too close to it there).
TEST(Solve, SolverCpuTimeGrowsAlongTheTraceAndExcludesTheCallback) {
  constexpr double kBurn = 50e-3;
  const SolveRequest req = paper_linear(6, Method::newton_group, Differential::finite_difference);
  const SolveResult r = solve(req, [&](const TraceRecord&) {
    const double until = thread_cpu_seconds() + kBurn;
    while (thread_cpu_seconds() < until) {
    }
    return true;
  });
  ASSERT_EQ(r.status, Status::converged);
  ASSERT_GE(r.trace.size(), 3u);
  EXPECT_GT(r.trace[1].cpu_seconds, 0.0);
  for (std::size_t i = 1; i < r.trace.size(); ++i) EXPECT_GE(r.trace[i].cpu_seconds, r.trace[i - 1].cpu_seconds);
  EXPECT_GE(r.cpu_seconds, r.trace.back().cpu_seconds);
  const double burnt = kBurn * static_cast<double>(r.trace.size());
  EXPECT_LT(r.cpu_seconds, 0.5 * burnt) << "the callback's CPU time leaked into the solver's";
}

// Untimed (sweeps, basin maps) the monitor reads no CPU clock: the result and its records carry no CPU time, the
// same iterate and status as a timed solve, and the wall time of the whole solve.
TEST(Solve, UntimedSolveReadsNoCpuClockAndFindsTheSameIterate) {
  SolveRequest req = paper_linear(6, Method::newton_group, Differential::exact);
  const SolveResult timed = solve(req);
  req.solver.timed = false;
  const SolveResult r = solve(req);
  ASSERT_EQ(r.status, Status::converged);
  EXPECT_EQ(r.y, timed.y);
  EXPECT_EQ(r.iterations, timed.iterations);
  EXPECT_EQ(r.cpu_seconds, 0.0);
  for (const TraceRecord& t : r.trace) EXPECT_EQ(t.cpu_seconds, 0.0);
  EXPECT_GT(r.seconds, 0.0);
  EXPECT_GT(timed.cpu_seconds, 0.0);
}

TEST(Solve, LastAllowedIterateIsStillTested) {
  SolveRequest req = paper_linear(4, Method::newton_group, Differential::exact);
  const int needed = solve(req).iterations;
  req.solver.max_iterations = needed;
  EXPECT_EQ(solve(req).status, Status::converged);
  req.solver.max_iterations = needed - 1;
  const SolveResult r = solve(req);
  EXPECT_EQ(r.status, Status::max_iterations);
  EXPECT_EQ(r.iterations, needed - 1);
}

TEST(Solve, ClosedFormAndSpectralPathsAgreeAtN3) {
  for (Method m : kAllMethods) {
    for (ProblemKind p : kAllProblems) {
      if (!defined_on(p, SO3Group{})) continue;  // heavy-top, stiff-body: problems on SO(3) x R^3
      SolveRequest req = paper_linear(3, m, Differential::exact);
      req.problem.kind = p;
      const Eigen::MatrixXd z = start_point(3, req.problem.seed);
      const SolveResult closed = solve(req);
      const SONGroup son(3);
      const auto field = make_field(son, p, req.problem.rigid_body);
      const auto eq = Equation<SONGroup>::implicit_euler(son, z, req.h, *field);
      const SolveResult spectral = run_method(m, eq, req.solver, {});
      EXPECT_EQ(closed.status, spectral.status) << to_string(m) << " " << to_string(p);
      if (closed.status != Status::converged) continue;  // e.g. fixed point on paper-sine: chaotic, not comparable
      EXPECT_EQ(closed.iterations, spectral.iterations) << to_string(m) << " " << to_string(p);
      EXPECT_LT((closed.y - spectral.y).norm(), 1e-13) << to_string(m) << " " << to_string(p);
    }
  }
}

// Classical Newton on R^n by hand, for f(x) = (x0^2 - 2, x0 x1 + sin(x1) - 1).
Eigen::VectorXd f_rn(const Eigen::VectorXd& x) {
  return Eigen::Vector2d(x(0) * x(0) - 2.0, x(0) * x(1) + std::sin(x(1)) - 1.0);
}
Eigen::MatrixXd jacobian_rn(const Eigen::VectorXd& x) {
  return (Eigen::Matrix2d() << 2.0 * x(0), 0.0, x(1), x(0) + std::cos(x(1))).finished();
}

TEST(AbelianReduction, BothVersionsAreClassicalNewtonOnRn) {  // Corollary 3.3
  const RnGroup rn(2);
  const Eigen::VectorXd z = Eigen::Vector2d(1.0, 0.5);
  const auto eq = Equation<RnGroup>::general(rn, z, f_rn, [](const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
    return Eigen::VectorXd(jacobian_rn(x) * u);
  });
  const SolverOptions opt{.tol = 1e-13, .max_iterations = 50, .include_iterates = true};
  const SolveResult v1 = newton_group(eq, opt);
  const SolveResult v2 = newton_algebra(eq, opt);
  ASSERT_EQ(v1.status, Status::converged);
  ASSERT_EQ(v2.status, Status::converged);
  ASSERT_EQ(v1.iterations, v2.iterations);
  Eigen::VectorXd x = z;
  for (int n = 0; n <= v1.iterations; ++n) {
    EXPECT_LE((v1.trace[n].y - x).norm(), 1e-15 * (1.0 + x.norm())) << "n = " << n;
    EXPECT_LE((v2.trace[n].y - x).norm(), 1e-15 * (1.0 + x.norm())) << "n = " << n;
    x -= Eigen::PartialPivLU<Eigen::MatrixXd>(jacobian_rn(x)).solve(f_rn(x));
  }
}

TEST(AbelianReduction, HomomorphismConvergesInOneStep) {  // Remark 3.1
  const RnGroup rn(3);
  Eigen::Matrix3d a;
  a << 2, 1, 0, 1, 3, 1, 0, 1, 4;
  const auto eq = Equation<RnGroup>::general(
      rn, Eigen::Vector3d(1, -2, 3), [a](const Eigen::VectorXd& x) { return Eigen::VectorXd(a * x); },
      [a](const Eigen::VectorXd&, const Eigen::VectorXd& u) { return Eigen::VectorXd(a * u); });
  const SolveResult r = newton_group(eq, {.tol = 1e-13, .max_iterations = 10});
  EXPECT_EQ(r.status, Status::converged);
  EXPECT_EQ(r.iterations, 1);

  // On the abelian SO(2), f(y) = 3 log(y) is a homomorphism: Version 1 reaches f = 0 in one step.
  const SONGroup so2(2);
  const Eigen::Matrix2d y0 = so2.exp(Eigen::VectorXd::Constant(1, 2.5));
  const auto eq2 = Equation<SONGroup>::general(
      so2, y0, [&](const Eigen::MatrixXd& y) { return Eigen::VectorXd(3.0 * so2.vee(son::log(y))); });
  const SolveResult r2 = newton_group(eq2, {.differential = Differential::finite_difference, .tol = 1e-13, .max_iterations = 10});
  EXPECT_EQ(r2.status, Status::converged);
  EXPECT_EQ(r2.iterations, 1);
}

// Theorem 3.2: from y_n = z exp(v_n), the Version 1 step lands at z exp(v^(1)) with
// v^(1) = v_n + u^(2) + O(|u|^2), u^(2) the Version 2 step.
TEST(Theorem32, VersionTwoLinearisesVersionOne) {
  const SONGroup g(4);
  const Eigen::MatrixXd z = start_point(4, 7);
  const double h = 0.5;
  const auto field = make_field(g, ProblemKind::paper_sine, RigidBodyParams{});
  const auto eq = Equation<SONGroup>::implicit_euler(g, z, h, *field);
  const SolveResult sol = newton_algebra(eq, {.tol = 1e-14, .max_iterations = 50});
  ASSERT_EQ(sol.status, Status::converged);
  const Eigen::VectorXd v_star = g.vee(son::log(z.transpose() * sol.y));
  const Eigen::VectorXd dir = Eigen::VectorXd::LinSpaced(g.dim(), -1.0, 1.0).normalized();

  auto newton_system = [&](auto apply) {
    Eigen::MatrixXd d(g.dim(), g.dim());
    for (int i = 0; i < g.dim(); ++i) d.col(i) = apply(basis_vector(g, i));
    return d;
  };
  std::vector<double> ratios;
  for (double delta : {1e-1, 3e-2, 1e-2, 3e-3, 1e-3}) {
    const Eigen::VectorXd v = v_star + delta * dir;
    const auto p2 = eq.at_algebra(v);
    const auto p1 = eq.at(p2.y);
    const Eigen::VectorXd u1 = -newton_system([&](const Eigen::VectorXd& e) {
                                 return eq.df(p1, e, Differential::exact);
                               }).lu().solve(p1.f);
    const Eigen::VectorXd u2 = -newton_system([&](const Eigen::VectorXd& e) {
                                 return eq.dftilde(p2, e, Differential::exact);
                               }).lu().solve(p2.f);
    const Eigen::VectorXd v1 = g.vee(son::log(z.transpose() * p2.y * g.exp(u1)));
    const double diff = (v1 - (v + u2)).norm();
    ratios.push_back(diff / (u1.norm() * u1.norm()));
    EXPECT_LT(diff, u1.norm()) << "delta = " << delta;
  }
  // diff / |u|^2 stays bounded (and roughly constant) while |u| shrinks by 100.
  for (double r : ratios) {
    EXPECT_GT(r, 0.2 * ratios.front());
    EXPECT_LT(r, 5.0 * ratios.front());
  }
}

}  // namespace
}  // namespace lienewton
