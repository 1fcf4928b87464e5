// The higher-order integrators: the implicit RKMK methods, rkmk4 and dirk-cg3. Their orders fitted against an
// independent reference (RK4 on the matrix ODE, nothing shared with the project's RKMK4 reference), y' = y A
// integrated exactly, and Newton's quadratic convergence on the coupled stage system.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/integrate.hpp"
#include "core/order_fit.hpp"
#include "core/problems.hpp"
#include "core/request_error.hpp"
#include "core/integrators/methods.hpp"
#include "core/integrators/rkmk_stages.hpp"
#include "core/work_precision.hpp"
#include "matrix_ode_reference.hpp"

namespace lienewton {
namespace {

struct OrderCase {
  Integrator integrator;
  std::vector<double> h;  // in the asymptotic range on both problems: errors from ~1e-3 down to ~1e-11
};

void PrintTo(const OrderCase& c, std::ostream* os) { *os << to_string(c.integrator); }

std::string name_of(const ::testing::TestParamInfo<OrderCase>& info) {
  std::string s(to_string(info.param.integrator));
  for (char& c : s)
    if (c == '-') c = '_';
  return s;
}

class FittedOrder : public ::testing::TestWithParam<OrderCase> {};

constexpr double kTEnd = 2.0;

void expect_order(const OrderCase& c, const ProblemSpec& problem,
                  const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& g) {
  const Eigen::MatrixXd y_ref = test::matrix_ode_reference(g, problem.start(), kTEnd);
  std::vector<double> errors;
  for (double h : c.h) {
    IntegrateRequest req{.problem = problem, .h = h, .t_end = kTEnd, .integrator = c.integrator, .reference = false};
    req.solver.tol = 1e-15;
    const IntegrateResult r = integrate(req);
    ASSERT_EQ(r.status, Status::converged) << r.reason;
    errors.push_back((r.y - y_ref).norm());
  }
  const AsymptoticRange range = asymptotic_range(c.h, errors);
  EXPECT_GE(range.indices.size(), 4u);
  EXPECT_NEAR(range.order.value(), order_of(c.integrator), 0.15) << to_string(c.integrator);
}

TEST_P(FittedOrder, RigidBody) {
  ProblemSpec problem{.kind = ProblemKind::rigid_body};
  const RigidBody body{problem.rigid_body};
  expect_order(GetParam(), problem, [&](const Eigen::MatrixXd& y) { return Eigen::MatrixXd(body.g(Eigen::Matrix3d(y))); });
}

TEST_P(FittedOrder, PaperLinearN5) {
  const ProblemSpec problem{.kind = ProblemKind::paper_linear, .n = 5};
  expect_order(GetParam(), problem, [](const Eigen::MatrixXd& y) { return PaperLinear{}.g(y); });
}

INSTANTIATE_TEST_SUITE_P(
    Integrators, FittedOrder,
    ::testing::Values(OrderCase{Integrator::rkmk_gauss1, {1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64}},
                      OrderCase{Integrator::rkmk_gauss2, {1.0 / 4, 1.0 / 8, 1.0 / 16, 1.0 / 32}},
                      OrderCase{Integrator::rkmk_gauss3, {1.0 / 4, 1.0 / 5, 1.0 / 6, 1.0 / 7, 1.0 / 8}},
                      OrderCase{Integrator::rkmk_radau2, {1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64}},
                      OrderCase{Integrator::rkmk_radau3, {1.0 / 4, 1.0 / 6, 1.0 / 8, 1.0 / 16}},
                      OrderCase{Integrator::rkmk_lobatto3c, {1.0 / 4, 1.0 / 8, 1.0 / 16, 1.0 / 32}},
                      OrderCase{Integrator::dirk_cg3, {1.0 / 8, 1.0 / 16, 1.0 / 32, 1.0 / 64}},
                      OrderCase{Integrator::rkmk4, {1.0 / 4, 1.0 / 8, 1.0 / 16, 1.0 / 32}}),
    name_of);

const Integrator kRkmk[] = {Integrator::rkmk_gauss1, Integrator::rkmk_gauss2, Integrator::rkmk_gauss3,
                            Integrator::rkmk_radau2, Integrator::rkmk_radau3, Integrator::rkmk_lobatto3c,
                            Integrator::rkmk4};

// y' = y A, A constant: K_i = A solves every stage system (each bracket [c_i h A, A] vanishes), so every RKMK step is
// y exp(hA) and the integration is exact; checked against Eigen's matrix exponential, on SO(3) and SO(5), to the
// rounding of one exp and one product per step (16 eps ||y|| each, 4.8e-14 over these 6 steps): how far below that
// the error lands is rounding's choice, and differs between CPUs.
TEST(Rkmk, ConstantFieldIsIntegratedExactly) {
  for (int n : {3, 5}) {
    Eigen::MatrixXd a(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) a(i, j) = i < j ? 0.125 * (1 + i + 2 * j) * (j % 2 ? 1 : -1) : 0.0;
    a -= Eigen::MatrixXd(a.transpose());
    std::string literal = "[";  // A as the user's program: g(y) = A
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) literal += std::to_string(a(i, j)) + (j + 1 < n ? " " : i + 1 < n ? "; " : "]");
    ProblemSpec problem{.n = n};
    problem.g = literal;
    const Eigen::MatrixXd exact = problem.start() * Eigen::MatrixXd(3.0 * a).exp();
    for (Integrator integrator : kRkmk) {
      const IntegrateRequest req{.problem = problem, .h = 0.5, .t_end = 3.0, .integrator = integrator,
                                 .reference = false};
      const IntegrateResult r = integrate(req);
      ASSERT_EQ(r.status, Status::converged) << r.reason;
      const double rounding = 16 * std::numeric_limits<double>::epsilon() * exact.norm() * (req.t_end / *req.h);
      EXPECT_LT((r.y - exact).norm(), rounding) << to_string(integrator) << " N = " << n;
    }
  }
}

// Newton with the exact Jacobian of the truncated coupled system converges quadratically: the paper's rate
// r = log(r_p-1 / r_p-2) / log(r_p-2 / r_p-3) of the stage residuals h ||F(K_n)|| (section 5), from K = 0, on
// paper-linear N = 5 at h = 1 (four iterations above rounding).
TEST(Rkmk, ExactJacobianConvergesQuadratically) {
  for (Integrator integrator : {Integrator::rkmk_gauss2, Integrator::rkmk_gauss3, Integrator::rkmk_radau3}) {
    const SONGroup group(5);
    const auto field = make_field(group, ProblemKind::paper_linear, RigidBodyParams{});
    const ProblemSpec problem{.kind = ProblemKind::paper_linear, .n = 5};
    const RkmkStages<SONGroup> sys(group, *field, integrators::tableau_of(integrator), problem.start(), 0.0, 1.0);
    SolverOptions opt;
    opt.tol = 1e-16;
    const StageSolution s = sys.solve(Eigen::VectorXd::Zero(sys.size()), Method::newton_group, Differential::exact, opt);
    ASSERT_EQ(s.status, Status::converged) << s.reason;
    const auto& r = s.residuals;
    ASSERT_GE(r.size(), 5u);
    const std::size_t p = r.size() - 1;
    const double rate = std::log(r[p - 1] / r[p - 2]) / std::log(r[p - 2] / r[p - 3]);
    EXPECT_NEAR(rate, 2.0, 0.2) << to_string(integrator) << ": " << r[p - 3] << " " << r[p - 2] << " " << r[p - 1];
  }
}

// Every way to solve the stage system reaches the same stages: Newton with the exact, truncated-and-frozen and
// finite-difference matrices, and the fixed point, each step to its tolerance.
TEST(Rkmk, EveryDifferentialAndMethodReachesTheSameStep) {
  IntegrateRequest req{.h = 1.0 / 8, .t_end = 1.0, .integrator = Integrator::rkmk_gauss2, .reference = false};
  const Eigen::MatrixXd exact = integrate(req).y;
  for (Method m : kAllMethods)
    for (Differential d : kAllDifferentials) {
      req.solver.method = m;
      req.solver.differential = d;
      const IntegrateResult r = integrate(req);
      ASSERT_EQ(r.status, Status::converged) << r.reason;
      EXPECT_LT((r.y - exact).norm(), 1e-11) << to_string(m) << " " << to_string(d);
      EXPECT_GT(r.total_iterations, 0);
    }
}

// Which root: from K = 0 (predictor none) the stages must reach the same root, continued from h = 0, as from the
// extrapolation; on paper-sine N = 5 at h = 1/4, where a DIRK stage from its Z_i lands on a distant root. There
// h ||dg|| > 1 at every step, so both start linearly implicit from K = 0 (rkmk_stages.hpp) and cost about the same
// (the extrapolation is tried first where the last step passed the tangent's test, and its root, not certified on
// this non-dissipative field, costs a few iterations); at h = 1/64, inside the tangent's regime, the extrapolation
// saves iterations.
TEST(Rkmk, PredictorNoneKeepsTheContinuedRoot) {
  for (Integrator integrator : {Integrator::rkmk_gauss2, Integrator::rkmk_radau3})
    for (double h : {0.25, 1.0 / 64}) {
      IntegrateRequest req{.problem = {.kind = ProblemKind::paper_sine, .n = 5}, .h = h, .t_end = 1.0,
                           .integrator = integrator, .reference = false};
      const IntegrateResult extrapolated = integrate(req);
      req.predictor = Predictor::none;
      const IntegrateResult from_zero = integrate(req);
      ASSERT_EQ(extrapolated.status, Status::converged) << extrapolated.reason;
      ASSERT_EQ(from_zero.status, Status::converged) << from_zero.reason;
      EXPECT_LT((from_zero.y - extrapolated.y).norm(), 1e-11) << to_string(integrator);
      if (h == 0.25) {
        EXPECT_NEAR(from_zero.total_iterations, extrapolated.total_iterations, 0.05 * from_zero.total_iterations)
            << to_string(integrator);
      } else {
        EXPECT_GT(from_zero.total_iterations, extrapolated.total_iterations) << to_string(integrator);
      }
    }
}

// The dense stage system is refused where the dense Newton step ends (n > 16 on SO(n)), naming the integrator; on
// the integrate request and on every work-precision choice.
TEST(Rkmk, LargeStageSystemsAreRefused) {
  const IntegrateRequest req{.problem = {.kind = ProblemKind::paper_linear, .n = 17}, .h = 0.5,
                             .integrator = Integrator::rkmk_gauss3};
  try {
    validate(req);
    ADD_FAILURE() << "n = 17 accepted";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "integrator");
  }
  WorkPrecisionRequest wp{.problem = req.problem};
  wp.choices = {{Integrator::implicit_euler}, {Integrator::rkmk_radau2}};
  EXPECT_THROW(validate(wp), RequestError);
  wp.choices.pop_back();
  EXPECT_NO_THROW(validate(wp));
}

