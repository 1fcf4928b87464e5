#pragma once
// The globalised Newton iteration (request field "globalization"), one loop for both versions and both
// strategies: at every iterate x_n (y_n of Version 1, v_n of Version 2) build the local model of
// phi = 1/2 ||f||^2 (newton_model.hpp) and let the strategy choose the step,
//   line-search   Armijo backtracking along Newton's direction, Levenberg-Marquardt when that fails (line_search.hpp)
//   trust-region  dogleg steps inside a radius Delta (trust_region.hpp),
// so that phi decreases at every iteration. Near a root both take the full Newton step (3.5)/(3.20), so the
// convergence stays quadratic. The iterate is recorded, stopped and classified exactly as in the paper's
// iteration (solver_run.hpp): converged means ||f(y)|| <= tol for the returned y; a stationary point of phi
// that is no root ends as local_minimum.
#include "charts.hpp"
#include "line_search.hpp"
#include "newton_model.hpp"
#include "solver_run.hpp"
#include "trust_region.hpp"
#include "watchdog.hpp"

namespace lienewton {

template <LieGroup G, class Chart, class Strategy>
SolveResult globalized_newton(const Chart& chart, typename Chart::State start, const SolverOptions& opt,
                              const TraceCallback& cb, Strategy strategy) {
  const Equation<G>& eq = chart.equation();
  const bool krylov = detail::use_krylov(eq.group(), opt.linear_solver);
  SolverRun<G> run(eq, opt, cb, krylov);
  auto p = chart.at(start);
  double step = 0.0;
  StepInfo info;
  for (;;) {
    if (!p.in_domain) return run.left_log_domain(p);
    if (auto stop = run.record(p, step, info)) return run.finish(*stop);
    NewtonModel<G, Chart> model(chart, p, krylov);
    Advance<Chart> advance;
    try {
      advance = strategy.step(model, run.floor());
    } catch (const LogDomainError& e) {  // a difference quotient of D crossed angle pi
      return run.finish(Status::left_log_domain, e.what());
    }
    if (!advance.next) return run.finish(advance.failure, advance.detail);
    if (advance.projected) run.projected();
    step = advance.s.norm();
    info = advance.info;
    p = std::move(*advance.next);
    if (chart.size(p) > kDivergenceBound) return run.diverged(Chart::kSizeName, chart.size(p));
    run.next();
  }
}

// Version 1 or 2 (by chart) with the requested globalization (not none) from the given start.
template <LieGroup G, class Chart>
SolveResult globalized_newton(const Chart& chart, typename Chart::State start, const SolverOptions& opt,
                              const TraceCallback& cb) {
  const bool watchdog = opt.watchdog && Chart::kMeritJumps;
  if (opt.globalization == Globalization::trust_region)
    return globalized_newton<G>(
        chart, std::move(start), opt, cb,
        Watchdog<G, Chart, TrustRegion<G, Chart>>(TrustRegion<G, Chart>(opt.tol), opt.tol, watchdog));
  return globalized_newton<G>(chart, std::move(start), opt, cb,
                              Watchdog<G, Chart, LineSearch<G, Chart>>(LineSearch<G, Chart>(opt.tol), opt.tol, watchdog));
}

}  // namespace lienewton
