// The abelian group R^n behind the group interface: exp = log = Id, compose = +, ad = 0, dexp = dexpinv = Id,
// so that the solvers reduce to classical Newton there.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "core/solvers/run_method.hpp"
#include "rn_group.hpp"

namespace lienewton {
namespace {

Eigen::VectorXd random_vector(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = normal(rng);
  return v;
}

TEST(RnGroup, BasicIdentitiesHoldExactly) {
  std::mt19937_64 rng(1);
  for (int n : {1, 2, 5, 40}) {
    const RnGroup g(n);
    EXPECT_EQ(g.n(), n);
    EXPECT_EQ(g.dim(), n);
    EXPECT_EQ(zero_vector(g), Eigen::VectorXd::Zero(n));
    EXPECT_EQ(g.identity(), Eigen::VectorXd::Zero(n));
    for (int i = 0; i < n; ++i) EXPECT_EQ(basis_vector(g, i), Eigen::VectorXd::Unit(n, i));
    EXPECT_EQ(zero_operator(g), Eigen::MatrixXd::Zero(n, n));
    const Eigen::VectorXd a = random_vector(n, rng), b = random_vector(n, rng), u = random_vector(n, rng);
    EXPECT_EQ(g.compose(a, b), a + b);
    EXPECT_EQ(g.compose(a, b), g.compose(b, a));  // abelian
    EXPECT_EQ(g.compose(a, g.inverse(a)), g.identity());
    EXPECT_EQ(g.compose(g.identity(), a), a);
    EXPECT_EQ(g.exp(a), a);
    EXPECT_EQ(g.vector(g.log(a)), a);
    EXPECT_EQ(g.vector(g.spectral(a)), a);
    EXPECT_EQ(g.hat(a), a);
    EXPECT_EQ(g.vee(a), a);
    EXPECT_EQ(g.bracket(a, b), Eigen::VectorXd::Zero(n));
    EXPECT_EQ(g.dexp(g.spectral(a), u), u);
    EXPECT_EQ(g.dexpinv(g.log(a), u), u);
    EXPECT_EQ(g.angle(g.log(a)), 0.0);
    EXPECT_TRUE(inside_log_domain<RnGroup>(g.angle(g.log(1e300 * a))));  // no domain edge
    EXPECT_EQ(g.defect(a), 0.0);
    // exp is a homomorphism of the abelian group: exp(a + b) = exp(a) exp(b); BCH is a + b.
    EXPECT_EQ(g.exp(a + b), g.compose(g.exp(a), g.exp(b)));
    EXPECT_EQ(g.vector(g.log(g.compose(g.exp(a), g.exp(b)))), a + b);
  }
}

// On R^n Version 1 is classical Newton: on an affine f(y) = A y - c it lands on the solution in one step
// (to rounding: residual <= 1e-13) and reports iterations = 1.
TEST(RnGroup, NewtonIsClassicalNewton) {
  std::mt19937_64 rng(2);
  const int n = 6;
  const RnGroup g(n);
  Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) += 0.1 * random_vector(1, rng)(0);
  const Eigen::VectorXd c = random_vector(n, rng);
  const Eigen::VectorXd z = random_vector(n, rng);
  const auto eq = Equation<RnGroup>::general(
      g, z, [&](const Eigen::VectorXd& y) { return Eigen::VectorXd(a * y - c); },
      [&](const Eigen::VectorXd&, const Eigen::VectorXd& u) { return Eigen::VectorXd(a * u); });
  SolverOptions opt;
  opt.tol = 1e-13;
  const SolveResult exact = newton_group(eq, opt);
  EXPECT_EQ(exact.status, Status::converged);
  EXPECT_EQ(exact.iterations, 1);
  const Eigen::VectorXd y = exact.y;
  EXPECT_LE((y - a.partialPivLu().solve(c)).norm(), 1e-13);
  // Version 2 starts at v = 0 (y = z) and takes the same step.
  const SolveResult algebra = newton_algebra(eq, opt);
  EXPECT_EQ(algebra.status, Status::converged);
  EXPECT_EQ(algebra.iterations, 1);
  EXPECT_LE((Eigen::VectorXd(algebra.y) - y).norm(), 1e-13);
}

// A nonlinear f on R^n: quadratic convergence, as classical Newton (residual ratios r_{k+1} / r_k^2 bounded).
TEST(RnGroup, NewtonConvergesQuadraticallyOnNonlinearF) {
  const int n = 3;
  const RnGroup g(n);
  // f(y) = (y0^2 + y1 - 2, y1^3 - y2, exp(y2) - 1 + y0 - 1): root near (1, 1, 1)... solved from z = (1.2, 0.8, 0.9)
  auto f = [](const Eigen::VectorXd& y) {
    Eigen::VectorXd r(3);
    r << y(0) * y(0) + y(1) - 2.0, y(1) * y(1) * y(1) - y(2), std::exp(y(2) - 1.0) + y(0) - 2.0;
    return r;
  };
  auto df = [](const Eigen::VectorXd& y, const Eigen::VectorXd& u) {
    Eigen::Matrix3d j;
    j << 2 * y(0), 1, 0, 0, 3 * y(1) * y(1), -1, 1, 0, std::exp(y(2) - 1.0);
    return Eigen::VectorXd(j * u);
  };
  const auto eq = Equation<RnGroup>::general(g, Eigen::Vector3d(1.2, 0.8, 0.9), f, df);
  SolverOptions opt;
  opt.tol = 1e-14;
  const SolveResult res = newton_group(eq, opt);
  ASSERT_EQ(res.status, Status::converged);
  EXPECT_LE((Eigen::VectorXd(res.y) - Eigen::Vector3d(1, 1, 1)).norm(), 1e-13);
  EXPECT_LE(res.iterations, 7);
  ASSERT_GE(res.trace.size(), 3u);
  for (std::size_t k = 1; k + 1 < res.trace.size(); ++k) {
    const double r0 = res.trace[k - 1].residual, r1 = res.trace[k].residual;
    if (r1 > 1e-10) {
      EXPECT_LE(r1, 10.0 * r0 * r0) << "not quadratic at k = " << k;
    }
  }
}

}  // namespace
}  // namespace lienewton
