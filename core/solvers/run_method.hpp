#pragma once
// The three solvers of f(y) = 0 on a Lie group behind one switch: fixed_point (1.2), newton_group (3.5),
// newton_algebra (3.20); and the searches around them for an implicit Euler equation: continuation along z's
// branch of roots (continuation.hpp), then, when no root was found, multistart (multistart.hpp). Every result
// says which search produced y and which root it is.
#include "continuation.hpp"
#include "core/cpu_clock.hpp"
#include "fixed_point.hpp"
#include "multistart.hpp"
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

// The root continued from z at eq's h, the method solving at h (continuation.hpp), its first solve started as
// first_try says.
template <LieGroup G>
SolveResult continued_root(Method method, const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb,
                           FirstTry first_try = FirstTry::tangent) {
  SolverOptions near = opt;  // from a prediction the method follows the root near it: no watchdog jumps
  near.watchdog = false;
  return BranchPath<G>(eq, method, cb,
                       [&](const Equation<G>& e, const TraceCallback& c) { return run_directly(method, e, near, c); },
                       first_try)
      .run();
}

template <LieGroup G>
SolveResult run_method(Method method, const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb) {
  const bool search = eq.is_implicit_euler() && (opt.continuation || opt.multistart > 0);
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = search && opt.timed ? thread_cpu_seconds() : 0.0;
  SolveResult r = search && opt.continuation ? continued_root(method, eq, opt, cb) : run_directly(method, eq, opt, cb);
  if (search && opt.multistart > 0 && !is_root(r) && r.status != Status::cancelled && !cancellation_requested())
    r = multistart(eq, opt, std::move(r),
                   [&](const Equation<G>& e, const SolverOptions& o) { return run_directly(method, e, o, {}); });
  if (search) {  // what the whole search cost, not only the returned solve
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    if (opt.timed) r.cpu_seconds = thread_cpu_seconds() - cpu_start;
  }
  const Eigen::MatrixXd z = eq.group().matrix(eq.z());
  if (r.y.rows() == z.rows() && r.y.cols() == z.cols()) r.distance_from_z = (r.y - z).norm();
  return r;
}

}  // namespace lienewton

#include "rotation_instances.hpp"  // after the templates: their SO(3) and SO(N) instances are compiled once
