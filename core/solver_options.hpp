#pragma once
// How a request solves each equation f(y) = 0: the method, the differential, the stopping rule and the linear
// solver of the Newton system. Shared by solve, sweep, integrate and work-precision, and read by the solvers.
#include "options.hpp"

namespace lienewton {

struct SolverOptions {
  Method method = Method::newton_group;
  Differential differential = Differential::exact;
  double tol = 1e-13;
  int max_iterations = 100;
  LinearSolver linear_solver = LinearSolver::auto_select;
  Stopping stopping = Stopping::residual;  // Version 2 and fixed point: ||f(y_n)|| (section 5) or ||f~(v_n)||
  bool include_iterates = false;  // keep every iterate y_n in the trace (solve only; sweeps and steps drop them)
  // Newton only: none = the paper's full steps; line-search, trust-region (solvers/globalization.hpp)
  Globalization globalization = Globalization::none;
  // Globalised Version 1 only: full Newton steps that do not decrease 1/2 ||f||^2 may be taken for a while
  // (solvers/watchdog.hpp). Off by default: its episodes can spend the iterations in which the strategy alone
  // would reach a stationary point without a root (local_minimum) or log's cut (no_descent).
  bool watchdog = false;
  // The root continued from z: follow z's branch of roots from h = 0 to h (solvers/continuation.hpp).
  bool continuation = false;
  // When no root was found: up to this many solves at h from seeded starts around the request's start
  // (solvers/multistart.hpp).
  int multistart = 0;
  // Wall and CPU time of every trace record, and the solve's CPU time. Sweeps and basin maps turn it off: reading
  // the thread's CPU clock is a system call that costs more than an SO(3) iteration (two per solve were 13 % of a
  // 256 x 256 SO(3) basin map's CPU time). Untimed, a result's cpu_seconds is 0 (neither reports it); its wall
  // seconds are kept (the steady clock is read without a system call).
  bool timed = true;
  // An integrator's stage: the solve ends as soon as its driven residual is down to what rounding alone leaves of
  // it (a few times the rounding of one evaluation, far below the floor the stall rule accepts), stagnated there:
  // no later iterate can be told better, and waiting for the stall rule spends iterations that buy nothing (the
  // RKMK stages stop at their floor likewise).
  bool stop_at_rounding = false;
};

// Checks the bounds of its rows in the field table (core/fields.hpp: tol, max_iterations, multistart); throws
// RequestError naming the field.
void validate(const SolverOptions& options);
// A globalization other than none needs a Newton method: 422 naming "globalization" for the fixed point.
void check_globalization(Method method, const SolverOptions& options);

}  // namespace lienewton
