#pragma once
// globalization = trust-region: one iteration of a dogleg trust-region method on the model
// m(s) = 1/2 ||f + D s||^2 of phi = 1/2 ||f||^2 (newton_model.hpp), steps s taken as y exp(s) (Version 1, (3.5))
// or v + s (Version 2, (3.20)) (Powell's dogleg; Nocedal & Wright, Numerical Optimization, 2nd ed., Alg. 4.1
// and sec. 4.1, 11.2):
//   - Newton's u (D u = -f) when ||u|| <= Delta: near a root every step is the full Newton step (quadratic);
//   - otherwise the dogleg point: the Cauchy point s_C = -(||g||^2 / ||D g||^2) g, g = D^T f, cut at Delta, or the
//     point of the segment s_C -> u at distance Delta;
//   - when D is singular, the Levenberg-Marquardt step (D^T D + mu I) s = -g with mu = ||g|| / Delta, which
//     has ||s|| <= ||g|| / mu = Delta;
//   - rho = (phi(x) - phi(x + s)) / (m(0) - m(s)): the step is accepted when rho > 1e-4; Delta quartered
//     when rho < 1/4, doubled (up to pi) when rho > 3/4 and the step reached the boundary;
//   - local_minimum when phi is stationary to rounding while ||f|| is not small.
// Delta starts at pi, the largest step exp maps one-to-one, and carries over from iteration to iteration.
#include <algorithm>
#include <cmath>

#include "charts.hpp"
#include "core/cancellation.hpp"
#include "line_search.hpp"
#include "newton_model.hpp"

namespace lienewton {

inline constexpr double kAcceptRatio = 1e-4;
inline constexpr int kMaxRejections = 60;  // Delta quartered 60 times: 4^-60 pi, far below rounding

template <LieGroup G, class Chart>
class TrustRegion {
 public:
  using Vector = typename G::Vector;

  explicit TrustRegion(double tol) : tol_(tol) {}

  Advance<Chart> step(NewtonModel<G, Chart>& model, double floor) {
    Vector u;
    const detail::StepOutcome newton = model.newton(u);
    if (newton == detail::StepOutcome::non_finite) return Advance<Chart>::stop(Status::non_finite);
    const bool have_newton = newton == detail::StepOutcome::ok && u.allFinite();
    const double phi0 = model.merit();
    for (int k = 0; k < kMaxRejections; ++k) {
      if (cancellation_requested()) return Advance<Chart>::stop(Status::cancelled);
      const bool newton_inside = have_newton && u.norm() <= radius_;
      if (!newton_inside)
        if (auto why = stationary_without_root(model, tol_, floor))
          return Advance<Chart>::stop(Status::local_minimum, *why);
      std::string_view kind = "newton";
      const Vector s = newton_inside ? u : have_newton ? dogleg(model, u, kind) : levenberg_marquardt(model, kind);
      const double predicted = model.predicted_decrease(s);
      const Trial<Chart> t = try_step(model.chart(), model.point(), s);
      const double rho = (phi0 - t.merit) / predicted;
      const double used = radius_;
      if (!(rho >= 0.25)) {
        radius_ = 0.25 * s.norm();
      } else if (rho > 0.75 && s.norm() >= 0.99 * radius_) {
        radius_ = std::min(2.0 * radius_, G::kLogRadius);
      }
      if (predicted > 0.0 && rho > kAcceptRatio) {
        Advance<Chart> a;
        a.next = t.p;
        a.s = s;
        a.info = {kind, {}, used, {}};
        a.projected = t.projected;
        return a;
      }
      if (!(radius_ > 0.0) || !s.allFinite()) break;
    }
    return Advance<Chart>::stop(no_decrease_status(model.point().f.norm(), floor),
                                "the trust radius shrank to " + format_number(radius_) +
                                    " without a decrease of 1/2 ||f||^2 (||f|| = " +
                                    format_number(model.point().f.norm()) + ", " +
                                    angle_detail<G>(model.point().angle) + ")");
  }

 private:
  // The dogleg point at distance radius_ (Newton's u lies outside).
  Vector dogleg(NewtonModel<G, Chart>& model, const Vector& u, std::string_view& kind) const {
    const Vector& g = model.gradient();
    const double gg = g.squaredNorm();
    const double dg = model.product(g).squaredNorm();
    const Vector cauchy = -(gg / dg) * g;
    if (!(dg > 0.0) || !cauchy.allFinite() || cauchy.norm() >= radius_) {
      kind = "cauchy";
      return -(radius_ / std::sqrt(gg)) * g;
    }
    // ||cauchy + tau d|| = radius_, tau in [0, 1]
    kind = "dogleg";
    const Vector d = u - cauchy;
    const double a = d.squaredNorm(), b = 2.0 * cauchy.dot(d), c = cauchy.squaredNorm() - radius_ * radius_;
    const double tau = (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
    return cauchy + std::clamp(tau, 0.0, 1.0) * d;
  }

  Vector levenberg_marquardt(NewtonModel<G, Chart>& model, std::string_view& kind) const {
    kind = "levenberg-marquardt";
    const double mu = std::max(model.gradient().norm() / radius_, std::numeric_limits<double>::min());
    return model.levenberg_marquardt(mu);
  }

  double tol_;
  double radius_ = G::kLogRadius;  // exp is injective within the log radius
};

}  // namespace lienewton
