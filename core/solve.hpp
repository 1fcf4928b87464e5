#pragma once
// One solve of the implicit Euler equation y = z exp(h g(y)), i.e. f(y) = log(z^-1 y) - h g(y) = 0 (3.6),
// by a chosen method and differential. This is the request/result model shared by the CLI and the service.
#include <Eigen/Dense>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "options.hpp"
#include "rigid_body_params.hpp"
#include "solvers/solve_result.hpp"
#include "status.hpp"

namespace lienewton {

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
  Stopping stopping = Stopping::residual;  // Version 2 and fixed point: ||f(y_n)|| (section 5) or ||f~(v_n)||
};

// Validates the request (throws RequestError naming the field) and solves it.
SolveResult solve(const SolveRequest& request, const TraceCallback& on_iteration = {});

// Checks every field of the request; throws RequestError. Called by solve(); exposed for front ends.
void validate(const SolveRequest& request);

}  // namespace lienewton
