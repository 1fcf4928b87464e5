// Continuation in h (core/solvers/continuation.hpp): the path, its honesty against the
// independent oracle (Eigen's matrix log and exp), the identity with the plain solve at small h, and cancellation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/solve.hpp"
#include "core/problems.hpp"
#include "core/solvers/continuation.hpp"
#include "residual_oracle.hpp"
#include "scripted_search.hpp"
#include "gtest_printers.hpp"

namespace lienewton {
namespace {

SolveRequest request(ProblemKind problem, int n, double h, Method method, bool continuation) {
  SolveRequest r;
  r.problem.kind = problem;
  r.problem.n = n;
  r.h = h;
  r.solver.method = method;
  r.solver.differential = Differential::exact;
  r.solver.continuation = continuation;
  return r;
}

TEST(Continuation, FirstStepIsTheLargestHalvingOfHNotAboveOneSixteenth) {
  EXPECT_EQ(first_continuation_step(1.0 / 32), 1.0 / 32);
  EXPECT_EQ(first_continuation_step(1.0 / 16), 1.0 / 16);
  EXPECT_EQ(first_continuation_step(1.0), 1.0 / 16);
  EXPECT_EQ(first_continuation_step(1024.0), 1.0 / 16);
  EXPECT_EQ(first_continuation_step(0.1), 0.05);
  EXPECT_EQ(first_continuation_step(3.0), 3.0 / 64);
}

// Below 1/16 the path is one stage: the plain solve itself.
TEST(Continuation, SmallHIsThePlainSolve) {
  const SolveResult plain = solve(request(ProblemKind::paper_sine, 6, 1.0 / 32, Method::newton_group, false));
  const SolveResult continued = solve(request(ProblemKind::paper_sine, 6, 1.0 / 32, Method::newton_group, true));
  ASSERT_EQ(continued.continuation.size(), 1u);
  EXPECT_EQ(continued.continuation[0].h, 1.0 / 32);
  EXPECT_EQ(continued.status, plain.status);
  EXPECT_EQ(continued.iterations, plain.iterations);
  EXPECT_EQ(continued.total_iterations(), plain.iterations);
  EXPECT_EQ(continued.y, plain.y);
  EXPECT_TRUE(plain.continuation.empty());
}

struct Cell {
  ProblemKind problem;
  int n;
  double h;
  Method method;
};

void PrintTo(const Cell& c, std::ostream* os) {
  *os << to_string(c.problem) << " N = " << c.n << " h = " << c.h << " " << to_string(c.method);
}

// A continued solve and its stream: every stage's records, in order, with their iterates.
struct Continued {
  SolveRequest req;
  SolveResult result;
  std::vector<TraceRecord> records;
};

Continued continued_solve(SolveRequest req) {
  req.solver.include_iterates = true;
  Continued c{req, {}, {}};
  c.result = solve(req, [&](const TraceRecord& t) {
    c.records.push_back(t);
    return true;
  });
  return c;
}

// What holds of any continued solve, whichever path rounding sends it along (on these cells tries fail by wandering
// for 100 iterations, and another build's rounding converges on some and not others):
//  - the answer is honest: its residual is the oracle's at the requested h for the returned y, and converged means
//    ||f(y)|| <= tol there (the oracle rounds at ~1e-14 in its own log and, like f, at the result's rounding floor:
//    tol + 1e-13 + floor) with h g(y) inside log's branch, from the last stage, at h;
//  - the stream holds every stage's records (iterations + 1 each), tagged with its h, and the stages add up;
//  - the path starts with the solve at h from the given start, and every stage starts where the search says: a
//    given stage at z, an identity stage at z's component identity (I, or diag(-1, 1, ..., 1) when det z < 0)
//    at h 2^k, k <= kStiffDoublings, and a root stage at an iterate of an earlier stage that ended at a root, at
//    most doubling or halving its h (but for a last try at h itself).
void expect_honest_path(const Continued& c) {
  const SolveResult& r = c.result;
  const double h = c.req.h;
  const Eigen::MatrixXd z = c.req.problem.start();
  const Oracle o = oracle(c.req.problem.kind, h, z, r.y);
  if (std::isfinite(o.residual) && std::isfinite(r.residual)) {
    EXPECT_NEAR(o.residual, r.residual, 1e-13 + r.floor + 1e-8 * o.residual) << r.reason;
  }
  ASSERT_FALSE(r.continuation.empty());
  if (r.status == Status::converged) {
    EXPECT_LE(o.residual, c.req.solver.tol + 1e-13 + r.floor) << r.reason;
    EXPECT_LE(o.angle, std::numbers::pi + 1e-9);  // a root f of (3.6) sees: h g(y) inside log's branch
    EXPECT_EQ(r.continuation.back().h, h);
    EXPECT_EQ(r.continuation.back().status, Status::converged);
  }
  EXPECT_EQ(r.continuation.front().h, h);
  EXPECT_EQ(r.continuation.front().start, StageStart::given);

  Eigen::MatrixXd j = Eigen::MatrixXd::Identity(z.rows(), z.cols());
  if (z.determinant() < 0) j(0, 0) = -1.0;
  const auto near = [](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return (a - b).norm() < 1e-12; };
  std::vector<std::size_t> first_record;  // of each stage in the stream
  std::size_t records = 0;
  int total = 0;
  for (const ContinuationStage& s : r.continuation) {
    first_record.push_back(records);
    records += static_cast<std::size_t>(s.iterations) + 1;
    total += s.iterations;
  }
  ASSERT_EQ(c.records.size(), records);
  EXPECT_EQ(r.total_iterations(), total);
  for (std::size_t k = 0; k < r.continuation.size(); ++k) {
    const ContinuationStage& s = r.continuation[k];
    const std::size_t first = first_record[k], end = first + static_cast<std::size_t>(s.iterations) + 1;
    for (std::size_t i = first; i < end; ++i) ASSERT_EQ(c.records[i].stage_h, s.h) << "stage " << k;
    const Eigen::MatrixXd& start = c.records[first].y;
    switch (s.start) {
      case StageStart::given:
        EXPECT_TRUE(near(start, z)) << "stage " << k << " at h = " << s.h;
        EXPECT_LE(s.h, h);
        break;
      case StageStart::identity: {
        EXPECT_TRUE(near(start, j)) << "stage " << k << " at h = " << s.h;
        int e = 0;
        EXPECT_EQ(std::frexp(s.h / h, &e), 0.5) << "stage " << k << " at h = " << s.h;
        EXPECT_LE(s.h, std::ldexp(h, kStiffDoublings));
        break;
      }
      case StageStart::root: {
        std::optional<std::size_t> from;  // the earlier stage whose root this stage starts at
        for (std::size_t m = 0; m < k && !from; ++m) {
          const Status st = r.continuation[m].status;
          if (st != Status::converged && st != Status::stagnated) continue;
          const std::size_t m_end = first_record[m] + static_cast<std::size_t>(r.continuation[m].iterations) + 1;
          for (std::size_t i = first_record[m]; i < m_end; ++i)
            if (near(start, c.records[i].y)) from = m;
        }
        ASSERT_TRUE(from.has_value()) << "stage " << k << " at h = " << s.h << " starts at no earlier root";
        const double ratio = s.h / r.continuation[*from].h;
        if (s.h != h) {
          EXPECT_LE(ratio, 2.0) << "stage " << k;
          EXPECT_GE(ratio, 0.5) << "stage " << k;
        }
        break;
      }
      case StageStart::restart:
        EXPECT_EQ(s.h, h);
        break;
    }
  }
}

class ContinuedCell : public ::testing::TestWithParam<Cell> {};

// Why: continuation's answer must be as honest as a plain solve's on cells where its paths are erratic. Without a
// globalization the path first tries h itself, and goes on from h_0 <= 1/16 only when that fails.
TEST_P(ContinuedCell, ConvergedIsTrueAtTheRequestedH) {
  const Cell c = GetParam();
  const Continued run = continued_solve(request(c.problem, c.n, c.h, c.method, true));
  expect_honest_path(run);
  const SolveResult& r = run.result;
  if (r.continuation.size() > 1) {
    EXPECT_NE(r.continuation.front().status, Status::converged);
    EXPECT_LE(r.continuation[1].h, kContinuationStart);
  }
}

// Cells of the paper's grid where the plain solve fails for a structural reason (measured, exact differential,
// seed 1): Version 2 leaves log's branch (off_branch) or blows up (diverged), after 8 to 14 iterations as rounding
// goes (-march=native and plain x86-64 differ by up to 4). From h_0 = 1/16 every stage of the path converges in 3
// to 7 iterations from the previous root, each doubling h: a path of well-conditioned solves, which no rounding
// turns. (paper-sine N = 5, h = 2 was here: its path fails a stage at h = 2 and gets there from 1.41, a detour
// rounding may take or not; N = 4, h = 1: its plain run diverged after 13 iterations, or 21 since the Newton step
// solves in the spectral basis.)
const Cell kRescued[] = {{ProblemKind::paper_linear, 3, 16.0, Method::newton_algebra},
                         {ProblemKind::paper_linear, 8, 64.0, Method::newton_algebra},
                         {ProblemKind::paper_sine, 6, 0.5, Method::newton_algebra}};
INSTANTIATE_TEST_SUITE_P(Rescued, ContinuedCell, ::testing::ValuesIn(kRescued));
// Erratic cells: the plain solve or a stage of the path wanders for 100 iterations or converges after dozens
// (measured: the plain solve wanders on paper-linear N = 3, h = 32 and converges after 71 at N = 8, h = 32 and
// after 29 on paper-sine N = 5, h = 8), so only what holds on any path is checked.
INSTANTIATE_TEST_SUITE_P(Erratic, ContinuedCell,
                         ::testing::Values(Cell{ProblemKind::paper_sine, 5, 2.0, Method::newton_algebra},
                                           Cell{ProblemKind::paper_linear, 3, 32.0, Method::newton_group},
                                           Cell{ProblemKind::paper_linear, 8, 32.0, Method::newton_group},
                                           Cell{ProblemKind::paper_sine, 5, 8.0, Method::newton_group}));

// Why: continuation exists to rescue cells the paper's iteration loses. On the well-conditioned rescues the plain
// solve fails, and not by running out of iterations; the continued one converges along the path from 1/16,
// every stage converged from the previous stage's root at twice its h.
TEST(Continuation, RescuesCellsThePlainSolveLoses) {
  for (const Cell& c : kRescued) {
    const SolveResult plain = solve(request(c.problem, c.n, c.h, c.method, false));
    EXPECT_TRUE(plain.status == Status::diverged || plain.status == Status::off_branch)
        << to_string(c.method) << " N = " << c.n << " h = " << c.h << ": " << plain.reason;
    const SolveResult r = solve(request(c.problem, c.n, c.h, c.method, true));
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    ASSERT_GE(r.continuation.size(), 3u);
    EXPECT_EQ(r.continuation[1].h, first_continuation_step(c.h));
    EXPECT_EQ(r.continuation[1].start, StageStart::given);
    for (std::size_t k = 1; k < r.continuation.size(); ++k) {
      EXPECT_EQ(r.continuation[k].status, Status::converged) << "stage " << k;
      if (k > 1) {
        EXPECT_EQ(r.continuation[k].start, StageStart::root) << "stage " << k;
        EXPECT_EQ(r.continuation[k].h, 2.0 * r.continuation[k - 1].h) << "stage " << k;
      }
    }
    EXPECT_EQ(r.continuation.back().h, c.h);
  }
}

// Why: where the plain solve converges, continuing costs nothing: the continued solve is that solve, one stage at
// h, the same y and iterations. (paper-linear N = 8, h = 4: plain converges in 5 iterations, quadratically from z.)
TEST(Continuation, ConvergedFirstTryIsThePlainSolve) {
  const SolveResult plain = solve(request(ProblemKind::paper_linear, 8, 4.0, Method::newton_group, false));
  const SolveResult continued = solve(request(ProblemKind::paper_linear, 8, 4.0, Method::newton_group, true));
  ASSERT_EQ(plain.status, Status::converged);
  ASSERT_EQ(continued.continuation.size(), 1u);
  EXPECT_EQ(continued.continuation[0].h, 4.0);
  EXPECT_EQ(continued.status, Status::converged);
  EXPECT_EQ(continued.iterations, plain.iterations);
  EXPECT_EQ(continued.total_iterations(), plain.iterations);
  EXPECT_EQ(continued.y, plain.y);
  EXPECT_EQ(continued.reason, plain.reason);
}

// The stream sees every stage's records tagged with their h (the failed first try at h, then the path from 1/16);
// the result's trace is the last stage's, and its reason names both its own and the path's iteration counts.
TEST(Continuation, StreamTagsEveryStageWithItsH) {
  const Cell c = kRescued[0];
  std::vector<double> tags;
  const SolveResult r = solve(request(c.problem, c.n, c.h, c.method, true), [&](const TraceRecord& t) {
    tags.push_back(t.stage_h.value_or(-1.0));
    return true;
  });
  ASSERT_EQ(r.status, Status::converged);
  ASSERT_GE(r.continuation.size(), 3u);
  std::size_t records = 0;
  for (const ContinuationStage& s : r.continuation) records += static_cast<std::size_t>(s.iterations) + 1;
  ASSERT_EQ(tags.size(), records);
  EXPECT_EQ(tags.front(), c.h);
  EXPECT_EQ(tags[static_cast<std::size_t>(r.continuation[0].iterations) + 1], r.continuation[1].h);
  EXPECT_EQ(r.continuation[1].h, 1.0 / 16);
  EXPECT_EQ(tags.back(), c.h);
  for (const TraceRecord& t : r.trace) EXPECT_EQ(t.stage_h, c.h);
  EXPECT_NE(r.reason.find("after " + std::to_string(r.iterations) + " iterations"), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("the last of " + std::to_string(r.continuation.size()) + " continuation stages, " +
                          std::to_string(r.total_iterations()) + " over all"),
            std::string::npos)
      << r.reason;
}

// The identity of z's component: in z's component (det J = det z), and an equilibrium g(J) = 0 of both paper
// problems (by the oracle's g), for z of either determinant (seed 1: det z = -1 at N = 8, +1 at N = 5).
TEST(Continuation, ComponentIdentityIsAnEquilibriumInTheComponentOfZ) {
  for (ProblemKind problem : {ProblemKind::paper_linear, ProblemKind::paper_sine})
    for (int n : {2, 3, 5, 8}) {
      const SolveRequest req = request(problem, n, 1.0, Method::newton_group, false);
      const Eigen::MatrixXd z = req.problem.start();
      const SONGroup group(n);
      const auto field = make_field(group, problem, req.problem.rigid_body);
      const auto eq = Equation<SONGroup>::implicit_euler(group, z, 1.0, *field);
      const Eigen::MatrixXd j = eq.component_identity();
      EXPECT_NEAR(j.determinant(), z.determinant(), 1e-12) << "N = " << n;
      EXPECT_EQ((j.transpose() * j - Eigen::MatrixXd::Identity(n, n)).norm(), 0.0);
      EXPECT_EQ(oracle_g(problem, j).norm(), 0.0) << to_string(problem) << " N = " << n;
    }
}

// A stage as "h where": "64 identity".
std::string stage(double h, StageStart start) {
  std::ostringstream os;
  os << h << " " << to_string(start);
  return os.str();
}

// The search's stages, read off a scripted run.
std::vector<std::string> stages_of(const SolveResult& r) {
  std::vector<std::string> out;
  for (const ContinuationStage& s : r.continuation) out.push_back(stage(s.h, s.start));
  return out;
}

// Where a scripted stage started: at z, at the identity J = I, or elsewhere (an earlier stage's root).
StageStart start_of(const ScriptedSearch& s, const Eigen::MatrixXd& y) {
  if ((y - s.z).norm() < 1e-12) return StageStart::given;
  if ((y - Eigen::MatrixXd::Identity(5, 5)).norm() < 1e-12) return StageStart::identity;
  return StageStart::root;
}

// A root of the script: the stage's start, turned a little (so that a stage from it starts at neither z nor J).
Eigen::MatrixXd scripted_root(const ScriptedSearch& s, const Equation<SONGroup>& e) {
  return restart_start(s.g, e.start(), 0);
}

// A continued solve on the scripted search, where a stage finds a root exactly when finds_root(its start, its h).
template <class FindsRoot>
SolveResult run_continued(ScriptedSearch& s, FindsRoot finds_root) {
  SolverOptions opt;
  opt.continuation = true;
  return s.run(opt, [&](const Equation<SONGroup>& e, const SolverOptions&) -> ScriptedSearch::Root {
    if (finds_root(start_of(s, e.start()), e.h())) return scripted_root(s, e);
    return std::nullopt;
  });
}

// Why: the path from the stiff end (4. in continuation.hpp) is tried, in its order, when the tries from z find no
// root, whatever the cell: scripted, J's solves find no root at h and 2h and one at 4h; every stage from a root
// finds one. After the tries from z (at h, the path from 1/16 shrinking its first step kMaxFailedStages times, a
// last try at h), J at h, 2h, 4h, then halving from the root at 4h down to h. On the paper's cells this path is
// taken where rounding sends the tries from z astray (paper-sine N = 5, h = 1024; N = 8, h = 8; N = 10, h = 4 and
// 64 in Release), checked there as every continued solve is, by expect_honest_path.
TEST(Continuation, StiffEndStartsAtTheIdentityWhenThePathFromZeroFails) {
  constexpr double h = 32.0;
  ScriptedSearch s(h);
  const SolveResult r = run_continued(s, [&](StageStart from, double at) {
    return from == StageStart::root || (from == StageStart::identity && at >= 4 * h);
  });
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  std::vector<std::string> want = {stage(h, StageStart::given)};
  for (int k = 0; k < kMaxFailedStages; ++k)  // the path from 1/16, a quarter of the step after each failure
    want.push_back(stage(std::ldexp(kContinuationStart, -2 * k), StageStart::given));
  want.push_back(stage(h, StageStart::given));
  for (double at : {h, 2 * h, 4 * h}) want.push_back(stage(at, StageStart::identity));
  for (double at : {2 * h, h}) want.push_back(stage(at, StageStart::root));
  EXPECT_EQ(stages_of(r), want);
}

// Cells of the paper's grid (paper-linear N = 9, h = 64 and 128, exact, seed 1) that no try from z and no
// stiff-end path reached in Release: z's path folds back below h = 6, and J at h, 2h, ..., 16h found no root; J at
// h/2 did (after 74 iterations: erratic), and its root continued up to h. Another build's rounding takes another
// path (an Intel Xeon's AVX-512 build did not converge at h = 64), so only what holds on any path is checked.
INSTANTIATE_TEST_SUITE_P(FromBelow, ContinuedCell,
                         ::testing::Values(Cell{ProblemKind::paper_linear, 9, 64.0, Method::newton_group},
                                           Cell{ProblemKind::paper_linear, 9, 128.0, Method::newton_group}));
// The paper-sine cells where the tries from z wandered and the stiff end's path converged (Release).
INSTANTIATE_TEST_SUITE_P(StiffEnd, ContinuedCell,
                         ::testing::Values(Cell{ProblemKind::paper_sine, 5, 1024.0, Method::newton_group},
                                           Cell{ProblemKind::paper_sine, 8, 8.0, Method::newton_group},
                                           Cell{ProblemKind::paper_sine, 10, 64.0, Method::newton_group},
                                           Cell{ProblemKind::paper_sine, 10, 4.0, Method::newton_group}));

// Why: the paths from below (5. in continuation.hpp) are tried, in their order, when neither z's path nor the
// stiff end finds a root: scripted, J finds a root at h/4 and below only, z nowhere; every stage from a root finds
// one. After the stiff end (J at h ... 16h), at h/2 from z then J, at h/4 from z then J (a root), then up from it,
// doubling, to h.
TEST(Continuation, PathFromBelowGoesUpFromARootAtASmallerStep) {
  constexpr double h = 64.0;
  ScriptedSearch s(h);
  const SolveResult r = run_continued(s, [&](StageStart from, double at) {
    return from == StageStart::root || (from == StageStart::identity && at <= h / 4);
  });
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  const std::vector<std::string> stages = stages_of(r);
  const auto stiff = std::find(stages.begin(), stages.end(), stage(h, StageStart::identity));
  ASSERT_NE(stiff, stages.end());
  std::vector<std::string> want;
  for (int k = 0; k <= kStiffDoublings; ++k) want.push_back(stage(std::ldexp(h, k), StageStart::identity));
  for (double low : {h / 2, h / 4}) {
    want.push_back(stage(low, StageStart::given));
    want.push_back(stage(low, StageStart::identity));
  }
  for (double at : {h / 2, h}) want.push_back(stage(at, StageStart::root));
  EXPECT_EQ(std::vector<std::string>(stiff, stages.end()), want);
}

// With a globalization the second try at h is the paper's full-step Newton from the same start: a cell the plain
// solve converges on is never lost (paper-sine N = 6, h = 1/4: plain converges in 7 iterations; the line search
// alone wandered for 100 in Release, so where another build's rounding lets it converge the second try is not
// needed and only the first stage is checked).
TEST(Continuation, GlobalisedSecondTryIsThePlainSolve) {
  SolveRequest plain_req = request(ProblemKind::paper_sine, 6, 0.25, Method::newton_group, false);
  const SolveResult plain = solve(plain_req);
  SolveRequest ls_req = plain_req;
  ls_req.solver.globalization = Globalization::line_search;
  const SolveResult ls = solve(ls_req);
  ASSERT_EQ(plain.status, Status::converged);
  ls_req.solver.continuation = true;
  const SolveResult r = solve(ls_req);
  EXPECT_EQ(r.status, Status::converged);
  EXPECT_EQ(r.continuation[0].globalization, Globalization::line_search);
  if (ls.status == Status::converged) {
    EXPECT_EQ(r.continuation.size(), 1u);
    return;
  }
  ASSERT_EQ(r.continuation.size(), 2u);
  EXPECT_EQ(r.continuation[1].globalization, Globalization::none);
  EXPECT_EQ(r.continuation[1].start, StageStart::given);
  EXPECT_EQ(r.y, plain.y);
  EXPECT_EQ(r.total_iterations(), ls.iterations + plain.iterations);
}

// Why: with a globalization every stage of a path is tried as the first two tries at h are: a globalised stage
// that finds no root is solved again from the same start with full steps (a descent method stalls where the path
// of roots folds back; full steps jump on). Scripted, so that it is exercised whatever the rounding: the line
// search finds no root anywhere, full steps find one everywhere but at h from z. On paper-sine N = 15, h = 1/16
// (exact) the line search stalled at ||f|| = 0.004 where the path of roots folds back (near h = 0.189), and line
// search + continuation converged on 293 of paper-sine's 294 cells, missing this one, before this rule; which
// stages its full steps then converge on is rounding's to decide (measured: the retry at h from z after 56
// iterations in plain x86-64, 42 with AVX2 and FMA; with -march=native (AVX-512) none, and the path from J), so
// there the rule is checked on whatever path it takes, with an honest answer.
TEST(Continuation, GlobalisedStageWithoutRootIsRetriedWithFullSteps) {
  constexpr double h = 1.0;
  ScriptedSearch s(h);
  SolverOptions opt;
  opt.continuation = true;
  opt.globalization = Globalization::line_search;
  const auto script = [&](const Equation<SONGroup>& e, const SolverOptions& o) -> ScriptedSearch::Root {
    if (o.globalization != Globalization::none || (e.h() == h && start_of(s, e.start()) == StageStart::given))
      return std::nullopt;
    return scripted_root(s, e);
  };
  const SolveResult scripted = s.run(opt, script);
  ASSERT_EQ(scripted.status, Status::converged) << scripted.reason;
  std::vector<std::string> want;
  const auto both = [&](double at, StageStart start) {
    want.push_back(stage(at, start) + " line-search");
    want.push_back(stage(at, start) + " none");
  };
  both(h, StageStart::given);
  both(1.0 / 16, StageStart::given);
  for (double at : {1.0 / 8, 1.0 / 4, 1.0 / 2, 1.0}) both(at, StageStart::root);
  std::vector<std::string> got;
  for (const ContinuationStage& st : scripted.continuation)
    got.push_back(stage(st.h, st.start) + " " + std::string(to_string(st.globalization)));
  EXPECT_EQ(got, want);

  SolveRequest req = request(ProblemKind::paper_sine, 15, 1.0 / 16, Method::newton_group, true);
  req.solver.globalization = Globalization::line_search;
  const Continued run = continued_solve(req);
  expect_honest_path(run);
  const SolveResult& r = run.result;
  for (std::size_t k = 0; k + 1 < r.continuation.size(); ++k) {
    const ContinuationStage& st = r.continuation[k];
    const bool root = st.status == Status::converged || st.status == Status::stagnated;
    if (st.globalization != Globalization::line_search || root) continue;
    const ContinuationStage& next = r.continuation[k + 1];
    EXPECT_EQ(next.globalization, Globalization::none) << "stage " << k << " at h = " << st.h;
    EXPECT_EQ(next.h, st.h);
    EXPECT_EQ(next.start, st.start);
  }
}

// A client that leaves once the path has started (its first record below h) stops the path in that stage; the
// result says cancelled, and its residual is the returned y's at the requested h (by the oracle), not at the
// stage's.
TEST(Continuation, CancelledOnTheWayReportsTheResidualAtTheRequestedH) {
  const Cell c = kRescued[0];
  const SolveRequest req = request(c.problem, c.n, c.h, c.method, true);
  const SolveResult r = solve(req, [&](const TraceRecord& t) { return t.stage_h == c.h; });
  EXPECT_EQ(r.status, Status::cancelled);
  ASSERT_EQ(r.continuation.size(), 2u);
  EXPECT_EQ(r.continuation[1].h, 1.0 / 16);
  EXPECT_NEAR(r.residual, oracle(req.problem.kind, req.h, req.problem.start(), r.y).residual, 1e-12);
}

}  // namespace
}  // namespace lienewton
