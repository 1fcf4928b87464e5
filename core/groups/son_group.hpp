#pragma once
// SO(N), any N >= 2, through the spectral forms of son.hpp; coordinates on the paper's basis E_ij - E_ji.
#include <Eigen/Dense>
#include <string>

#include "lie_group.hpp"
#include "log_domain.hpp"
#include "polar_factor.hpp"
#include "rotation_facts.hpp"
#include "son.hpp"

namespace lienewton {

struct SONGroup : RotationFacts<SONGroup, Eigen::MatrixXd> {
  using Element = Eigen::MatrixXd;
  using Vector = Eigen::VectorXd;
  using Operator = Eigen::MatrixXd;
  using Spectral = son::SpectralForm;
  static constexpr double kLogMargin = kLogDomainMargin;

  explicit SONGroup(int n) : n_(n) {}
  int n() const { return n_; }
  std::string name() const { return "SO(" + std::to_string(n_) + ")"; }
  int dim() const { return son::algebra_dim(n_); }
  Element identity() const { return Element::Identity(n_, n_); }
  Element compose(const Element& a, const Element& b) const { return a * b; }
  Element inverse(const Element& a) const { return a.transpose(); }
  Element hat(const Vector& v) const { return son::hat(v, n_); }
  Vector vee(const Element& m) const { return son::vee(m); }
  Vector bracket(const Vector& a, const Vector& b) const { return vee(son::bracket(hat(a), hat(b))); }
  Operator ad_matrix(const Vector& v) const { return son::ad_matrix(hat(v)); }

  Element exp(const Vector& v) const { return son::exp(hat(v)); }
  // y exp(v); a multiple of one basis element E_ab - E_ba (the difference quotients' directions) is a plane
  // rotation of columns a and b, O(N) instead of the O(N^3) spectral expm1.
  Element times_exp(const Element& y, const Vector& v) const {
    Eigen::Index i = 0;
    if ((v.array() != 0.0).count() == 1) {
      v.cwiseAbs().maxCoeff(&i);
      int a = 0, k = static_cast<int>(i);  // basis element k is E_ab - E_ba in row-major order of the pairs a < b
      while (k >= n_ - 1 - a) k -= n_ - 1 - a++;
      return son::times_givens(y, a, a + 1 + k, v(i));
    }
    return y + y * son::expm1(hat(v));
  }
  Spectral spectral(const Vector& v) const { return son::spectral_form_of_skew(hat(v)); }
  Spectral log(const Element& r) const { return son::spectral_form_of_rotation(r); }  // throws LogDomainError
  // log alone (no spectral form for the differentials): cheaper, see son::log.
  Vector log_vector(const Element& r, double& angle) const { return vee(son::log(r, &angle)); }
  Vector vector(const Spectral& s) const { return vee(s.skew()); }
  double angle(const Spectral& s) const { return s.max_angle(); }
  Vector dexp(const Spectral& s, const Vector& u) const { return vee(son::dexp(s, hat(u))); }
  Vector dexpinv(const Spectral& s, const Vector& u) const { return vee(son::dexpinv(s, hat(u))); }
  Operator dexp_matrix(const Spectral& s) const { return son::dexp_matrix(s); }
  Operator dexpinv_matrix(const Spectral& s) const { return son::dexpinv_matrix(s); }
  // Optional (solvers/equation.hpp uses it when a group has it): the spectral basis P of v with dexp_v P
  // resp. dexpinv_v P, in O(N^4); the Newton step solves in it without forming the O(N^5) matrices.
  son::SpectralBasis dexp_in_spectral_basis(const Spectral& s) const { return son::dexp_in_spectral_basis(s); }
  son::SpectralBasis dexpinv_in_spectral_basis(const Spectral& s) const { return son::dexpinv_in_spectral_basis(s); }

  double defect(const Element& y) const { return (y.transpose() * y - identity()).norm(); }
  Element project(const Element& y) const { return orthogonal_polar_factor(y); }

 private:
  int n_;
};
static_assert(LieGroup<SONGroup>);

}  // namespace lienewton
