#include "render/work_precision_scene.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "core/fields.hpp"
#include "render/log_axis.hpp"
#include "render/options.hpp"
#include "render/short_names.hpp"

namespace lienewton::render {
namespace {

bool drawable(const WorkPrecisionPoint& p) {
  return p.status == Status::converged && p.error > 0 && p.cpu_seconds > 0;
}

// Against tolerance: every point of the result is an adaptive run (work_precision.hpp).
bool against_tolerance(const WorkPrecisionResult& result) {
  for (const auto& s : result.series)
    for (const auto& p : s.points)
      if (p.tolerance) return true;
  return false;
}

// "Euler, Newton group, exact  p = 1.01 (2 of 6 failed)"; against tolerance without the order.
std::string legend_label(const WorkPrecisionSeries& s, std::size_t failed, bool tolerance) {
  std::string label = series_name(s.choice.integrator, s.choice.method, s.choice.differential);
  char order[32];
  if (s.fitted_order) {
    std::snprintf(order, sizeof order, "  p = %.2f", *s.fitted_order);
  } else {
    std::snprintf(order, sizeof order, "  p = -");
  }
  if (!tolerance) label += order;
  if (failed > 0) label += " (" + std::to_string(failed) + " of " + std::to_string(s.points.size()) + " failed)";
  return label;
}

}  // namespace

Figure work_precision_scene(const WorkPrecisionResult& result, const std::string& title, int width, int height) {
  validate_size("width", width, false);
  validate_size("height", height, false);
  LineChart chart;
  chart.title = title;
  chart.x = {.label = "global error \u2016y_N \u2212 y(t_end)\u2016", .scale = AxisScale::log, .unit = AxisUnit::plain, .min_step = 0};
  chart.y = {.label = "solver CPU time", .scale = AxisScale::log, .unit = AxisUnit::seconds, .min_step = 0};
  chart.legend = LegendPlace::right;
  const bool tolerance = against_tolerance(result);
  chart.legend_title = tolerance ? "adaptive steps; markers labelled with the tolerance (rtol = atol)"
                                 : "markers labelled with h; p: fitted order";
  bool any = false;
  for (std::size_t i = 0; i < result.series.size(); ++i) {
    const WorkPrecisionSeries& s = result.series[i];
    std::vector<const WorkPrecisionPoint*> points;
    for (const auto& p : s.points) {
      if (drawable(p)) points.push_back(&p);
    }
    // Along decreasing h, or decreasing tolerance.
    std::stable_sort(points.begin(), points.end(), [](const auto* a, const auto* b) {
      return a->tolerance && b->tolerance ? *a->tolerance > *b->tolerance : a->h > b->h;
    });
    LineSeries line;
    line.label = legend_label(s, s.points.size() - points.size(), tolerance);
    line.style = series_style(i);
    for (const auto* p : points) {
      line.x.push_back(p->error);
      line.y.push_back(p->cpu_seconds);
      line.point_labels.push_back(p->tolerance ? fields::format_bound(*p->tolerance) : power_of_two_label(p->h));
      line.muted.push_back(!tolerance && !p->in_fit);
    }
    any = any || !points.empty();
    chart.series.push_back(std::move(line));
  }
  if (!any) throw std::invalid_argument("no converged run with a positive error and time to draw");
  return {width, height, {{std::move(chart), Box{0, 0, static_cast<float>(width), static_cast<float>(height)}}}};
}

}  // namespace lienewton::render
