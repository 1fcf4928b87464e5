#pragma once
// The equation f(y) = 0, f: G -> g, that the solvers work on. Either the implicit Euler residual
//   f(y) = v(y) - h g(y),  z^-1 y = exp(v(y))                                  (3.6), (3.7)
// built from a vector field, or a user-supplied f with an optional exact differential df_y(u) (3.4).
// It provides f at a point of the group (Version 1) or of the algebra, y = z exp(v) (Version 2, (3.21)),
// and the differentials the user can choose between:
//   Version 1: df_y(u) = dexpinv_v(u) - h dg_y(u)  exact (3.8), u - h dg_y(u) (3.10), u + [v,u]/2 - h dg_y(u) (3.11)
//   Version 2: u - h dg_y(dexp_v(u))  exact (3.22), u - h dg_y(u) (3.16), u - h dg_y(u - [v,u]/2) (3.17)
// Finite differences (3.18)/(3.19) are built by the solvers from f alone.
#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include "core/cancellation.hpp"
#include "core/groups/lie_group.hpp"
#include "core/groups/log_domain.hpp"
#include "core/options.hpp"
#include "core/problems.hpp"
#include "factored_operator.hpp"
#include "product_skipping_zeros.hpp"

namespace lienewton {

template <LieGroup G>
class Equation {
 public:
  using Element = typename G::Element;
  using Vector = typename G::Vector;
  using Spectral = typename G::Spectral;
  using Operator = typename G::Operator;
  using UserF = std::function<Vector(const Element&)>;
  using UserDf = std::function<Vector(const Element& y, const Vector& u)>;

  // f evaluated at a point, with what the differentials reuse.
  struct Point {
    Element y;
    Spectral v_form;       // Version 1: log of z^-1 y; Version 2: the spectral form of v (from exp)
    Vector v;              // coordinates of v
    Vector hg;             // h g(y) (implicit Euler only)
    Vector f;              // f(y) (Version 1) or f~(v) (Version 2): what the iteration drives to 0
    double residual = 0;   // ||f(y)||, f of (3.6) at y (Version 2: set by read_group_residual)
    std::optional<double> algebra_residual;  // ||f~(v)|| (Version 2, fixed point)
    double angle = 0;      // largest rotation angle of z^-1 y, in [0, kLogRadius]
    double algebra_angle = 0;  // largest rotation angle of v as an algebra element (may exceed kLogRadius)
    bool in_domain = true; // false: z^-1 y is at the boundary of log's domain, log (hence f) undefined
  };

  // What an evaluation must provide: f alone (difference quotients, fixed point), or also the spectral
  // form that the exact and truncated differentials reuse.
  enum class Need { residual, differential };

  static Equation implicit_euler(G group, Element z, double h, const VectorField<G>& field) {
    return Equation(group, std::move(z), h, &field, {}, {});
  }
  static Equation general(G group, Element z, UserF f, UserDf df = {}) {
    return Equation(group, std::move(z), 0.0, nullptr, std::move(f), std::move(df));
  }

  // The same implicit Euler equation at another step size h (continuation's stages), starting where this one does.
  Equation at_step(double h) const {
    Equation e = *this;
    e.h_ = h;
    return e;
  }

  const G& group() const { return group_; }
  const Element& z() const { return z_; }
  double h() const { return h_; }
  bool is_implicit_euler() const { return field_ != nullptr; }
  const VectorField<G>* field() const { return field_; }

  // Version 1: f(y).
  Point at(const Element& y, Need need = Need::differential) const {
    Point p;
    p.y = y;
    if (!read_log(p, need)) return p;
    if (field_) {
      p.hg = h_ * field_->g(y);
      p.f = p.v - p.hg;
    } else {
      p.hg = zero_vector(group_);  // no h g for a user f; fixed-size vectors would otherwise hold garbage
      p.f = f_(y);
    }
    p.residual = p.f.norm();
    return p;
  }

