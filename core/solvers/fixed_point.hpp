#pragma once
// The fixed-point iteration (1.2), started at y_0 = z: y_{n+1} = z exp(h g(y_n)).
#include <cmath>

#include "equation.hpp"
#include "solver_run.hpp"

namespace lienewton {

template <LieGroup G>
SolveResult fixed_point(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb = {}) {
  SolverRun<G> run(eq, opt, cb, false);
  typename G::Element y = eq.z();
  double step = 0.0;
  for (;;) {
    const auto p = eq.at(y, Equation<G>::Need::residual);
    if (!p.in_domain) return run.left_log_domain(p);
    if (auto stop = run.record(p, step)) return run.finish(*stop, y);
    const typename G::Element next = eq.fixed_point_map(p);  // (1.2)
    if (!next.allFinite()) return run.finish(Status::non_finite, y);
    step = (next - y).norm() / std::sqrt(2.0);
    y = next;
    run.next();
  }
}

}  // namespace lienewton
