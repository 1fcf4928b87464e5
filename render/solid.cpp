#include "render/solid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lienewton::render {

Mesh ellipsoid_mesh(const Eigen::Vector3d& semi_axes, int segments) {
  // Rings of latitude from the south pole to the north pole, each of `segments` points; the poles are single
  // vertices.
  const int rings = std::max(2, segments / 2);
  Mesh mesh;
  mesh.vertices.push_back({0, 0, -semi_axes.z()});
  for (int r = 1; r < rings; ++r) {
    const double theta = std::numbers::pi * r / rings - std::numbers::pi / 2;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      mesh.vertices.push_back(semi_axes.cwiseProduct(
          Eigen::Vector3d(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), std::sin(theta))));
    }
  }
  mesh.vertices.push_back({0, 0, semi_axes.z()});
  const int north = static_cast<int>(mesh.vertices.size()) - 1;
  const auto at = [&](int ring, int s) { return 1 + (ring - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) {
    mesh.faces.push_back({0, at(1, s + 1), at(1, s)});
    for (int r = 1; r + 1 < rings; ++r) {
      mesh.faces.push_back({at(r, s), at(r, s + 1), at(r + 1, s + 1)});
      mesh.faces.push_back({at(r, s), at(r + 1, s + 1), at(r + 1, s)});
    }
    mesh.faces.push_back({north, at(rings - 1, s), at(rings - 1, s + 1)});
  }
  return mesh;
}

void draw_solids(Canvas& canvas, const Camera& camera, const std::vector<PlacedSolid>& solids) {
  struct Face {
    double depth;
    Point a, b, c;
    Color color;
  };
  const Eigen::Vector3d light = (0.75 * camera.toward_viewer() + 0.5 * camera.up() - 0.3 * camera.right()).normalized();
  std::vector<Face> faces;
  for (const PlacedSolid& solid : solids) {
    std::vector<Eigen::Vector3d> world;
    world.reserve(solid.mesh->vertices.size());
    for (const Eigen::Vector3d& v : solid.mesh->vertices) world.push_back(solid.rotation * v + solid.position);
    for (const auto& [i, j, k] : solid.mesh->faces) {
      const Eigen::Vector3d normal = (world[j] - world[i]).cross(world[k] - world[i]);
      const double length = normal.norm();
      if (!(length > 0) || normal.dot(camera.toward_viewer()) <= 0) continue;  // degenerate or facing away
      const double lit = 0.35 + 0.65 * std::max(0.0, normal.dot(light) / length);
      const Color shaded{static_cast<std::uint8_t>(std::lround(solid.color.r * lit)),
                         static_cast<std::uint8_t>(std::lround(solid.color.g * lit)),
                         static_cast<std::uint8_t>(std::lround(solid.color.b * lit)), 255};
      faces.push_back({camera.depth(world[i] + world[j] + world[k]), camera.project(world[i]),
                       camera.project(world[j]), camera.project(world[k]), shaded});
    }
  }
  std::stable_sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.depth < y.depth; });
  for (const Face& f : faces) canvas.triangle(f.a, f.b, f.c, f.color);
}

Eigen::Vector3d inertia_ellipsoid(const Eigen::Vector3d& inertia, double mass, double min_fraction) {
  const double sum = inertia.sum();
  Eigen::Vector3d squared;
  for (int i = 0; i < 3; ++i) squared[i] = std::max(0.0, 5.0 * (sum - 2 * inertia[i]) / (2 * mass));
  Eigen::Vector3d axes = squared.cwiseSqrt();
  const double largest = axes.maxCoeff();
  return axes.cwiseMax(min_fraction * largest);
}

}  // namespace lienewton::render
