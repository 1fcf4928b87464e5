#pragma once
// Work-precision data: for each (integrator, method, differential) and each step size h, the CPU time of
// the integration and its global error, so that speed can be charted against accuracy.
#include <optional>
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
  std::vector<WorkPrecisionChoice> choices{};
  std::vector<double> h{};  // default: 2^-2 .. 2^-7
  Predictor predictor = Predictor::lie_euler;  // where every stage's iteration starts (IntegrateRequest)
};

struct WorkPrecisionPoint {
  double h = 0;
  double cpu_seconds = 0;  // minimum over repeated runs (short runs are repeated up to 5 ms of CPU time)
  double error = 0;
  Status status = Status::converged;
  int iterations = 0;  // total Newton/fixed-point iterations of the run
};

struct WorkPrecisionSeries {
  WorkPrecisionChoice choice;
  std::vector<WorkPrecisionPoint> points;
  // Least-squares slope of log error vs log h over the converged points (order_fit.hpp): the observed order.
  std::optional<double> fitted_order;
};

struct WorkPrecisionResult {
  std::vector<WorkPrecisionSeries> series;
  double reference_seconds = 0;
  double seconds = 0;
};

void validate(const WorkPrecisionRequest& request);
using SeriesCallback = std::function<bool(const WorkPrecisionSeries&)>;
WorkPrecisionResult work_precision(const WorkPrecisionRequest& request, const SeriesCallback& on_series = {});

}  // namespace lienewton
