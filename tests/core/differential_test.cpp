// The assembled Newton matrices against independent truth: column-by-column application, and central
// differences of f with a step-size slope check.
#include <gtest/gtest.h>

#include <limits>

#include "core/solve.hpp"
#include "core/solvers/run_method.hpp"
#include "core/start_point.hpp"
#include "gtest_printers.hpp"

namespace lienewton {
namespace {

template <class G>
Equation<G> equation(const G& g, const VectorField<G>& field, std::uint64_t seed, double h) {
  return Equation<G>::implicit_euler(g, typename G::Element(start_point(g.n(), seed)), h, field);
}

class Differentials : public ::testing::TestWithParam<std::tuple<ProblemKind, int>> {};

TEST_P(Differentials, AssembledMatricesMatchColumnApplication) {
  const auto [problem, n] = GetParam();
  const SONGroup g(n);
  const auto field = make_field(g, problem, RigidBodyParams{});
  const auto eq = equation(g, *field, 3, 0.7);
  const Eigen::MatrixXd y1 = g.times_exp(eq.z(), 0.3 * Eigen::VectorXd::LinSpaced(g.dim(), -1, 1));
  const auto p1 = eq.at(y1);
  const auto p2 = eq.at_algebra(0.3 * Eigen::VectorXd::LinSpaced(g.dim(), 1, -0.5));
  for (Differential d : {Differential::dexpinv_0, Differential::dexpinv_1, Differential::exact}) {
    const Eigen::MatrixXd m1 = eq.df_matrix(p1, d), m2 = eq.dftilde_matrix(p2, d);
    for (int i = 0; i < g.dim(); ++i) {
      EXPECT_LT((m1.col(i) - eq.df(p1, basis_vector(g, i), d)).norm(), 1e-13 * (1 + m1.norm())) << to_string(d) << " col " << i;
      EXPECT_LT((m2.col(i) - eq.dftilde(p2, basis_vector(g, i), d)).norm(), 1e-13 * (1 + m2.norm())) << to_string(d) << " col " << i;
    }
  }
  // dg's structured matrix equals the generic column loop.
  const Eigen::MatrixXd dg = field->dg_matrix(g, y1);
  for (int i = 0; i < g.dim(); ++i) EXPECT_LT((dg.col(i) - field->dg(y1, basis_vector(g, i))).norm(), 1e-13 * (1 + dg.norm()));
}

// The exact Newton step's factored form D = A P^T (SO(N), equation.hpp df_factored / dftilde_factored): P
// orthogonal to rounding (its entries are 2x2 minors of Q), and A P^T equal to the matrix-free differential
// (two N^3 products with Q per application, no P) column by column.
TEST_P(Differentials, FactoredMatricesMatchColumnApplication) {
  const auto [problem, n] = GetParam();
  const SONGroup g(n);
  const auto field = make_field(g, problem, RigidBodyParams{});
  const auto eq = equation(g, *field, 3, 0.7);
  const auto p1 = eq.at(g.times_exp(eq.z(), 0.3 * Eigen::VectorXd::LinSpaced(g.dim(), -1, 1)));
  const auto p2 = eq.at_algebra(0.3 * Eigen::VectorXd::LinSpaced(g.dim(), 1, -0.5));
  const auto f1 = eq.df_factored(p1, Differential::exact);
  const auto f2 = eq.dftilde_factored(p2, Differential::exact);
  ASSERT_TRUE(f1.basis && f2.basis);
  const int q = g.dim();
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  for (const Eigen::MatrixXd* b : {&*f1.basis, &*f2.basis})
    EXPECT_LT((b->transpose() * *b - Eigen::MatrixXd::Identity(q, q)).norm(), 16.0 * n * kEps * q);
  const Eigen::MatrixXd m1 = f1.a * f1.basis->transpose(), m2 = f2.a * f2.basis->transpose();
  for (int i = 0; i < q; ++i) {
    const Eigen::VectorXd e = basis_vector(g, i);
    EXPECT_LT((m1.col(i) - eq.df(p1, e, Differential::exact)).norm(), 1e-13 * (1 + m1.norm())) << "col " << i;
    EXPECT_LT((m2.col(i) - eq.dftilde(p2, e, Differential::exact)).norm(), 1e-13 * (1 + m2.norm())) << "col " << i;
  }
}

TEST_P(Differentials, ExactDifferentialMatchesCentralDifferencesWithSlopeTwo) {
  const auto [problem, n] = GetParam();
  const SONGroup g(n);
  const auto field = make_field(g, problem, RigidBodyParams{});
  const auto eq = equation(g, *field, 5, 0.4);
  const Eigen::MatrixXd y = g.times_exp(eq.z(), 0.2 * Eigen::VectorXd::LinSpaced(g.dim(), 1, -1));
  const auto p = eq.at(y);
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(g.dim(), -0.3, 0.7).normalized();
  const Eigen::VectorXd exact = eq.df(p, u, Differential::exact);
  // (3.4): df_y(u) = d/dt f(y exp(t u)); the central difference error must fall like t^2.
  std::vector<double> err;
  for (double t : {1e-2, 5e-3, 2.5e-3}) {
    const Eigen::VectorXd c = (eq.at(g.times_exp(y, t * u)).f - eq.at(g.times_exp(y, -t * u)).f) / (2 * t);
    err.push_back((c - exact).norm());
  }
  EXPECT_NEAR(err[0] / err[1], 4.0, 0.4);
  EXPECT_NEAR(err[1] / err[2], 4.0, 0.4);
  EXPECT_LT(err[2], 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Problems, Differentials,
                         ::testing::Combine(::testing::Values(ProblemKind::paper_linear, ProblemKind::paper_sine),
                                            ::testing::Values(2, 3, 5, 8)));

TEST(Krylov, MatrixFreeNewtonAgreesWithDenseAndStaysQuadratic) {
  for (Method m : {Method::newton_group, Method::newton_algebra}) {
    for (Differential d : {Differential::exact, Differential::finite_difference}) {
      SolveRequest req;
      req.problem.n = 12;
      req.h = 0.25;
      req.solver.method = m;
      req.solver.differential = d;
      req.solver.linear_solver = LinearSolver::lu;
      const SolveResult dense = solve(req);
      req.solver.linear_solver = LinearSolver::gmres;
      const SolveResult krylov = solve(req);
      ASSERT_EQ(krylov.status, Status::converged) << krylov.reason;
      EXPECT_EQ(krylov.linear_solver, Factorization::gmres);
      EXPECT_EQ(dense.linear_solver, Factorization::dense_lu);
      EXPECT_LT((krylov.y - dense.y).norm(), 1e-12) << to_string(m) << " " << to_string(d);
      EXPECT_LE(krylov.iterations, dense.iterations + 1);
      ASSERT_TRUE(krylov.rate.has_value());
      EXPECT_GT(*krylov.rate, 1.6) << to_string(m) << " " << to_string(d);
    }
  }
}

TEST(Krylov, ChosenAutomaticallyAboveTheThreshold) {
  SolveRequest req;
  req.problem.n = kKrylovThreshold + 1;
  req.h = 0.25;
  req.solver.max_iterations = 1;
  EXPECT_EQ(solve(req).linear_solver, Factorization::gmres);
  req.problem.n = kKrylovThreshold;
  EXPECT_EQ(solve(req).linear_solver, Factorization::dense_lu);
}

}  // namespace
}  // namespace lienewton
