#pragma once
// What every solver does around its own update rule, written once: the iteration monitor (trace, callback,
// stopping rule of section 5), the record of each iterate with its residuals and the group's defect, and the
// end of the solve, classified against the y it returns:
//   - stagnated returns the best iterate (smallest driven residual), every other ending the last recorded one;
//   - max_iterations whose driven residual sits at the rounding floor is stagnated;
//   - converged is stagnated too when tol lies below the rounding of the residual's own evaluation (the floor
//     without its safety factor), the iterate before was already at the floor and the residual did not even halve
//     from it: it dipped below tol by rounding, not by the method (the same y evaluated another way may well lie
//     above tol);
//   - any ending whose y solves (1.1) while h g(y) has an angle beyond pi is off_branch.
// The result's residual, floor and reason describe that returned y.
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

#include "equation.hpp"
#include "iteration_monitor.hpp"
#include "newton_step.hpp"
#include "solve_result.hpp"

namespace lienewton {

// How a globalised iteration found the step to the iterate being recorded (solvers/globalization.hpp).
struct StepInfo {
  std::string_view kind;              // empty: a plain full step
  std::optional<double> length;       // line search: the accepted alpha
  std::optional<double> radius;       // trust region: the radius the step was taken in
  std::optional<int> from_iterate;    // watchdog: the step starts at this earlier iterate, not the last one
};

// The rounding floor's safety factor over the rounding of one evaluation of the residual.
inline constexpr double kFloorMargin = 64.0;
// The same over what one evaluation's residual shows at rounding: the estimate without its factor is a few times low
// on a stiff field (||dg|| of 1e5 at 128 bodies: 1.4x).
inline constexpr double kRoundingMargin = 8.0;

template <LieGroup G>
class SolverRun {
 public:
  using Point = typename Equation<G>::Point;
  using Element = typename G::Element;

  SolverRun(const Equation<G>& eq, const SolverOptions& options, const TraceCallback& callback, bool krylov)
      : eq_(eq), options_(options), krylov_(krylov), monitor_(options, callback) {}

  // Records iterate y_n = p.y; the status to stop with, or nothing to go on.
  std::optional<Status> record(const Point& p, double step, const StepInfo& info = {}) {
    if (!kappa_) kappa_ = eq_.conditioning(p.y);  // at y_0 = z: the floor's conditioning term
    const bool algebra = p.algebra_residual.has_value();
    const double driven = p.algebra_residual.value_or(p.residual);
    const double stop = options_.stopping == Stopping::algebra_residual && algebra ? driven : p.residual;
    const double floor = floor_of(p, driven);
    TraceRecord rec;
    rec.residual = p.residual;
    rec.algebra_residual = p.algebra_residual;
    rec.step = step;
    rec.angle = p.angle;
    rec.log_boundary_distance = log_boundary_distance<G>(p.angle);
    rec.orthogonality_error = eq_.group().defect(p.y);
    if (options_.include_iterates) rec.y = p.y;
    rec.step_kind = info.kind;
    rec.step_length = info.length;
    rec.trust_radius = info.radius;
    rec.step_from_iterate = info.from_iterate;
    const Iterate it{p.y, monitor_.iteration(), p.residual, p.algebra_residual, driven, floor};
    if (!(best_.driven <= driven)) best_ = it;
    if (recorded_) previous_ = last_;
    last_ = it;
    recorded_ = true;
    return monitor_.record(std::move(rec),
                           {stop, driven, algebra ? "||f~(v)||" : "||f(y)||", floor, floor / kRoundingMargin});
  }
  void next() { monitor_.next(); }
  // The rounding floor of the driven residual at the last recorded iterate.
  double floor() const { return last_.floor; }
  // The iterate about to be recorded was replaced by the group's projection of it (its defect had drifted).
  void projected() { ++projections_; }
  // Version 2's algebra iterate v grew past kDivergenceBound.
  SolveResult diverged(const char* what, double value) {
    monitor_.diverged_because(std::string(what) + " = " + format_number(value));
    return finish(Status::diverged);
  }

