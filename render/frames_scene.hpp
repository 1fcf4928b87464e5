#pragma once
// Rotation frames: each 3x3 rotation's columns (the body axes) drawn as x red, y green, z blue from the origin,
// inside a faint unit sphere with its three coordinate great circles. Earlier frames fade toward the
// background, the last is bold, the start point is dashed. Serves Newton iterates and integration
// trajectories alike: both are a list of frames in order.
#include <Eigen/Dense>
#include <vector>

#include "render/camera.hpp"
#include "render/canvas.hpp"

namespace lienewton::render {

inline constexpr Color kAxisColors[3] = {{215, 35, 35, 255}, {25, 150, 55, 255}, {35, 75, 215, 255}};
inline constexpr float kFinalAxisWidth = 4.0f;

// Throws std::invalid_argument if a matrix has a non-finite entry or one beyond +-10.
void draw_frames(Canvas& canvas, const Camera& camera, const std::vector<Eigen::Matrix3d>& frames,
                 const Eigen::Matrix3d& start);

}  // namespace lienewton::render
