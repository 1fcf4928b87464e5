#pragma once
// Continuation in the step size. The implicit Euler equation
//   f_h(y) = log(z^-1 y) - h g(y) = 0                                                     (3.6)
// has the root y = z at h = 0, and its root moves continuously with h while h g(y) stays inside log's branch.
// A continued solve tries, in this order, until one converges at the requested h:
//   1. the plain solve at h from where eq starts (a cell it converges on costs nothing more and keeps its y);
//   2. with a globalization, the paper's full-step Newton at h from the same start (so a globalised continued
//      solve never loses a cell the plain method converges on);
//   3. the path from h = 0: h_0 < h_1 < ... < h_K = h, each stage started at the previous stage's root,
//        h_k = h 2^(k-K),  K = max(0, ceil(log2(h / kContinuationStart))),
//      while no stage fails: h_0 <= 1/16 and every stage doubles h;
//   4. the path from the stiff end: as h -> infinity the roots of (1.1) tend to equilibria of y' = y g(y)
//      (g(y) = 0), and the component identity J of z (I, or diag(-1, 1, ..., 1) when det z < 0) is one for
//      both paper problems. Solve at h from J; failing that at 2h, 4h, ..., 2^kStiffDoublings h from J until a
//      root is found, then halve back down to h, each stage from the previous root;
//   5. the paths from below: at h/2, h/4, ... down to kContinuationStart, the solve from the given start and then
//      from J; from the first root found, the path up to h (doubling, as in 3.). A root z's path cannot reach
//      (it folds back or leaves log's branch) often lies on a branch that a smaller step meets and that then
//      continues to h: on paper-linear N = 9, h = 64..512, J at h/2..h/16; N = 14, h = 32..1024, z at 16.
//   6. with opt.restarts = K > 0, the restarts: up to K solves at h from the seeded starts y_0 exp(x_k),
//      k = 0 .. K-1 (restart_start.hpp), with the requested globalization and at most kRestartIterations
//      iterations each, until one converges. Where every path fails, roots may still lie away from all of them:
//      paper-linear N = 11, h = 32 has roots that 1 % of such starts reach (line search); every start that
//      reached one did so within 27 iterations.
// Every stage of 3., 4. and 5. is tried as in 1. and 2.: with a globalization, a stage that finds no root is solved
// again with full steps (a descent method stalls where the path of roots folds back; full steps jump on).
// A path's stage that fails shrinks its ratio to the square root (2, 1.41, 1.19, ... going up; 1/2, 0.71, ...
// coming down) and is retried that much beyond the last root (a failed first stage of the path from 0: at a
// quarter of its h). After kMaxFailedStages failures, a ratio within 1% of 1 or kMaxContinuationStages stages,
// the path's last stage is the requested h itself, started at the last root found. A stage whose solve ends
// converged or stagnated (a root to rounding: at large h tol can be below the floor) is a root to go on from.
// Only a solve at the requested h decides the result: its status, y, residual and trace are the plain solver's,
// so a continued result is as honest as a plain one; result.continuation lists every stage (the tries at h
// included, with where each started and its globalization), and the reason says which stage its iteration count
// is and what the whole search cost.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/cancellation.hpp"
#include "core/solver_options.hpp"
#include "equation.hpp"
#include "restart_start.hpp"
#include "solve_result.hpp"

namespace lienewton {

inline constexpr double kContinuationStart = 1.0 / 16;
inline constexpr int kMaxContinuationStages = 64;
inline constexpr int kMaxFailedStages = 8;
inline constexpr double kSmallestContinuationRatio = 1.01;
inline constexpr int kStiffDoublings = 4;
inline constexpr int kRestartIterations = 32;

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

// The searches of the file comment over one equation. solve(equation, options, callback) is the plain solver of
// one stage; the callback sees the records of every stage, each tagged with its stage's h (the iteration count
// restarts at 0 with every stage).
template <LieGroup G, class Solve>
class ContinuationSearch {
 public:
  using Element = typename G::Element;

