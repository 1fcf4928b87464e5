// Continuation along z's branch of roots (core/solvers/continuation.hpp) and multistart (multistart.hpp): which root
// a result is, judged by truths the solver does not share: a closed-form fold on SO(2), and an independent branch
// tracker (branch_tracker.hpp: natural-parameter continuation with its own Newton, differences and matrix
// functions) on the paper's problems.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/problems.hpp"
#include "core/solve.hpp"
#include "core/solvers/run_method.hpp"
#include "gtest_printers.hpp"

namespace lienewton {
namespace {

// On SO(2) with z = I, y = exp(theta J) and g(y) = gamma(theta) J, gamma = 1 + 2 (1 - cos theta), the implicit
// Euler equation is the scalar theta = h gamma(theta): its branch from (0, 0) is h(theta) = theta / gamma(theta),
// which rises to a maximum h* (a fold) at 1 + 2 (1 - cos theta) = 2 theta sin theta and falls after.
struct GrowingRotation {
  static Eigen::Matrix2d generator() { return (Eigen::Matrix2d() << 0, -1, 1, 0).finished(); }
  static double angle(const Eigen::MatrixXd& y) { return std::atan2(y(1, 0), y(0, 0)); }
  static double gamma(double theta) { return 1.0 + 2.0 * (1.0 - std::cos(theta)); }
  Eigen::MatrixXd g(const Eigen::MatrixXd& y) const { return gamma(angle(y)) * generator(); }
  Eigen::MatrixXd dg(const Eigen::MatrixXd& y, const Eigen::MatrixXd&, const Eigen::MatrixXd& dy) const {
    const double dtheta = (y(0, 0) * dy(1, 0) - y(1, 0) * dy(0, 0)) / (y(0, 0) * y(0, 0) + y(1, 0) * y(1, 0));
    return 2.0 * std::sin(angle(y)) * dtheta * generator();
  }
};

// The fold of GrowingRotation by bisection on d h / d theta = 0, and the branch's theta at h below it.
double fold_angle() {
  double lo = 0.5, hi = 2.0;  // the numerator gamma - theta gamma' changes sign once in between
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (GrowingRotation::gamma(mid) - mid * 2.0 * std::sin(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}
double fold_h() { return fold_angle() / GrowingRotation::gamma(fold_angle()); }
double branch_angle(double h) {
  double lo = 0.0, hi = fold_angle();  // theta / gamma(theta) increases on [0, the fold]
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (mid / GrowingRotation::gamma(mid) < h ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

SolveResult continued_on_so2(double h, Method method) {
  static const VectorFieldOf<SONGroup, GrowingRotation> field(SONGroup(2), GrowingRotation{});
  const auto eq = Equation<SONGroup>::implicit_euler(SONGroup(2), Eigen::MatrixXd::Identity(2, 2), h, field);
  SolverOptions opt;
  opt.method = method;
  opt.continuation = true;
  return run_method(method, eq, opt, {});
}

// Why: below the fold the continued root is the branch's (closed form); beyond it no continued root exists, and
// the answer must say so with the fold's h, not hand over another root.
TEST(Continuation, FoldOnSO2IsReportedWhereTheClosedFormTurns) {
  const double star = fold_h();
  for (Method method : {Method::newton_group, Method::newton_algebra, Method::fixed_point}) {
    for (double h : {0.3 * star, 0.9 * star, 0.99 * star}) {
      const SolveResult r = continued_on_so2(h, method);
      ASSERT_EQ(r.status, Status::converged) << to_string(method) << " h = " << h << ": " << r.reason;
      EXPECT_EQ(r.branch, Branch::continued) << r.reason;
      EXPECT_EQ(r.found_by, Search::continuation);
      EXPECT_NEAR(GrowingRotation::angle(r.y), branch_angle(h), 1e-9) << to_string(method) << " h = " << h;
    }
    for (double h : {1.01 * star, 1.5 * star, 8 * star}) {
      const SolveResult r = continued_on_so2(h, method);
      EXPECT_EQ(r.status, Status::fold) << to_string(method) << " h = " << h << ": " << r.reason;
      EXPECT_EQ(r.branch, Branch::other);
      ASSERT_TRUE(r.fold_h.has_value());
      EXPECT_NEAR(*r.fold_h, star, 0.01 * star) << to_string(method) << " h = " << h;
      ASSERT_FALSE(r.continuation.empty());
      EXPECT_EQ(r.continuation.back().kind, PathPointKind::fold);
    }
  }
}

// The path's points climb in h up to h (no point beyond it), and its tangents point to larger h until a fold.
TEST(Continuation, PathPointsClimbToH) {
  const double h = 0.95 * fold_h();
  const SolveResult r = continued_on_so2(h, Method::newton_group);
  double last = 0.0;
  for (const PathPoint& p : r.continuation) {
    if (p.kind != PathPointKind::path) continue;
    EXPECT_GE(p.h, last);
    EXPECT_LE(p.h, h);
    EXPECT_GT(p.dh_ds, 0.0);
    last = p.h;
  }
  EXPECT_EQ(r.continuation.back().kind, PathPointKind::final);
  EXPECT_EQ(r.total_iterations(), r.iterations + r.extra_iterations);
}

SolveRequest request(ProblemKind problem, int n, double h, Method method) {
  SolveRequest r;
  r.problem.kind = problem;
  r.problem.n = n;
  r.h = h;
  r.solver.method = method;
  return r;
}

// Why: at small h the plain solve from z finds the continued root (where it converges: the fixed point does not
// from z at N = 6), and continuation must find the same one.
TEST(Continuation, SmallStepFindsThePlainRoot) {
  for (Method method : {Method::newton_group, Method::newton_algebra, Method::fixed_point}) {
    SolveRequest req = request(ProblemKind::paper_sine, 6, 1.0 / 32, method);
    const SolveResult plain = solve(req);
    req.solver.continuation = true;
    const SolveResult continued = solve(req);
    ASSERT_TRUE(continued.status == Status::converged || continued.status == Status::stagnated) << continued.reason;
    EXPECT_EQ(plain.branch, Branch::unchecked);
    EXPECT_EQ(continued.branch, Branch::continued);
    if (plain.status == Status::converged) {
      EXPECT_LT((continued.y - plain.y).norm(), 1e-10) << to_string(method);
    }
    EXPECT_NEAR(continued.distance_from_z, (continued.y - Eigen::MatrixXd(req.problem.start())).norm(), 1e-15);
  }
}

// The seeded starts of multistart depend on k alone: the same bits on every call, on the group, turning by at
// most kMultistartAngle.
TEST(Multistart, StartsAreSeededByTheirIndexAlone) {
  const SONGroup g(5);
  const Eigen::MatrixXd y0 = SolveRequest{}.problem.start();
  const SONGroup g3(3);
  for (int k = 0; k < 20; ++k) {
    const Eigen::MatrixXd y = multistart_start(g3, Eigen::MatrixXd(y0), k);
    EXPECT_EQ(y, Eigen::MatrixXd(multistart_start(g3, Eigen::MatrixXd(y0), k)));
    EXPECT_LT(g3.defect(y), 1e-13);
    double angle = 0;
    g3.log_vector(g3.compose(g3.inverse(y0), y), angle);
    EXPECT_LE(angle, kMultistartAngle + 1e-12);
  }
  EXPECT_NE(Eigen::MatrixXd(multistart_start(g, Eigen::MatrixXd::Identity(5, 5), 0)),
            Eigen::MatrixXd(multistart_start(g, Eigen::MatrixXd::Identity(5, 5), 1)));
}

// Multistart runs only when no root was found, stops at its first root, and says so.
TEST(Multistart, FirstRootEndsTheSearchAndIsLabelled) {
  SolveRequest req = request(ProblemKind::paper_linear, 10, 16, Method::newton_group);
  req.solver.differential = Differential::exact;
  req.solver.globalization = Globalization::line_search;
  const SolveResult plain = solve(req);
  req.solver.multistart = 40;
  const SolveResult r = solve(req);
  if (plain.status == Status::converged || plain.status == Status::stagnated) {
    EXPECT_EQ(r.found_by, Search::plain);
    EXPECT_EQ(r.multistart_tries, 0);
    return;
  }
  if (r.found_by == Search::multistart) {
    ASSERT_TRUE(r.multistart_start.has_value());
    EXPECT_EQ(r.multistart_tries, *r.multistart_start + 1);
    EXPECT_TRUE(r.status == Status::converged || r.status == Status::stagnated) << r.reason;
    EXPECT_EQ(r.branch, Branch::unchecked);
    EXPECT_GT(r.total_iterations(), r.iterations);
  } else {
    EXPECT_EQ(r.multistart_tries, 40);
    EXPECT_EQ(r.status, plain.status);
  }
}

// multistart without continuation is a request of its own now: no 422.
TEST(Multistart, NeedsNoContinuation) {
  SolveRequest req = request(ProblemKind::paper_sine, 3, 1.0, Method::newton_group);
  req.solver.multistart = 4;
  EXPECT_NO_THROW(validate(req));
}

}  // namespace
}  // namespace lienewton
