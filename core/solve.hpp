#pragma once
// One solve of the implicit Euler equation y = z exp(h g(y)), i.e. f(y) = log(z^-1 y) - h g(y) = 0 (3.6),
// by a chosen method and differential: the request shared by the CLI and the service.
#include "problem_spec.hpp"
#include "solver_options.hpp"
#include "solvers/solve_result.hpp"

namespace lienewton {

struct SolveRequest {
  ProblemSpec problem{};
  SolverOptions solver{};
  double h = 0.5;
  std::optional<Eigen::MatrixXd> y0{};  // where the iteration starts; when absent, z (as the paper); z stays the equation's
};

// Validates the request (throws RequestError naming the field) and solves it.
SolveResult solve(const SolveRequest& request, const TraceCallback& on_iteration = {});
// Solves a request the caller has already validated (the server, before its answer's status line): it is not
// checked again, nor is a user's g evaluated again for it.
SolveResult solve_validated(const SolveRequest& request, const TraceCallback& on_iteration = {});

// Checks every field of the request; throws RequestError. Called by solve(); exposed for front ends.
void validate(const SolveRequest& request);

}  // namespace lienewton