  ContinuationSearch(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb, Solve solve)
      : eq_(eq), opt_(opt), cb_(cb), solve_(std::move(solve)), h_(eq.h()) {}

  SolveResult run() {
    SolveResult r = try_at(h_, nullptr, StageStart::given);  // 1. and 2.
    if (settled(r)) return finish(std::move(r));
    if (first_continuation_step(h_) < h_) {  // 3. (below kContinuationStart there is no path from 0)
      r = walk(std::nullopt, 0.0, first_continuation_step(h_), 2.0);
      if (settled(r)) return finish(std::move(r));
    }
    r = from_stiff_end(std::move(r));  // 4.
    if (settled(r)) return finish(std::move(r));
    r = from_below(std::move(r));  // 5.
    if (settled(r)) return finish(std::move(r));
    return finish(from_restarts(std::move(r)));  // 6.
  }

 private:
  bool stopped(const SolveResult& r) const {
    return r.status == Status::cancelled || cancellation_requested();
  }
  // The search ends here: converged at h, or stopped.
  bool settled(const SolveResult& r) const {
    return stopped(r) || (result_h_ == h_ && r.status == Status::converged);
  }
  // A root to go on from: converged, or stagnated at its rounding floor.
  static bool is_root(const SolveResult& r) {
    return r.status == Status::converged || r.status == Status::stagnated;
  }

  // The solve at h from start (null: where eq starts) with the requested options and, with a globalization,
  // when that fails, with the paper's full steps (plain Newton crosses log's cut where a descent method will not).
  // It fails at the requested h when it does not converge, at any other h when it finds no root to go on from.
  SolveResult try_at(double h, const Element* start, StageStart start_name) {
    SolveResult r = stage(h, start, start_name, opt_);
    const bool enough = h == h_ ? settled(r) : stopped(r) || is_root(r);
    if (enough || opt_.globalization == Globalization::none) return r;
    SolverOptions plain = opt_;
    plain.globalization = Globalization::none;
    return stage(h, start, start_name, plain);
  }

  // One stage: eq at step h from start (null: where eq starts), recorded on the path.
  SolveResult stage(double h, const Element* start, StageStart start_name, const SolverOptions& o,
                    std::optional<int> restart = std::nullopt) {
    Equation<G> e = eq_.at_step(h);
    if (start) e.start_at(*start);
    SolverOptions monotone = o;  // a stage follows the root near its start: no watchdog jumps to another branch
    monotone.watchdog = false;
    SolveResult r = solve_(e, monotone, tagged_with_step(cb_, h));
    path_.push_back({h, r.status, r.iterations, r.residual, start_name, o.globalization, restart});
    result_h_ = h;
    seconds_ += r.seconds;
    cpu_seconds_ += r.cpu_seconds;
    return r;
  }

  // From root (the root at h = reached; none: eq's start, the root at h = 0) to h_ in steps of ratio (> 1 going
  // up, < 1 coming down), first to target; the last stage's result.
  SolveResult walk(std::optional<Element> root, double reached, double target, double ratio) {
    const auto toward_h = [&](double x) { return ratio > 1.0 ? std::min(h_, x) : std::max(h_, x); };
    const int first = static_cast<int>(path_.size());
    int failures = 0;
    bool final_try = false;  // the path is stuck or long: solve at h from the last root
    for (;;) {
      if (static_cast<int>(path_.size()) - first + 1 >= kMaxContinuationStages || failures >= kMaxFailedStages)
        final_try = true;
      if (final_try) target = h_;
      SolveResult r = root ? try_at(target, &*root, StageStart::root) : try_at(target, nullptr, StageStart::given);
      if (settled(r) || final_try) return r;
      if (is_root(r)) {
        root = Element(r.y);
        reached = target;
        target = toward_h(ratio * target);
        continue;
      }
      ++failures;
      if (!root) {
        target /= 4.0;
        continue;
      }
      ratio = ratio > 1.0 ? std::sqrt(ratio) : 1.0 / std::sqrt(1.0 / ratio);  // coming down: 1 / the ratio going up
      if (std::abs(std::log(ratio)) < std::log(kSmallestContinuationRatio)) final_try = true;
      target = toward_h(ratio * reached);
    }
  }

