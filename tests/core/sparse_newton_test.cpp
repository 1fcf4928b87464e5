// The structured Newton on (SE(3) x R^6)^k (newton_step.hpp, stage_decoupling.hpp, rkmk_stages.hpp): with the
// spring chain (block-tridiagonal dg), every solver variant and the integrators land where the dense LU lands on the
// same system (the bound dense_lu_max_dim() moved to force either path), and each reports the factorization it used.
// Both paths solve to tol 1e-12 a system whose Newton matrix is well conditioned (h ||dg|| < 1), so their roots agree
// far within 1e-9 whatever the rounding.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <algorithm>
#include <climits>
#include <cmath>
#include <string>
#include <vector>

#include "core/integrators/methods.hpp"
#include "core/integrators/stepper.hpp"
#include "core/solvers/run_method.hpp"
#include "spring_chain_field.hpp"

namespace lienewton {
namespace {

using G = SE3xR6PowerGroup;

// Moves the dense/sparse bound for one scope: 0 factors every sparse Newton matrix sparse, INT_MAX densely.
class DenseLuBound {
 public:
  explicit DenseLuBound(int bound) : saved_(dense_lu_max_dim()) { dense_lu_max_dim() = bound; }
  ~DenseLuBound() { dense_lu_max_dim() = saved_; }
  DenseLuBound(const DenseLuBound&) = delete;
  DenseLuBound& operator=(const DenseLuBound&) = delete;

