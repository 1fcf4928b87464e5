#pragma once
// Work-precision data: for each (integrator, method, differential) and each step size h, the CPU time of
// the integration and its global error, so that speed can be charted against accuracy.
#include <optional>
#include <string>
#include <vector>

#include "integrate.hpp"

namespace lienewton {

struct WorkPrecisionChoice {
  Integrator integrator = Integrator::implicit_euler;
  Method method = Method::newton_group;
  Differential differential = Differential::exact;
};

// Every run integrates problem with solver, its integrator, method and differential taken from one of choices.
struct WorkPrecisionRequest {
  ProblemSpec problem{.kind = ProblemKind::rigid_body};
  SolverOptions solver{};
  double t_end = 1.0;
  std::vector<WorkPrecisionChoice> choices{};  // default: default_choices()
  std::vector<double> h{};  // default: from the problem's time scale (time_scale.hpp)
  Predictor predictor = Predictor::lie_euler;  // where every stage's iteration starts (IntegrateRequest)
  // Against tolerance instead of h: each choice runs with adaptive steps at rtol = atol = each tolerance, from the
  // first step IntegrateRequest's default h (at most t_end), and at most max_steps tries per run (the server
  // lowers it to share its step budget among the runs).
  std::vector<double> tolerances{};
  int max_steps = static_cast<int>(fields::max_steps.default_value);
};

struct WorkPrecisionPoint {
  double h = 0;            // fixed steps: the step size; adaptive: the mean accepted step, t_end / steps
  std::optional<double> tolerance{};  // adaptive: the run's rtol = atol
  int rejected = 0;        // adaptive: tries rejected
  double cpu_seconds = 0;  // minimum over repeated runs (short runs are repeated up to 5 ms of CPU time)
  double error = 0;
  Status status = Status::converged;
  int iterations = 0;  // total Newton/fixed-point iterations of the run
  int substeps = 0;    // steps taken (more than t_end / h where halving kept the solution's branch)
  InvariantValues drifts{};  // the run's invariant_drifts (IntegrateResult): the problem's invariants' drift
  bool in_fit = false;   // one of the points the series' order is fitted from
  std::string excluded;  // why the fit leaves it out (empty when in_fit)
};

struct WorkPrecisionSeries {
  WorkPrecisionChoice choice;
  std::vector<WorkPrecisionPoint> points;
  // Least-squares slope of log error vs log h over the points in the asymptotic regime (work_precision.cpp's
  // fit_order): the observed order. Only honest points enter: runs whose every stage kept the solution's branch,
  // errors well between the reference's accuracy and the solution's size. None against tolerance: adaptive runs'
  // mean steps are no h an order is read from.
  std::optional<double> fitted_order;
  std::string fit_reason;  // how the order was fitted, or why it is null
};

struct WorkPrecisionResult {
  std::vector<WorkPrecisionSeries> series;
  std::optional<double> reference_error;  // the reference's estimated error (none without a reference)
  double reference_seconds = 0;
  double seconds = 0;
};

// Without choices: every integrator with Newton on the group and the exact differential. Without h or tolerances:
// the step sizes of the problem's time scale (time_scale.hpp; the problem must be valid).
std::vector<WorkPrecisionChoice> default_choices();
WorkPrecisionRequest with_defaults(const WorkPrecisionRequest& request);
void validate(const WorkPrecisionRequest& request);
using SeriesCallback = std::function<bool(const WorkPrecisionSeries&)>;
WorkPrecisionResult work_precision(const WorkPrecisionRequest& request, const SeriesCallback& on_series = {});
// work_precision() of a request the caller has already validated: it is not checked again.
WorkPrecisionResult work_precision_validated(const WorkPrecisionRequest& request, const SeriesCallback& on_series = {});

}  // namespace lienewton