  // 4. of the file comment; last: the given start's last try at h, returned when this path finds no root.
  SolveResult from_stiff_end(SolveResult last) {
    const Element j = eq_.component_identity();
    SolveResult r = try_at(h_, &j, StageStart::identity);
    if (settled(r)) return r;
    for (int k = 1; k <= kStiffDoublings; ++k) {
      const double big_h = std::ldexp(h_, k);
      if (big_h > kLargestStiffStep) break;
      SolveResult up = try_at(big_h, &j, StageStart::identity);
      if (stopped(up)) return up;
      if (is_root(up)) return walk(Element(up.y), big_h, std::max(h_, big_h / 2), 0.5);
    }
    // No root above h: the answer stays the last try from the given start (its failure class says more of it).
    result_h_ = h_;
    return last;
  }

  // 5. of the file comment; last: the answer so far, returned when no root below h leads up to it.
  SolveResult from_below(SolveResult last) {
    const Element j = eq_.component_identity();
    for (double low = h_ / 2; low >= kContinuationStart; low /= 2) {
      for (const Element* start : {static_cast<const Element*>(nullptr), &j}) {
        SolveResult r = try_at(low, start, start ? StageStart::identity : StageStart::given);
        if (stopped(r)) return r;
        if (!is_root(r)) continue;
        r = walk(Element(r.y), low, std::min(h_, 2 * low), 2.0);
        if (settled(r)) return r;
      }
    }
    result_h_ = h_;
    return last;
  }

  // 6. of the file comment; last: the answer so far, returned when no restart converges.
  SolveResult from_restarts(SolveResult last) {
    SolverOptions brief = opt_;
    brief.max_iterations = std::min(opt_.max_iterations, kRestartIterations);
    for (int k = 0; k < opt_.restarts; ++k) {
      const Element start = restart_start(eq_.group(), eq_.start(), k);
      SolveResult r = stage(h_, &start, StageStart::restart, brief, k);
      if (settled(r)) return r;
    }
    result_h_ = h_;
    return last;
  }

  SolveResult finish(SolveResult result) {
    if (result_h_ != h_) {  // cancelled on the way: the returned y's residual at the requested h
      const auto p = eq_.at(Element(result.y), Equation<G>::Need::residual);
      result.status = Status::cancelled;
      result.residual = p.in_domain ? p.residual : std::numeric_limits<double>::quiet_NaN();
      result.algebra_residual.reset();
      result.reason = "cancelled during continuation, at the stage h = " + std::to_string(result_h_) +
                      " of " + std::to_string(h_) + ": " + result.reason;
    }
    for (TraceRecord& rec : result.trace) rec.stage_h = result_h_;
    result.seconds = seconds_;  // the whole search's time: what the answer cost
    result.cpu_seconds = cpu_seconds_;
    result.continuation = std::move(path_);
    if (result.continuation.size() > 1)
      result.reason += "; the iterations of the last of " + std::to_string(result.continuation.size()) +
                       " continuation stages, " + std::to_string(result.total_iterations()) + " over all";
    return result;
  }

  static constexpr double kLargestStiffStep = 1e6;  // the largest h a request may give

  const Equation<G>& eq_;
  const SolverOptions& opt_;
  const TraceCallback& cb_;
  Solve solve_;
  const double h_;
  std::vector<ContinuationStage> path_;
  double result_h_ = 0.0;  // the h of the stage the answer comes from
  double seconds_ = 0.0, cpu_seconds_ = 0.0;
};

template <LieGroup G, class Solve>
SolveResult continued(const Equation<G>& eq, const SolverOptions& opt, const TraceCallback& cb, Solve solve) {
  return ContinuationSearch<G, Solve>(eq, opt, cb, std::move(solve)).run();
}

}  // namespace lienewton
