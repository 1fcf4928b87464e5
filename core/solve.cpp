#include "solve.hpp"

#include "groups/with_group.hpp"
#include "problems.hpp"
#include "solvers/run_method.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

template <class G>
SolveResult solve_on(const G& group, const SolveRequest& req, const TraceCallback& cb) {
  const auto field = make_field(group, req.problem.kind, req.problem.rigid_body);
  auto eq = Equation<G>::implicit_euler(group, typename G::Element(req.problem.start()), req.h, *field);
  if (req.y0) eq.start_at(typename G::Element(*req.y0));
  return run_method(req.solver.method, eq, req.solver, cb);
}

}  // namespace

void validate(const SolveRequest& req) {
  validate(req.problem);
  validation::check(fields::h, req.h, "h");
  validate(req.solver);
  check_globalization(req.solver.method, req.solver);
  if (req.y0) validation::check_start_guess(*req.y0, req.problem.start());
}

SolveResult solve(const SolveRequest& req, const TraceCallback& on_iteration) {
  validate(req);
  return with_group(req.problem.n, [&](const auto& group) { return solve_on(group, req, on_iteration); });
}

}  // namespace lienewton
