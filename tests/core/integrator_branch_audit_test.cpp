// Which root each integration step took, audited: every step of every implicit integrator (each implicit RKMK
// method with the exact Newton and, for Radau IIA 3 and Gauss 2, the simplified Newton; each DIRK method stage by
// stage) is recomputed by the independent tracker of stage_branch_tracker.hpp from the method's own y_k, and the
// method's y_k+1 must be the tracker's wherever the tracker followed the branch to h. On the stiff body at
// k = c = 1e4 and 1e6 with steps of 0.5 and 0.1 (h ||dg|| up to 5e5: the linearly implicit start's regime) and on
// paper-sine N = 5 from ten seeded starts at h = 1/4, 1/8 and 1/16 (the paper's field, not dissipative: its
// branches curve, and a root near the tangent's prediction may lie on another one). The sanitizer build audits the
// largest step of each case, and of paper-sine's seeds the first two at h = 1/8.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/integrate.hpp"
#include "core/integrators/methods.hpp"
#include "core/problems.hpp"
#include "gtest_printers.hpp"
#include "stage_branch_tracker.hpp"

namespace lienewton {
namespace {

struct AuditCase {
  std::string name;
  ProblemSpec problem;
  std::vector<double> h;
  int seeds = 1;  // the problem's start from seeds 1 .. seeds
};

std::vector<Eigen::MatrixXd> so3xr3_basis() {
  std::vector<Eigen::MatrixXd> basis;
  for (int a = 0; a < 3; ++a) {
    Eigen::MatrixXd e = Eigen::MatrixXd::Zero(7, 7);
    e.topLeftCorner(3, 3) = so3::hat(Eigen::Vector3d::Unit(a));
    basis.push_back(e);
  }
  for (int a = 0; a < 3; ++a) {
    Eigen::MatrixXd e = Eigen::MatrixXd::Zero(7, 7);
    e(3 + a, 6) = 1.0;
    basis.push_back(e);
  }
  return basis;
}

std::vector<Eigen::MatrixXd> son_basis(int n) {
  std::vector<Eigen::MatrixXd> basis;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      Eigen::MatrixXd e = Eigen::MatrixXd::Zero(n, n);
      e(i, j) = 1.0;
      e(j, i) = -1.0;
      basis.push_back(e);
    }
  return basis;
}

test::TimedField field_of(const ProblemSpec& p) {
  if (p.is(ProblemKind::stiff_body))
    return [body = StiffBody{p.stiff_body}](double t, const Eigen::MatrixXd& y) {
      StiffBody at = body;
      at.set_time(t);
      return Eigen::MatrixXd(at.g(y));
    };
  return [](double, const Eigen::MatrixXd& y) { return Eigen::MatrixXd(PaperSine{}.g(y)); };
}

ProblemSpec stiff_body(double k) {
  ProblemSpec p{.kind = ProblemKind::stiff_body, .group = "SOxR", .n = 3};
  p.stiff_body.k = k;
  return p;
}

struct Choice {
  Integrator integrator;
  Differential differential = Differential::exact;
};

std::vector<Choice> choices() {
  std::vector<Choice> out;
  for (Integrator i : kAllIntegrators)
    if (solves_stages(i)) out.push_back({i});
  out.push_back({Integrator::rkmk_radau3, Differential::dexpinv_0});
  out.push_back({Integrator::rkmk_gauss2, Differential::dexpinv_0});
  return out;
}

// The tracker's y_k+1 from y_k at t: the coupled stages, or a DIRK method's stages one by one.
struct Tracked {
  bool reached = false;
  Eigen::MatrixXd y;
  double tau = 0.0;  // where the tracker stopped (of the stage that stopped)
};
Tracked tracked_step(const integrators::Tableau& tab, const test::TimedField& g,
                     const std::vector<Eigen::MatrixXd>& basis, const Eigen::MatrixXd& y, double t, double h) {
  if (tab.form == integrators::Form::implicit_rkmk) {
    const test::StageSystem sys{g, basis, tab.a, tab.dexpinv_degree(), true};
    const test::StageTracker tracker(sys, y, t);
    const test::TrackedStages k = tracker.track(h);
    return {k.reached, k.reached ? tracker.next(k.k, h, tab.b) : Eigen::MatrixXd(), k.tau};
  }
  std::vector<Eigen::MatrixXd> hg;  // h g(Y_j) of the stages so far
  const test::StageSystem euler{g, basis, Eigen::MatrixXd::Identity(1, 1), 0, false};
  for (int i = 0; i < tab.stages(); ++i) {
    Eigen::MatrixXd z = y;
    for (int j = 0; j < i; ++j) z = z * oracle_exp(tab.a(i, j) * hg[static_cast<std::size_t>(j)]);
    const double time = t + tab.c(i) * h;
    const test::StageTracker tracker(euler, z, time);
    const test::TrackedStages k = tracker.track(h * tab.a(i, i));
    if (!k.reached) return {false, {}, k.tau};
    const Eigen::MatrixXd stage = tracker.next(k.k, h * tab.a(i, i), Eigen::VectorXd::Ones(1));
    hg.push_back(h * g(time, stage));
  }
  Eigen::MatrixXd next = y;
  for (int i = 0; i < tab.stages(); ++i) next = next * oracle_exp(tab.b(i) * hg[static_cast<std::size_t>(i)]);
  return {true, next};
}

class IntegratorBranchAudit : public ::testing::TestWithParam<int> {};

TEST_P(IntegratorBranchAudit, EveryStepIsTheTrackersRoot) {
  const std::vector<AuditCase> cases = {
      {"stiff-body k = 1e4", stiff_body(1e4), {0.5, 0.1}},
      {"stiff-body k = 1e6", stiff_body(1e6), {0.5, 0.1}},
      {"paper-sine N = 5", {.kind = ProblemKind::paper_sine, .n = 5}, {0.25, 0.125, 1.0 / 16}, 10}};
  const AuditCase& c = cases[static_cast<std::size_t>(GetParam())];
  const std::vector<Eigen::MatrixXd> basis = c.problem.is(ProblemKind::stiff_body) ? so3xr3_basis() : son_basis(5);
  const test::TimedField g = field_of(c.problem);
#if defined(LIENEWTON_SANITIZED)
  const std::vector<double> steps{c.seeds > 1 ? c.h[1] : c.h.front()};
  const int seeds = std::min(c.seeds, 2);
#else
  const std::vector<double> steps = c.h;
  const int seeds = c.seeds;
#endif
  int audited = 0, unreached = 0, other = 0, halved = 0, failed = 0;
  double largest = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    for (const Choice& choice : choices())
      for (double h : steps) {
        const int n = static_cast<int>(std::lround(1.0 / h));
        IntegrateRequest req{.problem = c.problem, .h = h, .t_end = 1.0, .integrator = choice.integrator,
                             .frames = n, .reference = false};
        req.problem.seed = static_cast<std::uint64_t>(seed);
        req.solver.differential = choice.differential;
        const IntegrateResult r = integrate(req);
        const std::string what = c.name + " seed " + std::to_string(seed) + " " +
                                 std::string(to_string(choice.integrator)) + " " +
                                 std::string(to_string(choice.differential)) + " h = " + std::to_string(h);
        if (r.status != Status::converged) {  // an honest failure: nothing to audit
          std::printf("%s: %s\n", what.c_str(), r.reason.c_str());
          ++failed;
          continue;
        }
        ASSERT_EQ(r.frames.size(), static_cast<std::size_t>(n + 1)) << what;
        const integrators::Tableau& tab = integrators::tableau_of(choice.integrator);
        for (int k = 0; k < n; ++k) {
          if (r.steps[static_cast<std::size_t>(k)].substeps != 1) {  // taken as halves: not one step of h
            ++halved;
            continue;
          }
          const Tracked t = tracked_step(tab, g, basis, r.frames[static_cast<std::size_t>(k)], k * h, h);
          if (!t.reached) {
            std::printf("%s step %d: the tracker stopped at tau = %g\n", what.c_str(), k + 1, t.tau);
            ++unreached;
            continue;
          }
          ++audited;
          const double distance = (t.y - r.frames[static_cast<std::size_t>(k + 1)]).norm();
          largest = std::max(largest, distance);
          if (distance > 1e-6) {
            ++other;
            ADD_FAILURE() << what << " step " << k + 1 << ": " << distance << " from the tracker's root";
          }
        }
      }
  }
  std::printf("%s: %d steps audited, %d on another branch (largest distance %.1e), tracker short of h on %d; "
              "%d steps taken as halves, %d runs failed\n",
              c.name.c_str(), audited, other, largest, unreached, halved, failed);
  EXPECT_EQ(other, 0);
  EXPECT_GE(audited, 9 * (audited + unreached) / 10) << "the tracker must reach h on most steps";
}

INSTANTIATE_TEST_SUITE_P(Cases, IntegratorBranchAudit, ::testing::Range(0, 3));

// The step whose second dirk-cg3 stage once took a root of another branch (0.070 from the tangent's prediction,
// inside the radius test's 0.113, on a branch that turns back before tau = 0) and ended converged 2.61 from the
// solution: now on the solution's branch, within the method's own error of the reference.
TEST(IntegratorBranchAudit, DirkCg3OnPaperSineKeepsTheSolutionsBranch) {
  IntegrateRequest req{.problem = {.kind = ProblemKind::paper_sine, .n = 5}, .h = 0.125, .t_end = 1.0,
                       .integrator = Integrator::dirk_cg3};
  req.problem.seed = 1;
  const IntegrateResult r = integrate(req);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  ASSERT_TRUE(r.global_error.has_value()) << r.reason;
  std::printf("dirk-cg3, paper-sine N = 5, seed 1, h = 1/8: global error %.3e\n", *r.global_error);
  EXPECT_LE(*r.global_error, 2e-3);
}

}  // namespace
}  // namespace lienewton
