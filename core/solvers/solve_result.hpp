#pragma once
// What a solver returns: the trace of every iterate and the result; TraceCallback streams the trace.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/options.hpp"
#include "core/status.hpp"

namespace lienewton {

// One record per iterate y_n, n = 0, 1, ... (y_0 = z).
struct TraceRecord {
  int iteration = 0;
  double residual = 0;             // ||f(y_n)||: 2-norm of coordinates in the basis E_ij - E_ji = ||f||_F / sqrt(2),
                                   // f(y) = log(z^-1 y) - h g(y) (3.6) for every method
  std::optional<double> algebra_residual;  // ||f~(v_n)|| (3.21), Version 2 and the fixed point (v_n = h g(y_{n-1}))
  double step = 0;                 // ||u_{n-1}||, the update that produced y_n (0 for n = 0)
  double angle = 0;                // largest rotation angle of z^-1 y_n
  double log_boundary_distance = 0;  // how far z^-1 y_n is from the boundary of log's domain (pi - angle on SO(N))
  double orthogonality_error = 0;  // ||y_n^T y_n - I||_F (the group's defect of y_n)
  double seconds = 0;              // wall time since the solve started
  double cpu_seconds = 0;          // the solver's own CPU time so far (thread CPU time, callbacks excluded)
  Eigen::MatrixXd y;               // y_n when include_iterates, else empty
  // Globalised Newton only (solvers/globalization.hpp): how u_{n-1} was found ("newton", "levenberg-marquardt",
  // "dogleg", "cauchy", "watchdog": a full step that did not decrease phi, solvers/watchdog.hpp), the accepted
  // line-search length alpha, the trust radius the step was taken in, and the earlier iterate the step started
  // from when the watchdog went back to it.
  std::string step_kind;
  std::optional<double> step_length;
  std::optional<double> trust_radius;
  std::optional<int> step_from_iterate;
  std::optional<double> stage_h;   // continuation only: the h of the stage this iterate belongs to
};

// One stage of a continued solve (solvers/continuation.hpp): the equation at step size h, started where `start`
// says, solved with `globalization`.
struct ContinuationStage {
  double h = 0;
  Status status = Status::max_iterations;
  int iterations = 0;
  double residual = 0;  // ||f(y)|| at this stage's h of the stage's returned y
  StageStart start = StageStart::given;
  Globalization globalization = Globalization::none;
  std::optional<int> restart;  // start == restart: which of the seeded starts (restart_start.hpp), from 0
};

struct SolveResult {
  Status status = Status::max_iterations;
  std::string reason;
  int iterations = 0;           // the n at which the loop stopped (converged: first n with ||f(y_n)|| <= tol)
  std::optional<double> rate;   // the paper's r from the last three residuals, when iterations >= 3
  bool rate_reliable = false;   // the last three residuals decrease, contract and lie above the floor (see README)
  int iterate = 0;              // the n of the returned y = y_n (the best iterate when stagnated)
  double residual = 0;          // ||f(y)|| of the returned y, f of (3.6)
  std::optional<double> algebra_residual;  // ||f~(v)|| of the returned y (Version 2, fixed point)
  double floor = 0;             // the rounding floor of the stopping residual at the returned y (README)
  double orthogonality_error = 0;  // ||y^T y - I||_F of the returned y
  double z_adjustment = 0;      // ||z - polar(z)||_F: how far the z rule moved the given z
  int reorthogonalisations = 0; // iterates replaced by their polar factor because ||y^T y - I|| drifted
  Eigen::MatrixXd y;            // the returned iterate y_iterate (never NaN)
  std::vector<TraceRecord> trace;
  double seconds = 0;           // wall time
  double cpu_seconds = 0;       // the solver's own CPU time (thread CPU time, callbacks excluded; 0 untimed)
  std::string linear_solver;    // "lu" (dense, assembled) or "gmres" (matrix-free, large N)
  // continuation only: every stage, the last at the requested h (whose solve is this result's status, trace, y)
  std::vector<ContinuationStage> continuation;
  // Newton iterations the answer cost: summed over the continuation's stages, else iterations.
  int total_iterations() const {
    if (continuation.empty()) return iterations;
    int total = 0;
    for (const ContinuationStage& s : continuation) total += s.iterations;
    return total;
  }
};

// Called once per trace record as it is computed; return false to cancel the solve (status cancelled).
using TraceCallback = std::function<bool(const TraceRecord&)>;

}  // namespace lienewton
