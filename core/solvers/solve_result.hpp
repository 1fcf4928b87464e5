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

// One point of continuation's path (solvers/continuation.hpp): a root (y = z exp(v), h) of
// F(v, h) = v - h g(z exp v) = 0 (3.21) on z's branch, or the method's solve at the requested h.
struct PathPoint {
  PathPointKind kind = PathPointKind::path;
  double h = 0;
  double distance = 0;     // ||v||: how far y = z exp(v) is from z, in the algebra's coordinates
  double angle = 0;        // largest rotation angle of v (the group's angle; log's branch ends at kLogRadius)
  double dh_ds = 0;        // the h-component of the branch's unit tangent: it changes sign at a fold
  double step_length = 0;  // the arclength s of the predictor step that reached this point
  int iterations = 0;      // the corrector's Newton iterations (final: the method's)
  double residual = 0;     // ||F(v, h)|| (final: ||f(y)|| of the method's returned y)
  Status status = Status::converged;  // final: the method's status
};

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
  std::optional<double> stage_h;   // continuation only: the h of the equation this iterate belongs to
  std::optional<PathPoint> path_point;  // continuation only: a record that is a point of the path, not an iterate
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
  Factorization linear_solver = Factorization::dense_lu;  // how its Newton systems were solved
  // Which root y is, and which search found it (core/options.hpp).
  Branch branch = Branch::unchecked;
  Search found_by = Search::plain;
  double distance_from_z = 0;          // ||y - z||_F
  std::optional<double> fold_h;        // continuation: the h at which z's branch turns back (status fold when < h)
  std::optional<double> path_h;        // continuation: the largest h the path reached when it stopped short of h
  std::optional<int> multistart_start; // found_by multistart: which seeded start, from 0
  int multistart_tries = 0;            // seeded starts solved
  // continuation only: the path's points, the method's solves at h included (the last is this result's)
  std::vector<PathPoint> continuation;
  int extra_iterations = 0;  // iterations of the searches besides the returned solve (path, multistart tries)
  // Newton iterations the answer cost: the returned solve's and every other the search made.
  int total_iterations() const { return iterations + extra_iterations; }
};

// A root to rounding: converged, or stagnated at its rounding floor.
inline bool is_root(const SolveResult& r) { return r.status == Status::converged || r.status == Status::stagnated; }

// Called once per trace record as it is computed; return false to cancel the solve (status cancelled).
using TraceCallback = std::function<bool(const TraceRecord&)>;

}  // namespace lienewton
