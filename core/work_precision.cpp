#include "work_precision.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include "cpu_clock.hpp"
#include "solvers/iteration_monitor.hpp"
#include "cancellation.hpp"
#include "order_fit.hpp"
#include "parallel_for.hpp"
#include "reference_solution.hpp"
#include "time_scale.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

constexpr std::size_t kMaxRuns = 200;
// A global error below this is rounding's, not the method's: no order can be read from it.
constexpr double kErrorAtRounding = 1e-12;

// The run of choice c at its k-th step size, or (against tolerance) its k-th tolerance.
IntegrateRequest run_request(const WorkPrecisionRequest& req, const WorkPrecisionChoice& c, std::size_t k) {
  IntegrateRequest r{.problem = req.problem, .solver = req.solver, .t_end = req.t_end, .integrator = c.integrator,
                     .predictor = req.predictor, .reference = false};
  r.solver.method = c.method;
  r.solver.differential = c.differential;
  if (req.tolerances.empty()) {
    r.h = req.h[k];
  } else {
    r.h = std::min(kDefaultIntegrationStep, req.t_end);  // the first step tried: the controller sizes the rest
    r.rtol = r.atol = req.tolerances[k];
    r.max_steps = req.max_steps;
  }
  return r;
}


std::size_t runs_per_choice(const WorkPrecisionRequest& req) {
  return req.tolerances.empty() ? req.h.size() : req.tolerances.size();
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

// The observed order (order_fit.hpp) over the points in the asymptotic regime: converged, with an error above
// the reference's own (kReferenceErrorFactor times its estimated error) and well below the solution's size
// (kSolutionScaleFraction of ||y_ref||, integrate.hpp), and consecutive slopes that agree (asymptotic_range). Each
// point says whether it is in the fit and, if not, why; an order needs kMinFitPoints of them, else it is null and
// fit_reason says why.
constexpr std::size_t kMinFitPoints = 3;

void fit_order(WorkPrecisionSeries& series, const ReferenceSolution& reference) {
  series.fitted_order.reset();
  if (!series.points.empty() && series.points.front().tolerance) {
    for (WorkPrecisionPoint& p : series.points)
      p.excluded = "against tolerance: no order is fitted from adaptive runs";
    series.fit_reason = "against tolerance: no order is fitted from adaptive runs";
    return;
  }
  const double size = reference.y ? reference.y->norm() : 0.0;
  const double floor = std::max(kErrorAtRounding, kReferenceErrorFactor * reference.error);
  const double ceiling = kSolutionScaleFraction * size;
  std::vector<double> h, error;
  std::vector<WorkPrecisionPoint*> usable;
  int failed = 0, at_floor = 0, too_large = 0;
  for (WorkPrecisionPoint& p : series.points) {
    p.in_fit = false;
    if (p.status != Status::converged) {
      ++failed;
      p.excluded = "the run did not converge on the solution's branch (" + std::string(to_string(p.status)) + ")";
    } else if (!reference.y) {
      ++failed;
      p.excluded = reference.note;
    } else if (!std::isfinite(p.error)) {
      ++failed;
      p.excluded = "the run's result is not finite";
    } else if (p.error <= floor) {
      ++at_floor;
      p.excluded = "its error is within " + format_number(kReferenceErrorFactor) +
                   "x of the reference's estimated error, or at rounding (below " + format_number(floor) + ")";
    } else if (p.error >= ceiling) {
      ++too_large;
      p.excluded = "its error is not small against the solution (at least " + format_number(kSolutionScaleFraction) +
                   " ||y_ref|| = " + format_number(ceiling) + "): outside the asymptotic regime";
    } else {
      usable.push_back(&p);
      h.push_back(p.h);
      error.push_back(p.error);
    }
  }
  const AsymptoticRange range = asymptotic_range(h, error);
  for (std::size_t i = 0; i < usable.size(); ++i) {
    usable[i]->in_fit = range.contains(i);
    if (!usable[i]->in_fit) usable[i]->excluded = "its slope disagrees with the smaller h's (not yet asymptotic)";
  }
  if (range.indices.size() >= kMinFitPoints && range.order) {
    series.fitted_order = range.order;
    series.fit_reason = "fitted over " + std::to_string(range.indices.size()) + " points in the asymptotic regime";
    return;
  }
  for (WorkPrecisionPoint* p : usable) {
    if (!p->in_fit) continue;
    p->in_fit = false;
    p->excluded = "too few points in the asymptotic regime to fit an order";
  }
  const auto count = [](int k, const char* what) { return k ? ", " + std::to_string(k) + " " + what : std::string(); };
  series.fit_reason = "no order: " + std::to_string(range.indices.size()) + " of " +
                      std::to_string(series.points.size()) + " points in the asymptotic regime, at least " +
                      std::to_string(kMinFitPoints) + " with consistent slopes needed (" +
                      std::to_string(usable.size() - range.indices.size()) + " with inconsistent slopes" +
                      count(at_floor, "at the reference's accuracy: larger h would show the order") +
                      count(too_large, "too large against the solution: smaller h would") + count(failed, "failed") +
                      ")";
}

}  // namespace

