#include "integrate.hpp"

#include <cmath>

#include "cpu_clock.hpp"
#include "group_registry.hpp"
#include "reference_solution.hpp"
#include "rkmk_tableau.hpp"
#include "solvers/newton_step.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

constexpr double kMaxSteps = 1e5;

}  // namespace

void validate(const IntegrateRequest& req) {
  validate(req.problem);
  validation::check(fields::h, req.h, "h");
  validation::check(fields::t_end, req.t_end, "t_end");
  if (req.h > req.t_end) validation::invalid("h", "h must not exceed t_end");
  if (req.t_end / req.h > kMaxSteps) validation::invalid("h", "t_end / h must be at most 1e5 steps");
  if (req.rtol) validation::check_tolerance(fields::rtol, *req.rtol, "rtol");
  if (req.atol) validation::check_tolerance(fields::atol, *req.atol, "atol");
  validation::check(fields::max_steps, req.max_steps, "max_steps");
  validate(req.solver);
  check_globalization(req.solver.method, req.solver);
  if (req.frames < 0 || req.frames > 1000) validation::invalid("frames", "frames must be an integer in [0, 1000]");
  // An implicit RKMK method's Newton factors its s q x s q stage system densely: as large as the dense Newton
  // step of a single equation goes (beyond it the time and memory grow as (s q)^3 and (s q)^2).
  if (rkmk_tableau(req.integrator) && req.problem.n > kKrylovThreshold)
    validation::invalid("integrator", std::string(to_string(req.integrator)) +
                                          " solves its coupled stage system densely: n must be at most " +
                                          std::to_string(kKrylovThreshold));
}

IntegrateResult integrate(const IntegrateRequest& req, const StepCallback& on_step) {
  validate(req);
  const Eigen::MatrixXd y0 = req.problem.start();
  IntegrateResult res = group_family(req.problem.group).integrate(req, y0, on_step);
  if (req.reference && res.status == Status::converged) {
    const double start = thread_cpu_seconds();
    const ReferenceSolution ref = reference_solution(req.problem, y0, req.t_end);
    if (ref.y)
      res.global_error = (res.y - *ref.y).norm();
    else
      res.reason += "; global_error is null: " + ref.note;
    res.reference_seconds = thread_cpu_seconds() - start;
  }
  return res;
}

}  // namespace lienewton
