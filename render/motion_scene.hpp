#pragma once
// The motion of bodies as a scene: each body a flat-shaded solid at its pose, a chosen point's path traced and
// coloured by time (viridis, early dark to late yellow), the world's axes with z up, gravity and the vertical
// through the pivot, and, for a free rigid body, its momentum sphere with the energy curves on it. One Motion holds
// every state; a picture shows the bodies at one state and the paths up to it, so that an animation is the same
// scene drawn at each state in turn.
#include <Eigen/Dense>
#include <optional>
#include <string>
#include <vector>

#include "render/camera.hpp"
#include "render/canvas.hpp"
#include "render/solid.hpp"

namespace lienewton::render {

struct Motion {
  struct Body {
    int mesh = 0;  // index into meshes
    Color color{};
    std::vector<Eigen::Matrix3d> rotation;  // per state
    std::vector<Eigen::Vector3d> position;  // per state, in the world (metres, or the field's own units)
  };
  std::vector<double> times;  // per state
  std::string time_name = "t";  // what the times are: t, or n for a solve's iterates
  std::vector<Mesh> meshes;   // in the bodies' own frames, world units
  std::vector<Body> bodies;
  std::vector<Eigen::Vector3d> trace;  // the traced point per state (empty: no path)
  std::string trace_label;             // what the path is, for the legend
  bool trace_arrow = false;            // an arrow from the origin to the path's head (a vector's tip, e.g. M(t))
  bool pivot = false;                  // a fixed point at the origin
  std::optional<Eigen::Vector3d> gravity{};  // its direction: an arrow, and the vertical through the origin
  std::optional<double> sphere{};            // a sphere about the origin of this radius ...
  std::vector<std::vector<Eigen::Vector3d>> sphere_curves;  // ... and curves on it (closed or not)
  std::string sphere_label;
};

// Throws std::invalid_argument when the states disagree in number, a value is non-finite or beyond 1e6, or a
// mesh index is out of range.
void check_motion(const Motion& motion);

// The scene at state `at` (0 <= at < times.size()).
void draw_motion(Canvas& canvas, const Camera& camera, const Motion& motion, std::size_t at);

}  // namespace lienewton::render
