#include "render/residuals_scene.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "render/options.hpp"
#include "render/short_names.hpp"

namespace lienewton::render {
namespace {

constexpr float kTimePanelShare = 0.42f;  // the time panel has no legend column, so it needs less width

// Three significant digits: "958 µs", not "957.998 µs".
std::string time_text(double seconds) {
  char rounded[32];
  std::snprintf(rounded, sizeof rounded, "%.3g", seconds);
  return tick_label(std::strtod(rounded, nullptr), AxisUnit::seconds);
}

std::string legend_label(const ResidualRun& run) {
  std::string label = series_name(run.method, run.differential) + ": ";
  const int iterations = static_cast<int>(run.residual.size()) - 1;
  if (run.status == Status::converged) {
    label += std::to_string(iterations) + " it, " + time_text(run.cpu_seconds.back());
  } else {
    label += std::string(to_string(run.status)) + " after " + std::to_string(iterations) + " it";
  }
  return label;
}

}  // namespace

Figure residuals_scene(const std::vector<ResidualRun>& runs, const std::string& title, int width, int height) {
  validate_size("width", width, false);
  validate_size("height", height, false);
  const ChartAxis residual_axis{.label = "\u2016f(y\u2099)\u2016", .scale = AxisScale::log, .unit = AxisUnit::plain, .min_step = 0};
  LineChart by_time{.title = title, .x = {.label = "solver CPU time", .scale = AxisScale::log, .unit = AxisUnit::seconds, .min_step = 0},
                    .y = residual_axis, .series = {}, .legend_title = {}, .legend = LegendPlace::none};
  LineChart by_iteration{.title = "the same against the iteration",
                         .x = {.label = "iteration n", .scale = AxisScale::linear, .unit = AxisUnit::plain, .min_step = 1},
                         .y = residual_axis, .series = {}, .legend_title = "it: iterations; time: solver CPU time to the last",
                         .legend = LegendPlace::right};
  bool any = false;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const ResidualRun& run = runs[i];
    if (run.cpu_seconds.size() != run.residual.size() || run.residual.empty()) {
      throw std::invalid_argument("a residual run needs one CPU time per residual, and at least one");
    }
    LineSeries timed{.label = {}, .style = series_style(i), .x = {}, .y = {}, .point_labels = {}, .muted = {}};
    LineSeries counted{.label = legend_label(run), .style = series_style(i), .x = {}, .y = {}, .point_labels = {},
                       .muted = {}};
    for (std::size_t n = 0; n < run.residual.size(); ++n) {
      if (!(run.residual[n] > 0) || !std::isfinite(run.residual[n])) continue;
      counted.x.push_back(static_cast<double>(n));
      counted.y.push_back(run.residual[n]);
      if (!(run.cpu_seconds[n] > 0) || !std::isfinite(run.cpu_seconds[n])) continue;
      timed.x.push_back(run.cpu_seconds[n]);
      timed.y.push_back(run.residual[n]);
    }
    any = any || !timed.x.empty();
    by_time.series.push_back(std::move(timed));
    by_iteration.series.push_back(std::move(counted));
  }
  if (!any) throw std::invalid_argument("no iterate with a positive residual and time to draw");
  const float w = static_cast<float>(width), h = static_cast<float>(height), split = kTimePanelShare * w;
  return {width, height, {{std::move(by_time), Box{0, 0, split, h}}, {std::move(by_iteration), Box{split, 0, w, h}}}};
}

}  // namespace lienewton::render
