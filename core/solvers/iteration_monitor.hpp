#pragma once
// The bookkeeping every solver shares: the trace, the callback, the stopping rule of section 5 and the
// failure classes. A solver reports each iterate y_n with its residuals; the monitor says whether to stop.
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/solver_options.hpp"
#include "solve_result.hpp"

namespace lienewton {

// Past this, a residual, step or algebra iterate counts as diverged: no solution of interest on a compact
// group has coordinates near 1e8 (on SO(N) ||f|| <= pi sqrt(q) + h ||g||).
inline constexpr double kDivergenceBound = 1e8;
// Reciprocal condition number below which the Newton system is reported singular instead of solved.
inline constexpr double kSingularRcond = 1e-14;

// What the monitor is told about iterate n besides its trace record.
struct Measurement {
  double stop;          // compared with tol: ||f(y_n)||, or ||f~(v_n)|| under Stopping::algebra_residual
  double driven;        // the residual the iteration drives to 0 (f~ for Version 2 and the fixed point, else f)
  const char* driven_name;  // how the reason names it
  double floor;         // rounding floor of `driven`: below it a non-decreasing residual means stagnation
  double rounding;      // what rounding alone leaves of `driven` (solver_run.hpp: kRoundingMargin)
};

class IterationMonitor {
 public:
  IterationMonitor(const SolverOptions& options, const TraceCallback& callback);

  // Records iterate n. Returns the status to stop with, or nothing to go on.
  std::optional<Status> record(TraceRecord rec, const Measurement& m);

  // Ends the solve: fills status, iterations, rate, trace, seconds; the caller fills what describes the
  // returned iterate (y, residual, reason).
  SolveResult finish(Status status);
  int iteration() const { return iteration_; }
  void next() { ++iteration_; }
  double elapsed() const;
  // CPU time of this thread since the solve started, less the time spent in the callback (which streams the
  // record to a client): what the solver itself cost, measured as work_precision measures runs.
  double solver_cpu_seconds() const;
  // Why the run diverged: which quantity passed kDivergenceBound, and its value.
  const std::string& divergence() const { return divergence_; }
  void diverged_because(std::string what) { divergence_ = std::move(what); }

 private:
  SolverOptions options_;
  const TraceCallback& callback_;
  std::chrono::steady_clock::time_point start_;
  double cpu_start_;
  double callback_cpu_seconds_ = 0;
  std::vector<TraceRecord> trace_;
  std::vector<double> stops_;
  std::vector<double> floors_;  // each stop's rounding floor
  int iteration_ = 0;
  int stalled_ = 0;
  double best_ = std::numeric_limits<double>::infinity();
  std::string divergence_;
};

std::string reason_for(Status status, const SolveResult& result, const std::string& angle_name,
                       const std::string& log_boundary_name);
std::string format_number(double x);

}  // namespace lienewton
