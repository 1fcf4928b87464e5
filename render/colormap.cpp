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
    case Status::max_iterations: return {215, 48, 39, 255};        // red
    case Status::diverged: return {40, 40, 40, 255};               // near black
    case Status::non_finite: return {231, 41, 138, 255};           // magenta
    case Status::left_log_domain: return {253, 141, 60, 255};      // orange
    case Status::singular_differential: return {140, 86, 75, 255}; // brown
    case Status::stagnated: return {158, 218, 229, 255};           // pale cyan
    case Status::off_branch: return {247, 182, 210, 255};          // pink
    case Status::local_minimum: return {188, 189, 34, 255};        // olive
    case Status::no_descent: return {107, 110, 207, 255};          // slate blue
    case Status::fold: return {255, 217, 47, 255};                 // yellow
    case Status::cancelled: return {120, 120, 120, 255};           // mid gray: not computed
    case Status::min_step: return {31, 120, 180, 255};             // blue
    case Status::max_steps: return {178, 223, 138, 255};           // light green
  }
  return kNoValueColor;
}

}  // namespace lienewton::render