  // Ends the solve with the iterate the status calls for (see the file comment).
  SolveResult finish(Status status, std::string detail = {}) {
    if (status == Status::max_iterations && last_.driven <= last_.floor) status = Status::stagnated;
    const bool dipped = status == Status::converged && last_.n > 0 && last_.floor / kFloorMargin > options_.tol &&
                        previous_.driven <= previous_.floor && last_.driven > 0.5 * previous_.driven;
    if (dipped) status = Status::stagnated;
    const Iterate& it = status == Status::stagnated ? best_ : last_;
    if (status != Status::cancelled && eq_.is_implicit_euler() &&
        eq_.check_implicit_euler(it.y, eq_.conditioning(it.y)).off_branch())
      status = Status::off_branch;
    SolveResult res = monitor_.finish(status);
    res.y = it.y;
    res.iterate = it.n;
    res.residual = it.residual;
    res.algebra_residual = it.algebra_residual;
    res.floor = it.floor;
    res.orthogonality_error = eq_.group().defect(it.y);
    res.z_adjustment = eq_.z_adjustment();
    res.reorthogonalisations = projections_;
    res.linear_solver = detail::factorization_for<G>(krylov_, eq_.group().dim());
    res.reason = reason_for(status, res, G::kAngleName, G::kLogBoundaryName);
    if (dipped)
      res.reason = "stagnated at the rounding floor " + format_number(res.floor) + ": ||f(y)|| = " +
                   format_number(res.residual) + " at y_" + std::to_string(res.iterate) + " fell below tol only by "
                   "rounding, less than halved from y_" + std::to_string(previous_.n) + " already at the floor (tol "
                   "is below what double precision resolves here)";
    if (status == Status::diverged && !monitor_.divergence().empty()) detail = monitor_.divergence();
    if (!detail.empty()) res.reason += " (" + detail + ")";
    return res;
  }
  // The iterate p.y (not recorded) is at the boundary of log's domain: f(p.y) is undefined, so the last
  // recorded iterate is returned (p.y itself when it is the start y_0: f is undefined there too).
  SolveResult left_log_domain(const Point& p) {
    if (!recorded_) {
      Iterate start;
      start.y = p.y;
      last_ = best_ = start;
    }
    char buf[112];
    std::snprintf(buf, sizeof buf, "iterate %d has %s %.17g, %s - %.3g", monitor_.iteration(), G::kAngleName, p.angle,
                  G::kLogBoundaryName, log_boundary_distance<G>(p.angle));
    return finish(Status::left_log_domain, buf);
  }

 private:
  struct Iterate {
    Element y;
    int n = 0;
    double residual = std::numeric_limits<double>::quiet_NaN();
    std::optional<double> algebra_residual;
    double driven = std::numeric_limits<double>::infinity();
    double floor = 0;
  };

  // kFloorMargin eps sqrt(q) (1 + ||f|| + ||v|| + h ||g|| + kappa): the rounding of the terms of f, plus
  // kappa ~ h ||dg|| for the rounding of y amplified by df (3.8), with a safety factor.
  double floor_of(const Point& p, double driven) const {
    double s = 1.0 + driven + *kappa_;
    if (p.v.size() > 0) s += p.v.norm();
    if (p.hg.size() > 0) s += p.hg.norm();
    return kFloorMargin * std::numeric_limits<double>::epsilon() * std::sqrt(double(eq_.group().dim())) * s;
  }

  const Equation<G>& eq_;
  SolverOptions options_;
  bool krylov_;
  IterationMonitor monitor_;
  std::optional<double> kappa_;
  Iterate last_, best_, previous_;  // previous_: the iterate recorded before last_
  bool recorded_ = false;
  int projections_ = 0;
};

}  // namespace lienewton
