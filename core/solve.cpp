#include "solve.hpp"

#include "group_registry.hpp"
#include "validation.hpp"

namespace lienewton {

void validate(const SolveRequest& req) {
  validate(req.problem);
  validation::check(fields::h, req.h, "h");
  validate(req.solver);
  check_globalization(req.solver.method, req.solver);
  if (req.y0) validation::check_start_guess(req.problem, *req.y0);
}

SolveResult solve(const SolveRequest& req, const TraceCallback& on_iteration) {
  validate(req);
  return solve_validated(req, on_iteration);
}

SolveResult solve_validated(const SolveRequest& req, const TraceCallback& on_iteration) {
  return req.problem.family().solve(req, on_iteration);
}

}  // namespace lienewton
