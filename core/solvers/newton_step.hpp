#pragma once
// The Newton step both Newton versions share: D u = -f with D the differential of (3.5) or (3.20), assembled on
// the coordinate basis and solved by LU with partial pivoting (its reciprocal condition number checked first:
// singular_differential), or for large N applied matrix-free inside GMRES. A group with sparse operators (a system
// of bodies) keeps the matrix sparse and factors it with SparseLU, or densely when it is small.
#include <Eigen/LU>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "core/gmres.hpp"
#include "core/groups/lie_group.hpp"
#include "core/status.hpp"
#include "factored_operator.hpp"
#include "iteration_monitor.hpp"

namespace lienewton {

// Above this N (q = N(N-1)/2 = 120 unknowns) the Newton system is solved matrix-free by GMRES: assembling
// and factoring it costs O(N^6) time and O(N^4) memory, one application of the spectral dexpinv O(N^3).
inline constexpr int kKrylovThreshold = 16;
inline constexpr int kMaxKrylovIterations = 300;

// A sparse Newton matrix of at most this dimension is factored dense: the crossover of factor + solve on
// block-tridiagonal matrices of 12 x 12 blocks, dense LU against sparse LU with its rcond estimate
// (bench/sparse_lu_bench.cpp; docs/many_bodies.md has the figures). Dense up to 12 bodies of SE(3) x R^6.
inline constexpr int kDenseLuMaxDim = 144;
// The bound in force on this thread: kDenseLuMaxDim, unless a test moves it to compare both paths on one system.
inline int& dense_lu_max_dim() {
  thread_local int bound = kDenseLuMaxDim;
  return bound;
}

// Of two factorizations used in one run, the one reported: of the larger kind (dense LU < sparse LU < GMRES), as a
// step may factor small decoupled blocks densely and its whole stage system sparse.
inline std::optional<Factorization> widest(std::optional<Factorization> a, std::optional<Factorization> b) {
  if (!a) return b;
  if (!b) return a;
  return static_cast<int>(*a) >= static_cast<int>(*b) ? a : b;
}

namespace detail {

// The auto rule is for dense operators, whose assembly and LU grow like dim^3 (SO(N) above N = 16). A sparse
// operator's LU grows like its nonzeros (k bodies: O(k)), so the body count never picks GMRES; asked, it runs.
template <class G>
bool use_krylov(const G& group, LinearSolver choice) {
  if (choice == LinearSolver::auto_select) return !kSparseOperator<G> && group.n() > kKrylovThreshold;
  return choice == LinearSolver::gmres;
}

// The factorization newton_step uses for a Newton matrix of this dimension (the one reported as linear_solver).
template <class G>
Factorization factorization_for(bool krylov, int dim) {
  if (krylov) return Factorization::gmres;
  return kSparseOperator<G> && dim > dense_lu_max_dim() ? Factorization::sparse_lu : Factorization::dense_lu;
}

enum class StepOutcome { ok, singular, non_finite };

// rcond() >= kSingularRcond, estimated only when the pivots of U spread over more than 1e6: cond(A) is at
// least max|u_ii| / min|u_ii| up to the growth of L, so a well-spread U never hides a singular system, and
// the estimate (several triangular solves, 3x the cost of a 3x3 solve) stays off the common path.
template <class Lu>
bool well_conditioned(const Lu& lu) {
  const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
  if (pivots.minCoeff() > 1e-6 * pivots.maxCoeff()) return true;
  return lu.rcond() >= kSingularRcond;
}

// SparseLU keeps no cheap pivot list: its reciprocal condition number is estimated as Eigen's dense LUs do
// (Hager/Higham, a few solves), through a view whose adjoint() is const as that estimator needs.
template <class Lu>
struct ConstLuView {
  using MatrixType = typename Lu::MatrixType;
  using Scalar = typename Lu::Scalar;
  using RealScalar = typename Lu::RealScalar;
  Lu* lu;
  Eigen::Index rows() const { return lu->rows(); }
  Eigen::Index cols() const { return lu->cols(); }
  template <class Rhs>
  auto solve(const Rhs& b) const {
    return lu->solve(b);
  }
  auto adjoint() const { return lu->adjoint(); }
};
template <class Scalar>
bool well_conditioned_sparse(Eigen::SparseLU<Eigen::SparseMatrix<Scalar>>& lu, const Eigen::SparseMatrix<Scalar>& a) {
  if (lu.info() != Eigen::Success) return false;
  double norm1 = 0.0;
  for (Eigen::Index c = 0; c < a.outerSize(); ++c) norm1 = std::max(norm1, a.col(c).cwiseAbs().sum());
  const ConstLuView<Eigen::SparseLU<Eigen::SparseMatrix<Scalar>>> view{&lu};
  return Eigen::internal::rcond_estimate_helper(norm1, view) >= kSingularRcond;
}

// SparseLU whose symbolic analysis (COLAMD ordering, elimination tree) is kept while the pattern repeats: a
// Newton iteration's matrices, and a step's after it, share one pattern.
template <class Scalar>
class SparseNewtonLu {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar>;
  // Factors a; false when it is singular to kSingularRcond.
  bool factorize(Matrix a) {
    a.makeCompressed();
    if (!same_pattern(a)) {
      lu_->analyzePattern(a);
      outer_.assign(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1);
      inner_.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
    }
    lu_->factorize(a);
    return well_conditioned_sparse(*lu_, a);
  }
  template <class Rhs>
  auto solve(const Rhs& b) const {
    return lu_->solve(b);
  }

