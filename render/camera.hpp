#pragma once
// An orthographic orbit camera looking at the world origin, for the rotation-frames scene.
//
// Convention: with azimuth = 0 and elevation = 0 the world x axis points right on screen, y up and z toward
// the viewer. The camera sits in direction (sin az cos el, sin el, cos az cos el): a positive azimuth swings
// it about the world y axis from +z toward +x, a positive elevation raises it above the x-z plane, looking
// down. The unit sphere is centered in the picture with a radius of kSphereFraction * min(width, height).
#include <Eigen/Dense>

#include "render/canvas.hpp"

namespace lienewton::render {

class Camera {
 public:
  static constexpr double kSphereFraction = 0.36;

  Camera(double azimuth_deg, double elevation_deg, int width, int height);

  Point project(const Eigen::Vector3d& world) const;  // pixel position, top-down
  double depth(const Eigen::Vector3d& world) const;   // larger is nearer the viewer
  double pixels_per_unit() const { return scale_; }
  Point center() const { return {static_cast<float>(cx_), static_cast<float>(cy_)}; }
  // The view's directions in the world: a solid's shading and its hidden faces need them.
  const Eigen::Vector3d& toward_viewer() const { return toward_viewer_; }
  const Eigen::Vector3d& up() const { return up_; }
  const Eigen::Vector3d& right() const { return right_; }

 private:
  Eigen::Vector3d right_, up_, toward_viewer_;
  double cx_, cy_, scale_;
};

}  // namespace lienewton::render
