#pragma once
// What SO(N) owns beyond the group law, shared by SO3Group and SONGroup (derived as RotationFacts<Group, Element>):
// the paper's z lies in O(N) (qr(rand) has det -1 half the time), so a request's matrix is accepted when it is
// orthogonal to 1e-10, whatever its determinant, and a start y0 must lie in z's component, where z^-1 y0 is a
// rotation that log can reach. Angles are rotation angles, log's boundary is pi, and the angle of exp(v) is v's
// angle wrapped into [0, pi].
#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <string>

#include "core/start_point.hpp"

namespace lienewton {

template <class Group, class Element>
struct RotationFacts {
  static constexpr double kLogRadius = std::numbers::pi;  // log is defined for rotation angles below pi
  static constexpr const char* kAngleName = "rotation angle";
  static constexpr const char* kLogBoundaryName = "pi";
  static constexpr const char* kAlgebraDimension = "n(n-1)/2";
  // ||m^T m - I||_F above which a request's z or y0 is refused.
  static constexpr double kMemberTolerance = 1e-10;

  Element tangent(const Element& y, const Element& u) const { return y * u; }  // d/dt y exp(tU) at t = 0
  Element element(const Eigen::MatrixXd& m) const { return Element(m); }
  Eigen::MatrixXd matrix(const Element& y) const { return Eigen::MatrixXd(y); }
  // The paper's qr(rand(N, N)), bit for bit (start_point.hpp).
  Element random(std::uint64_t seed) const { return Element(start_point(self().n(), seed)); }
  std::string not_an_element(const Eigen::MatrixXd& m, const std::string& name) const {
    const double orth = (m.transpose() * m - Eigen::MatrixXd::Identity(m.rows(), m.cols())).norm();
    if (orth <= kMemberTolerance) return {};
    return name + " must be orthogonal to 1e-10 (||" + name + "^T " + name + " - I||_F = " + std::to_string(orth) + ")";
  }
  std::string not_reachable(const Eigen::MatrixXd& y0, const Eigen::MatrixXd& z) const {
    if (!(y0.determinant() * z.determinant() < 0)) return {};
    return "y0 must lie in the component of z (det y0 = det z): z^-1 y0 must be a rotation";
  }
  double principal_angle(double theta) const { return std::abs(std::remainder(theta, 2.0 * kLogRadius)); }

 private:
  const Group& self() const { return static_cast<const Group&>(*this); }
};

}  // namespace lienewton