 private:
  int saved_;
};

constexpr int kSparse = 0, kDense = INT_MAX;

struct Variant {
  Method method;
  Differential differential;
  Globalization globalization = Globalization::none;
};

std::string name_of(const Variant& v) {
  return std::string(to_string(v.method)) + " " + std::string(to_string(v.differential)) + " " +
         std::string(to_string(v.globalization));
}

SolveResult solve_with(int bound, const Equation<G>& eq, const Variant& v) {
  const DenseLuBound scope(bound);
  SolverOptions opt;
  opt.method = v.method;
  opt.differential = v.differential;
  opt.globalization = v.globalization;
  opt.tol = 1e-12;
  return run_method(v.method, eq, opt, {});
}

TEST(SparseNewton, EveryVariantLandsWhereTheDenseLuLands) {
  const G group(6);  // 72 unknowns
  const test::SpringChain field(group, 1.0);
  const auto eq = Equation<G>::implicit_euler(group, group.random(5), 0.1, field);
  std::vector<Variant> variants = {{Method::fixed_point, Differential::exact}};
  for (Method m : {Method::newton_group, Method::newton_algebra})
    for (Differential d : kAllDifferentials) variants.push_back({m, d});
  for (Globalization g : {Globalization::line_search, Globalization::trust_region})
    variants.push_back({Method::newton_group, Differential::exact, g});
  for (const Variant& v : variants) {
    const SolveResult sparse = solve_with(kSparse, eq, v), dense = solve_with(kDense, eq, v);
    ASSERT_EQ(sparse.status, Status::converged) << name_of(v) << ": " << sparse.reason;
    ASSERT_EQ(dense.status, Status::converged) << name_of(v) << ": " << dense.reason;
    EXPECT_EQ(sparse.linear_solver, Factorization::sparse_lu) << name_of(v);
    EXPECT_EQ(dense.linear_solver, Factorization::dense_lu) << name_of(v);
    EXPECT_LE((sparse.y - dense.y).norm(), 1e-9) << name_of(v);
    EXPECT_LE(sparse.residual, 1e-12) << name_of(v);
  }
}

// The default bound: 12 bodies (144 unknowns) are factored densely, 13 (156) sparse; the body count never picks
// GMRES (20 bodies: n = 20 is above SO(N)'s Krylov threshold), which still runs when asked and agrees.
TEST(SparseNewton, TheBoundAndNotTheBodyCountPicksTheFactorization) {
  const Variant newton{Method::newton_group, Differential::exact};
  for (const auto& [k, expected] : {std::pair{12, Factorization::dense_lu}, std::pair{13, Factorization::sparse_lu},
                                    std::pair{20, Factorization::sparse_lu}}) {
    const G group(k);
    const test::SpringChain field(group, 1.0);
    const auto eq = Equation<G>::implicit_euler(group, group.random(9), 0.1, field);
    const SolveResult r = solve_with(kDenseLuMaxDim, eq, newton);
    ASSERT_EQ(r.status, Status::converged) << k << ": " << r.reason;
    EXPECT_EQ(r.linear_solver, expected) << k;
    if (k != 20) continue;
    SolverOptions opt;
    opt.tol = 1e-12;
    opt.linear_solver = LinearSolver::gmres;
    const SolveResult gmres = newton_group(eq, opt);
    ASSERT_EQ(gmres.status, Status::converged) << gmres.reason;
    EXPECT_EQ(gmres.linear_solver, Factorization::gmres);
    EXPECT_LE((gmres.y - r.y).norm(), 1e-9);
  }
}

// Continuation's search (its bordered system, sparse or dense) ends at the same root, at an h small enough to solve
// directly and at one whose path has to be followed.
TEST(SparseNewton, ContinuationLandsWhereTheDenseLuLands) {
  const G group(6);
  const test::SpringChain field(group, 1.0);
  for (double h : {0.1, 4.0}) {
    const auto eq = Equation<G>::implicit_euler(group, group.random(11), h, field);
    std::vector<SolveResult> results;
    for (int bound : {kSparse, kDense}) {
      const DenseLuBound scope(bound);
      SolverOptions opt;
      opt.tol = 1e-12;
      results.push_back(continued_root(Method::newton_group, eq, opt, {}, FirstTry::tangent));
    }
    EXPECT_EQ(results[0].status, results[1].status) << h << ": " << results[0].reason << " / " << results[1].reason;
    if (results[0].status == Status::converged) {
      EXPECT_LE((results[0].y - results[1].y).norm(), 1e-9) << h;
    }
  }
}

// Steps of dirk-cg2 (stages through the equation solvers) and rkmk-radau3 (coupled stages: the exact Jacobian, and
// the simplified Newton's decoupled real and complex blocks) end where the dense LU's steps end.
TEST(SparseNewton, IntegratorStepsMatchTheDenseLu) {
  const G group(6);
  test::SpringChain field(group, 1.0);
  const G::Element y0 = group.random(3);
  for (Integrator integrator : {Integrator::dirk_cg2, Integrator::rkmk_radau3})
    for (Differential d : {Differential::exact, Differential::dexpinv_0}) {
      std::vector<G::Element> ends;
      for (int bound : {kSparse, kDense}) {
        const DenseLuBound scope(bound);
        SolverOptions opt;
        opt.differential = d;
        opt.tol = 1e-12;
        integrators::Stepper<G> stepper(group, field, integrators::tableau_of(integrator), opt, Predictor::lie_euler);
        G::Element y = y0;
        for (int step = 0; step < 4; ++step) {
          StepRecord rec;
          const auto next = stepper.take(y, 0.05 * step, 0.05, rec);
          ASSERT_TRUE(next) << to_string(integrator) << " " << to_string(d) << ": " << stepper.failure();
          y = *next;
        }
        ASSERT_TRUE(stepper.factorization());
        EXPECT_EQ(*stepper.factorization(), bound == kSparse ? Factorization::sparse_lu : Factorization::dense_lu)
            << to_string(integrator) << " " << to_string(d);
        ends.push_back(y);
      }
      EXPECT_LE((ends[0] - ends[1]).norm(), 1e-9) << to_string(integrator) << " " << to_string(d);
      EXPECT_LE(group.defect(ends[0]), 1e-10);
    }
}

// The simplified Newton's decoupled blocks factored sparse (real and complex SparseLU) solve the whole sq x sq
// stage system, for a stiff block-tridiagonal J, as the dense LU of that system does (stiff_solver_test's check).
TEST(SparseNewton, DecoupledSparseBlocksSolveTheStageSystem) {
  constexpr int q = 60, block = 12;
  std::vector<Eigen::Triplet<double>> entries;
  for (int r = 0; r < q; ++r)
    for (int c = std::max(0, (r / block - 1) * block); c < std::min(q, (r / block + 2) * block); ++c)
      entries.emplace_back(r, c, (r == c ? -1e4 : 0.0) + 50.0 * std::sin(1.1 * r + 2.3 * c));
  Eigen::SparseMatrix<double> j(q, q);
  j.setFromTriplets(entries.begin(), entries.end());
  const Eigen::MatrixXd dense_j(j);
  for (Integrator integrator : {Integrator::rkmk_radau3, Integrator::rkmk_gauss3}) {
    const integrators::Tableau& tab = integrators::tableau_of(integrator);
    const int s = tab.stages();
    const DenseLuBound scope(kSparse);
    integrators::DecoupledNewtonMatrix m(tab);
    for (double h : {1.0, 1e-5}) {
      ASSERT_TRUE(m.factorize(h, j)) << to_string(integrator);
      EXPECT_EQ(m.factorization(), Factorization::sparse_lu);
      Eigen::MatrixXd system = Eigen::MatrixXd::Identity(s * q, s * q);
      for (int a = 0; a < s; ++a)
        for (int b = 0; b < s; ++b) system.block(a * q, b * q, q, q) -= h * tab.a(a, b) * dense_j;
      Eigen::VectorXd r(s * q);
      for (int i = 0; i < s * q; ++i) r[i] = std::cos(0.37 * i);
      const Eigen::VectorXd expected = system.partialPivLu().solve(r);
      EXPECT_LE((m.solve(r) - expected).norm(), 1e-12 * expected.norm()) << to_string(integrator) << " h " << h;
      const Eigen::VectorXd x = r.head(q);
      const Eigen::VectorXd filtered =
          (Eigen::MatrixXd::Identity(q, q) - h * m.decoupling().gamma0 * dense_j).partialPivLu().solve(x);
      EXPECT_LE((m.filter(x) - filtered).norm(), 1e-12 * filtered.norm()) << to_string(integrator) << " h " << h;
    }
  }
}

// With no springs the bodies are independent: the sparse solve of 6 bodies is each body's own solve on one body
// (PowerGroup(1), 12 unknowns: factored densely).
TEST(SparseNewton, UncoupledBodiesSolveAsSingleBodies) {
  const G group(6), one(1);
  const test::SpringChain field(group, 0.0), body_field(one, 0.0);
  const G::Element z = group.random(21);
  const Variant newton{Method::newton_algebra, Differential::exact};
  const SolveResult all = solve_with(kSparse, Equation<G>::implicit_euler(group, z, 0.2, field), newton);
  ASSERT_EQ(all.status, Status::converged) << all.reason;
  const G::Element y = all.y;  // the solvers return the strip of bodies
  for (int i = 0; i < group.bodies(); ++i) {
    const G::Element zi = G::body(z, i);
    const auto eq = Equation<G>::implicit_euler(one, zi, 0.2, body_field);
    const SolveResult single = solve_with(kDenseLuMaxDim, eq, newton);
    ASSERT_EQ(single.status, Status::converged) << i;
    EXPECT_EQ(single.linear_solver, Factorization::dense_lu);
    EXPECT_LE((G::body(y, i) - single.y).norm(), 1e-10) << "body " << i;
  }
}

}  // namespace
}  // namespace lienewton
