#pragma once
// The local model a globalised iteration works with at the iterate x (y for Version 1, v for Version 2):
//   merit     phi(x) = 1/2 ||f(x)||^2
//   model     m(s) = 1/2 ||f + D s||^2, D the differential of (3.5) (df_y) or of (3.20) (df~_v) on the basis
//   gradient  D^T f, the gradient of phi when D is f's differential (exact, or finite differences (3.18)/(3.19))
//   Newton    D u = -f (3.5)/(3.20); its slope f^T D u = -||f||^2 < 0, so it is a descent direction for phi
//   LM        (D^T D + mu I) s = -D^T f (Levenberg-Marquardt): always a descent direction, defined when D is singular
// D is assembled lazily: a Krylov Newton step (large N) needs only products D w.
#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "newton_step.hpp"
#include "solver_run.hpp"

namespace lienewton {

template <LieGroup G, class Chart>
class NewtonModel {
 public:
  using Point = typename Chart::Point;
  using Vector = typename G::Vector;
  using Operator = typename G::Operator;

  NewtonModel(const Chart& chart, const Point& p, bool krylov) : chart_(chart), p_(p), krylov_(krylov) {}

  const Point& point() const { return p_; }
  const Chart& chart() const { return chart_; }
  bool krylov() const { return krylov_; }
  double merit() const { return 0.5 * p_.f.squaredNorm(); }

  // Newton's step u: D u = -f, (3.5) or (3.20), by the configured linear solver; solved once per model (the
  // watchdog and the strategy both ask for it).
  detail::StepOutcome newton(Vector& u) {
    if (!newton_outcome_)
      newton_outcome_ = detail::newton_step<G>(
          krylov_, [&] { return FactoredOperator<Operator>{matrix(), std::nullopt}; },
          [&](const Vector& w) { return chart_.apply(p_, w); }, p_.f, newton_u_);
    u = newton_u_;
    return *newton_outcome_;
  }
  const Operator& matrix() {
    if (!d_) d_ = chart_.matrix(p_);
    return *d_;
  }
  const Vector& gradient() {
    if (!g_) g_ = matrix().transpose() * p_.f;
    return *g_;
  }
  // (D^T D + mu I) s = -D^T f; mu > 0 makes the matrix positive definite.
  Vector levenberg_marquardt(double mu) {
    if constexpr (kSparseOperator<G>) {
      Operator shift(matrix().cols(), matrix().cols());
      shift.setIdentity();
      const Operator a = Operator(matrix().transpose() * matrix()) + mu * shift;
      return -Eigen::SimplicialLDLT<Operator>(a).solve(gradient());
    } else {
      Operator a = matrix().transpose() * matrix();
      a.diagonal().array() += mu;
      return -a.ldlt().solve(gradient());
    }
  }
  // D s, from the assembled matrix when there is one.
  Vector product(const Vector& s) const { return d_ ? Vector(*d_ * s) : chart_.apply(p_, s); }
  // d/dalpha phi(x + alpha s) at alpha = 0: f^T D s.
  double slope(const Vector& s) const { return p_.f.dot(product(s)); }
  // m(0) - m(s) = -(f^T D s + 1/2 ||D s||^2).
  double predicted_decrease(const Vector& s) const {
    const Vector ds = product(s);
    return -(p_.f.dot(ds) + 0.5 * ds.squaredNorm());
  }

 private:
  const Chart& chart_;
  const Point& p_;
  bool krylov_;
  std::optional<Operator> d_;
  std::optional<Vector> g_;
  std::optional<detail::StepOutcome> newton_outcome_;
  Vector newton_u_;
};

// ||D^T f|| <= delta ||D||_F ||f||: f lies in the null space of D^T to the accuracy the gradient can be known
// to, so phi is stationary there. delta = 64 sqrt(eps): finite differences (3.18)/(3.19) carry ~sqrt(eps) of
// relative error, and even an exact gradient cannot be driven lower by descent, since phi's rounding
// (eps phi) hides changes of phi below a distance ~sqrt(eps) from a minimiser, where ||grad phi|| is ~sqrt(eps)
// ||D|| ||f||. Truncated differentials (3.10)/(3.11) are not f's differential, so D^T f says nothing about phi
// and no test is made.
inline std::optional<double> stationarity_threshold(Differential d) {
  if (d != Differential::finite_difference && d != Differential::exact) return std::nullopt;
  return 64.0 * std::sqrt(std::numeric_limits<double>::epsilon());
}

// How a globalised step that finds no decrease of phi ends: stagnated when ||f|| is within 16x its rounding floor
// (no decrease is left to find), else no_descent: far above the floor, phi is not smooth at the iterate (the jump
// of log at angle pi) or D is not its derivative.
inline Status no_decrease_status(double f, double floor) {
  return f <= 16.0 * floor ? Status::stagnated : Status::no_descent;
}

// Where the iterate is with respect to log's cut, for a reason, in G's words: "z^-1 y at rotation angle pi - 1e-10".
template <LieGroup G>
std::string angle_detail(double angle) {
  return std::string("z^-1 y at ") + G::kAngleName + " " + G::kLogBoundaryName + " - " +
         format_number(log_boundary_distance<G>(angle));
}

// The local_minimum detail when the model's iterate is a stationary point of phi that is no root: ||f|| above
// tol and well above its rounding floor, ||D^T f|| at rounding. Empty otherwise.
template <LieGroup G, class Chart>
std::optional<std::string> stationary_without_root(NewtonModel<G, Chart>& model, double tol, double floor) {
  const auto delta = stationarity_threshold(model.chart().differential());
  const double f = model.point().f.norm();
  if (!delta || f <= tol || f <= 16.0 * floor) return std::nullopt;
  const double g = model.gradient().norm();
  const double d = model.matrix().norm();
  if (!(g <= *delta * d * f)) return std::nullopt;
  return "||f|| = " + format_number(f) + " while ||D^T f|| = " + format_number(g) + " = " +
         format_number(g / (d * f)) + " ||D||_F ||f||, at most " + format_number(*delta) + " ||D||_F ||f||";
}

// The point x exp(s) (Version 1) or v + s (Version 2) and its merit; +inf where f is undefined (log's domain
// edge) or not finite, so that a search steps back from there.
template <class Chart>
struct Trial {
  typename Chart::Point p;
  bool projected = false;
  double merit = std::numeric_limits<double>::infinity();
};
template <class Chart>
Trial<Chart> try_step(const Chart& chart, const typename Chart::Point& from, const typename Chart::Vector& s) {
  Trial<Chart> t;
  const auto x = chart.move(from, s, t.projected);
  if (!x.allFinite()) return t;
  try {
    t.p = chart.at(x);
  } catch (const LogDomainError&) {
    return t;
  }
  const double phi = 0.5 * t.p.f.squaredNorm();
  if (t.p.in_domain && std::isfinite(phi) && std::isfinite(t.p.residual)) t.merit = phi;
  return t;
}

// What one globalised iteration produced: the next iterate and the step to it, or the status to stop with.
template <class Chart>
struct Advance {
  std::optional<typename Chart::Point> next;
  typename Chart::Vector s;
  StepInfo info;
  bool projected = false;
  Status failure = Status::max_iterations;  // when next is empty
  std::string detail;
  static Advance stop(Status status, std::string detail = {}) {
    Advance a;
    a.failure = status;
    a.detail = std::move(detail);
    return a;
  }
};

}  // namespace lienewton