 private:
  bool same_pattern(const Matrix& a) const {
    return static_cast<std::size_t>(a.outerSize() + 1) == outer_.size() &&
           std::equal(outer_.begin(), outer_.end(), a.outerIndexPtr()) &&
           static_cast<std::size_t>(a.nonZeros()) == inner_.size() &&
           std::equal(inner_.begin(), inner_.end(), a.innerIndexPtr());
  }
  // Behind a pointer: SparseLU cannot be moved, and its owners are kept in vectors.
  std::unique_ptr<Eigen::SparseLU<Matrix>> lu_ = std::make_unique<Eigen::SparseLU<Matrix>>();
  std::vector<typename Matrix::StorageIndex> outer_, inner_;
};

// One Newton matrix's LU: dense, or sparse (SparseNewtonLu) for a sparse matrix above kDenseLuMaxDim. Kept by its
// owner across factorizations, so that the sparse analysis is reused.
template <class Scalar>
class NewtonLu {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Sparse = Eigen::SparseMatrix<Scalar>;
  // false when a is singular to kSingularRcond.
  bool factorize(const Dense& a) {
    sparse_ = false;
    dense_.compute(a);
    return well_conditioned(dense_);
  }
  bool factorize(const Sparse& a) {
    if (a.rows() <= dense_lu_max_dim()) return factorize(Dense(a));
    sparse_ = true;
    return sparse_lu_.factorize(a);
  }
  Vector solve(const Vector& b) const { return sparse_ ? Vector(sparse_lu_.solve(b)) : Vector(dense_.solve(b)); }
  Factorization factorization() const { return sparse_ ? Factorization::sparse_lu : Factorization::dense_lu; }

 private:
  bool sparse_ = false;
  Eigen::PartialPivLU<Dense> dense_;
  SparseNewtonLu<Scalar> sparse_lu_;
};

// Solves D u = -f for the Newton step, D = A P^T given by `assemble` (dense LU of A with partial pivoting, refused
// when its reciprocal condition number is below kSingularRcond) or, matrix-free, by `apply` inside GMRES with the
// forcing term eta = min(0.1, ||f||): ||D u + f|| <= eta ||f|| keeps Newton's convergence quadratic
// (Eisenstat & Walker 1996; Dembo, Eisenstat & Steihaug 1982).
template <class G, class Assemble, class Apply>
StepOutcome newton_step(bool krylov, const Assemble& assemble, const Apply& apply,
                        const typename G::Vector& f, typename G::Vector& u) {
  if (krylov) {
    Eigen::VectorXd x;
    const double eta = std::clamp(f.norm(), 1e-12, 0.1);
    const GmresResult r = gmres([&](const Eigen::VectorXd& w) { return Eigen::VectorXd(apply(w)); },
                                Eigen::VectorXd(-f), x, eta, kMaxKrylovIterations);
    if (!x.allFinite()) return StepOutcome::non_finite;
    if (r.iterations == 0 || r.relative_residual >= 1.0) return StepOutcome::singular;
    u = x;
    return StepOutcome::ok;
  }
  const FactoredOperator<typename G::Operator> d = assemble();
  if (!operator_all_finite(d.a)) return StepOutcome::non_finite;
  if constexpr (kSparseOperator<G>) {
    // One per thread, so that a solve's iterations (one request runs on one thread) share the sparse analysis.
    thread_local NewtonLu<double> lu;
    if (!lu.factorize(d.a)) return StepOutcome::singular;
    u = -lu.solve(f);
  } else {
    const Eigen::PartialPivLU<typename G::Operator> lu(d.a);
    if (!well_conditioned(lu)) return StepOutcome::singular;
    u = -lu.solve(f);
  }
  if (d.basis) u = *d.basis * u;
  return StepOutcome::ok;
}

inline Status status_of(StepOutcome o) {
  return o == StepOutcome::singular ? Status::singular_differential : Status::non_finite;
}

}  // namespace detail

}  // namespace lienewton