  // Version 2: f~(v) = f(z exp(v)); for implicit Euler v - h g(z exp v) (3.21), which needs no log.
  Point at_algebra(const Vector& v, Need need = Need::differential) const {
    Point p;
    p.v = v;
    p.y = group_.times_exp(z_, v);
    if (need == Need::differential) {
      p.v_form = group_.spectral(v);
      p.algebra_angle = group_.angle(p.v_form);
      p.angle = group_.principal_angle(p.algebra_angle);
    }
    if (field_) {
      p.hg = h_ * field_->g(p.y);
      p.f = v - p.hg;
    } else {
      p.hg = zero_vector(group_);
      p.f = f_(p.y);
    }
    p.algebra_residual = p.residual = p.f.norm();
    return p;
  }

  // Version 2: ||f(y)|| = ||log(z^-1 y) - h g(y)|| at y = z exp(v), as section 5 measures every method. It
  // equals ||f~(v)|| while v's angles stay below pi; beyond, log(z^-1 y) = v - 2 pi k and the two part.
  // in_domain = false (residual NaN) when z^-1 y is at the edge of log's domain.
  void read_group_residual(Point& p) const {
    if (!field_) return;  // a user f: f~(v) = f(z exp v) is f(y) itself
    double angle = 0;
    try {
      const Vector log_v = group_.log_vector(group_.compose(z_inv_, p.y), angle);
      p.in_domain = inside_log_domain<G>(angle);
      p.residual = p.in_domain ? (log_v - p.hg).norm() : std::numeric_limits<double>::quiet_NaN();
    } catch (const LogDomainError&) {
      p.in_domain = false;
      p.residual = std::numeric_limits<double>::quiet_NaN();
    }
  }

  // Version 1 differential df_y(u), (3.8) / (3.10) / (3.11); finite-difference: the directional quotient (3.18).
  Vector df(const Point& p, const Vector& u, Differential d) const {
    if (d == Differential::finite_difference) {
      const double t = difference_step(p, u);
      const Point q = at(group_.times_exp(p.y, t * u), Need::residual);
      if (!q.in_domain) throw_crossed_log_boundary(q.angle);
      return (q.f - p.f) / t;
    }
    if (!field_) return df_(p.y, u);
    switch (d) {
      case Differential::dexpinv_0: return u - h_ * field_->dg(p.y, u);
      case Differential::dexpinv_1: return u + 0.5 * group_.bracket(p.v, u) - h_ * field_->dg(p.y, u);
      default: return group_.dexpinv(p.v_form, u) - h_ * field_->dg(p.y, u);
    }
  }

  // Version 2 differential df~_v(u), (3.22) / (3.16) / (3.17); for a user f, df_y o dexp_v (3.24);
  // finite-difference: the directional quotient (3.19).
  Vector dftilde(const Point& p, const Vector& u, Differential d) const {
    if (d == Differential::finite_difference) {
      const double t = difference_step(p, u);
      return (at_algebra(p.v + t * u, Need::residual).f - p.f) / t;
    }
    if (!field_) return df_(p.y, group_.dexp(p.v_form, u));
    switch (d) {
      case Differential::dexpinv_0: return u - h_ * field_->dg(p.y, u);
      case Differential::dexpinv_1: return u - h_ * field_->dg(p.y, u - 0.5 * group_.bracket(p.v, u));
      default: return u - h_ * field_->dg(p.y, group_.dexp(p.v_form, u));
    }
  }

  // The q x q matrix of df_y on the basis (throws LogDomainError if a difference quotient crosses pi).
  // Exact and truncated differentials are assembled from the closed/spectral matrices of dexpinv and ad
  // plus dg's matrix; differences perturb y by exp(t b_i), a plane rotation on SO(N).
  Operator df_matrix(const Point& p, Differential d) const {
    if (d == Differential::finite_difference) {
      const double t = difference_step(p, basis_vector(group_, 0));
      return operator_from_columns(group_, [&](const Vector& b) -> Vector {
        throw_if_cancelled();  // q columns of exp and log: seconds for large N
        const Point q = at(group_.times_exp(p.y, t * b), Need::residual);
        if (!q.in_domain) throw_crossed_log_boundary(q.angle);
        return (q.f - p.f) / t;
      });
    }
    if (!field_) return columns([&](const Vector& u) { return df_(p.y, u); });
    const Operator hdg = h_ * field_->dg_matrix(group_, p.y);
    switch (d) {
      case Differential::dexpinv_0: return identity_operator(group_) - hdg;
      case Differential::dexpinv_1: return identity_operator(group_) + 0.5 * group_.ad_matrix(p.v) - hdg;
      default: return group_.dexpinv_matrix(p.v_form) - hdg;
    }
  }

