#pragma once
// Newton's method in the algebra, Version 2 (3.20), started at v_0 = 0 (y_0 = z):
//   df~_{v_n}(u_n) = -f~(v_n),   v_{n+1} = v_n + u_n,   y_n = z exp(v_n).
#include "equation.hpp"
#include "newton_step.hpp"
#include "solver_run.hpp"

namespace lienewton {

template <LieGroup G>
SolveResult newton_algebra(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  const G& group = eq.group();
  const bool krylov = detail::use_krylov(group, opt.linear_solver);
  SolverRun<G> run(eq, opt, cb, krylov);
  typename G::Vector v = zero_vector(group);
  typename G::Vector u = zero_vector(group);
  double step = 0.0;
  for (;;) {
    const auto p = eq.at_algebra(v);
    if (auto stop = run.record(p, step)) {
      Status s = *stop;
      // f~(v) = 0 solves y = z exp(v), v = h g(y); log(z^-1 y) = v only while v's angles stay inside log's radius.
      if (s == Status::converged && eq.is_implicit_euler() && p.algebra_angle > G::kLogRadius) s = Status::off_branch;
      return run.finish(s, p.y);
    }
    const detail::StepOutcome outcome = detail::newton_step<G>(
        krylov, [&] { return eq.dftilde_matrix(p, opt.differential); },
        [&](const typename G::Vector& w) { return eq.dftilde(p, w, opt.differential); }, p.f, u);
    if (outcome != detail::StepOutcome::ok) return run.finish(detail::status_of(outcome), p.y);
    step = u.norm();
    if (v.norm() + step > kDivergenceBound) return run.finish(Status::diverged, p.y);
    v += u;  // (3.20): v_{n+1} = v_n + u_n
    run.next();
  }
}

}  // namespace lienewton
