#include "render/options.hpp"

#include <stdexcept>
#include <string>

namespace lienewton::render {

Words words(HeatmapMetric metric) {
  switch (metric) {
    case HeatmapMetric::iterations: return {"iterations", "Iterations", "iterations", "iterations to converge", {}};
    case HeatmapMetric::rate:
      return {"rate", "Convergence rate r", "rate", "observed convergence rate (needs 3 residuals)", {}};
    case HeatmapMetric::residual: return {"residual", "Final residual", "residual", "log10 of the final ‖f(y)‖", {}};
  }
  return {};
}

std::optional<HeatmapMetric> heatmap_metric_from_string(std::string_view name) {
  return from_api_name(kAllHeatmapMetrics, name);
}

std::string_view to_string(HeatmapMetric metric) { return words(metric).api; }

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
