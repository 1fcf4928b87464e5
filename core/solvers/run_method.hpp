#pragma once
// The three solvers of f(y) = 0 on a Lie group behind one switch: fixed_point (1.2), newton_group (3.5),
// newton_algebra (3.20).
#include "continuation.hpp"
#include "fixed_point.hpp"
#include "newton_algebra.hpp"
#include "newton_group.hpp"

namespace lienewton {

template <LieGroup G>
SolveResult run_directly(Method method, const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb) {
  switch (method) {
    case Method::fixed_point: return fixed_point(eq, opt, cb);
    case Method::newton_group: return newton_group(eq, opt, cb);
    case Method::newton_algebra: return newton_algebra(eq, opt, cb);
  }
  return {};
}

// With opt.continuation, an implicit Euler equation is reached through smaller step sizes (continuation.hpp).
template <LieGroup G>
SolveResult run_method(Method method, const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb) {
  if (!opt.continuation || !eq.is_implicit_euler()) return run_directly(method, eq, opt, cb);
  return continued(eq, opt, cb, [&](const Equation<G>& stage, const SolverOptions& o, const TraceCallback& stage_cb) {
    return run_directly(method, stage, o, stage_cb);
  });
}

}  // namespace lienewton

#include "rotation_instances.hpp"  // after the templates: their SO(3) and SO(N) instances are compiled once
