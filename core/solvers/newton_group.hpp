#pragma once
// Newton's method on the group, Version 1 (3.5), started at y_0 = eq.start() (z unless moved):
//   df_{y_n}(u_n) = -f(y_n),   y_{n+1} = y_n exp(u_n).
// With a globalization other than none, the globalised iteration of globalization.hpp.
#include "charts.hpp"
#include "equation.hpp"
#include "globalization.hpp"
#include "newton_step.hpp"
#include "solver_run.hpp"

namespace lienewton {

template <LieGroup G>
SolveResult newton_group(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  const GroupChart<G> chart(eq, opt.differential);
  if (opt.globalization != Globalization::none) return globalized_newton<G>(chart, eq.start(), opt, cb);
  const G& group = eq.group();
  const bool krylov = detail::use_krylov(group, opt.linear_solver);
  SolverRun<G> run(eq, opt, cb, krylov);
  typename G::Element y = eq.start();
  typename G::Vector u = zero_vector(group);
  double step = 0.0;
  for (;;) {
    const auto p = chart.at(y);
    if (!p.in_domain) return run.left_log_domain(p);
    if (auto stop = run.record(p, step)) return run.finish(*stop);
    detail::StepOutcome outcome;
    try {
      outcome = detail::newton_step<G>(
          krylov, [&] { return chart.factored_matrix(p); }, [&](const typename G::Vector& w) { return chart.apply(p, w); },
          p.f, u);
    } catch (const LogDomainError& e) {
      return run.finish(Status::left_log_domain, e.what());
    }
    if (outcome != detail::StepOutcome::ok) return run.finish(detail::status_of(outcome));
    bool projected = false;
    typename G::Element next = chart.move(p, u, projected);  // (3.5): y_{n+1} = y_n exp(u_n)
    step = u.norm();
    if (!next.allFinite()) return run.finish(Status::non_finite);
    if (projected) run.projected();
    y = next;
    run.next();
  }
}

}  // namespace lienewton
