// The linear algebra of the stiff stage solver (core/integrators/stage_decoupling.hpp, embedded_estimate.hpp) and
// what it buys on a stiff field:
//   - the decoupled blocks solve the dense simplified Newton system (I - h A (x) J) dK = r, and the filter is
//     (I - h gamma0 J)^-1, for every implicit RKMK tableau, against Eigen's dense LU;
//   - Radau IIA's embedded weights are Radau5's (Hairer & Wanner's radau5.f: gamma0 = 1 / U1, e = gamma0 DD);
//   - the embedded estimate shrinks like h^(s+1) on a smooth field (slope check);
//   - on a stiff spring-damper rigid body, steps far beyond the stiff scale land on the solution with a few Newton
//     iterations each, the simplified Newton keeping one Jacobian for many steps.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "core/groups/so3_group.hpp"
#include "core/integrate.hpp"
#include "core/integrators/embedded_estimate.hpp"
#include "core/integrators/methods.hpp"
#include "core/integrators/stage_decoupling.hpp"
#include "core/integrators/stepper.hpp"
#include "core/user_field/user_vector_field.hpp"
#include "core/problems.hpp"
#include "gtest_printers.hpp"
#include "stiff_body_reference_values.hpp"

namespace lienewton {
namespace {

using integrators::DecoupledNewtonMatrix;
using integrators::Form;
using integrators::Tableau;

std::vector<Integrator> implicit_rkmk() {
  std::vector<Integrator> out;
  for (Integrator i : kAllIntegrators)
    if (integrators::tableau_of(i).form == Form::implicit_rkmk) out.push_back(i);
  return out;
}

// Every implicit RKMK tableau's blocks against the dense sq x sq system, for a J with a stiff and an oscillating part
// and at a large and a small h.
TEST(StiffSolver, DecoupledBlocksSolveTheDenseSystem) {
  constexpr int q = 6;
  std::srand(7);
  const Eigen::MatrixXd j = -1e4 * Eigen::MatrixXd::Identity(q, q) + 50.0 * Eigen::MatrixXd::Random(q, q);
  for (Integrator integrator : implicit_rkmk()) {
    const Tableau& tab = integrators::tableau_of(integrator);
    const int s = tab.stages();
    DecoupledNewtonMatrix m(tab);
    for (double h : {1.0, 1e-5}) {
      ASSERT_TRUE(m.factorize(h, j)) << to_string(integrator);
      Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(s * q, s * q);
      for (int a = 0; a < s; ++a)
        for (int b = 0; b < s; ++b) dense.block(a * q, b * q, q, q) -= h * tab.a(a, b) * j;
      const Eigen::VectorXd r = Eigen::VectorXd::Random(s * q);
      const Eigen::VectorXd expected = dense.partialPivLu().solve(r);
      EXPECT_LE((m.solve(r) - expected).norm(), 1e-12 * expected.norm()) << to_string(integrator) << " h " << h;
      const double gamma0 = m.decoupling().gamma0;
      const Eigen::VectorXd x = Eigen::VectorXd::Random(q);
      const Eigen::VectorXd filtered =
          (Eigen::MatrixXd::Identity(q, q) - h * gamma0 * j).partialPivLu().solve(x);
      EXPECT_LE((m.filter(x) - filtered).norm(), 1e-12 * filtered.norm()) << to_string(integrator) << " h " << h;
    }
  }
}

// radau5.f (Hairer & Wanner, "Solving ODEs II", code published with the book): U1 = 1 / ((6 + 81^(1/3) - 9^(1/3)) / 30)
// is A^-1's real eigenvalue, and its estimate is (fac1 I - J)^-1 (f0 + sum_i DD_i Z_i / h) with fac1 = U1 / h,
// DD = (-(13 + 7 sqrt 6) / 3, (-13 + 7 sqrt 6) / 3, -1 / 3): in embedded_estimate.hpp's terms gamma0 = 1 / U1 and
// e = gamma0 DD.
TEST(StiffSolver, RadauWeightsAreRadau5s) {
  const Tableau& tab = integrators::tableau_of(Integrator::rkmk_radau3);
  const double gamma0 = (6.0 + std::cbrt(81.0) - std::cbrt(9.0)) / 30.0;
  const double s6 = std::sqrt(6.0);
  const Eigen::Vector3d dd(-(13.0 + 7.0 * s6) / 3.0, (-13.0 + 7.0 * s6) / 3.0, -1.0 / 3.0);
  const DecoupledNewtonMatrix m(tab);
  EXPECT_NEAR(m.decoupling().gamma0, gamma0, 1e-14);
  const integrators::EmbeddedWeights w = integrators::embedded_weights(tab, m.decoupling().gamma0);
  EXPECT_EQ(w.order, 3);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(w.e(i), gamma0 * dd(i), 1e-12) << i;
}

// The estimate of one step from the rigid body's start shrinks like h^(s+1): halving h divides it by 2^(s+1) within
// 25 % at h = 1/8 -> 1/16 -> 1/32.
TEST(StiffSolver, EmbeddedEstimateHasItsOrder) {
  const ProblemSpec problem{.kind = ProblemKind::rigid_body};
  const SO3Group group;
  for (Integrator integrator : implicit_rkmk()) {
    const Tableau& tab = integrators::tableau_of(integrator);
    auto field = make_field(group, problem);
    SolverOptions opt;
    opt.tol = 1e-15;
    integrators::Stepper<SO3Group> stepper(group, *field, tab, opt, Predictor::lie_euler);
    std::vector<double> sizes;
    for (double h : {1.0 / 8, 1.0 / 16, 1.0 / 32}) {
      StepRecord rec;
      ASSERT_TRUE(stepper.take(group.element(problem.start()), 0.0, h, rec)) << stepper.failure();
      sizes.push_back(stepper.error_estimate(false, rec).norm());
    }
    const double expected = std::ldexp(1.0, stepper.estimate_order() + 1);
    for (std::size_t k = 1; k < sizes.size(); ++k)
      EXPECT_NEAR(sizes[k - 1] / sizes[k] / expected, 1.0, 0.25) << to_string(integrator) << " " << sizes[k];
  }
}

ProblemSpec stiff_body(double k) {
  ProblemSpec p{.kind = ProblemKind::stiff_body, .group = "SOxR", .n = 3};
  p.stiff_body.k = k;
  return p;
}

// Steps far beyond the stiff scale (h = 0.1 at k = c = 1e4 ... 1e8: h ||dg|| up to 1e7) converge on the stiff body
// with at most 6 Newton iterations per step for every implicit RKMK method (the exact Newton), every step starting
// linearly implicit instead of following the branch from h = 0. The simplified Newton reaches the same state
// with fewer Jacobians than steps, and counts what it formed.
TEST(StiffSolver, LargeStepsOnTheStiffBodyCostAFewIterations) {
  for (double k : {1e4, 1e6, 1e8}) {
    for (Integrator integrator : implicit_rkmk()) {
      IntegrateRequest req{.problem = stiff_body(k), .h = 0.1, .t_end = 1.0, .integrator = integrator,
                           .reference = false};
      const IntegrateResult r = integrate(req);
      ASSERT_EQ(r.status, Status::converged) << to_string(integrator) << " k " << k << ": " << r.reason;
      EXPECT_LE(r.mean_iterations, 6.0) << to_string(integrator) << " k " << k;
      ASSERT_TRUE(r.jacobian_evaluations && r.factorizations);
      EXPECT_EQ(*r.jacobian_evaluations, r.total_iterations) << "the exact Newton forms one matrix per iteration";
    }
    IntegrateRequest exact{.problem = stiff_body(k), .h = 0.1, .t_end = 1.0, .integrator = Integrator::rkmk_radau3,
                           .reference = false};
    IntegrateRequest simplified = exact;
    simplified.solver.differential = Differential::dexpinv_0;
    const IntegrateResult a = integrate(exact), b = integrate(simplified);
    ASSERT_EQ(b.status, Status::converged) << b.reason;
    EXPECT_LE((a.y - b.y).norm(), 1e-9) << "k " << k;
    EXPECT_LT(*b.jacobian_evaluations, static_cast<int>(b.steps.size())) << "k " << k;
    EXPECT_LE(*b.factorizations, *b.jacobian_evaluations) << "fixed h: one factorization per Jacobian";
  }
}

// Adaptive steps with the embedded estimate do not collapse in the stiff body's initial layer: at k = c = 1e6,
// rtol = atol = 1e-6, from a first step of 0.1, a few dozen steps reach t = 1 within 1e-5 of the scipy-checked state
// at k = 1e6 (tests/core/stiff_body_reference_values.hpp), and no step is shorter than 1e-7.
TEST(StiffSolver, AdaptiveStepsCrossTheStiffLayer) {
  IntegrateRequest req{.problem = stiff_body(1e6), .h = 0.1, .t_end = 1.0, .integrator = Integrator::rkmk_radau3,
                       .reference = false};
  req.rtol = req.atol = 1e-6;
  req.solver.differential = Differential::dexpinv_0;
  const IntegrateResult r = integrate(req);
  ASSERT_EQ(r.status, Status::converged) << r.reason;
  EXPECT_LE(r.steps.size(), 100u);
  for (const StepRecord& s : r.steps) EXPECT_GE(s.h, 1e-7) << "t " << s.t;
  const test::StiffBodyCase& scipy = test::kStiffBodyCases[1];
  ASSERT_EQ(scipy.k, 1e6);
  Eigen::MatrixXd expected = Eigen::MatrixXd::Identity(7, 7);
  expected.topLeftCorner(3, 3) = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(scipy.rotation);
  expected.block(3, 6, 3, 1) = Eigen::Map<const Eigen::Vector3d>(scipy.omega);
  EXPECT_LE((r.y - expected).norm(), 1e-5);
  std::printf("adaptive radau3 at k = 1e6: %zu steps, %d rejected, %d Jacobians, %d factorizations\n",
              r.steps.size(), r.rejected, *r.jacobian_evaluations, *r.factorizations);
}

}  // namespace
}  // namespace lienewton
