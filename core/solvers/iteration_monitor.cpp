#include "iteration_monitor.hpp"

#include <cstdio>

#include "core/cpu_clock.hpp"

namespace lienewton {
namespace {

constexpr int kStallIterations = 3;  // residual not halved this many times in a row at the floor: stagnated

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// The paper's rate r from the last three residuals before convergence (section 5); needs p >= 3.
std::optional<double> convergence_rate(const std::vector<double>& r, int p) {
  if (p < 3 || static_cast<int>(r.size()) <= p - 1) return std::nullopt;
  const double num = std::log(r[p - 1] / r[p - 2]);
  const double den = std::log(r[p - 2] / r[p - 3]);
  const double rate = num / den;
  if (!std::isfinite(rate) || den == 0.0) return std::nullopt;
  return rate;
}

}  // namespace

IterationMonitor::IterationMonitor(const SolverOptions& options, const TraceCallback& callback, int algebra_dim)
    : options_(options), callback_(callback), sqrt_q_(std::sqrt(double(algebra_dim))),
      start_(std::chrono::steady_clock::now()), cpu_start_(thread_cpu_seconds()) {
  trace_.reserve(static_cast<std::size_t>(options.max_iterations) + 1);
  residuals_.reserve(static_cast<std::size_t>(options.max_iterations) + 1);
}

double IterationMonitor::solver_cpu_seconds() const {
  return thread_cpu_seconds() - cpu_start_ - callback_cpu_seconds_;
}

double IterationMonitor::elapsed() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

std::optional<Status> IterationMonitor::commit(TraceRecord& rec, double scale) {
  const double r = rec.residual;
  residuals_.push_back(r);
  trace_.push_back(std::move(rec));
  if (callback_) {
    const double before = thread_cpu_seconds();
    const bool go_on = callback_(trace_.back());
    callback_cpu_seconds_ += thread_cpu_seconds() - before;
    if (!go_on) return Status::cancelled;
  }
  if (!std::isfinite(r) || !std::isfinite(trace_.back().step)) return Status::non_finite;
  if (r <= options_.tol) return Status::converged;
  if (r > kDivergenceBound || trace_.back().step > kDivergenceBound) return Status::diverged;
  const double floor = 64.0 * std::numeric_limits<double>::epsilon() * sqrt_q_ * scale;
  stalled_ = (r > 0.5 * best_ && best_ <= floor) ? stalled_ + 1 : 0;
  best_ = std::min(best_, r);
  if (stalled_ >= kStallIterations) return Status::stagnated;
  if (iteration_ >= options_.max_iterations) return Status::max_iterations;
  return std::nullopt;
}

SolveResult IterationMonitor::finish(Status status, std::string detail) {
  SolveResult res;
  res.status = status;
  res.iterations = iteration_;
  res.residual = residuals_.empty() ? std::numeric_limits<double>::quiet_NaN() : residuals_.back();
  if (status == Status::converged) res.rate = convergence_rate(residuals_, iteration_);
  if (status == Status::stagnated) res.residual = best_;
  if (!trace_.empty()) res.orthogonality_error = trace_.back().orthogonality_error;
  res.seconds = elapsed();
  res.cpu_seconds = solver_cpu_seconds();
  res.trace = std::move(trace_);
  res.reason = reason_for(status, res);
  if (!detail.empty()) res.reason += " (" + detail + ")";
  return res;
}

std::string reason_for(Status status, const SolveResult& r) {
  switch (status) {
    case Status::converged:
      return "converged: ||f(y)|| = " + format_number(r.residual) + " after " + std::to_string(r.iterations) +
             " iterations";
    case Status::max_iterations:
      return "no convergence in " + std::to_string(r.iterations) + " iterations: ||f(y)|| = " +
             format_number(r.residual);
    case Status::diverged:
      return "diverged: residual or step exceeded " + format_number(kDivergenceBound);
    case Status::non_finite: return "a NaN or Inf appeared in the residual, the step or the iterate";
    case Status::left_log_domain:
      return "z^-1 y reached rotation angle pi, where log (and so f) is undefined";
    case Status::singular_differential:
      return "the Newton system is singular or too ill-conditioned (reciprocal condition < " +
             format_number(kSingularRcond) + ")";
    case Status::stagnated:
      return "stagnated at the rounding floor: best ||f(y)|| = " + format_number(r.residual) +
             ", above tol (for large h an absolute tol cannot be met)";
    case Status::off_branch:
      return "y solves y = z exp(h g(y)) to rounding, but h g(y) has a rotation angle beyond pi, so "
             "log(z^-1 y) != h g(y)";
    case Status::cancelled: return "cancelled by the caller";
  }
  return "unknown";
}

}  // namespace lienewton
