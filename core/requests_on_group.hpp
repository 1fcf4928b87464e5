#pragma once
// Every request on one group G: what register_group<Family>() (register_group.hpp) compiles for each group of a
// family. The requests' own files (solve.cpp, basins.cpp, integrate.cpp, reference_solution.cpp) validate (or are
// handed a validated request) and reach these through the problem's family (ProblemSpec::family()).
// integrate_on() and reference_on() are the integrators' (integrators/).
#include <Eigen/Dense>
#include <algorithm>
#include <string>

#include "basin_map.hpp"
#include "integrators/integrate_on.hpp"
#include "integrators/reference_on.hpp"
#include "problems.hpp"
#include "solve.hpp"
#include "solvers/run_method.hpp"
#include "user_field/user_vector_field.hpp"

namespace lienewton {

// solve(): the implicit Euler equation of the request's problem, from z (or y0), by the request's method.
template <LieGroup G>
SolveResult solve_on(const G& group, const SolveRequest& req, const TraceCallback& cb) {
  const auto field = make_field(group, req.problem);
  auto eq = Equation<G>::implicit_euler(group, group.element(req.problem.start()), req.h, *field);
  if (req.y0) eq.start_at(group.element(*req.y0));
  SolveResult result = run_method(req.solver.method, eq, req.solver, cb);
  if (result.status == Status::non_finite) {
    if (std::string why = off_algebra_reason(group, *field, result.total_iterations()); !why.empty())
      result.reason = std::move(why);
  }
  return result;
}

// basins(): the map of the request's implicit Euler equation over its plane of starts.
template <LieGroup G>
BasinResult basins_on(const G& group, const BasinRequest& req, const BasinRowCallback& on_row, const WorkFarm* farm) {
  const BasinGrid grid = basin_grid(req);
  const BasinPlane plane{grid.b1,      grid.b2,          req.size,    grid.radius,
                         req.methods,  req.solve.solver, req.threads, req.shard};
  const auto field = make_field(group, req.solve.problem);
  const auto eq = Equation<G>::implicit_euler(group, group.element(req.solve.problem.start()), req.solve.h, *field);
  BasinResult result = basin_map(eq, plane, on_row, farm);
  result.grid.group = grid.group;
  return result;
}

// field_rate(): the field's speed and the size of its differential at y, whichever is larger.
template <LieGroup G>
double field_rate_on(const G& group, const ProblemSpec& problem, const Eigen::MatrixXd& y0) {
  const auto field = make_field(group, problem);
  const typename G::Element y = group.element(y0);
  return std::max(field->g(y).norm(), field->dg_matrix(group, y).norm());
}

}  // namespace lienewton
