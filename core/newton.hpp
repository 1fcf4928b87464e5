#pragma once
// The three solvers of f(y) = 0 on a Lie group, all started at y_0 = z:
//   fixed_point     (1.2)  y_{n+1} = z exp(h g(y_n))
//   newton_group    (3.5)  df_{y_n}(u_n) = -f(y_n),   y_{n+1} = y_n exp(u_n)         (Version 1)
//   newton_algebra  (3.20) df~_{v_n}(u_n) = -f~(v_n), v_{n+1} = v_n + u_n, v_0 = 0   (Version 2)
// The Newton system is assembled on the coordinate basis and solved by LU with partial pivoting; its
// reciprocal condition number is checked first (singular_differential).
#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <string>

#include "equation.hpp"
#include "iteration_monitor.hpp"

namespace lienewton {

namespace detail {

// Forward-difference step t = sqrt(eps) scaled to the point, as the paper suggests for (3.12)/(3.18).
inline double difference_step(double point_norm) {
  return std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, point_norm);
}

template <class G>
double scale_of(const typename Equation<G>::Point& p) {
  double s = 1.0 + p.f.norm();
  if (p.v.size() > 0) s += p.v.norm();
  if (p.hg.size() > 0) s += p.hg.norm();
  return s;
}

// Solves D u = -f; false when D is singular or too ill-conditioned to trust.
template <class Operator, class Vector>
bool newton_step(const Operator& d, const Vector& f, Vector& u) {
  if (!d.allFinite()) return false;
  const Eigen::PartialPivLU<Operator> lu(d);
  if (!(lu.rcond() >= kSingularRcond)) return false;
  u = -lu.solve(f);
  return true;
}

inline std::string angle_detail(double angle, int n) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "iterate %d has rotation angle %.17g, pi - %.3g", n, angle, so3::kPi - angle);
  return buf;
}

template <class Element>
SolveResult with_final_iterate(SolveResult res, const Element& y) {
  res.y = y;
  res.linear_solver = "lu";
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
  IterationMonitor monitor(opt, cb, group.dim());
  typename G::Element y = eq.z();
  typename G::Operator d = group.operator_matrix();
  typename G::Vector u = group.zero();
  double step = 0.0;
  for (;;) {
    const Point p = eq.at(y);
    if (!p.in_domain) {
      const Status s = detail::classify_failure(eq, Status::left_log_domain, y);
      return detail::with_final_iterate(monitor.finish(s, detail::angle_detail(p.angle, monitor.iteration())), y);
    }
    if (auto stop = monitor.record(p.f.norm(), step, p.angle, y, detail::scale_of<G>(p))) {
      return detail::with_final_iterate(monitor.finish(detail::classify_failure(eq, *stop, y)), y);
    }
    // Assemble df_y on the basis: exact/truncated columns (3.8)/(3.10)/(3.11), or differences (3.18).
    if (opt.differential == Differential::finite_difference) {
      const double t = detail::difference_step(p.v.size() > 0 ? p.v.norm() : 0.0);
      for (int i = 0; i < group.dim(); ++i) {
        const Point q = eq.at(group.times_exp(y, t * group.unit(i)));
        if (!q.in_domain)
          return detail::with_final_iterate(monitor.finish(Status::left_log_domain, "in a difference quotient"), y);
        d.col(i) = (q.f - p.f) / t;
      }
    } else {
      for (int i = 0; i < group.dim(); ++i) d.col(i) = eq.df(p, group.unit(i), opt.differential);
    }
    if (!detail::newton_step(d, p.f, u)) {
      const Status s = d.allFinite() ? Status::singular_differential : Status::non_finite;
      return detail::with_final_iterate(monitor.finish(s), y);
    }
    const typename G::Element next = group.times_exp(y, u);
    step = u.norm();
    if (!next.allFinite()) return detail::with_final_iterate(monitor.finish(Status::non_finite), y);
    y = next;
    monitor.next();
  }
}

template <class G>
SolveResult newton_algebra(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  using Point = typename Equation<G>::Point;
  const G& group = eq.group();
  IterationMonitor monitor(opt, cb, group.dim());
  typename G::Vector v = group.zero();
  typename G::Operator d = group.operator_matrix();
  typename G::Vector u = group.zero();
  double step = 0.0;
  for (;;) {
    const Point p = eq.at_algebra(v);
    if (auto stop = monitor.record(p.f.norm(), step, p.angle, p.y, detail::scale_of<G>(p))) {
      Status s = *stop;
      // f~(v) = 0 solves y = z exp(v), v = h g(y); log(z^-1 y) = v only while v's angles stay below pi.
      if (s == Status::converged && eq.is_implicit_euler() && p.algebra_angle > so3::kPi) s = Status::off_branch;
      return detail::with_final_iterate(monitor.finish(detail::classify_failure(eq, s, p.y)), p.y);
    }
    if (opt.differential == Differential::finite_difference) {  // (3.19)
      const double t = detail::difference_step(v.norm());
      for (int i = 0; i < group.dim(); ++i) d.col(i) = (eq.at_algebra(v + t * group.unit(i)).f - p.f) / t;
    } else {
      for (int i = 0; i < group.dim(); ++i) d.col(i) = eq.dftilde(p, group.unit(i), opt.differential);
    }
    if (!detail::newton_step(d, p.f, u)) {
      const Status s = d.allFinite() ? Status::singular_differential : Status::non_finite;
      return detail::with_final_iterate(monitor.finish(s), p.y);
    }
    step = u.norm();
    if (!u.allFinite()) return detail::with_final_iterate(monitor.finish(Status::non_finite), p.y);
    if (v.norm() + step > kDivergenceBound) return detail::with_final_iterate(monitor.finish(Status::diverged), p.y);
    v += u;
    monitor.next();
  }
}

template <class G>
SolveResult fixed_point(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  using Point = typename Equation<G>::Point;
  const G& group = eq.group();
  IterationMonitor monitor(opt, cb, group.dim());
  typename G::Element y = eq.z();
  double step = 0.0;
  for (;;) {
    const Point p = eq.at(y);
    if (!p.in_domain) {
      const Status s = detail::classify_failure(eq, Status::left_log_domain, y);
      return detail::with_final_iterate(monitor.finish(s, detail::angle_detail(p.angle, monitor.iteration())), y);
    }
    const double scale = detail::scale_of<G>(p);
    if (auto stop = monitor.record(p.f.norm(), step, p.angle, y, scale)) {
      return detail::with_final_iterate(monitor.finish(detail::classify_failure(eq, *stop, y)), y);
    }
    const typename G::Element next = eq.fixed_point_map(p);
    if (!next.allFinite()) return detail::with_final_iterate(monitor.finish(Status::non_finite), y);
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
