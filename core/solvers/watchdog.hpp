#pragma once
// The watchdog around a globalised iteration's strategy (line search or trust region): the nonmonotone
// safeguard of Chamberlain, Powell, Lemarechal & Pedersen (Math. Prog. Study 16, 1982; Nocedal & Wright,
// Numerical Optimization, 2nd ed., sec. 15.6).
// Why: phi = 1/2 ||f||^2 jumps where z^-1 y turns through angle pi (log's cut in f of (3.6)), and plain Newton
// (3.5)/(3.20) often reaches a root through iterates where phi first grows. A monotone descent refuses those
// steps and lost cells and basin area that the paper's full steps win.
// How, at an iterate x (the reference) whose full Newton step u does not decrease phi sufficiently
// (phi(x + u) > (1 - 2 c1) phi(x), Armijo at alpha = 1 with slope -||f||^2):
//   - the full step is taken anyway, and up to kWatchdogSteps full steps in all, until an iterate falls below
//     that bound; that iterate is the next reference (monotone progress over the episode);
//   - when none does (or a full step is undefined: singular D, log's domain left), the iteration goes back to x
//     and takes the strategy's own step from there, as if the episode had not been;
//   - after kWatchdogEpisodes episodes that went back, the strategy alone runs: the cost of a hopeless watchdog
//     is bounded by kWatchdogEpisodes * kWatchdogSteps iterations.
// A stationary point of phi without a root is left to the strategy (local_minimum). Near a root the full step
// decreases phi, so the iteration is Newton's and stays quadratic.
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

#include "charts.hpp"
#include "line_search.hpp"
#include "newton_model.hpp"

namespace lienewton {

inline constexpr int kWatchdogSteps = 32;
inline constexpr int kWatchdogEpisodes = 3;

template <LieGroup G, class Chart, class Strategy>
class Watchdog {
 public:
  using Point = typename Chart::Point;
  using Vector = typename G::Vector;

  // enabled = false: the strategy alone.
  Watchdog(Strategy strategy, double tol, bool enabled)
      : strategy_(std::move(strategy)), tol_(tol), episodes_left_(enabled ? kWatchdogEpisodes : 0) {}

  Advance<Chart> step(NewtonModel<G, Chart>& model, double floor) {
    const int iterate = iterate_++;
    if (reference_) {
      if (model.merit() <= reference_->bound) {
        reference_.reset();  // the episode paid off: this iterate is the next reference
      } else {
        if (relaxed_ < kWatchdogSteps)
          if (auto a = full_step(model, "watchdog")) {
            ++relaxed_;
            return *a;
          }
        return back(model);
      }
    }
    if (episodes_left_ > 0 && !stationary_without_root(model, tol_, floor))
      if (auto a = full_step(model, "newton")) {
        const double bound = (1.0 - 2.0 * kArmijoC1) * model.merit();
        if (a->next->f.squaredNorm() * 0.5 <= bound) return *a;
        reference_.emplace(Reference{model.point(), bound, floor, iterate});
        relaxed_ = 1;
        a->info.kind = "watchdog";
        return *a;
      }
    return strategy_.step(model, floor);
  }

 private:
  struct Reference {
    Point p;
    double bound;  // the Armijo bound (1 - 2 c1) phi(x) an iterate of the episode must reach
    double floor;
    int iterate;
  };

  // x exp(u) (Version 1) or v + u (Version 2) with Newton's u, where both are defined.
  std::optional<Advance<Chart>> full_step(NewtonModel<G, Chart>& model, std::string_view kind) const {
    Vector u;
    if (model.newton(u) != detail::StepOutcome::ok || !u.allFinite()) return std::nullopt;
    Trial<Chart> t = try_step(model.chart(), model.point(), u);
    if (!std::isfinite(t.merit)) return std::nullopt;
    Advance<Chart> a;
    a.next = std::move(t.p);
    a.s = u;
    a.info = {kind, {}, {}, {}};
    a.projected = t.projected;
    return a;
  }

  // The strategy's step from the reference, which the episode's iterates did not improve on. When the strategy
  // stops there (no_descent, local_minimum, ...), the reference itself is the next iterate (a step of length 0),
  // and with no episodes left the strategy stops again at it: the status is then true of the y the solve returns,
  // not of the episode's last iterate.
  Advance<Chart> back(const NewtonModel<G, Chart>& last) {
    const Reference r = std::move(*reference_);
    reference_.reset();
    --episodes_left_;
    NewtonModel<G, Chart> model(last.chart(), r.p, last.krylov());
    Advance<Chart> a = strategy_.step(model, r.floor);
    if (!a.next && a.failure != Status::cancelled) {
      episodes_left_ = 0;
      a.next = r.p;
      a.s = Vector::Zero(r.p.f.size());
      a.info = {"watchdog", {}, {}, {}};
    }
    a.info.from_iterate = r.iterate;
    return a;
  }

  Strategy strategy_;
  double tol_;
  std::optional<Reference> reference_;
  int relaxed_ = 0;
  int episodes_left_;
  int iterate_ = 0;
};

}  // namespace lienewton
