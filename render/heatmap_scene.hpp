#pragma once
// The convergence heatmap: converged cells colored by a metric through viridis, failed cells in their
// status' flat color, with panel titles, axis ticks and labels, a colorbar and a legend of failure classes.
#include <optional>

#include "render/heatmap_layout.hpp"

namespace lienewton::render {

// The metric of a converged cell: iterations, rate, or log10 of the residual (floored at 1e-18 so an exact
// zero stays drawable). Empty for failed cells and for a converged cell without a (finite) rate.
std::optional<double> metric_value(const SweepCell& cell, HeatmapMetric metric);

// Rates are coloured on this fixed range, where linear (1) and quadratic (2) convergence sit apart whatever
// else the grid holds; a rate outside it gets the end colour and a dot (a first iteration far from the
// asymptotic regime can give r = 267).
inline constexpr double kRateColorLo = 0, kRateColorHi = 3;
bool rate_outlier(const SweepCell& cell);

// The colorbar's range: the smallest and largest metric value in the grid (widened by 1 when they are equal);
// for rates [kRateColorLo, kRateColorHi].
struct MetricScale {
  double lo = 0, hi = 1;
  double position(double value) const { return (value - lo) / (hi - lo); }
  Color color(double value) const;
};
MetricScale metric_scale(const HeatmapGrid& grid, HeatmapMetric metric);

// The color a cell is drawn in (missing cells are left as background).
Color cell_color(const SweepCell& cell, HeatmapMetric metric, const MetricScale& scale);

void draw_heatmap(Canvas& canvas, const HeatmapGrid& grid, const HeatmapLayout& layout, HeatmapMetric metric);

}  // namespace lienewton::render
