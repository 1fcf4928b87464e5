#pragma once
// What a problem's motion looks like: its bodies' solids (proportions from their inertia), the point whose path
// tells the motion apart, and the world's marks. Model no more than the scene needs:
//   heavy-top   a disc on a rod from the fixed pivot (the benchmark's top), the tip of its symmetry axis traced,
//               gravity and the vertical through the pivot;
//   rigid-body  the body angular momentum M(t) = y(t)^T m on its sphere |M| = |m| with the energy levels
//               M . I^-1 M / 2 = E that cut it (Hairer, Lubich & Wanner, Geometric Numerical Integration,
//               Fig. IV.1.1): the motion is the level it started on;
//   stiff-body  its inertia ellipsoid, the tip of its longest axis traced;
//   chain       its links as rods hanging from the pivot, the free end of the last traced, gravity;
//   any other group with bodies (a user's g): each body an ellipsoid that shows its turning, the first body's
//               e1 tip traced.
#include <Eigen/Dense>
#include <vector>

#include "core/group_registry.hpp"
#include "core/problem_spec.hpp"
#include "render/motion_scene.hpp"

namespace lienewton::render {

// states: y at times (the same count). The group must have body frames (GroupFamily::body_frames).
Motion motion_of(const ProblemSpec& problem, const std::vector<Eigen::MatrixXd>& states, const std::vector<double>& times);

// Points where the sphere |M| = radius meets the ellipsoid M . I^-1 M = 2 E, for `levels` energies spread between
// the least and the most the sphere holds, and the given E (the motion's own): a marching-squares walk over a
// longitude-latitude grid of the sphere, as line segments (pairs of points).
std::vector<std::vector<Eigen::Vector3d>> energy_curves(const Eigen::Vector3d& inertia, double radius, int levels,
                                                        double own_energy);

}  // namespace lienewton::render
