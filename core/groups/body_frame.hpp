#pragma once
// One body's frame as pictures draw it: its axes (the columns of its rotation) placed at its position.
#include <Eigen/Dense>

namespace lienewton {

struct BodyFrame {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d position;
};

}  // namespace lienewton
