// Every failure class, produced by a constructed input and reported with its reason.
#include <gtest/gtest.h>

#include <cmath>

#include <numbers>

#include "core/groups/so3_group.hpp"
#include "core/solvers/run_method.hpp"
#include "core/request_error.hpp"
#include "core/solve.hpp"
#include "core/start_point.hpp"
#include "rn_group.hpp"

namespace lienewton {
namespace {

// g(y) = w, constant: y = z exp(h w) is the exact solution of (1.1), so every quantity is known in closed form.
class ConstantField final : public VectorField<SO3Group> {
 public:
  explicit ConstantField(Eigen::Vector3d w) : w_(w) {}
  Eigen::Vector3d g(const Eigen::Matrix3d&) const override { return w_; }
  Eigen::Vector3d dg(const Eigen::Matrix3d&, const Eigen::Vector3d&) const override { return Eigen::Vector3d::Zero(); }

 private:
  Eigen::Vector3d w_;
};

void expect_reason(const SolveResult& r, Status status) {
  EXPECT_EQ(r.status, status) << r.reason;
  EXPECT_FALSE(r.reason.empty());
  EXPECT_TRUE(r.y.allFinite());  // no solver returns a NaN matrix as its answer
}

TEST(FailureClasses, ConvergedAndMaxIterations) {
  SolveRequest req;
  req.solver.method = Method::fixed_point;
  expect_reason(solve(req), Status::converged);
  req.solver.max_iterations = 3;
  const SolveResult r = solve(req);
  expect_reason(r, Status::max_iterations);
  EXPECT_NE(r.reason.find("3 iterations"), std::string::npos);
}

TEST(FailureClasses, DivergedOnClassicNewtonCounterexample) {
  // Newton on atan from |x0| > 1.39 overshoots further every step.
  const RnGroup r1(1);
  const auto eq = Equation<RnGroup>::general(
      r1, Eigen::VectorXd::Constant(1, 2.0), [](const Eigen::VectorXd& x) { return Eigen::VectorXd(x.array().atan()); },
      [](const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
        return Eigen::VectorXd(u.array() / (1.0 + x.array().square()));
      });
  expect_reason(newton_group(eq, {.tol = 1e-13, .max_iterations = 100}), Status::diverged);
}

TEST(FailureClasses, NonFiniteWhenFLeavesItsDomain) {
  // f(x) = sqrt(x) + 1 has no root; the first Newton step lands at x < 0, where f is NaN.
  const RnGroup r1(1);
  const auto eq = Equation<RnGroup>::general(
      r1, Eigen::VectorXd::Constant(1, 1.0), [](const Eigen::VectorXd& x) { return Eigen::VectorXd(x.array().sqrt() + 1.0); },
      [](const Eigen::VectorXd& x, const Eigen::VectorXd& u) { return Eigen::VectorXd(u.array() / (2.0 * x.array().sqrt())); });
  const SolveResult r = newton_group(eq, {.tol = 1e-13, .max_iterations = 100});
  expect_reason(r, Status::non_finite);
  EXPECT_EQ(r.y(0), -3.0);  // x1 = 1 - f/f' = 1 - 2 / (1/2)
  EXPECT_EQ(r.trace.size(), 2u);
}

TEST(FailureClasses, SingularDifferential) {
  const RnGroup r1(1);
  const auto eq = Equation<RnGroup>::general(
      r1, Eigen::VectorXd::Zero(1), [](const Eigen::VectorXd& x) { return Eigen::VectorXd(x.array().square() + 1.0); },
      [](const Eigen::VectorXd& x, const Eigen::VectorXd& u) { return Eigen::VectorXd(2.0 * x.array() * u.array()); });
  expect_reason(newton_group(eq, {.tol = 1e-13, .max_iterations = 100}), Status::singular_differential);
}

TEST(FailureClasses, LeftLogDomainWhenTheSolutionIsAtPi) {
  // |h w| = pi: the first Newton step (dexpinv_0 = Id) lands exactly on z^-1 y = exp(h w), angle pi.
  const ConstantField field(Eigen::Vector3d(0.0, std::numbers::pi, 0.0));
  const Eigen::Matrix3d z = start_point(3, 1);
  const auto eq = Equation<SO3Group>::implicit_euler(SO3Group{}, z, 1.0, field);
  const SolveResult r = newton_group(eq, {.tol = 1e-13, .max_iterations = 100});
  expect_reason(r, Status::left_log_domain);
  EXPECT_NE(r.reason.find("iterate 1 has rotation angle 3.14159"), std::string::npos) << r.reason;
  // f is undefined at the iterate that reached pi, so the answer is the last iterate inside log's domain,
  // y_0 = z, with its residual (the result describes the y it returns); the trace ends before pi.
  EXPECT_EQ(r.iterate, 0);
  EXPECT_LT((Eigen::Matrix3d(r.y) - z).norm(), 1e-15);
  EXPECT_EQ(r.residual, r.trace[0].residual);
  EXPECT_NEAR(r.residual, std::numbers::pi, 1e-12);
  EXPECT_EQ(r.trace.size(), 1u);
}

TEST(FailureClasses, OffBranchWhenHgTurnsBeyondPi) {
  // |h w| = 4 > pi: y = z exp(h w) solves (1.1) exactly, but log(z^-1 y) = (4 - 2 pi) w/|w| != h w.
  const ConstantField field(Eigen::Vector3d(0.0, 0.0, 4.0));
  const Eigen::Matrix3d z = start_point(3, 2);
  const auto eq = Equation<SO3Group>::implicit_euler(SO3Group{}, z, 1.0, field);
  const SolveResult fp = fixed_point(eq, {.tol = 1e-13, .max_iterations = 100});
  expect_reason(fp, Status::off_branch);
  EXPECT_LT((fp.y - z * so3::exp(Eigen::Vector3d(0, 0, 4.0))).norm(), 1e-14);
  EXPECT_NEAR(fp.residual, 2.0 * std::numbers::pi, 1e-12);
  // Version 2 never takes a log: it converges to v = h w and is flagged for the same reason.
  expect_reason(newton_algebra(eq, {.tol = 1e-13, .max_iterations = 100}), Status::off_branch);
}

TEST(FailureClasses, StagnatedAtTheRoundingFloorForLargeH) {
  // The floor ~ h eps ||g|| sqrt(q) is above tol = 1e-16: Newton reaches it in a few steps and stops decreasing.
  SolveRequest req;
  req.problem.n = 6;
  req.h = 2.0;
  req.solver.tol = 1e-16;
  req.solver.method = Method::newton_group;
  req.solver.differential = Differential::exact;
  const SolveResult r = solve(req);
  expect_reason(r, Status::stagnated);
  EXPECT_GT(r.residual, req.solver.tol);
  EXPECT_LT(r.residual, 1e-14);
  EXPECT_LT(r.iterations, 15);
  EXPECT_NE(r.reason.find("floor"), std::string::npos);
}

TEST(FailureClasses, CancelledByTheCallback) {
  SolveRequest req;
  req.solver.method = Method::fixed_point;
  int calls = 0;
  const SolveResult r = solve(req, [&](const TraceRecord&) { return ++calls < 3; });
  expect_reason(r, Status::cancelled);
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(r.trace.size(), 3u);
}

TEST(Validation, NamesTheOffendingField) {
  auto field_of = [](SolveRequest req) {
    try {
      solve(req);
    } catch (const RequestError& e) {
      return e.field() + (e.kind() == RequestError::Kind::invalid ? ":400" : ":422");
    }
    return std::string("accepted");
  };
  SolveRequest ok;
  SolveRequest bad = ok;
  bad.h = -1;
  EXPECT_EQ(field_of(bad), "h:400");
  bad = ok;
  bad.h = std::nan("");
  EXPECT_EQ(field_of(bad), "h:400");
  bad = ok;
  bad.problem.n = 1;
  EXPECT_EQ(field_of(bad), "n:400");
  bad = ok;
  bad.problem.kind = ProblemKind::rigid_body;
  bad.problem.n = 4;
  EXPECT_EQ(field_of(bad), "n:422");
  bad = ok;
  bad.problem.z = Eigen::MatrixXd::Constant(3, 3, 1.0);
  EXPECT_EQ(field_of(bad), "z:422");
  bad = ok;
  bad.problem.z = Eigen::MatrixXd::Identity(2, 2);
  EXPECT_EQ(field_of(bad), "z:400");
  bad = ok;
  bad.solver.tol = 0;
  EXPECT_EQ(field_of(bad), "tol:400");
  bad = ok;
  bad.solver.max_iterations = 0;
  EXPECT_EQ(field_of(bad), "max_iterations:400");
  // det -1 start points are allowed, as in the paper (O(N)): iterates stay in z SO(N).
  SolveRequest reflect = ok;
  reflect.problem.z = Eigen::Vector3d(1, 1, -1).asDiagonal().toDenseMatrix();
  EXPECT_EQ(field_of(reflect), "accepted");
  EXPECT_EQ(solve(reflect).status, Status::converged);
}

}  // namespace
}  // namespace lienewton
