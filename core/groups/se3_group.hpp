#pragma once
// SE(3), the rigid motions T = [[R, p], [0, 1]], in closed form (se3.hpp) on fixed-size types, and its family SE
// (requests name it "group": "SE" with n = 3, the dimension of the space it moves, as in SE(3)). Coordinates are
// xi = (w, r): the rotation vector first, then the translation part; Spectral is xi itself. Angles are the
// rotation angle |w|: log's boundary is pi, as on SO(3), and exp is periodic in w only.
#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>

#include "core/start_point.hpp"
#include "lie_group.hpp"
#include "log_domain.hpp"
#include "polar_factor.hpp"
#include "se3.hpp"
#include "single_group_family.hpp"

namespace lienewton {

struct SE3Group {
  using Element = Eigen::Matrix4d;
  using Vector = se3::Vec6;
  using Operator = se3::Mat6;
  using Spectral = se3::Vec6;
  static constexpr double kLogRadius = std::numbers::pi;  // log is defined for rotation angles below pi
  static constexpr double kLogMargin = kLogDomainMargin;
  static constexpr const char* kAngleName = "rotation angle";
  static constexpr const char* kLogBoundaryName = "pi";
  static constexpr const char* kAlgebraDimension = "n(n+1)/2";
  // ||R^T R - I||_F above which a request's rotation block is refused (SO(N)'s tolerance).
  static constexpr double kMemberTolerance = 1e-10;

  int n() const { return 3; }
  std::string name() const { return "SE(3)"; }
  int dim() const { return 6; }
  Element identity() const { return Element::Identity(); }
  Element compose(const Element& a, const Element& b) const { return a * b; }
  Element inverse(const Element& a) const {  // [[R^T, -R^T p], [0, 1]]: exact in the last row
    Element out = Element::Identity();
    out.topLeftCorner<3, 3>() = a.topLeftCorner<3, 3>().transpose();
    out.topRightCorner<3, 1>() = -(a.topLeftCorner<3, 3>().transpose() * a.topRightCorner<3, 1>());
    return out;
  }
  Element hat(const Vector& v) const { return se3::hat(v); }
  Vector vee(const Element& m) const { return se3::vee(m); }
  Vector bracket(const Vector& a, const Vector& b) const { return se3::bracket(a, b); }
  Operator ad_matrix(const Vector& v) const { return se3::ad_matrix(v); }

  Element exp(const Vector& v) const { return se3::exp(v); }
  Element times_exp(const Element& y, const Vector& v) const { return y + y * se3::expm1(v); }
  Spectral spectral(const Vector& v) const { return v; }
  Spectral log(const Element& t) const { return se3::checked_log(t); }  // throws LogDomainError
  Vector log_vector(const Element& t, double& angle) const {
    const Vector v = se3::checked_log(t);
    angle = so3::safe_norm(v.head<3>());
    return v;
  }
  Vector vector(const Spectral& s) const { return s; }
  double angle(const Spectral& s) const { return so3::safe_norm(s.head<3>()); }
  Vector dexp(const Spectral& s, const Vector& u) const { return se3::dexp(s, u); }
  Vector dexpinv(const Spectral& s, const Vector& u) const { return se3::dexpinv(s, u); }
  Operator dexp_matrix(const Spectral& s) const { return se3::dexp_matrix(s); }
  Operator dexpinv_matrix(const Spectral& s) const { return se3::dexpinv_matrix(s); }

  // ||R^T R - I||_F and the last row's distance from (0, 0, 0, 1), together.
  double defect(const Element& y) const {
    const Eigen::Matrix3d r = y.topLeftCorner<3, 3>();
    return std::hypot((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(),
                      (y.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).norm());
  }
  Eigen::Matrix3d rotation(const Element& y) const { return y.topLeftCorner<3, 3>(); }  // the body axes
  Eigen::Vector3d position(const Element& y) const { return y.topRightCorner<3, 1>(); }
  Element project(const Element& y) const {  // the rotation block's polar factor, the translation kept
    Element out = Element::Identity();
    out.topLeftCorner<3, 3>() = orthogonal_polar_factor(Eigen::Matrix3d(y.topLeftCorner<3, 3>()));
    out.topRightCorner<3, 1>() = y.topRightCorner<3, 1>();
    return out;
  }
  double principal_angle(double theta) const { return std::abs(std::remainder(theta, 2.0 * kLogRadius)); }
  Element tangent(const Element& y, const Element& u) const { return y * u; }  // d/dt y exp(tU) at t = 0

  // A request's matrix is the 4 x 4 T itself.
  Element element(const Eigen::MatrixXd& m) const { return Element(m); }
  Eigen::MatrixXd matrix(const Element& y) const { return Eigen::MatrixXd(y); }
  // The paper's qr(rand(3, 3)) turned into a rotation (negated when det = -1) and a translation with entries in
  // [0, 1) drawn after it from the same seed, column by column.
  Element random(std::uint64_t seed) const {
    Eigen::Matrix3d r = start_point(3, seed);
    if (r.determinant() < 0) r = -r;
    std::mt19937_64 rng(seed ^ 0x5e3u);
    Element y = Element::Identity();
    y.topLeftCorner<3, 3>() = r;
    for (int i = 0; i < 3; ++i) y(i, 3) = static_cast<double>(rng() >> 11) * 0x1.0p-53;
    return y;
  }
  std::string not_an_element(const Eigen::MatrixXd& m, const std::string& name) const {
    if (m.row(3) != Eigen::RowVector4d(0, 0, 0, 1))
      return "the last row of " + name + " must be (0, 0, 0, 1) (an element of SE(3) is [[R, p], [0, 1]])";
    const Eigen::Matrix3d r = m.topLeftCorner<3, 3>();
    const double orth = (r.transpose() * r - Eigen::Matrix3d::Identity()).norm();
    if (!(orth <= kMemberTolerance))
      return "the rotation block R of " + name + " must be orthogonal to 1e-10 (||R^T R - I||_F = " +
             std::to_string(orth) + ")";
    if (r.determinant() < 0) return "the rotation block R of " + name + " must have det R = +1 (got -1)";
    return {};
  }
  std::string not_reachable(const Eigen::MatrixXd&, const Eigen::MatrixXd&) const { return {}; }  // connected
};
static_assert(LieGroup<SE3Group>);

// The family SE: SE(3) alone, at n = 3.
using SEFamily = SingleGroupFamily<"SE", SE3Group, 3>;

}  // namespace lienewton
