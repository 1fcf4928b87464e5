#include "render/camera.hpp"

#include <algorithm>
#include <numbers>

namespace lienewton::render {

Camera::Camera(double azimuth_deg, double elevation_deg, int width, int height) {
  const double az = azimuth_deg * std::numbers::pi / 180.0;
  const double el = elevation_deg * std::numbers::pi / 180.0;
  toward_viewer_ = {std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)};
  right_ = {std::cos(az), 0.0, -std::sin(az)};
  up_ = toward_viewer_.cross(right_);
  cx_ = 0.5 * width;
  cy_ = 0.5 * height;
  scale_ = kSphereFraction * std::min(width, height);
}

Point Camera::project(const Eigen::Vector3d& world) const {
  return {static_cast<float>(cx_ + scale_ * right_.dot(world)), static_cast<float>(cy_ - scale_ * up_.dot(world))};
}

double Camera::depth(const Eigen::Vector3d& world) const { return toward_viewer_.dot(world); }

}  // namespace lienewton::render
