#pragma once
// The groups the solvers run on, behind one compile-time interface:
//   Element (group element), Vector (algebra coordinates), Operator (q x q matrix on coordinates),
//   Spectral (what log/exp computed that dexp/dexpinv can reuse: the decomposition of z^-1 y serves both
//   log and dexpinv), compose/inverse, exp/log through Spectral, dexp/dexpinv, hat/vee, bracket, and
//   times_exp(y, v) = y exp(v), formed as y + y (exp(v) - I) to keep long products on the group.
// SO3Group uses fixed-size types (no heap allocation), SONGroup the spectral forms of son.hpp, RnGroup the
// abelian group R^n (exp = log = identity), where both Newton versions must reduce to classical Newton.
#include <Eigen/Dense>
#include <limits>

#include "so3.hpp"
#include "son.hpp"

namespace lienewton {

struct SO3Group {
  using Element = Eigen::Matrix3d;
  using Vector = Eigen::Vector3d;
  using Operator = Eigen::Matrix3d;
  using Spectral = Eigen::Vector3d;  // the rotation vector itself: closed forms need nothing else

  int n() const { return 3; }
  int dim() const { return 3; }
  Vector zero() const { return Vector::Zero(); }
  Vector unit(int i) const { return Vector::Unit(i); }
  Operator operator_matrix() const { return Operator::Zero(); }
  Operator identity_operator() const { return Operator::Identity(); }
  Element identity() const { return Element::Identity(); }
  Element compose(const Element& a, const Element& b) const { return a * b; }
  Element inverse(const Element& a) const { return a.transpose(); }  // O(N): every iterate stays in z SO(N)
  Element hat(const Vector& v) const { return so3::hat(v); }
  Vector vee(const Element& m) const { return so3::vee(m); }
  Vector bracket(const Vector& a, const Vector& b) const { return a.cross(b); }

  Spectral exp_form(const Vector& v) const { return v; }
  Spectral log_form(const Element& r) const { return so3::checked_log(r); }  // throws LogDomainError
  Vector log_coords(const Element& r, double& angle) const {
    const Vector v = so3::checked_log(r);
    angle = v.norm();
    return v;
  }
  Vector coords(const Spectral& s) const { return s; }
  Element element(const Spectral& s) const { return so3::exp(s); }
  double angle(const Spectral& s) const { return s.norm(); }
  Vector dexp(const Spectral& s, const Vector& u) const { return so3::dexp(s, u); }
  Vector dexpinv(const Spectral& s, const Vector& u) const { return so3::dexpinv(s, u); }
  Element exp(const Vector& v) const { return so3::exp(v); }
  Element times_exp(const Element& y, const Vector& v) const { return y + y * so3::expm1(v); }
  Element times_exp_form(const Element& y, const Spectral& s) const { return times_exp(y, s); }
  Element times_exp_unit(const Element& y, int i, double t) const { return times_exp(y, t * unit(i)); }
  Operator dexp_matrix(const Spectral& s) const { return so3::dexp_matrix(s); }
  Operator dexpinv_matrix(const Spectral& s) const { return so3::dexpinv_matrix(s); }
  Operator ad_matrix(const Vector& v) const { return so3::hat(v); }
  bool log_defined(const Spectral& s) const { return s.norm() <= so3::kPi - son::kLogDomainMargin; }
};

struct SONGroup {
  using Element = Eigen::MatrixXd;
  using Vector = Eigen::VectorXd;
  using Operator = Eigen::MatrixXd;
  using Spectral = son::SpectralForm;

  explicit SONGroup(int n) : n_(n) {}
  int n() const { return n_; }
  int dim() const { return son::algebra_dim(n_); }
  Vector zero() const { return Vector::Zero(dim()); }
  Vector unit(int i) const { return Vector::Unit(dim(), i); }
  Operator operator_matrix() const { return Operator::Zero(dim(), dim()); }
  Operator identity_operator() const { return Operator::Identity(dim(), dim()); }
  Element identity() const { return Element::Identity(n_, n_); }
  Element compose(const Element& a, const Element& b) const { return a * b; }
  Element inverse(const Element& a) const { return a.transpose(); }
  Element hat(const Vector& v) const { return son::hat(v, n_); }
  Vector vee(const Element& m) const { return son::vee(m); }
  Vector bracket(const Vector& a, const Vector& b) const { return vee(son::bracket(hat(a), hat(b))); }

