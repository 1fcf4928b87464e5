#pragma once
// Rotation frames: each 3x3 rotation's columns (the body axes) drawn as x red, y green, z blue from the origin,
// inside a faint unit sphere with its three coordinate great circles. Earlier frames fade toward the
// background, the last is bold, the start point is dashed. Serves Newton iterates and integration
// trajectories alike: both are a list of frames in order.
#include <Eigen/Dense>
#include <vector>

#include "core/groups/body_frame.hpp"
#include "render/camera.hpp"
#include "render/canvas.hpp"

namespace lienewton::render {

inline constexpr Color kAxisColors[3] = {{215, 35, 35, 255}, {25, 150, 55, 255}, {35, 75, 215, 255}};
inline constexpr float kFinalAxisWidth = 4.0f;

// Throws std::invalid_argument if a matrix has a non-finite entry or one beyond +-10.
void draw_frames(Canvas& canvas, const Camera& camera, const std::vector<Eigen::Matrix3d>& frames,
                 const Eigen::Matrix3d& start);

// A system of bodies: each state is every body's frame, drawn as its axes at its position, the bodies joined in
// order by a line from the origin (where the first hangs), with the world's z up (gravity's usual down is -z). The scene is fitted to the unit sphere's place: every
// position of every state, and the origin, inside it. The last state is bold with its axes, earlier states are
// their chains fading toward the background, the start is dashed. Throws std::invalid_argument if a rotation has
// a non-finite entry or one beyond +-10, a position is non-finite or beyond +-1e6, or the states differ in size.
void draw_bodies(Canvas& canvas, const Camera& camera, const std::vector<std::vector<BodyFrame>>& states,
                 const std::vector<BodyFrame>& start);

}  // namespace lienewton::render
