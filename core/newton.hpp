#pragma once
// The three solvers of f(y) = 0 on a Lie group, all started at y_0 = z:
//   fixed_point     (1.2)  y_{n+1} = z exp(h g(y_n))
//   newton_group    (3.5)  df_{y_n}(u_n) = -f(y_n),   y_{n+1} = y_n exp(u_n)         (Version 1)
//   newton_algebra  (3.20) df~_{v_n}(u_n) = -f~(v_n), v_{n+1} = v_n + u_n, v_0 = 0   (Version 2)
// The Newton system is assembled on the coordinate basis and solved by LU with partial pivoting (its
// reciprocal condition number checked first: singular_differential), or for large N applied matrix-free
// inside GMRES.
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "equation.hpp"
#include "gmres.hpp"
#include "iteration_monitor.hpp"

namespace lienewton {

// Above this N (q = N(N-1)/2 = 120 unknowns) the Newton system is solved matrix-free by GMRES: assembling
// and factoring it costs O(N^6) time and O(N^4) memory, one application of the spectral dexpinv O(N^3).
inline constexpr int kKrylovThreshold = 16;
inline constexpr int kMaxKrylovIterations = 300;

namespace detail {

inline std::string angle_detail(double angle, int n) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "iterate %d has rotation angle %.17g, pi - %.3g", n, angle, so3::kPi - angle);
  return buf;
}

template <class G>
double scale_of(const typename Equation<G>::Point& p) {
  double s = 1.0 + p.f.norm();
  if (p.v.size() > 0) s += p.v.norm();
  if (p.hg.size() > 0) s += p.hg.norm();
  return s;
}

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

// Solves D u = -f for the Newton step, D given by `assemble` (dense LU with partial pivoting, refused when
// its reciprocal condition number is below kSingularRcond) or, matrix-free, by `apply` inside GMRES with the
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
  const typename G::Operator d = assemble();
  if (!d.allFinite()) return StepOutcome::non_finite;
  const Eigen::PartialPivLU<typename G::Operator> lu(d);
  if (!well_conditioned(lu)) return StepOutcome::singular;
  u = -lu.solve(f);
  return StepOutcome::ok;
}

inline Status status_of(StepOutcome o) {
  return o == StepOutcome::singular ? Status::singular_differential : Status::non_finite;
}

template <class Element>
SolveResult with_final_iterate(SolveResult res, const Element& y, bool krylov) {
  res.y = y;
  res.linear_solver = krylov ? "gmres" : "lu";
  return res;
}

// Non-converged endings of a solve on an implicit Euler equation may be true solutions off log's branch.
template <class G>
Status classify_failure(const Equation<G>& eq, Status status, const typename G::Element& y) {
  const bool may_be_solution = status == Status::stagnated || status == Status::max_iterations ||
                               status == Status::left_log_domain;
  if (may_be_solution && eq.is_off_branch_solution(y)) return Status::off_branch;
  return status;
}

}  // namespace detail

template <class G>
SolveResult newton_group(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  using Point = typename Equation<G>::Point;
  const G& group = eq.group();
  const bool krylov = detail::use_krylov(group, opt.linear_solver);
  IterationMonitor monitor(opt, cb, group.dim());
  auto finish = [&](Status s, const typename G::Element& y, std::string detail = {}) {
    return detail::with_final_iterate(monitor.finish(detail::classify_failure(eq, s, y), std::move(detail)), y, krylov);
  };
  typename G::Element y = eq.z();
  typename G::Vector u = group.zero();
  double step = 0.0;
  // Difference quotients need f alone, also at y_n: the same log path as in the perturbed points.
  const auto need = opt.differential == Differential::finite_difference ? Equation<G>::Need::residual
                                                                        : Equation<G>::Need::differential;
  for (;;) {
    const Point p = eq.at(y, need);
    if (!p.in_domain) return finish(Status::left_log_domain, y, detail::angle_detail(p.angle, monitor.iteration()));
    if (auto stop = monitor.record(p.f.norm(), step, p.angle, y, detail::scale_of<G>(p))) return finish(*stop, y);
    detail::StepOutcome outcome;
    try {
      outcome = detail::newton_step<G>(
          krylov, [&] { return eq.df_matrix(p, opt.differential); },
          [&](const typename G::Vector& w) { return eq.df(p, w, opt.differential); }, p.f, u);
    } catch (const LogDomainError& e) {
      return finish(Status::left_log_domain, y, e.what());
    }
    if (outcome != detail::StepOutcome::ok) return finish(detail::status_of(outcome), y);
    const typename G::Element next = group.times_exp(y, u);  // (3.5): y_{n+1} = y_n exp(u_n)
    step = u.norm();
    if (!next.allFinite()) return finish(Status::non_finite, y);
    y = next;
    monitor.next();
  }
}

