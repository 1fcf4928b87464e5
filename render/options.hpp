#pragma once
// What a caller may choose about a picture. Sizes are checked by validate_size before any GL work.
#include <optional>
#include <string_view>

#include "core/vocabulary.hpp"

namespace lienewton::render {

inline constexpr int kMinImageSize = 64;
inline constexpr int kMaxImageSize = 4096;

// A picture as PNG pixels, or as an SVG document (svg.hpp: its text and lines stay vectors).
enum class ImageFormat { png, svg };

struct FramesOptions {
  int width = 512;
  int height = 512;
  double azimuth_deg = 35;    // see camera.hpp for the convention
  double elevation_deg = 20;
};

enum class HeatmapMetric { iterations, rate, residual };
inline constexpr HeatmapMetric kAllHeatmapMetrics[] = {HeatmapMetric::iterations, HeatmapMetric::rate,
                                                       HeatmapMetric::residual};
// The metric's row of the vocabulary (core/vocabulary.hpp): its API name and its words.
Words words(HeatmapMetric metric);
std::optional<HeatmapMetric> heatmap_metric_from_string(std::string_view name);  // "iterations"|"rate"|"residual"
std::string_view to_string(HeatmapMetric metric);

struct HeatmapOptions {
  int width = 0;   // 0 = automatic from the grid
  int height = 0;  // 0 = automatic from the grid
  HeatmapMetric metric = HeatmapMetric::iterations;
};

// Throws std::invalid_argument naming the field ("width"/"height") unless value is in [64, 4096]
// (or 0 where automatic is allowed).
void validate_size(std::string_view field, int value, bool zero_means_automatic);

}  // namespace lienewton::render
