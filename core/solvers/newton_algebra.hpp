#pragma once
// Newton's method in the algebra, Version 2 (3.20), started at v_0 = log(z^-1 y_0) (0 when y_0 = z):
//   df~_{v_n}(u_n) = -f~(v_n),   v_{n+1} = v_n + u_n,   y_n = z exp(v_n).
// With a globalization other than none, the globalised iteration of globalization.hpp.
#include "charts.hpp"
#include "equation.hpp"
#include "globalization.hpp"
#include "newton_step.hpp"
#include "solver_run.hpp"

namespace lienewton {

template <LieGroup G>
SolveResult newton_algebra(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  const G& group = eq.group();
  const AlgebraChart<G> chart(eq, opt.differential);
  const auto v0 = eq.start_algebra();
  if (opt.globalization != Globalization::none && v0) return globalized_newton<G>(chart, *v0, opt, cb);
  const bool krylov = detail::use_krylov(group, opt.linear_solver);
  SolverRun<G> run(eq, opt, cb, krylov);
  if (!v0) return run.left_log_domain(eq.at(eq.start(), Equation<G>::Need::residual));
  typename G::Vector v = *v0;
  typename G::Vector u = zero_vector(group);
  double step = 0.0;
  for (;;) {
    // Section 5 measures ||f(y_n)|| with f(y) = log(z^-1 y) - h g(y); it needs log of z^-1 y_n.
    const auto p = chart.at(v);
    if (!p.in_domain) return run.left_log_domain(p);
    if (auto stop = run.record(p, step)) return run.finish(*stop);
    const detail::StepOutcome outcome = detail::newton_step<G>(
        krylov, [&] { return chart.factored_matrix(p); }, [&](const typename G::Vector& w) { return chart.apply(p, w); },
        p.f, u);
    if (outcome != detail::StepOutcome::ok) return run.finish(detail::status_of(outcome));
    step = u.norm();
    if (v.norm() + step > kDivergenceBound) return run.diverged("||v|| + ||u||", v.norm() + step);
    v += u;  // (3.20): v_{n+1} = v_n + u_n
    run.next();
  }
}

}  // namespace lienewton