std::vector<WorkPrecisionChoice> default_choices() {
  std::vector<WorkPrecisionChoice> choices;
  for (Integrator i : kAllIntegrators) choices.push_back({.integrator = i});
  return choices;
}

WorkPrecisionRequest with_defaults(const WorkPrecisionRequest& request) {
  WorkPrecisionRequest req = request;
  if (req.choices.empty()) req.choices = default_choices();
  if (req.h.empty() && req.tolerances.empty()) req.h = default_step_sizes(req.problem, req.t_end);
  return req;
}

void validate(const WorkPrecisionRequest& request) {
  if (!request.h.empty() && !request.tolerances.empty())
    validation::unprocessable("tolerances", "give either h (fixed steps) or tolerances (adaptive steps), not both");
  for (double tol : request.tolerances) validation::check_tolerance(fields::tolerances, tol, "tolerances");
  validate(request.problem);  // before its field sets the default steps
  const WorkPrecisionRequest req = with_defaults(request);
  const std::size_t runs = runs_per_choice(req);
  if (req.choices.size() * runs > kMaxRuns)
    validation::invalid(req.tolerances.empty() ? "h" : "tolerances",
                        "choices x " + std::string(req.tolerances.empty() ? "h" : "tolerances") + " must be at most " +
                            std::to_string(kMaxRuns) + " runs");
  // The runs go on up to every core at once, each with its own workspace for g.
  const std::size_t threads = std::min(static_cast<std::size_t>(resolve_thread_count(0)), req.choices.size() * runs);
  validation::check_workspace(req.problem, static_cast<int>(threads));
  for (std::size_t k = 0; k < runs; ++k) validate(run_request(req, req.choices.front(), k));
  for (const WorkPrecisionChoice& c : req.choices) validate(run_request(req, c, 0));
  for (const WorkPrecisionChoice& c : req.choices) check_globalization(c.method, req.solver);
}

WorkPrecisionResult work_precision(const WorkPrecisionRequest& request, const SeriesCallback& on_series) {
  validate(request);
  return work_precision_validated(request, on_series);
}

WorkPrecisionResult work_precision_validated(const WorkPrecisionRequest& request, const SeriesCallback& on_series) {
  const WorkPrecisionRequest req = with_defaults(request);
  const std::size_t per_choice = runs_per_choice(req);
  const auto start = std::chrono::steady_clock::now();
  WorkPrecisionResult res;
  const double ref_start = thread_cpu_seconds();
  const ReferenceSolution reference = reference_solution(req.problem, req.problem.start(), req.t_end);
  res.reference_seconds = thread_cpu_seconds() - ref_start;
  if (reference.y) res.reference_error = reference.error;

  res.series.resize(req.choices.size());
  for (std::size_t c = 0; c < req.choices.size(); ++c) {
    res.series[c].choice = req.choices[c];
    res.series[c].points.resize(per_choice);
  }
  const int runs = static_cast<int>(req.choices.size() * per_choice);
  std::vector<int> remaining(req.choices.size(), static_cast<int>(per_choice));
  std::mutex mutex;
  parallel_for(runs, 0, [&](int index) {
    const std::size_t c = static_cast<std::size_t>(index) / per_choice, k = static_cast<std::size_t>(index) % per_choice;
    const IntegrateRequest ir = run_request(req, req.choices[c], k);
    const IntegrateResult run = integrate(ir);
    WorkPrecisionPoint& p = res.series[c].points[k];
    p.h = ir.adaptive() ? (run.steps.empty() ? 0.0 : run.steps.back().t / double(run.steps.size())) : *ir.h;
    p.tolerance = ir.rtol;
    p.rejected = run.rejected;
    p.cpu_seconds = min_cpu_seconds(ir, run.cpu_seconds);
    p.status = run.status;
    p.error = reference.y ? (run.y - *reference.y).norm() : std::numeric_limits<double>::quiet_NaN();
    for (const auto& s : run.steps) p.iterations += s.iterations;
    p.substeps = run.substeps;
    p.drifts = run.invariant_drifts;
    std::lock_guard lock(mutex);
    if (--remaining[c] > 0) return true;
    fit_order(res.series[c], reference);
    return !on_series || on_series(res.series[c]);
  });
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return res;
}

}  // namespace lienewton
