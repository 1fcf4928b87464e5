#pragma once
// SO(3) in closed form (so3.hpp) on fixed-size types: nothing allocates. Coordinates are the rotation vector,
// and so is Spectral: the closed forms need nothing else.
#include <Eigen/Dense>
#include <string>

#include "lie_group.hpp"
#include "log_domain.hpp"
#include "polar_factor.hpp"
#include "rotation_facts.hpp"
#include "so3.hpp"

namespace lienewton {

struct SO3Group : RotationFacts<SO3Group, Eigen::Matrix3d> {
  using Element = Eigen::Matrix3d;
  using Vector = Eigen::Vector3d;
  using Operator = Eigen::Matrix3d;
  using Spectral = Eigen::Vector3d;
  static constexpr double kLogMargin = kLogDomainMargin;

  int n() const { return 3; }
  std::string name() const { return "SO(3)"; }
  int dim() const { return 3; }
  Element identity() const { return Element::Identity(); }
  Element compose(const Element& a, const Element& b) const { return a * b; }
  Element inverse(const Element& a) const { return a.transpose(); }  // O(N): every iterate stays in z SO(N)
  Element hat(const Vector& v) const { return so3::hat(v); }
  Vector vee(const Element& m) const { return so3::vee(m); }
  Vector bracket(const Vector& a, const Vector& b) const { return a.cross(b); }
  Operator ad_matrix(const Vector& v) const { return so3::hat(v); }

  Element exp(const Vector& v) const { return so3::exp(v); }
  Element times_exp(const Element& y, const Vector& v) const { return y + y * so3::expm1(v); }
  Spectral spectral(const Vector& v) const { return v; }
  Spectral log(const Element& r) const { return so3::checked_log(r); }  // throws LogDomainError
  Vector log_vector(const Element& r, double& angle) const {
    const Vector v = so3::checked_log(r);
    angle = so3::safe_norm(v);
    return v;
  }
  Vector vector(const Spectral& s) const { return s; }
  double angle(const Spectral& s) const { return so3::safe_norm(s); }
  Vector dexp(const Spectral& s, const Vector& u) const { return so3::dexp(s, u); }
  Vector dexpinv(const Spectral& s, const Vector& u) const { return so3::dexpinv(s, u); }
  Operator dexp_matrix(const Spectral& s) const { return so3::dexp_matrix(s); }
  Operator dexpinv_matrix(const Spectral& s) const { return so3::dexpinv_matrix(s); }

  double defect(const Element& y) const { return (y.transpose() * y - Element::Identity()).norm(); }
  Element project(const Element& y) const { return orthogonal_polar_factor(y); }
  Eigen::Matrix3d rotation(const Element& y) const { return y; }  // the body axes a picture of frames draws
};
static_assert(LieGroup<SO3Group>);

}  // namespace lienewton
