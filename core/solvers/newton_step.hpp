#pragma once
// The Newton step both Newton versions share: D u = -f with D the differential of (3.5) or (3.20), assembled on
// the coordinate basis and solved by LU with partial pivoting (its reciprocal condition number checked first:
// singular_differential), or for large N applied matrix-free inside GMRES.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "core/gmres.hpp"
#include "core/status.hpp"
#include "factored_operator.hpp"
#include "iteration_monitor.hpp"

namespace lienewton {

// Above this N (q = N(N-1)/2 = 120 unknowns) the Newton system is solved matrix-free by GMRES: assembling
// and factoring it costs O(N^6) time and O(N^4) memory, one application of the spectral dexpinv O(N^3).
inline constexpr int kKrylovThreshold = 16;
inline constexpr int kMaxKrylovIterations = 300;

namespace detail {

template <class G>
bool use_krylov(const G& group, LinearSolver choice) {
  if (choice == LinearSolver::auto_select) return group.n() > kKrylovThreshold;
  return choice == LinearSolver::gmres;
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
  if (!d.a.allFinite()) return StepOutcome::non_finite;
  const Eigen::PartialPivLU<typename G::Operator> lu(d.a);
  if (!well_conditioned(lu)) return StepOutcome::singular;
  u = -lu.solve(f);
  if (d.basis) u = *d.basis * u;
  return StepOutcome::ok;
}

inline Status status_of(StepOutcome o) {
  return o == StepOutcome::singular ? Status::singular_differential : Status::non_finite;
}

}  // namespace detail

}  // namespace lienewton
