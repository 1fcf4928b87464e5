#pragma once
// The fixed-point iteration (1.2), started at y_0 = eq.start() (z unless moved): y_{n+1} = z exp(h g(y_n)).
// In the algebra it is v_{n+1} = h g(z exp v_n) with v_0 = log(z^-1 y_0) (0 at z), so its algebra residual is
// f~(v_n) = v_n - h g(y_n) (3.21) with v_n = h g(y_{n-1}): no log needed.
#include <cmath>

#include "equation.hpp"
#include "solver_run.hpp"

namespace lienewton {

template <LieGroup G>
SolveResult fixed_point(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  SolverRun<G> run(eq, opt, cb, false);
  typename G::Element y = eq.start();
  const auto v0 = eq.start_algebra();
  if (!v0) return run.left_log_domain(eq.at(y, Equation<G>::Need::residual));
  typename G::Vector v = *v0;
  double step = 0.0;
  for (;;) {
    auto p = eq.at(y, Equation<G>::Need::residual);
    if (!p.in_domain) return run.left_log_domain(p);
    if (eq.is_implicit_euler()) p.algebra_residual = (v - p.hg).norm();
    if (auto stop = run.record(p, step)) return run.finish(*stop);
    const typename G::Element next = eq.fixed_point_map(p);  // (1.2)
    if (!next.allFinite()) return run.finish(Status::non_finite);
    step = (next - y).norm() / std::sqrt(2.0);
    y = next;
    v = p.hg;
    run.next();
  }
}

}  // namespace lienewton
