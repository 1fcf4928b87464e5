#include "work_precision.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>

#include "cpu_clock.hpp"
#include "cancellation.hpp"
#include "order_fit.hpp"
#include "parallel_for.hpp"
#include "reference_solution.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

constexpr std::size_t kMaxRuns = 200;

std::vector<double> default_step_sizes() {
  std::vector<double> h;
  for (int e = -2; e >= -7; --e) h.push_back(std::ldexp(1.0, e));
  return h;
}

IntegrateRequest run_request(const WorkPrecisionRequest& req, const WorkPrecisionChoice& c, double h) {
  IntegrateRequest r{.problem = req.problem, .solver = req.solver, .h = h, .t_end = req.t_end,
                     .integrator = c.integrator, .predictor = req.predictor, .reference = false};
  r.solver.method = c.method;
  r.solver.differential = c.differential;
  return r;
}

// Short runs (tens of microseconds) are timed again until kTimingBudget of CPU time is spent, at most
// kMaxRepeats times, and the minimum is kept: the minimum is the least disturbed by other work.
constexpr double kTimingBudget = 5e-3;
constexpr int kMaxRepeats = 20;

double min_cpu_seconds(const IntegrateRequest& ir, double first) {
  double best = first, spent = first;
  for (int r = 1; r < kMaxRepeats && spent < kTimingBudget; ++r) {
    throw_if_cancelled();
    const double t = integrate(ir).cpu_seconds;
    best = std::min(best, t);
    spent += t;
  }
  return best;
}

// The observed order from the points whose run converged (a failed run's error says nothing about h^p).
std::optional<double> series_order(const WorkPrecisionSeries& series) {
  std::vector<double> h, error;
  for (const WorkPrecisionPoint& p : series.points) {
    if (p.status != Status::converged) continue;
    h.push_back(p.h);
    error.push_back(p.error);
  }
  return fitted_order(h, error);
}

}  // namespace

void validate(const WorkPrecisionRequest& req) {
  if (req.choices.empty()) validation::invalid("choices", "choices must list at least one choice");
  const std::vector<double> hs = req.h.empty() ? default_step_sizes() : req.h;
  if (req.choices.size() * hs.size() > kMaxRuns)
    validation::invalid("h", "choices x h must be at most " + std::to_string(kMaxRuns) + " runs");
  for (double h : hs) validate(run_request(req, req.choices.front(), h));
  for (const WorkPrecisionChoice& c : req.choices) check_globalization(c.method, req.solver);
}

WorkPrecisionResult work_precision(const WorkPrecisionRequest& request, const SeriesCallback& on_series) {
  validate(request);
  WorkPrecisionRequest req = request;
  if (req.h.empty()) req.h = default_step_sizes();
  const auto start = std::chrono::steady_clock::now();
  WorkPrecisionResult res;
  const double ref_start = thread_cpu_seconds();
  const Eigen::MatrixXd y_ref =
      reference_solution(req.problem, req.problem.start(), req.t_end);
  res.reference_seconds = thread_cpu_seconds() - ref_start;

  res.series.resize(req.choices.size());
  for (std::size_t c = 0; c < req.choices.size(); ++c) {
    res.series[c].choice = req.choices[c];
    res.series[c].points.resize(req.h.size());
  }
  const int runs = static_cast<int>(req.choices.size() * req.h.size());
  std::vector<int> remaining(req.choices.size(), static_cast<int>(req.h.size()));
  std::mutex mutex;
  parallel_for(runs, 0, [&](int index) {
    const std::size_t c = static_cast<std::size_t>(index) / req.h.size(), k = static_cast<std::size_t>(index) % req.h.size();
    const IntegrateRequest ir = run_request(req, req.choices[c], req.h[k]);
    const IntegrateResult run = integrate(ir);
    WorkPrecisionPoint& p = res.series[c].points[k];
    p.h = req.h[k];
    p.cpu_seconds = min_cpu_seconds(ir, run.cpu_seconds);
    p.status = run.status;
    p.error = (run.y - y_ref).norm();
    for (const auto& s : run.steps) p.iterations += s.iterations;
    std::lock_guard lock(mutex);
    if (--remaining[c] > 0) return true;
    res.series[c].fitted_order = series_order(res.series[c]);
    return !on_series || on_series(res.series[c]);
  });
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return res;
}

}  // namespace lienewton
