#include "iteration_monitor.hpp"

#include <cstdio>

#include "core/cancellation.hpp"
#include "core/cpu_clock.hpp"

namespace lienewton {
namespace {

constexpr int kStallIterations = 3;  // residual not halved this many times in a row at the floor: stagnated

// The paper's rate r from the last three residuals before convergence (section 5); needs p >= 3.
std::optional<double> convergence_rate(const std::vector<double>& r, int p) {
  if (p < 3 || static_cast<int>(r.size()) <= p - 1) return std::nullopt;
  const double num = std::log(r[p - 1] / r[p - 2]);
  const double den = std::log(r[p - 2] / r[p - 3]);
  const double rate = num / den;
  if (!std::isfinite(rate) || den == 0.0) return std::nullopt;
  return rate;
}

// The rate means an order of convergence only when the three residuals it is read from decrease, lie above their
// rounding floors and the ratio of logs lies in [0.5, 3]: a last residual that rose (rate < 0), or that sits at
// the floor, where its size is rounding's and not the method's, says nothing about the method.
bool rate_is_reliable(const std::vector<double>& r, const std::vector<double>& floors, int p, double rate) {
  for (int k = p - 3; k < p; ++k)
    if (r[k] <= floors[k]) return false;
  return r[p - 3] > r[p - 2] && r[p - 2] > r[p - 1] && rate >= 0.5 && rate <= 3.0;
}

}  // namespace

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

IterationMonitor::IterationMonitor(const SolverOptions& options, const TraceCallback& callback)
    : options_(options), callback_(callback), start_(std::chrono::steady_clock::now()),
      cpu_start_(options.timed ? thread_cpu_seconds() : 0.0) {
  trace_.reserve(static_cast<std::size_t>(options.max_iterations) + 1);
  stops_.reserve(static_cast<std::size_t>(options.max_iterations) + 1);
  floors_.reserve(static_cast<std::size_t>(options.max_iterations) + 1);
}

double IterationMonitor::solver_cpu_seconds() const {
  if (!options_.timed) return 0.0;  // untimed: no clock reads at all (see SolverOptions::timed)
  return thread_cpu_seconds() - cpu_start_ - callback_cpu_seconds_;
}

double IterationMonitor::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::optional<Status> IterationMonitor::record(TraceRecord rec, const Measurement& m) {
  rec.iteration = iteration_;
  if (options_.timed) {
    rec.seconds = elapsed();
    rec.cpu_seconds = solver_cpu_seconds();
  }
  const double step = rec.step;
  stops_.push_back(m.stop);
  floors_.push_back(m.floor);
  trace_.push_back(std::move(rec));
  if (callback_) {
    const double before = options_.timed ? thread_cpu_seconds() : 0.0;
    const bool go_on = callback_(trace_.back());
    if (options_.timed) callback_cpu_seconds_ += thread_cpu_seconds() - before;
    if (!go_on) return Status::cancelled;
  }
  if (cancellation_requested()) return Status::cancelled;  // deadline, shutdown, client gone
  if (!std::isfinite(m.stop) || !std::isfinite(m.driven) || !std::isfinite(step)) return Status::non_finite;
  if (m.stop <= options_.tol) return Status::converged;
  if (m.driven > kDivergenceBound) {
    divergence_ = std::string(m.driven_name) + " = " + format_number(m.driven);
    return Status::diverged;
  }
  if (step > kDivergenceBound) {
    divergence_ = "step ||u|| = " + format_number(step);
    return Status::diverged;
  }
  if (options_.stop_at_rounding && m.driven <= m.rounding) return Status::stagnated;
  stalled_ = (m.driven > 0.5 * best_ && best_ <= m.floor) ? stalled_ + 1 : 0;
  best_ = std::min(best_, m.driven);
  if (stalled_ >= kStallIterations) return Status::stagnated;
  if (iteration_ >= options_.max_iterations) return Status::max_iterations;
  return std::nullopt;
}

SolveResult IterationMonitor::finish(Status status) {
  SolveResult res;
  res.status = status;
  res.iterations = iteration_;
  if (status == Status::converged) {
    res.rate = convergence_rate(stops_, iteration_);
    res.rate_reliable = res.rate && rate_is_reliable(stops_, floors_, iteration_, *res.rate);
  }
  res.seconds = elapsed();
  res.cpu_seconds = solver_cpu_seconds();
  res.trace = std::move(trace_);
  return res;
}

std::string reason_for(Status status, const SolveResult& r, const std::string& angle_name,
                       const std::string& log_boundary_name) {
  const std::string at = " at y_" + std::to_string(r.iterate);
  switch (status) {
    case Status::converged:
      return "converged: ||f(y)|| = " + format_number(r.residual) + " after " + std::to_string(r.iterations) +
             " iterations";
    case Status::max_iterations:
      return "no convergence in " + std::to_string(r.iterations) + " iterations: ||f(y)|| = " +
             format_number(r.residual);
    case Status::diverged:
      return "diverged: a residual, step or algebra iterate exceeded " + format_number(kDivergenceBound) +
             "; returned y_" + std::to_string(r.iterate) + " has ||f(y)|| = " + format_number(r.residual);
    case Status::non_finite: return "a NaN or Inf appeared in the residual, the step or the iterate";
    case Status::left_log_domain:
      return "z^-1 y reached " + angle_name + " " + log_boundary_name +
             ", where log (and so f) is undefined; returned the last iterate "
             "inside, y_" + std::to_string(r.iterate) + ", with ||f(y)|| = " + format_number(r.residual);
    case Status::singular_differential:
      return "the Newton system is singular or too ill-conditioned (reciprocal condition < " +
             format_number(kSingularRcond) + ")";
    case Status::stagnated:
      return "stagnated at the rounding floor " + format_number(r.floor) + ": best ||f(y)|| = " +
             format_number(r.residual) + at + ", above tol (for large h an absolute tol cannot be met)";
    case Status::off_branch:
      return "y solves y = z exp(h g(y)) to rounding, but h g(y) has a " + angle_name + " beyond " +
             log_boundary_name + ", so "
             "log(z^-1 y) != h g(y) and ||f(y)|| = " + format_number(r.residual);
    case Status::local_minimum:
      return "a stationary point of 1/2 ||f||^2 that is no root: ||f(y)|| = " + format_number(r.residual) + at;
    case Status::no_descent:
      return "no step decreases 1/2 ||f||^2 although ||f(y)|| = " + format_number(r.residual) + at +
             " is far above its floor and no stationary point: phi is not smooth there";
    case Status::fold:
      return "z's branch of roots turns back before h: no root continued from z exists at h; ||f(y)|| = " +
             format_number(r.residual);
    case Status::cancelled: return "cancelled by the caller";
    case Status::min_step:   // an integration's statuses: integrate_on words their reasons
    case Status::max_steps: break;
  }
  return "unknown";
}

}  // namespace lienewton