  // df_y as A P^T for the Newton step (newton_step.hpp). Exact, with a group that has a spectral basis P of v
  // (son::SpectralBasis): A = dexpinv_v P - h dg_y P, O(N^4) plus the product dg_y P (O(N^4) for a sparse dg_y,
  // as paper-linear's), where the matrix of (3.8) costs O(N^5). Otherwise A = df_matrix, no P.
  FactoredOperator<Operator> df_factored(const Point& p, Differential d) const {
    if constexpr (kHasSpectralBasis) {
      if (field_ && d == Differential::exact) {
        auto [basis, a] = group_.dexpinv_in_spectral_basis(p.v_form);
        a -= product_skipping_zeros(Operator(h_ * field_->dg_matrix(group_, p.y)), basis);
        return {std::move(a), std::move(basis)};
      }
    }
    return {df_matrix(p, d), std::nullopt};
  }

  // The q x q matrix of df~_v on the basis.
  Operator dftilde_matrix(const Point& p, Differential d) const {
    if (d == Differential::finite_difference) {
      const double t = difference_step(p, basis_vector(group_, 0));
      return operator_from_columns(group_, [&](const Vector& b) -> Vector {
        throw_if_cancelled();
        return (at_algebra(p.v + t * b, Need::residual).f - p.f) / t;
      });
    }
    if (!field_) return columns([&](const Vector& u) { return df_(p.y, group_.dexp(p.v_form, u)); });
    const Operator hdg = h_ * field_->dg_matrix(group_, p.y);
    switch (d) {
      case Differential::dexpinv_0: return identity_operator(group_) - hdg;
      case Differential::dexpinv_1:
        return identity_operator(group_) - hdg * (identity_operator(group_) - 0.5 * group_.ad_matrix(p.v));
      default: return identity_operator(group_) - hdg * group_.dexp_matrix(p.v_form);
    }
  }

  // df~_v as A P^T (see df_factored): exact, (3.22) times P is P - h dg_y (dexp_v P).
  FactoredOperator<Operator> dftilde_factored(const Point& p, Differential d) const {
    if constexpr (kHasSpectralBasis) {
      if (field_ && d == Differential::exact) {
        const auto [basis, dexp_basis] = group_.dexp_in_spectral_basis(p.v_form);
        return {basis - product_skipping_zeros(Operator(h_ * field_->dg_matrix(group_, p.y)), dexp_basis), basis};
      }
    }
    return {dftilde_matrix(p, d), std::nullopt};
  }

  // The fixed-point map (1.2): y -> z exp(h g(y)).
  Element fixed_point_map(const Point& p) const { return group_.times_exp(z_, p.hg); }

  // kappa ~ h ||dg_y||_2, the conditioning term of the floor and of the (1.1) tolerance: near a solution
  // df_y = dexpinv - h dg_y, so rounding eps in y is amplified to ~ eps h ||dg_y|| in f. Estimated by power
  // iteration on dg's matrix (a lower estimate of the 2-norm, within a few percent after 12 steps). 0 for a user f.
  double conditioning(const Element& y) const {
    if (!field_ || h_ == 0.0) return 0.0;
    const Operator m = field_->dg_matrix(group_, y);
    Vector x = Vector::Ones(group_.dim()) / std::sqrt(double(group_.dim()));
    double sigma2 = 0.0;
    for (int k = 0; k < 12; ++k) {
      const Vector mx = m.transpose() * (m * x);
      sigma2 = mx.norm();
      if (!(sigma2 > 0.0) || !std::isfinite(sigma2)) break;
      x = mx / sigma2;
    }
    return h_ * std::sqrt(sigma2);
  }

