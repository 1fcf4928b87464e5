// The restarts, continuation's last try ("restarts": K; core/solvers/restart_start.hpp, continuation.hpp): the
// seeded starts, the order and stopping of the search (with a scripted stage solver), and a paper-linear cell that
// every path misses, converged by the independent oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <numbers>
#include <vector>

#include "core/groups/so3_group.hpp"
#include "core/groups/son_group.hpp"
#include "core/problems.hpp"
#include "core/request_error.hpp"
#include "core/solve.hpp"
#include "core/solvers/continuation.hpp"
#include "core/start_point.hpp"
#include "gtest_printers.hpp"
#include "residual_oracle.hpp"
#include "scripted_search.hpp"

namespace lienewton {
namespace {

// The largest rotation angle of an orthogonal matrix's principal log (Eigen's, not the production one).
double oracle_angle(const Eigen::MatrixXd& q) {
  return Eigen::JacobiSVD<Eigen::MatrixXd>(oracle_log(q)).singularValues()(0);
}

// y_k = y_0 exp(x_k): the same bits for the same k, another start for another k, in y_0's component, and
// exp(x_k) within kRestartAngle of y_0 (by Eigen's log); for SO(3)'s closed forms and SO(N), N = 2 included.
template <class G>
void check_restart_starts(const G& g, const Eigen::MatrixXd& y0_matrix) {
  const typename G::Element y0(y0_matrix);
  std::vector<Eigen::MatrixXd> starts;
  for (int k = 0; k < 16; ++k) {
    const Eigen::MatrixXd y = restart_start(g, y0, k);
    EXPECT_EQ(y, Eigen::MatrixXd(restart_start(g, y0, k))) << g.name() << " k = " << k;
    EXPECT_LT((y.transpose() * y - Eigen::MatrixXd::Identity(g.n(), g.n())).norm(), 1e-13) << g.name();
    EXPECT_NEAR(y.determinant(), y0_matrix.determinant(), 1e-12) << g.name();
    EXPECT_LE(oracle_angle(y0_matrix.transpose() * y), kRestartAngle + 1e-12) << g.name() << " k = " << k;
    for (const Eigen::MatrixXd& earlier : starts) EXPECT_GT((y - earlier).norm(), 1e-3) << g.name() << " k = " << k;
    starts.push_back(y);
  }
}

TEST(RestartStart, DependsOnTheIndexAloneAndStaysWithinTheAngle) {
  check_restart_starts(SO3Group{}, start_point(3, 1));
  for (int n : {2, 5, 11}) check_restart_starts(SONGroup(n), start_point(n, 1));
}

// The search with a scripted stage solver (paper-linear N = 5, h = 32): every try of the paths fails, and so does
// every restart but the one from y_0 exp(x_3). The restarts come last, in the order k = 0, 1, ..., each from its
// seeded start, with at most kRestartIterations iterations and no watchdog; the first that converges ends the
// search and is the answer. With K = 3 none converges: the answer stays the earlier tries' (not converged).
struct Scripted {
  ScriptedSearch search{32.0};
  Eigen::MatrixXd winner = restart_start(search.g, search.eq.start(), 3);
  std::vector<SolverOptions>& seen = search.seen;

  SolveResult run(int restarts) {
    SolverOptions opt;
    opt.continuation = true;
    opt.globalization = Globalization::line_search;
    opt.watchdog = true;
    opt.max_iterations = 100;
    opt.restarts = restarts;
    return search.run(opt, [&](const Equation<SONGroup>& e, const SolverOptions&) -> ScriptedSearch::Root {
      if (e.h() == 32.0 && (e.start() - winner).norm() < 1e-12) return e.start();
      return std::nullopt;
    });
  }
};

TEST(Restarts, ComeLastInSeedOrderAndStopAtTheFirstRoot) {
  Scripted s;
  const SolveResult r = s.run(10);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  EXPECT_EQ(r.iterations, 7);
  EXPECT_LT((r.y - s.winner).norm(), 1e-12);
  const auto first = std::find_if(r.continuation.begin(), r.continuation.end(),
                                  [](const ContinuationStage& c) { return c.start == StageStart::restart; });
  ASSERT_EQ(r.continuation.end() - first, 4) << "restarts 0, 1, 2 fail, 3 converges, 4 ... 9 are not run";
  EXPECT_GT(first - r.continuation.begin(), 10) << "the paths' tries come first";
  for (auto c = r.continuation.begin(); c != first; ++c) EXPECT_FALSE(c->restart.has_value());
  for (int k = 0; k < 4; ++k) {
    const ContinuationStage& c = first[k];
    EXPECT_EQ(c.restart, k);
    EXPECT_EQ(c.h, 32.0);
    EXPECT_EQ(c.globalization, Globalization::line_search);
    EXPECT_EQ(c.iterations, k < 3 ? kRestartIterations : 7);
  }
  const std::size_t n = s.seen.size();
  for (std::size_t i = n - 4; i < n; ++i) {
    EXPECT_EQ(s.seen[i].max_iterations, kRestartIterations);
    EXPECT_FALSE(s.seen[i].watchdog);
  }
}

TEST(Restarts, NoneConvergingLeavesTheEarlierAnswer) {
  Scripted s;
  const SolveResult r = s.run(3);
  EXPECT_EQ(r.status, Status::max_iterations);
  EXPECT_EQ(r.iterations, 100);  // the earlier tries' last answer, not a restart's (kRestartIterations)
  EXPECT_EQ(std::count_if(r.continuation.begin(), r.continuation.end(),
                          [](const ContinuationStage& c) { return c.start == StageStart::restart; }),
            3);
}

// restarts are continuation's last try: without continuation 422 naming "restarts".
TEST(Restarts, NeedContinuation) {
  SolveRequest req;
  req.solver.restarts = 4;
  try {
    solve(req);
    ADD_FAILURE() << "restarts without continuation were accepted";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "restarts");
    EXPECT_EQ(e.kind(), RequestError::Kind::unprocessable);
  }
}

// paper-linear N = 11, h = 32 (line search, exact, seed 1) is one of the cells that every path misses (README);
// the restarts reach a root there. The paths' tries before them are erratic (470 stages with -march=native, 486
// in plain x86-64, 465 with AVX2 and FMA), but the restart that converges is not: restart 29 from its seeded
// start, in 11 iterations, in all three; another rounding that reaches a root sooner ends the search there.
// Converged is checked by Eigen's log and exp, and the root lies in log's principal branch.
TEST(Restarts, ReachARootThatEveryPathMisses) {
  SolveRequest req;
  req.problem.kind = ProblemKind::paper_linear;
  req.problem.n = 11;
  req.h = 32;
  req.solver.globalization = Globalization::line_search;
  req.solver.continuation = true;
  req.solver.restarts = 200;
  const SolveResult r = solve(req);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  const Oracle o = oracle(req.problem.kind, req.h, req.problem.start(), r.y);
  EXPECT_LE(o.residual, req.solver.tol + 1e-13 + r.floor);  // the oracle rounds like f, at the floor
  EXPECT_LT(o.angle, std::numbers::pi);
  EXPECT_EQ(r.continuation.back().h, req.h);
  const bool restarted = std::any_of(r.continuation.begin(), r.continuation.end(),
                                     [](const ContinuationStage& c) { return c.start == StageStart::restart; });
  if (restarted) {
    EXPECT_EQ(r.continuation.back().start, StageStart::restart);  // found by the last try
  }
}

}  // namespace
}  // namespace lienewton
