#pragma once
// One solve of the implicit Euler equation y = z exp(h g(y)), i.e. f(y) = log(z^-1 y) - h g(y) = 0 (3.6),
// by a chosen method and differential. This is the request/result model shared by the CLI and the service.
#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "options.hpp"
#include "status.hpp"

namespace lienewton {

// Parameters of the free rigid body y' = y hat(I^-1 y^T m) on SO(3).
struct RigidBodyParams {
  Eigen::Vector3d inertia{1.0, 2.0, 3.0};   // principal moments, diagonal of I
  Eigen::Vector3d momentum{0.6, 0.8, 0.5};  // constant spatial angular momentum m
};

struct SolveRequest {
  ProblemKind problem = ProblemKind::paper_linear;
  int n = 3;
  double h = 0.5;
  Method method = Method::newton_group;
  Differential differential = Differential::exact;
  double tol = 1e-13;
  int max_iterations = 100;
  std::uint64_t seed = 1;
  std::optional<Eigen::MatrixXd> z;  // start point; when absent, start_point(n, seed)
  bool include_iterates = false;
  RigidBodyParams rigid_body;
  LinearSolver linear_solver = LinearSolver::auto_select;
};

// One record per iterate y_n, n = 0, 1, ... (y_0 = z).
struct TraceRecord {
  int iteration = 0;
  double residual = 0;             // ||f(y_n)||: 2-norm of coordinates in the basis E_ij - E_ji = ||f||_F / sqrt(2)
  double step = 0;                 // ||u_{n-1}||, the update that produced y_n (0 for n = 0)
  double angle = 0;                // largest rotation angle of z^-1 y_n
  double orthogonality_error = 0;  // ||y_n^T y_n - I||_F
  double seconds = 0;              // since the solve started
  Eigen::MatrixXd y;               // y_n when include_iterates, else empty
  double distance_to_pi() const { return 3.14159265358979323846 - angle; }
};

struct SolveResult {
  Status status = Status::max_iterations;
  std::string reason;
  int iterations = 0;           // the n at which the loop stopped (converged: first n with ||f(y_n)|| <= tol)
  std::optional<double> rate;   // the paper's r from the last three residuals, when iterations >= 3
  double residual = 0;          // ||f(y_iterations)||
  double orthogonality_error = 0;
  Eigen::MatrixXd y;            // the final iterate (never NaN: a non-finite iterate is replaced by the last finite one)
  std::vector<TraceRecord> trace;
  double seconds = 0;
  std::string linear_solver;    // "lu" (dense, assembled) or "gmres" (matrix-free, large N)
};

// Called once per trace record as it is computed; return false to cancel the solve (status cancelled).
using TraceCallback = std::function<bool(const TraceRecord&)>;

// Validates the request (throws RequestError naming the field) and solves it.
SolveResult solve(const SolveRequest& request, const TraceCallback& on_iteration = {});

// Checks every field of the request; throws RequestError. Called by solve(); exposed for front ends.
void validate(const SolveRequest& request);

}  // namespace lienewton
