#include "render/invariants_scene.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/vocabulary.hpp"
#include "render/options.hpp"

namespace lienewton::render {

Figure invariants_scene(const IntegrateResult& result, const std::string& title, int width, int height) {
  validate_size("width", width, false);
  validate_size("height", height, false);
  LineChart chart;
  chart.title = title;
  // Against the step k (t = k h): the linear axis's margin of half a unit suits counts.
  chart.x = {.label = "step k (t = k h)", .scale = AxisScale::linear, .unit = AxisUnit::plain, .min_step = 1};
  chart.y = {.label = "|I(t) \u2212 I(0)| / scale", .scale = AxisScale::log, .unit = AxisUnit::plain, .min_step = 0};
  chart.legend = LegendPlace::inside;
  bool any = false;
  std::size_t index = 0;
  for (Invariant i : kAllInvariants) {
    const std::optional<double> initial = result.initial_invariants[i];
    if (!initial) continue;
    const double scale = result.invariant_scales[i].value_or(1.0);  // as InvariantDrift divides
    LineSeries line;
    char drift[48];
    std::snprintf(drift, sizeof drift, "  drift %.2e", result.invariant_drifts[i].value_or(0.0));
    line.label = std::string(words(i).short_label) + drift;
    line.style = series_style(index++);
    for (const StepRecord& s : result.steps) {
      const double d = s.invariants[i] ? std::abs(*s.invariants[i] - *initial) / scale : 0.0;
      if (!(d > 0.0) || !std::isfinite(d)) continue;
      line.x.push_back(s.step);
      line.y.push_back(d);
    }
    any = any || !line.x.empty();
    chart.series.push_back(std::move(line));
  }
  if (!any) throw std::invalid_argument("the run reports no invariant that changed");
  return {width, height, {{std::move(chart), Box{0, 0, static_cast<float>(width), static_cast<float>(height)}}}};
}

}  // namespace lienewton::render