// A solver option the integrator's steps would not use is a 422 naming it, not ignored: implicit RKMK methods solve
// their stage system by their own Newton, rkmk4 solves nothing, and no stage takes seeded starts. A DIRK method's
// stages are equations of (1.1): they take every option, and the globalised run still converges.
TEST(Rkmk, OptionsTheStagesDoNotUseAreRefusedNamingThem) {
  const auto refused_field = [](IntegrateRequest req) -> std::string {
    try {
      validate(req);
    } catch (const RequestError& e) {
      return e.field();
    }
    return "";
  };
  const auto with = [](Integrator integrator, auto set) {
    IntegrateRequest req{.h = 0.25, .integrator = integrator, .reference = false};
    set(req.solver);
    return req;
  };
  for (Integrator i : {Integrator::rkmk_gauss2, Integrator::rkmk_lobatto3c, Integrator::rkmk4}) {
    EXPECT_EQ(refused_field(with(i, [](SolverOptions& o) { o.globalization = Globalization::line_search; })),
              "globalization") << to_string(i);
    EXPECT_EQ(refused_field(with(i, [](SolverOptions& o) { o.linear_solver = LinearSolver::gmres; })), "linear_solver");
    EXPECT_EQ(refused_field(with(i, [](SolverOptions& o) { o.stopping = Stopping::algebra_residual; })), "stopping");
    EXPECT_EQ(refused_field(with(i, [](SolverOptions& o) { o.linear_solver = LinearSolver::lu; })), "");
  }
  for (Integrator i : kAllIntegrators)
    EXPECT_EQ(refused_field(with(i, [](SolverOptions& o) { o.multistart = 4; })), "multistart") << to_string(i);
  const IntegrateRequest dirk = with(Integrator::dirk_cg2, [](SolverOptions& o) {
    o.globalization = Globalization::line_search;
    o.linear_solver = LinearSolver::gmres;
  });
  EXPECT_EQ(refused_field(dirk), "");
  const IntegrateResult r = integrate(dirk);
  EXPECT_EQ(r.status, Status::converged) << r.reason;
}

}  // namespace
}  // namespace lienewton
