#pragma once
#include <Eigen/Core>

namespace lienewton {

// Parameters of the heavy top on SO(3) x R^3: R' = R hat(w), J w' = (J w) x w + m chi x (R^T gamma), from
// (R(0), w(0)) = (rotation, omega). The defaults are the heavy-top benchmark of Lie group integrators for
// multibody systems (Bruls, Cardona & Arnold 2012), which gives the inertia about the centre of mass; the equation
// turns about the pivot and takes J = pivot_inertia(params).
struct HeavyTopParams {
  double mass = 15.0;                                         // m
  Eigen::Vector3d inertia{0.234375, 0.46875, 0.234375};       // principal moments about the centre of mass (body axes)
  Eigen::Vector3d center{0.0, 1.0, 0.0};                      // chi: the centre of mass in the body frame
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};                   // gamma: gravity in the spatial frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();     // R(0)
  Eigen::Vector3d omega{0.0, 150.0, -4.61538};                // w(0): body angular velocity

  // The largest size a parameter may have (each entry of the vectors, the mass): beyond it the field's values
  // overflow long before any step is taken.
  static constexpr double kBound = 1e6;
};

// The inertia about the pivot (the body origin, which stays fixed): the parallel-axis theorem
// J = J_com + m (|chi|^2 I - chi chi^T). The one place the shift is made.
inline Eigen::Matrix3d pivot_inertia(const HeavyTopParams& p) {
  return Eigen::Matrix3d(p.inertia.asDiagonal()) +
         p.mass * (p.center.squaredNorm() * Eigen::Matrix3d::Identity() - p.center * p.center.transpose());
}

}  // namespace lienewton
