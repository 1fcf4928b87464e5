#pragma once
// What every solver does around its own update rule, written once: the iteration monitor (trace, callback,
// stopping rule of section 5), the record of each iterate with the group's defect, and the end of the solve
// (the final iterate, the linear solver used, and non-converged endings that are true solutions off log's
// branch reported as off_branch).
#include <cstdio>
#include <optional>
#include <string>

#include "equation.hpp"
#include "iteration_monitor.hpp"
#include "solve_result.hpp"

namespace lienewton {

template <LieGroup G>
class SolverRun {
 public:
  using Point = typename Equation<G>::Point;
  using Element = typename G::Element;

  SolverRun(const Equation<G>& eq, const SolverOptions& options, const TraceCallback& callback, bool krylov)
      : eq_(eq), krylov_(krylov), monitor_(options, callback, eq.group().dim()) {}

  // Records iterate y_n = p.y with ||f||; the status to stop with, or nothing to go on.
  std::optional<Status> record(const Point& p, double step) {
    return monitor_.record(p.f.norm(), step, p.angle, p.y, eq_.group().defect(p.y), scale_of(p));
  }
  void next() { monitor_.next(); }

  SolveResult finish(Status status, const Element& y, std::string detail = {}) {
    SolveResult res = monitor_.finish(classify_failure(status, y), std::move(detail));
    res.y = y;
    res.linear_solver = krylov_ ? "gmres" : "lu";
    return res;
  }
  // The iterate p.y is at the boundary of log's domain.
  SolveResult left_log_domain(const Point& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "iterate %d has rotation angle %.17g, pi - %.3g", monitor_.iteration(), p.angle,
                  G::kLogRadius - p.angle);
    return finish(Status::left_log_domain, p.y, buf);
  }

 private:
  // ~ 1 + ||f|| + ||v|| + h ||g||: the size of the terms whose rounding bounds how small ||f|| can get.
  static double scale_of(const Point& p) {
    double s = 1.0 + p.f.norm();
    if (p.v.size() > 0) s += p.v.norm();
    if (p.hg.size() > 0) s += p.hg.norm();
    return s;
  }

  // Non-converged endings of a solve on an implicit Euler equation may be true solutions off log's branch.
  Status classify_failure(Status status, const Element& y) const {
    const bool may_be_solution = status == Status::stagnated || status == Status::max_iterations ||
                                 status == Status::left_log_domain;
    if (may_be_solution && eq_.is_off_branch_solution(y)) return Status::off_branch;
    return status;
  }

  const Equation<G>& eq_;
  bool krylov_;
  IterationMonitor monitor_;
};

}  // namespace lienewton
