// The paper's section-5 experiment (Figures 5.1 and 5.2) as a sweep, and its qualitative claims.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/request_error.hpp"
#include "core/sweep.hpp"
#include "reversed_farm.hpp"
#include "gtest_printers.hpp"

namespace lienewton {
namespace {

// The paper's claims on its full grids are Release-only tests: the two grids took 167 s under ASan. The sanitizer
// build runs the sweep's code on the small grids below.
#if !defined(LIENEWTON_SANITIZED)
// The full default grid (3 methods x N = 2..15 x h = 2^-10..2^10) with the exact differential.
SweepResult default_sweep(ProblemKind problem) {
  SweepRequest req;
  req.problem.kind = problem;
  req.solver.differential = Differential::exact;
  return sweep(req);
}

void expect_grid_is_the_papers(const SweepResult& s) {
  ASSERT_EQ(s.cells.size(), 3u * 14u * 21u);
  EXPECT_EQ(s.cells.front().method, Method::fixed_point);
  EXPECT_EQ(s.cells.front().n, 2);
  EXPECT_EQ(s.cells.front().h, std::ldexp(1.0, -10));
  EXPECT_EQ(s.cells.back().method, Method::newton_algebra);
  EXPECT_EQ(s.cells.back().n, 15);
  EXPECT_EQ(s.cells.back().h, 1024.0);
}

void expect_fixed_point_fails_for_large_h(const SweepResult& s) {
  for (const auto& c : s.cells) {
    if (c.method == Method::fixed_point && c.h >= 4.0) {
      EXPECT_NE(c.status, Status::converged) << c.n << " " << c.h;
    }
  }
}

void expect_newton_converges_quadratically_where_it_converges(const SweepResult& s) {
  std::vector<double> rates;
  for (const auto& c : s.cells)
    if (c.method != Method::fixed_point && c.status == Status::converged && c.rate) rates.push_back(*c.rate);
  ASSERT_GT(rates.size(), 100u);
  std::sort(rates.begin(), rates.end());
  // The estimate r uses the last three residuals before convergence; where Newton wandered at large h
  // those are not yet asymptotic, so r is a distribution centred on 2, as in the paper's figures.
  const double median = rates[rates.size() / 2];
  EXPECT_GT(median, 1.85);
  EXPECT_LT(median, 2.15);
  const auto quadratic = std::count_if(rates.begin(), rates.end(), [](double r) { return r > 1.5 && r < 2.6; });
  EXPECT_GT(static_cast<double>(quadratic), 0.85 * rates.size());  // measured: 95% (linear), 88% (sine)
}

void expect_version_one_converges_on_more_cells_than_version_two_at_small_n(const SweepResult& s) {
  int v1 = 0, v2 = 0;
  for (const auto& c : s.cells) {
    if (c.n < 3 || c.n > 6 || c.status != Status::converged) continue;
    if (c.method == Method::newton_group) ++v1;
    if (c.method == Method::newton_algebra) ++v2;
  }
  EXPECT_GT(v1, v2);
}

void expect_every_method_converges_for_small_h(const SweepResult& s) {
  for (const auto& c : s.cells) {
    if (c.h <= 1.0 / 64) {
      EXPECT_EQ(c.status, Status::converged) << to_string(c.method) << " n=" << c.n << " h=" << c.h;
    }
  }
}

// One test per problem runs the grid once and checks every claim on it: ctest runs each test in its own
// process, so a test per claim would recompute the 882-cell grid five times (10 minutes of CPU under ASan).
class PaperClaims : public ::testing::TestWithParam<ProblemKind> {};

TEST_P(PaperClaims, HoldOnTheFullGrid) {
  const SweepResult s = default_sweep(GetParam());
  {
    SCOPED_TRACE("the grid is the paper's");
    expect_grid_is_the_papers(s);
  }
  {
    SCOPED_TRACE("the fixed point fails for h >= 4");
    expect_fixed_point_fails_for_large_h(s);
  }
  {
    SCOPED_TRACE("Newton converges quadratically where it converges");
    expect_newton_converges_quadratically_where_it_converges(s);
  }
  {
    SCOPED_TRACE("Version 1 converges on more cells than Version 2 at N = 3..6");
    expect_version_one_converges_on_more_cells_than_version_two_at_small_n(s);
  }
  {
    SCOPED_TRACE("every method converges for h <= 1/64");
    expect_every_method_converges_for_small_h(s);
  }
}

INSTANTIATE_TEST_SUITE_P(Figures, PaperClaims, ::testing::Values(ProblemKind::paper_linear, ProblemKind::paper_sine),
                         [](const ::testing::TestParamInfo<ProblemKind>& info) {
                           return info.param == ProblemKind::paper_linear ? "PaperLinear" : "PaperSine";
                         });
#endif

// A small paper-sine grid, 3 N x 3 h, for the tests of how cells are scheduled.
SweepRequest small_sine_grid(Differential d, std::vector<int> n) {
  SweepRequest req;
  req.problem.kind = ProblemKind::paper_sine;
  req.solver.differential = d;
  req.n = std::move(n);
  req.h = {0.125, 2.0, 64.0};
  return req;
}

// Every field of every cell, bit for bit.
void expect_same_cells(const SweepResult& want, const SweepResult& got) {
  ASSERT_EQ(got.cells.size(), want.cells.size());
  for (std::size_t i = 0; i < want.cells.size(); ++i) {
    const SweepCell &a = want.cells[i], &b = got.cells[i];
    EXPECT_TRUE(a.method == b.method && a.n == b.n && a.h == b.h && a.status == b.status && a.reason == b.reason &&
                a.iterations == b.iterations && a.rate == b.rate && a.residual == b.residual)
        << "cell " << i;
  }
}

TEST(Sweep, ResultDoesNotDependOnThreadCount) {
  SweepRequest req = small_sine_grid(Differential::finite_difference, {2, 5, 9});
  req.threads = 1;
  const SweepResult one = sweep(req);
  req.threads = 3;
  expect_same_cells(one, sweep(req));
}

// Shards partition the grid: 4 parts of the 2 x 3 x 3 = 18 cells (5, 5, 4, 4: every 4th in claim order) hold every
// cell once, and merge_shards gives the unsharded result cell for cell, bit for bit.
// A missing, repeated or unsharded part is refused.
TEST(Sweep, ShardsMergeToTheUnshardedSweep) {
  SweepRequest req = small_sine_grid(Differential::finite_difference, {2, 5, 9});
  req.methods = {Method::newton_group, Method::newton_algebra};
  const SweepResult whole = sweep(req);
  std::vector<SweepResult> parts;
  for (int i = 0; i < 4; ++i) {
    req.shard = Shard{i, 4};
    parts.push_back(sweep(req));
    EXPECT_EQ(parts.back().cells.size(), i < 2 ? 5u : 4u) << "part " << i;  // every 4th of 18 in claim order
  }
  std::swap(parts[0], parts[3]);  // any order
  const SweepResult merged = merge_shards(parts);
  expect_same_cells(whole, merged);
  EXPECT_FALSE(merged.shard);
  EXPECT_THROW((void)merge_shards({parts[0], parts[1], parts[2]}), RequestError);           // one missing
  EXPECT_THROW((void)merge_shards({parts[0], parts[1], parts[2], parts[2]}), RequestError); // one repeated
  EXPECT_THROW((void)merge_shards({whole}), RequestError);                                  // not sharded
}

// The farm path (MPI ranks in the CLI): cells computed in another order and passed as bytes give the threads'
// result bit for bit; a process that only computes for the farm returns no cells.
TEST(Sweep, FarmGivesTheSameCellsAsThreads) {
  const SweepRequest req = small_sine_grid(Differential::exact, {2, 3, 7});
  const ReversedFarm farm;
  expect_same_cells(sweep(req), sweep(req, {}, {}, &farm));
  const ReversedFarm worker(true);
  EXPECT_TRUE(sweep(req, {}, {}, &worker).cells.empty());
}

TEST(Sweep, CancelStopsWithinOneIterationAndKeepsFinishedCellsInOrder) {
  SweepRequest req;
  req.n = {4, 8};
  req.threads = 2;
  int cells = 0;
  const SweepResult s = sweep(req, [&](const SweepCell&) { return ++cells < 5; });
  EXPECT_GE(s.cells.size(), 5u);
  EXPECT_LT(s.cells.size(), 3u * 2u * 21u);
  int polls = 0;
  const SweepResult none = sweep(req, {}, [&] { return ++polls < 10; });
  EXPECT_LT(none.cells.size(), 3u);
}

}  // namespace
}  // namespace lienewton
