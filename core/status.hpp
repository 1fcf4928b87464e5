#pragma once
// How a solve ended. Every status comes with a one-line human reason (SolveResult::reason).
#include <optional>
#include <string_view>

namespace lienewton {

enum class Status {
  converged,              // ||f(y_n)|| <= tol
  max_iterations,         // max_iterations updates done, f(y_max) still above tol
  diverged,               // residual or step grew past kDivergenceBound (see solvers/iteration_monitor.hpp)
  non_finite,             // a NaN or Inf appeared in f, the differential or the iterate
  left_log_domain,        // z^-1 y_n reached rotation angle pi (within kLogDomainMargin): log undefined
  singular_differential,  // the q x q Newton system is singular or too badly conditioned to trust
  stagnated,              // residual stopped decreasing at the rounding floor, above tol
  off_branch,             // y = z exp(h g(y)) holds to rounding, but h g(y) has an angle beyond pi
  local_minimum,          // globalised Newton: ||D^T f|| fell to rounding while ||f|| did not (a stationary
                          // point of 1/2 ||f||^2 that is no root)
  no_descent,             // globalised Newton: no step, however short, decreases 1/2 ||f||^2 although ||f|| is far
                          // above its floor and ||D^T f|| is not small: phi is not smooth there (log's cut at angle pi)
  fold,                   // continuation: z's branch of roots turns back at fold_h < h, so no root continued from
                          // z exists at h
  cancelled,              // the caller's callback asked to stop (client left, deadline passed)
  min_step,               // adaptive integration: the step-size controller needed a step below the minimum step
  max_steps,              // adaptive integration: the bound on steps (accepted and rejected) was reached before t_end
};

std::string_view to_string(Status status);
std::optional<Status> status_from_string(std::string_view name);
inline constexpr Status kAllStatuses[] = {
    Status::converged, Status::max_iterations, Status::diverged,  Status::non_finite, Status::left_log_domain,
    Status::singular_differential, Status::stagnated, Status::off_branch, Status::local_minimum, Status::no_descent,
    Status::fold, Status::cancelled, Status::min_step, Status::max_steps};

}  // namespace lienewton
