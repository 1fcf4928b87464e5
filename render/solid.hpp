#pragma once
// Solid bodies for the motion scenes: closed triangle meshes placed in the world, drawn flat shaded back to front
// (the painter's algorithm: every visible face of every solid sorted by depth). No depth buffer, no textures: a
// scene of a few convex bodies needs neither, and the faces stay shapes a vector copy (SVG) can hold.
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "render/camera.hpp"
#include "render/canvas.hpp"

namespace lienewton::render {

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> faces;  // counter-clockwise seen from outside
};

// An ellipsoid with the given semi-axes along its own x, y, z: the shape of a body whose inertia it has.
Mesh ellipsoid_mesh(const Eigen::Vector3d& semi_axes, int segments = 24);

// A mesh at a pose: world point = rotation * (vertex) + position, in the scene's (unit-ball) coordinates.
struct PlacedSolid {
  const Mesh* mesh = nullptr;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Color color{};
};

// Every face that looks toward the camera, farthest first, shaded by a light over the viewer's left shoulder.
void draw_solids(Canvas& canvas, const Camera& camera, const std::vector<PlacedSolid>& solids);

// The semi-axes of the uniform solid ellipsoid with principal moments `inertia` and mass `mass`:
// a^2 = 5 (I_2 + I_3 - I_1) / (2 m) and its turns. A flat body (a disc, I_1 + I_2 = I_3) keeps a thickness of
// `min_fraction` of its largest semi-axis so that it can be seen edge on.
Eigen::Vector3d inertia_ellipsoid(const Eigen::Vector3d& inertia, double mass, double min_fraction = 0.08);

}  // namespace lienewton::render
