#pragma once
// Newton's method on the group, Version 1 (3.5), started at y_0 = z:
//   df_{y_n}(u_n) = -f(y_n),   y_{n+1} = y_n exp(u_n).
#include "equation.hpp"
#include "newton_step.hpp"
#include "solver_run.hpp"

namespace lienewton {

// Per unit of N: an iterate whose ||y^T y - I||_F exceeds this times N is replaced by its polar factor.
inline constexpr double kReorthogonaliseDefect = 16.0 * std::numeric_limits<double>::epsilon();

template <LieGroup G>
SolveResult newton_group(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  const G& group = eq.group();
  const bool krylov = detail::use_krylov(group, opt.linear_solver);
  SolverRun<G> run(eq, opt, cb, krylov);
  typename G::Element y = eq.z();
  typename G::Vector u = zero_vector(group);
  double step = 0.0;
  // Difference quotients need f alone, also at y_n: the same log path as in the perturbed points.
  const auto need = opt.differential == Differential::finite_difference ? Equation<G>::Need::residual
                                                                        : Equation<G>::Need::differential;
  for (;;) {
    const auto p = eq.at(y, need);
    if (!p.in_domain) return run.left_log_domain(p);
    if (auto stop = run.record(p, step)) return run.finish(*stop);
    detail::StepOutcome outcome;
    try {
      outcome = detail::newton_step<G>(
          krylov, [&] { return eq.df_matrix(p, opt.differential); },
          [&](const typename G::Vector& w) { return eq.df(p, w, opt.differential); }, p.f, u);
    } catch (const LogDomainError& e) {
      return run.finish(Status::left_log_domain, e.what());
    }
    if (outcome != detail::StepOutcome::ok) return run.finish(detail::status_of(outcome));
    typename G::Element next = group.times_exp(y, u);  // (3.5): y_{n+1} = y_n exp(u_n)
    step = u.norm();
    if (!next.allFinite()) return run.finish(Status::non_finite);
    // Long products drift off the group by rounding (a random walk of ~eps per step); the polar factor
    // puts y_{n+1} back before the drift reaches the floor's scale.
    if (group.defect(next) > kReorthogonaliseDefect * group.n()) {
      next = group.project(next);
      run.reorthogonalised();
    }
    y = next;
    run.next();
  }
}

}  // namespace lienewton
