#include "render/options.hpp"

#include <stdexcept>
#include <string>

namespace lienewton::render {

std::optional<HeatmapMetric> heatmap_metric_from_string(std::string_view name) {
  if (name == "iterations") return HeatmapMetric::iterations;
  if (name == "rate") return HeatmapMetric::rate;
  if (name == "residual") return HeatmapMetric::residual;
  return std::nullopt;
}

std::string_view to_string(HeatmapMetric metric) {
  switch (metric) {
    case HeatmapMetric::iterations: return "iterations";
    case HeatmapMetric::rate: return "rate";
    case HeatmapMetric::residual: return "residual";
  }
  return "unknown";
}

void validate_size(std::string_view field, int value, bool zero_means_automatic) {
  if (zero_means_automatic && value == 0) return;
  if (value < kMinImageSize || value > kMaxImageSize) {
    throw std::invalid_argument(std::string(field) + " must be in [" + std::to_string(kMinImageSize) + ", " +
                                std::to_string(kMaxImageSize) + "]" +
                                (zero_means_automatic ? " or 0 (automatic)" : "") + ", got " +
                                std::to_string(value));
  }
}

}  // namespace lienewton::render