  // How well y solves (1.1), y = z exp(h g(y)), checked without log: defect = ||y - z exp(w)||_F with
  // w = h g(y), against tolerance 256 eps sqrt(q) (1 + ||w|| + kappa); angle = the largest rotation angle of w
  // as an algebra element. angle > pi means log(z^-1 y) != w: a solution of (1.1) that f of (3.6) cannot see.
  struct ImplicitEulerCheck {
    double defect = std::numeric_limits<double>::infinity();
    double tolerance = 0;
    double angle = 0;
    bool solves() const { return defect <= tolerance; }
    bool off_branch() const { return solves() && angle > G::kLogRadius; }
  };
  ImplicitEulerCheck check_implicit_euler(const Element& y, double kappa) const {
    ImplicitEulerCheck c;
    if (!field_) return c;
    const Vector w = h_ * field_->g(y);
    c.angle = group_.angle(group_.spectral(w));
    c.defect = (group_.times_exp(z_, w) - y).norm();
    constexpr double eps = std::numeric_limits<double>::epsilon();
    c.tolerance = 256.0 * eps * std::sqrt(double(group_.dim())) * (1.0 + w.norm() + kappa);
    return c;
  }

  // The z rule: the given z replaced by the group's projection of it (SO(N): the orthogonal polar factor); how far
  // that moved it (Frobenius).
  double z_adjustment() const { return z_adjustment_; }

  // Where the solvers start: y_0 = z, as section 5 does, unless start_at(y0) moved it (a request's y0, a
  // basin map's pixel). y0 must be reachable from z (in z SO(N) on O(N)); it is projected onto the group, as z is.
  const Element& start() const { return y0_; }
  void start_at(const Element& y0) {
    y0_ = group_.project(y0);
    moved_start_ = true;
  }
  // v_0 with y_0 = z exp(v_0), Version 2's start (3.20): 0 at z, else log(z^-1 y_0); empty when z^-1 y_0 is at
  // the edge of log's domain.
  std::optional<Vector> start_algebra() const {
    if (!moved_start_) return zero_vector(group_);
    try {
      double angle = 0;
      Vector v = group_.log_vector(group_.compose(z_inv_, y0_), angle);
      if (inside_log_domain<G>(angle)) return v;
    } catch (const LogDomainError&) {
    }
    return std::nullopt;
  }

 private:
  static constexpr bool kHasSpectralBasis = requires(const G g, const Spectral s) {
    g.dexpinv_in_spectral_basis(s);
    g.dexp_in_spectral_basis(s);
  };

  Equation(G group, Element z, double h, const VectorField<G>* field, UserF f, UserDf df)
      : group_(group), z_(group_.project(z)), z_inv_(group_.inverse(z_)), h_(h), field_(field),
        f_(std::move(f)), df_(std::move(df)), z_adjustment_((z - z_).norm()), y0_(z_) {}

  // Forward-difference step t = sqrt(eps) scaled to the point and the direction, as the paper suggests
  // for (3.12)/(3.18): |t u| ~ sqrt(eps) max(1, |v|).
  static double difference_step(const Point& p, const Vector& u) {
    const double scale = std::max(1.0, p.v.size() > 0 ? p.v.norm() : 0.0);
    return std::sqrt(std::numeric_limits<double>::epsilon()) * scale / std::max(u.norm(), 1e-300);
  }

  template <class Apply>
  Operator columns(Apply apply) const {
    return operator_from_columns(group_, [&](const Vector& b) -> Vector { return apply(b); });
  }

  [[noreturn]] static void throw_crossed_log_boundary(double angle) {
    throw LogDomainError(std::string("a difference quotient crossed ") + G::kAngleName + " " + G::kLogBoundaryName,
                         angle);
  }

  // v = log(z^-1 y); false when z^-1 y is at the edge of log's domain.
  bool read_log(Point& p, Need need) const {
    const Element w = group_.compose(z_inv_, p.y);
    try {
      if (need == Need::differential) {
        p.v_form = group_.log(w);
        p.angle = group_.angle(p.v_form);
        p.v = group_.vector(p.v_form);
      } else {
        p.v = group_.log_vector(w, p.angle);
      }
    } catch (const LogDomainError& e) {
      p.angle = std::isnan(e.angle()) ? G::kLogRadius : e.angle();
      p.in_domain = !field_;  // a user f does not need log
      return p.in_domain;
    }
    p.algebra_angle = p.angle;
    p.in_domain = inside_log_domain<G>(p.angle) || !field_;
    return p.in_domain;
  }

  G group_;
  Element z_, z_inv_;
  double h_;
  const VectorField<G>* field_;
  UserF f_;
  UserDf df_;
  double z_adjustment_;
  Element y0_;
  bool moved_start_ = false;
};

}  // namespace lienewton
