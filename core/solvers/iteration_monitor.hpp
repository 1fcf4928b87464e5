#pragma once
// The bookkeeping every solver shares: the trace, the callback, the stopping rule of section 5 and the
// failure classes. A solver reports each iterate y_n with its residual; the monitor says whether to stop.
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/options.hpp"
#include "solve_result.hpp"

namespace lienewton {

// Past this, a residual, step or algebra iterate counts as diverged: no solution of interest on a compact
// group has coordinates near 1e8 (on SO(N) ||f|| <= pi sqrt(q) + h ||g||).
inline constexpr double kDivergenceBound = 1e8;
// Reciprocal condition number below which the Newton system is reported singular instead of solved.
inline constexpr double kSingularRcond = 1e-14;

struct SolverOptions {
  double tol = 1e-13;
  int max_iterations = 100;
  bool include_iterates = false;
  Differential differential = Differential::exact;
  LinearSolver linear_solver = LinearSolver::auto_select;
};

class IterationMonitor {
 public:
  IterationMonitor(const SolverOptions& options, const TraceCallback& callback, int algebra_dim);

  // Records iterate n and defect(y_n). Returns the status to stop with, or nothing to go on.
  // scale ~ 1 + ||v|| + h ||g|| sets the rounding floor 64 eps sqrt(q) scale below which a non-decreasing
  // residual means stagnation.
  template <class Element>
  std::optional<Status> record(double residual, double step, double angle, const Element& y, double defect,
                               double scale) {
    TraceRecord rec;
    rec.iteration = iteration_;
    rec.residual = residual;
    rec.step = step;
    rec.angle = angle;
    rec.orthogonality_error = defect;
    rec.seconds = elapsed();
    rec.cpu_seconds = solver_cpu_seconds();
    if (options_.include_iterates) rec.y = y;
    return commit(rec, scale);
  }

  // Ends the solve: fills status, reason, iterations, rate, residual; the caller sets y.
  SolveResult finish(Status status, std::string detail = {});
  int iteration() const { return iteration_; }
  void next() { ++iteration_; }
  double elapsed() const;
  // CPU time of this thread since the solve started, less the time spent in the callback (which streams the
  // record to a client): what the solver itself cost, measured as work_precision measures runs.
  double solver_cpu_seconds() const;
  double last_residual() const { return residuals_.empty() ? 0.0 : residuals_.back(); }
  double best_residual() const { return best_; }

 private:
  std::optional<Status> commit(TraceRecord& rec, double scale);

  SolverOptions options_;
  const TraceCallback& callback_;
  double sqrt_q_;
  std::chrono::steady_clock::time_point start_;
  double cpu_start_;
  double callback_cpu_seconds_ = 0;
  std::vector<TraceRecord> trace_;
  std::vector<double> residuals_;
  int iteration_ = 0;
  int stalled_ = 0;
  double best_ = std::numeric_limits<double>::infinity();
};

std::string reason_for(Status status, const SolveResult& result);

}  // namespace lienewton
