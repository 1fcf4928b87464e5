#include "render/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace lienewton::render {

Color viridis(double t) {
  // Degree-6 polynomial fit of matplotlib's 256-entry table (Matt Zucker's, within about 3/255 per
  // channel): shorter than the table, and the tests evaluate the same function.
  static constexpr double c[7][3] = {
      {0.2777273272234177, 0.005407344544966578, 0.3340998053353061},
      {0.1050930431085774, 1.404613529898575, 1.384590162594685},
      {-0.3308618287255563, 0.214847559468213, 0.09509516302823659},
      {-4.634230498983486, -5.799100973351585, -19.33244095627987},
      {6.228269936347081, 14.17993336680509, 56.69055260068105},
      {4.776384997670288, -13.74514537774601, -65.35303263337234},
      {-5.435455855934631, 4.645852612178535, 26.3124352495832}};
  t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
  std::uint8_t rgb[3];
  for (int k = 0; k < 3; ++k) {
    double v = c[6][k];
    for (int i = 5; i >= 0; --i) v = v * t + c[i][k];
    rgb[k] = static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
  }
  return {rgb[0], rgb[1], rgb[2], 255};
}

Color status_color(Status status) {
  switch (status) {
    case Status::converged: return kNoValueColor;  // not a failure; callers color it by the metric
    // Warm hues and greys only: viridis runs purple-blue-green-yellow, so none of these reads as an iteration
    // count (tests/render/colormap_test.cpp keeps each at least a CIELAB distance of 25 from every viridis shade).
    case Status::max_iterations: return {215, 48, 39, 255};        // red
    case Status::diverged: return {20, 20, 20, 255};               // black
    case Status::non_finite: return {231, 41, 138, 255};           // magenta
    case Status::left_log_domain: return {253, 141, 60, 255};      // orange
    case Status::singular_differential: return {140, 86, 75, 255}; // brown
    case Status::stagnated: return {200, 170, 130, 255};           // tan
    case Status::off_branch: return {247, 182, 210, 255};          // pink
    case Status::local_minimum: return {128, 0, 38, 255};          // maroon
    case Status::no_descent: return {255, 120, 120, 255};          // coral
    case Status::fold: return {102, 37, 6, 255};                   // dark rust
    case Status::cancelled: return {150, 150, 150, 255};           // mid gray: not computed
    // Integration statuses: never in a solve's map, so they may share greys with the map's own.
    case Status::min_step: return {95, 95, 95, 255};               // dark gray
    case Status::max_steps: return {225, 225, 225, 255};           // light gray
  }
  return kNoValueColor;
}

}  // namespace lienewton::render
