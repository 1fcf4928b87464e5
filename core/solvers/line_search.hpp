#pragma once
// globalization = line-search: one iteration of Newton with Armijo backtracking on phi = 1/2 ||f||^2
// (newton_model.hpp), along alpha -> y exp(alpha u) (Version 1, (3.5)) or v + alpha u (Version 2, (3.20)):
//   1. Newton's u (D u = -f) with alpha = 1 first, so that near a root every step is the full Newton step and
//      convergence stays quadratic; when the full step fails, first the local_minimum test of 3.;
//   2. if D is singular or no alpha gives sufficient decrease (u is no descent direction for the true phi, or
//      the curve crosses log's branch cut), Levenberg-Marquardt steps (D^T D + mu I) s = -D^T f with
//      mu = ||D^T f||, 100 ||D^T f||, ... until one gives sufficient decrease;
//   3. when phi is stationary to rounding while ||f|| is not small, local_minimum.
// Sufficient decrease (Armijo): phi(x + alpha s) <= phi(x) + c1 alpha phi'(0), c1 = 1e-4, with alpha
// backtracked by safeguarded quadratic interpolation into [alpha/10, alpha/2] (Nocedal & Wright, Numerical
// Optimization, 2nd ed., sec. 3.1 and 3.5).
#include <algorithm>
#include <cmath>
#include <limits>

#include "charts.hpp"
#include "core/cancellation.hpp"
#include "newton_model.hpp"

namespace lienewton {

inline constexpr double kArmijoC1 = 1e-4;
inline constexpr int kMaxBacktracks = 40;    // alpha >= 10^-40 at most: far below any useful step
inline constexpr int kMaxDampings = 12;
inline constexpr double kShortestStep = 1e-10;  // a shortened or damped step below this (relative) moves nothing      // mu up to 10^22 ||D^T f||: a steepest-descent step at rounding

template <LieGroup G, class Chart>
class LineSearch {
 public:
  using Vector = typename G::Vector;

  explicit LineSearch(double tol) : tol_(tol) {}

  Advance<Chart> step(NewtonModel<G, Chart>& model, double floor) {
    Vector u;
    const detail::StepOutcome newton = model.newton(u);
    if (newton == detail::StepOutcome::non_finite) return Advance<Chart>::stop(Status::non_finite);
    if (newton == detail::StepOutcome::ok) {
      const double slope = model.slope(u);
      if (slope < 0.0)
        if (auto a = backtrack(model, u, slope, "newton", floor)) return *a;
    }
    if (cancellation_requested()) return Advance<Chart>::stop(Status::cancelled);
    if (auto why = stationary_without_root(model, tol_, floor)) return Advance<Chart>::stop(Status::local_minimum, *why);
    const double gradient = model.gradient().norm();
    if (!std::isfinite(gradient)) return Advance<Chart>::stop(Status::non_finite);
    double mu = std::max(gradient, std::numeric_limits<double>::min());
    for (int k = 0; k < kMaxDampings; ++k, mu *= 100.0) {
      if (cancellation_requested()) return Advance<Chart>::stop(Status::cancelled);
      const Vector s = model.levenberg_marquardt(mu);
      const double slope = model.gradient().dot(s);  // f^T D s = (D^T f)^T s
      if (!s.allFinite() || !(slope < 0.0)) break;
      if (auto a = backtrack(model, s, slope, "levenberg-marquardt", floor)) return *a;
    }
    return Advance<Chart>::stop(no_decrease_status(model.point().f.norm(), floor),
                                "no step decreases 1/2 ||f||^2 (||f|| = " + format_number(model.point().f.norm()) +
                                    ", ||D^T f|| = " + format_number(gradient) + ", " +
                                    angle_detail<G>(model.point().angle) + ")");
  }

 private:
  // The first alpha of the backtracking sequence with sufficient decrease along s, or nothing. A full step that
  // fails where phi is stationary to rounding ends the solve as local_minimum (near a stationary point that is
  // no root, D is nearly singular and its Newton step, huge, only creeps along by backtracking).
  std::optional<Advance<Chart>> backtrack(NewtonModel<G, Chart>& model, const Vector& s, double slope,
                                          std::string_view kind, double floor) const {
    const double phi0 = model.merit();
    const double norm = s.norm();
    double alpha = std::min(1.0, G::kLogRadius / norm);  // ||s|| <= the log radius: exp is injective there
    // Only Newton's full step may be as short as rounding (near a root it is): pinned at log's cut, a shortened or
    // damped step shrinks until phi "decreases" by rounding alone, and the iteration would creep on in steps of
    // length ~1e-13 instead of saying that no step descends.
    const double shortest = kShortestStep * (1.0 + model.point().v.norm());
    for (int k = 0; k < kMaxBacktracks && ((k == 0 && kind == "newton") || alpha * norm > shortest); ++k) {
      if (cancellation_requested()) return Advance<Chart>::stop(Status::cancelled);
      const Trial<Chart> t = try_step(model.chart(), model.point(), Vector(alpha * s));
      if (t.merit <= phi0 + kArmijoC1 * alpha * slope) {
        Advance<Chart> a;
        a.next = t.p;
        a.s = alpha * s;
        a.info = {kind, alpha, {}, {}};
        a.projected = t.projected;
        return a;
      }
      if (k == 0)
        if (auto why = stationary_without_root(model, tol_, floor))
          return Advance<Chart>::stop(Status::local_minimum, *why);
      // The minimiser of the quadratic through phi(0), phi'(0) and phi(alpha), kept in [alpha/10, alpha/2].
      const double curvature = t.merit - phi0 - slope * alpha;
      const double quadratic = std::isfinite(curvature) && curvature > 0.0 ? -slope * alpha * alpha / (2.0 * curvature)
                                                                            : 0.1 * alpha;
      alpha = std::clamp(quadratic, 0.1 * alpha, 0.5 * alpha);
    }
    return std::nullopt;
  }

  double tol_;
};

}  // namespace lienewton