template <class G>
SolveResult newton_algebra(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  using Point = typename Equation<G>::Point;
  const G& group = eq.group();
  const bool krylov = detail::use_krylov(group, opt.linear_solver);
  IterationMonitor monitor(opt, cb, group.dim());
  auto finish = [&](Status s, const typename G::Element& y) {
    return detail::with_final_iterate(monitor.finish(detail::classify_failure(eq, s, y)), y, krylov);
  };
  typename G::Vector v = group.zero();
  typename G::Vector u = group.zero();
  double step = 0.0;
  for (;;) {
    const Point p = eq.at_algebra(v);
    if (auto stop = monitor.record(p.f.norm(), step, p.angle, p.y, detail::scale_of<G>(p))) {
      Status s = *stop;
      // f~(v) = 0 solves y = z exp(v), v = h g(y); log(z^-1 y) = v only while v's angles stay below pi.
      if (s == Status::converged && eq.is_implicit_euler() && p.algebra_angle > so3::kPi) s = Status::off_branch;
      return finish(s, p.y);
    }
    const detail::StepOutcome outcome = detail::newton_step<G>(
        krylov, [&] { return eq.dftilde_matrix(p, opt.differential); },
        [&](const typename G::Vector& w) { return eq.dftilde(p, w, opt.differential); }, p.f, u);
    if (outcome != detail::StepOutcome::ok) return finish(detail::status_of(outcome), p.y);
    step = u.norm();
    if (v.norm() + step > kDivergenceBound) return finish(Status::diverged, p.y);
    v += u;  // (3.20): v_{n+1} = v_n + u_n
    monitor.next();
  }
}

template <class G>
SolveResult fixed_point(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  using Point = typename Equation<G>::Point;
  const G& group = eq.group();
  IterationMonitor monitor(opt, cb, group.dim());
  auto finish = [&](Status s, const typename G::Element& y, std::string detail = {}) {
    return detail::with_final_iterate(monitor.finish(detail::classify_failure(eq, s, y), std::move(detail)), y, false);
  };
  typename G::Element y = eq.z();
  double step = 0.0;
  for (;;) {
    const Point p = eq.at(y, Equation<G>::Need::residual);
    if (!p.in_domain) return finish(Status::left_log_domain, y, detail::angle_detail(p.angle, monitor.iteration()));
    if (auto stop = monitor.record(p.f.norm(), step, p.angle, y, detail::scale_of<G>(p))) return finish(*stop, y);
    const typename G::Element next = eq.fixed_point_map(p);  // (1.2)
    if (!next.allFinite()) return finish(Status::non_finite, y);
    step = (next - y).norm() / std::sqrt(2.0);
    y = next;
    monitor.next();
  }
}

template <class G>
SolveResult run_method(Method method, const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb) {
  switch (method) {
    case Method::fixed_point: return fixed_point(eq, opt, cb);
    case Method::newton_group: return newton_group(eq, opt, cb);
    case Method::newton_algebra: return newton_algebra(eq, opt, cb);
  }
  return {};
}

}  // namespace lienewton