  Spectral exp_form(const Vector& v) const { return son::spectral_form_of_skew(hat(v)); }
  Spectral log_form(const Element& r) const { return son::spectral_form_of_rotation(r); }  // throws LogDomainError
  // log alone (no spectral form for the differentials): cheaper, see son::log.
  Vector log_coords(const Element& r, double& angle) const { return vee(son::log(r, &angle)); }
  Vector coords(const Spectral& s) const { return vee(s.skew()); }
  Element element(const Spectral& s) const { return s.rotation(); }
  double angle(const Spectral& s) const { return s.max_angle(); }
  Vector dexp(const Spectral& s, const Vector& u) const { return vee(son::dexp(s, hat(u))); }
  Vector dexpinv(const Spectral& s, const Vector& u) const { return vee(son::dexpinv(s, hat(u))); }
  Element exp(const Vector& v) const { return son::exp(hat(v)); }
  Element times_exp(const Element& y, const Vector& v) const { return y + y * son::expm1(hat(v)); }
  Element times_exp_form(const Element& y, const Spectral& s) const { return s.times_rotation(y); }
  Element times_exp_unit(const Element& y, int i, double t) const {
    int a = 0;  // basis element i is E_ab - E_ba in row-major order of the pairs a < b
    while (i >= n_ - 1 - a) i -= n_ - 1 - a++;
    return son::times_givens(y, a, a + 1 + i, t);
  }
  Operator dexp_matrix(const Spectral& s) const { return son::dexp_matrix(s); }
  Operator dexpinv_matrix(const Spectral& s) const { return son::dexpinv_matrix(s); }
  Operator ad_matrix(const Vector& v) const { return son::ad_matrix(hat(v)); }
  bool log_defined(const Spectral& s) const { return s.max_angle() <= so3::kPi - son::kLogDomainMargin; }

 private:
  int n_;
};

// The abelian group R^n under addition: exp and log are the identity, ad = 0, dexp = dexpinv = Id.
struct RnGroup {
  using Element = Eigen::VectorXd;
  using Vector = Eigen::VectorXd;
  using Operator = Eigen::MatrixXd;
  using Spectral = Eigen::VectorXd;

  explicit RnGroup(int n) : n_(n) {}
  int n() const { return n_; }
  int dim() const { return n_; }
  Vector zero() const { return Vector::Zero(n_); }
  Vector unit(int i) const { return Vector::Unit(n_, i); }
  Operator operator_matrix() const { return Operator::Zero(n_, n_); }
  Operator identity_operator() const { return Operator::Identity(n_, n_); }
  Element identity() const { return Element::Zero(n_); }
  Element compose(const Element& a, const Element& b) const { return a + b; }
  Element inverse(const Element& a) const { return -a; }
  Element hat(const Vector& v) const { return v; }
  Vector vee(const Element& m) const { return m; }
  Vector bracket(const Vector&, const Vector&) const { return zero(); }

  Spectral exp_form(const Vector& v) const { return v; }
  Spectral log_form(const Element& r) const { return r; }
  Vector log_coords(const Element& r, double& angle) const {
    angle = 0.0;
    return r;
  }
  Vector coords(const Spectral& s) const { return s; }
  Element element(const Spectral& s) const { return s; }
  double angle(const Spectral&) const { return 0.0; }
  Vector dexp(const Spectral&, const Vector& u) const { return u; }
  Vector dexpinv(const Spectral&, const Vector& u) const { return u; }
  Element exp(const Vector& v) const { return v; }
  Element times_exp(const Element& y, const Vector& v) const { return y + v; }
  Element times_exp_form(const Element& y, const Spectral& s) const { return y + s; }
  Element times_exp_unit(const Element& y, int i, double t) const { return y + t * unit(i); }
  Operator dexp_matrix(const Spectral&) const { return Operator::Identity(n_, n_); }
  Operator dexpinv_matrix(const Spectral&) const { return Operator::Identity(n_, n_); }
  Operator ad_matrix(const Vector&) const { return Operator::Zero(n_, n_); }
  bool log_defined(const Spectral&) const { return true; }

 private:
  int n_;
};

// ||y^T y - I||_F for matrix groups; 0 for R^n.
template <class Element>
double orthogonality_error(const Element& y) {
  if constexpr (Element::ColsAtCompileTime == 1) {
    return 0.0;
  } else {
    return (y.transpose() * y - Element::Identity(y.rows(), y.cols())).norm();
  }
}

}  // namespace lienewton
