#pragma once
#include <Eigen/Core>
#include <optional>

#include "groups/so3.hpp"

namespace lienewton {

// Parameters of the stiff rigid body on SO(3) x R^3: a body pulled toward the identity attitude by a torsional
// spring k and damper c under a smooth forcing torque,
//   R' = R hat(w),  J w' = (J w) x w - k vee(skew R) - c w + f(t),  skew R = (R - R^T)/2,
//   f(t) = (f1 sin 2t, f2 cos t, f3),
// from (R(0), w(0)) = (rotation, omega). At k = c = 1e4 the damper's eigenvalues are about -k/J_i against the slow
// part's ~1: the stiff benchmark of the implicit integrators.
struct StiffBodyParams {
  double k = 1e4;                                                  // spring stiffness
  std::optional<double> c{};                                       // damping; absent: c = k
  Eigen::Vector3d J{1.0, 2.0, 3.0};                                // principal moments (body axes)
  Eigen::Vector3d f{0.5, 0.3, 0.2};                                // amplitudes of (sin 2t, cos t, 1)
  Eigen::Matrix3d rotation = so3::exp(Eigen::Vector3d(0.5, -0.3, 0.8));  // R(0)
  Eigen::Vector3d omega{1.0, -2.0, 0.5};                           // w(0): body angular velocity

  // The largest size a parameter may have (k, c and each entry of the vectors): beyond it the field's values
  // overflow long before any step is taken. Above HeavyTopParams::kBound: k = 1e6 is a case the tests pin.
  static constexpr double kBound = 1e8;
};

// The damping the equation takes: c, or k when c is absent.
inline double damping(const StiffBodyParams& p) { return p.c.value_or(p.k); }

}  // namespace lienewton
