#pragma once
// Colors that carry meaning in the heatmap: viridis for a metric value, one flat color per failure class.
#include <string_view>

#include "core/status.hpp"
#include "render/color.hpp"

namespace lienewton::render {

// Viridis (matplotlib's perceptually uniform map) at t in [0, 1], clamped; NaN gives t = 0.
Color viridis(double t);

// A flat color per Status other than converged, chosen to lie outside viridis' purple-blue-green-yellow
// (reds, oranges, browns, pinks, greys), so that no failure reads as a converged cell's metric.
Color status_color(Status status);

// Converged cells whose metric has no value (a rate needs three residuals).
inline constexpr Color kNoValueColor{200, 200, 200, 255};
// The dot on a cell whose rate lies outside the rate colour range (heatmap_scene.hpp).
inline constexpr Color kOutlierDotColor{30, 30, 30, 255};

}  // namespace lienewton::render
