#pragma once
// Continuation in the step size (issue 14, section 3). The implicit Euler equation
//   f_h(y) = log(z^-1 y) - h g(y) = 0                                                     (3.6)
// has the root y = z at h = 0, and its root moves continuously with h while h g(y) stays inside log's branch.
// A continued solve first solves at the requested h from where eq starts (the plain solve: a cell it converges on
// costs nothing more, and converges on the same y). Only when that fails does it reach h through
// h_0 < h_1 < ... < h_K = h, each stage's iteration started at the previous stage's root:
//   h_k = h 2^(k-K),  K = max(0, ceil(log2(h / kContinuationStart))),
// while no stage fails: h_0 <= 1/16 and every stage doubles h. A stage that fails shrinks the ratio to its square
// root (2, 1.41, 1.19, 1.09, ...) and is retried that much beyond the last root (a failed first stage: at a quarter
// of its h). After kMaxFailedStages failures, a ratio below kSmallestContinuationRatio or kMaxContinuationStages
// stages, the last stage is the requested h itself, started at the last root found.
// Only the solve at the requested h decides the result: its status, y, residual and trace are the plain
// solver's, so a continued result is as honest as a plain one; result.continuation lists every stage (the first
// try included), and the reason says which stage its iteration count is and what the whole path cost.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/cancellation.hpp"
#include "equation.hpp"
#include "solve_result.hpp"

namespace lienewton {

inline constexpr double kContinuationStart = 1.0 / 16;
inline constexpr int kMaxContinuationStages = 64;
inline constexpr int kMaxFailedStages = 8;
inline constexpr double kSmallestContinuationRatio = 1.01;

// The first stage's h: h 2^-K, the largest h / 2^k not above kContinuationStart (h itself when h is below it).
inline double first_continuation_step(double h) {
  if (h <= kContinuationStart) return h;
  return std::ldexp(h, -static_cast<int>(std::ceil(std::log2(h / kContinuationStart))));
}

// The records of a stage, tagged with its h, for the caller's callback.
inline TraceCallback tagged_with_step(const TraceCallback& cb, double h) {
  if (!cb) return {};
  return [&cb, h](const TraceRecord& r) {
    TraceRecord t = r;
    t.stage_h = h;
    return cb(t);
  };
}

// solve(equation, callback) is the plain solver of one stage. The callback sees the records of every stage, each
// tagged with its stage's h (the iteration count restarts at 0 with every stage).
template <LieGroup G, class Solve>
SolveResult continued(const Equation<G>& eq, const TraceCallback& cb, Solve solve) {
  const double h = eq.h();
  std::vector<ContinuationStage> path;
  std::optional<typename G::Element> root;  // the last stage's root; none: start where eq starts
  double reached = 0.0;                     // the h of root (0: y = z solves f_0)
  double target = first_continuation_step(h);
  double ratio = 2.0;                       // h_k+1 / h_k after a stage converged
  int failures = 0;
  bool final_try = false;                   // the path is stuck or long: solve at h from the last root
  double seconds = 0.0, cpu_seconds = 0.0;
  SolveResult result = solve(eq, tagged_with_step(cb, h));  // the first try: the plain solve at h
  path.push_back({h, result.status, result.iterations, result.residual});
  seconds += result.seconds;
  cpu_seconds += result.cpu_seconds;
  const bool done = result.status == Status::converged || result.status == Status::cancelled ||
                    cancellation_requested() || target == h;  // below kContinuationStart there is no path
  while (!done) {
    if (static_cast<int>(path.size()) + 1 >= kMaxContinuationStages || failures >= kMaxFailedStages) final_try = true;
    if (final_try) target = h;
    Equation<G> stage = eq.at_step(target);
    if (root) stage.start_at(*root);
    result = solve(stage, tagged_with_step(cb, target));
    path.push_back({target, result.status, result.iterations, result.residual});
    seconds += result.seconds;
    cpu_seconds += result.cpu_seconds;
    if (result.status == Status::cancelled || cancellation_requested()) break;
    if (final_try || (target == h && result.status == Status::converged)) break;
    if (result.status == Status::converged) {
      root = typename G::Element(result.y);
      reached = target;
      target = std::min(h, ratio * target);
      continue;
    }
    ++failures;
    if (reached == 0.0) {
      target /= 4.0;
      continue;
    }
    ratio = std::sqrt(ratio);
    if (ratio < kSmallestContinuationRatio) final_try = true;
    target = std::min(h, ratio * reached);
  }
  if (path.back().h != h) {  // cancelled on the way: the returned y's residual at the requested h
    const auto p = eq.at(typename G::Element(result.y), Equation<G>::Need::residual);
    result.status = Status::cancelled;
    result.residual = p.in_domain ? p.residual : std::numeric_limits<double>::quiet_NaN();
    result.algebra_residual.reset();
    result.reason = "cancelled during continuation, at the stage h = " + std::to_string(path.back().h) + " of " +
                    std::to_string(h) + ": " + result.reason;
  }
  for (TraceRecord& r : result.trace) r.stage_h = path.back().h;
  result.seconds = seconds;  // the whole path's time: what the answer cost
  result.cpu_seconds = cpu_seconds;
  result.continuation = std::move(path);
  if (result.continuation.size() > 1)
    result.reason += "; the iterations of the last of " + std::to_string(result.continuation.size()) +
                     " continuation stages, " + std::to_string(result.total_iterations()) + " over all";
  return result;
}

}  // namespace lienewton
