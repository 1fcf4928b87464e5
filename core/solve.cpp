#include "solve.hpp"

#include "groups/with_group.hpp"
#include "problems.hpp"
#include "solvers/run_method.hpp"
#include "start_point.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

template <class G>
SolveResult solve_on(const G& group, const SolveRequest& req, const Eigen::MatrixXd& z, const TraceCallback& cb) {
  const auto field = make_field(group, req.problem, req.rigid_body);
  const auto eq = Equation<G>::implicit_euler(group, typename G::Element(z), req.h, *field);
  const SolverOptions opt{req.tol,           req.max_iterations,  req.include_iterates,
                          req.differential,  req.linear_solver,   req.stopping};
  return run_method(req.method, eq, opt, cb);
}

}  // namespace

void validate(const SolveRequest& req) {
  validation::check_n("n", req.n);
  validation::check_h("h", req.h);
  validation::check_tol(req.tol);
  validation::check_max_iterations(req.max_iterations);
  validation::check_problem_dimension(req.problem, req.n);
  validation::check_rigid_body(req.rigid_body);
  validation::check_start_point(req.z, req.n);
}

SolveResult solve(const SolveRequest& req, const TraceCallback& on_iteration) {
  validate(req);
  const Eigen::MatrixXd z = req.z ? *req.z : start_point(req.n, req.seed);
  return with_group(req.n, [&](const auto& group) { return solve_on(group, req, z, on_iteration); });
}

}  // namespace lienewton
