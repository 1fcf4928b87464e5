#pragma once
#include <Eigen/Core>

namespace lienewton {

// Parameters of the free rigid body y' = y hat(I^-1 y^T m) on SO(3).
struct RigidBodyParams {
  Eigen::Vector3d inertia{1.0, 2.0, 3.0};   // principal moments, diagonal of I
  Eigen::Vector3d momentum{0.6, 0.8, 0.5};  // constant spatial angular momentum m
};

}  // namespace lienewton
