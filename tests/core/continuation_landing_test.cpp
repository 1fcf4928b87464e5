// Continuation lands on h from either side: where the path's corrector carries tau past h while its predictor
// stayed below it, the root at h is still found and labelled continued (core/solvers/continuation.hpp, "at h").
// The cases are two stages of paper-sine, N = 5, seed 1, where the corrector overshoots h: implicit Euler's second
// step at h = 1/16 and dirk-cg2's second stage at h = 1/4. Their truth is the independent tracker of
// branch_tracker.hpp (natural-parameter continuation with its own Newton, differences and matrix functions).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "branch_tracker.hpp"
#include "core/integrate.hpp"
#include "core/problems.hpp"
#include "core/solve.hpp"
#include "core/work_precision.hpp"
#include "gtest_printers.hpp"
#include "residual_oracle.hpp"

namespace lienewton {
namespace {

const test::MatrixField kPaperSine = [](const Eigen::MatrixXd& y) { return PaperSine{}.g(y); };
// dirk-cg2's diagonal coefficient, 1 - 1/sqrt(2) (its tableau, core/requests_on_group.hpp).
const double kGamma = 1.0 - 1.0 / std::sqrt(2.0);

ProblemSpec paper_sine_n5() {
  ProblemSpec p;
  p.kind = ProblemKind::paper_sine;
  p.n = 5;
  p.seed = 1;
  return p;
}

SolveResult continued(const Eigen::MatrixXd& z, double h) {
  SolveRequest r;
  r.problem = paper_sine_n5();
  r.problem.z = z;
  r.h = h;
  r.solver.method = Method::newton_group;
  r.solver.differential = Differential::exact;
  r.solver.continuation = true;
  return solve(r);
}

// The root continued from z at h, by the tracker; the test cannot go on without it.
Eigen::MatrixXd tracked_root(const Eigen::MatrixXd& z, double h) {
  const test::TrackedBranch b = test::track_branch(kPaperSine, z, h);
  EXPECT_TRUE(b.reached) << "the tracker stopped at " << b.h_stop << " of " << h;
  return b.y;
}

// The start of implicit Euler's second step at h = 1/16: the first step's continued root.
Eigen::MatrixXd second_euler_step_start() { return tracked_root(paper_sine_n5().start(), 1.0 / 16); }

// The start of dirk-cg2's second stage at h = 1/4: Z_2 = y_0 exp(h (1 - gamma) g(Y_1)), Y_1 continued at gamma h.
Eigen::MatrixXd second_dirk_stage_start() {
  const Eigen::MatrixXd y0 = paper_sine_n5().start();
  const Eigen::MatrixXd y1 = tracked_root(y0, kGamma / 4);
  return y0 * oracle_exp((1.0 - kGamma) / 4 * kPaperSine(y1));
}

void expect_continued_root(const Eigen::MatrixXd& z, double h) {
  const SolveResult r = continued(z, h);
  ASSERT_EQ(r.status, Status::converged) << "h = " << h << ": " << r.reason;
  EXPECT_EQ(r.branch, Branch::continued) << "h = " << h << ": " << r.reason;
  EXPECT_EQ(r.found_by, Search::continuation) << "h = " << h;
  EXPECT_LT((r.y - tracked_root(z, h)).norm(), 1e-10) << "h = " << h;
}

// Why: both cases used to stop with "its step length fell below its smallest" (branch unchecked), so that the
// integrators halved steps whose continued root exists at the full step.
TEST(ContinuationLanding, OvershootingCorrectorStillLandsOnH) {
  expect_continued_root(second_euler_step_start(), 1.0 / 16);
  expect_continued_root(second_dirk_stage_start(), kGamma / 4);
}

// Across 0.8 ... 1.2 times each case's tau, wherever the corrector happens to land relative to h.
TEST(ContinuationLanding, ScanAroundBothCasesIsAlwaysContinued) {
  const Eigen::MatrixXd euler = second_euler_step_start();
  const Eigen::MatrixXd dirk = second_dirk_stage_start();
  for (int k = 0; k <= 8; ++k) {
    const double factor = 0.8 + 0.05 * k;
    expect_continued_root(euler, factor / 16);
    expect_continued_root(dirk, factor * kGamma / 4);
  }
}

// Every h of the default work-precision grid takes one step per h on paper-sine N = 5 (no halving), with
// implicit Euler and dirk-cg2, and each stage is the continued root (the integrator checks its label).
TEST(ContinuationLanding, PaperSineTakesOneStepPerH) {
  WorkPrecisionRequest req;
  req.problem = paper_sine_n5();
  req.choices = {{Integrator::implicit_euler, Method::newton_group, Differential::exact},
                 {Integrator::dirk_cg2, Method::newton_group, Differential::exact}};
  const WorkPrecisionResult r = work_precision(req);
  ASSERT_EQ(r.series.size(), 2u);
  for (const WorkPrecisionSeries& s : r.series)
    for (const WorkPrecisionPoint& p : s.points) {
      EXPECT_EQ(p.status, Status::converged) << to_string(s.choice.integrator) << " h = " << p.h;
      EXPECT_EQ(p.substeps, static_cast<int>(std::lround(req.t_end / p.h)))
          << to_string(s.choice.integrator) << " h = " << p.h;
    }
}

}  // namespace
}  // namespace lienewton
