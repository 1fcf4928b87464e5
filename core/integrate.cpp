#include "integrate.hpp"

#include <cmath>

#include "cpu_clock.hpp"
#include "group_registry.hpp"
#include "reference_solution.hpp"
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
  validate(req.solver);
  check_globalization(req.solver.method, req.solver);
  if (req.frames < 0 || req.frames > 1000) validation::invalid("frames", "frames must be an integer in [0, 1000]");
}

IntegrateResult integrate(const IntegrateRequest& req, const StepCallback& on_step) {
  validate(req);
  const Eigen::MatrixXd y0 = req.problem.start();
  IntegrateResult res = group_family(req.problem.group).integrate(req, y0, on_step);
  if (req.reference && res.status == Status::converged) {
    const double start = thread_cpu_seconds();
    res.global_error = (res.y - reference_solution(req.problem, y0, req.t_end)).norm();
    res.reference_seconds = thread_cpu_seconds() - start;
  }
  return res;
}

}  // namespace lienewton
