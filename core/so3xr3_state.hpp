#pragma once
// The state (R, w) of a rigid body on SO(3) x R^3 (SO3xR3Group) as its 7 x 7 block-diagonal matrix
// y = [[R, 0], [0, [[I, w], [0, 1]]]], and the algebra element [[hat(w), 0], [0, [[0, a], [0, 0]]]] of a field
// R' = R hat(w), w' = a: the layout the heavy top and the stiff body share.
#include <Eigen/Core>

#include "groups/so3.hpp"

namespace lienewton::so3xr3 {

template <class M>
Eigen::Matrix3d rotation(const M& y) {
  return y.template topLeftCorner<3, 3>();
}
template <class M>
Eigen::Vector3d omega(const M& y) {
  return y.template block<3, 1>(3, 6);
}
// The state of (R, w).
inline Eigen::MatrixXd state(const Eigen::Matrix3d& r, const Eigen::Vector3d& w) {
  Eigen::MatrixXd y = Eigen::MatrixXd::Identity(7, 7);
  y.topLeftCorner<3, 3>() = r;
  y.block<3, 1>(3, 6) = w;
  return y;
}
// The algebra element of (w, a): R' = R hat(w), w' = a.
template <class M>
M embed(const Eigen::Vector3d& w, const Eigen::Vector3d& a) {
  M out = M::Zero(7, 7);
  out.template topLeftCorner<3, 3>() = so3::hat(w);
  out.template block<3, 1>(3, 6) = a;
  return out;
}

}  // namespace lienewton::so3xr3
