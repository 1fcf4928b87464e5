#include "integrate.hpp"

#include <cmath>

#include "cpu_clock.hpp"
#include "group_registry.hpp"
#include "reference_solution.hpp"
#include "integrators/methods.hpp"
#include "solvers/iteration_monitor.hpp"
#include "solvers/newton_step.hpp"
#include "time_scale.hpp"
#include "validation.hpp"

namespace lienewton {
namespace {

// The solver options an integrator's steps do not use are refused rather than ignored. A DIRK method solves each
// stage as an equation of (1.1) by run_method, which takes them all; an implicit RKMK method solves its coupled
// stage system by its own Newton (LU, sparse for a system of bodies; stopping on h ||F||, rkmk_stages.hpp); an explicit
// one solves nothing.
// No integrator's stages start from seeded starts: each needs the root continued from its own start.
void check_stage_options(const IntegrateRequest& req) {
  const SolverOptions& o = req.solver;
  const std::string name(to_string(req.integrator));
  if (o.multistart > 0)
    validation::invalid("multistart", "integrate's stages take the root continued from their start, never one from "
                                      "seeded starts: multistart applies to solve and sweep");
  const integrators::Form form = integrators::tableau_of(req.integrator).form;
  if (form == integrators::Form::dirk_crouch_grossman) return;
  const std::string why = form == integrators::Form::explicit_rkmk
                              ? name + " is explicit: its steps solve no equation"
                              : name + " solves its coupled stage system by its own Newton (LU, stopping on "
                                       "h ||F||)";
  const auto refuse = [&](const char* field) {
    validation::invalid(field, why + "; " + field + " applies to the DIRK integrators' stage equations");
  };
  if (o.globalization != Globalization::none) refuse("globalization");
  if (o.watchdog) refuse("watchdog");
  if (o.linear_solver == LinearSolver::gmres) refuse("linear_solver");
  if (o.stopping != Stopping::residual) refuse("stopping");
}

// The warnings of a converged run (IntegrateWarning): a default step raised past the field's time scale, a global
// error that is not small against the solution, an invariant that is not conserved.
std::vector<IntegrateWarning> warnings_of(const IntegrateRequest& req, const IntegrateResult& res,
                                          const std::optional<Eigen::MatrixXd>& y_ref) {
  std::vector<IntegrateWarning> out;
  if (req.h_defaulted && !req.adaptive()) {
    const double over = *req.h * field_rate(req.problem);
    if (over > kDefaultStepOverTimeScale)
      out.push_back({kStepEnlarged, "the default step h = " + format_number(*req.h) + " is " + format_number(over) +
                                          " times the field's time scale 1/rho, raised with t_end (the default steps "
                                          "keep t_end within " + format_number(kMaxRunSteps) + " steps of h/" +
                                          format_number(std::ldexp(1.0, kMinDefaultStepCount - 1)) +
                                          "): give a smaller t_end or an h"});
  }
  if (res.global_error && y_ref && *res.global_error > kInaccurateFraction * y_ref->norm())
    out.push_back({kInaccurate, "global_error " + format_number(*res.global_error) + " is more than " +
                                     format_number(kInaccurateFraction) + " of the solution's size ||y_ref||_F = " +
                                     format_number(y_ref->norm()) + ": the trajectory is not the solution's"});
  for (Invariant i : kAllInvariants)
    if (const auto& drift = res.invariant_drifts[i]; drift && *drift > kInvariantDriftWarning)
      out.push_back({kInvariantDrift, std::string(to_string(i)) + " drifts by " + format_number(*drift) +
                                            " of its scale (more than " + format_number(kInvariantDriftWarning) +
                                            "), though the exact flow keeps it"});
  return out;
}

// An implicit RKMK method's Newton factors its s q x s q stage system densely: as large as the dense Newton step of a
// single equation goes (beyond it the time and memory grow as (s q)^3 and (s q)^2). A family that bounds its index
// itself (a system of bodies) keeps the stage system sparse.
bool stages_too_large(const IntegrateRequest& req) {
  return integrators::tableau_of(req.integrator).form == integrators::Form::implicit_rkmk &&
         !req.problem.family().max_index() && req.problem.n > kKrylovThreshold;
}

}  // namespace

void resolve_defaults(IntegrateRequest& req) {
  // DIRK-CG3 solves its stages one at a time by the request's method (Krylov above the dense bound): order 3, L-stable.
  if (req.integrator_defaulted && stages_too_large(req)) req.integrator = Integrator::dirk_cg3;
  if (req.h) return;
  validate(req.problem);
  validation::check(fields::t_end, req.t_end, "t_end");
  req.h = default_step(req.problem, req.t_end, kMaxRunSteps);
  req.h_defaulted = true;
}

void validate(const IntegrateRequest& req) {
  validate(req.problem);
  if (!req.h) validation::invalid("h", "h is not resolved (resolve_defaults)");
  const double h = *req.h;
  validation::check(fields::h, h, "h");
  validation::check(fields::t_end, req.t_end, "t_end");
  if (h > req.t_end) validation::invalid("h", "h must not exceed t_end");
  if (req.t_end / h > kMaxRunSteps) validation::invalid("h", "t_end / h must be at most 1e5 steps");
  if (req.rtol) validation::check_tolerance(fields::rtol, *req.rtol, "rtol");
  if (req.atol) validation::check_tolerance(fields::atol, *req.atol, "atol");
  validation::check(fields::max_steps, req.max_steps, "max_steps");
  validate(req.solver);
  check_globalization(req.solver.method, req.solver);
  check_stage_options(req);
  if (req.frames < 0 || req.frames > IntegrateRequest::kMaxFrames)
    validation::invalid("frames", "frames must be an integer in [0, " + std::to_string(IntegrateRequest::kMaxFrames) + "]");
  if (stages_too_large(req))
    validation::invalid("integrator", std::string(to_string(req.integrator)) +
                                          " solves its coupled stage system densely: n must be at most " +
                                          std::to_string(kKrylovThreshold));
}

IntegrateResult integrate(const IntegrateRequest& request, const StepCallback& on_step) {
  IntegrateRequest req = request;
  resolve_defaults(req);
  validate(req);
  return integrate_validated(req, on_step);
}

IntegrateResult integrate_validated(const IntegrateRequest& req, const StepCallback& on_step) {
  const Eigen::MatrixXd y0 = req.problem.start();
  IntegrateResult res = req.problem.family().integrate(req, y0, on_step);
  // More frames than steps: every step's state is a frame, and the answer says it has fewer than asked.
  if (res.status == Status::converged && req.frames > 0 &&
      res.frames.size() < static_cast<std::size_t>(req.frames) + 1)
    res.reason += "; frames: " + std::to_string(req.frames) + " asked, but the run took " +
                  std::to_string(res.frames.size() - 1) + " steps: every step's state is returned (" +
                  std::to_string(res.frames.size()) + " frames with y(0))";
  res.h = *req.h;
  std::optional<Eigen::MatrixXd> y_ref;
  if (req.reference && res.status == Status::converged) {
    const double start = thread_cpu_seconds();
    const ReferenceSolution ref = reference_solution(req.problem, y0, req.t_end);
    y_ref = ref.y;
    if (ref.y) {
      res.global_error = (res.y - *ref.y).norm();
      res.reference_error = ref.error;
      res.global_error_at_reference = *res.global_error <= kReferenceErrorFactor * ref.error;
      if (res.global_error_at_reference)
        res.reason += "; global_error is within " + format_number(kReferenceErrorFactor) +
                      "x of the reference's estimated error " + format_number(ref.error) +
                      ": it bounds the run's error, it does not measure it";
    } else
      res.reason += "; global_error is null: " + ref.note;
    res.reference_seconds = thread_cpu_seconds() - start;
  } else if (!req.reference) {
    res.reason += "; global_error is null: no reference solution was asked for (reference: false)";
  }
  if (res.status == Status::converged) res.warnings = warnings_of(req, res, y_ref);
  return res;
}

}  // namespace lienewton
