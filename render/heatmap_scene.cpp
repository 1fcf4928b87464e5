#include "render/heatmap_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "render/colormap.hpp"
#include "render/short_names.hpp"

namespace lienewton::render {
namespace {

constexpr Color kAxisColor{90, 90, 90, 255};
constexpr float kTick = 4;

// Tick values at 1, 2 or 5 times a power of ten, at most about max_ticks of them, inside [lo, hi].
std::vector<double> nice_ticks(double lo, double hi, int max_ticks, bool integers) {
  const double raw = (hi - lo) / std::max(1, max_ticks - 1);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  double step = power;
  for (double factor : {1.0, 2.0, 5.0, 10.0}) {
    step = factor * power;
    if (step >= raw) break;
  }
  if (integers) step = std::max(step, 1.0);
  std::vector<double> ticks;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) {
    ticks.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
  }
  return ticks;
}

std::string tick_label(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return with_minus_sign(text);
}

void draw_colorbar(Canvas& canvas, const HeatmapLayout& l, HeatmapMetric metric, const MetricScale& scale) {
  const int x = l.colorbar_x, top = l.top, height = l.panel_height();
  // One rect per pixel row: the bar is a sampled viridis, exactly as the cells are.
  for (int row = 0; row < height; ++row) {
    const double t = height > 1 ? 1.0 - static_cast<double>(row) / (height - 1) : 0.5;
    canvas.rect(float(x), float(top + row), float(x + l.colorbar_width), float(top + row + 1), viridis(t));
  }
  canvas.text(metric_label(metric), float(x), float(l.top - 12), TextSize::small, kTextColor);
  const int max_ticks = std::clamp(height / 28, 2, 8);
  for (double v : nice_ticks(scale.lo, scale.hi, max_ticks, metric == HeatmapMetric::iterations)) {
    const float y = float(top + (1.0 - scale.position(v)) * (height - 1) + 0.5);
    const float right = float(x + l.colorbar_width);
    canvas.rect(right, y - 0.5f, right + kTick, y + 0.5f, kAxisColor);
    canvas.text(tick_label(v), right + kTick + 3, y, TextSize::small, kTextColor);
  }
}

void draw_panel_axes(Canvas& canvas, const HeatmapGrid& grid, const HeatmapLayout& l, int panel) {
  const float x0 = float(l.panel_x(panel)), y0 = float(l.top);
  const float x1 = x0 + l.panel_width(), y1 = y0 + l.panel_height();
  canvas.text(std::string(short_name(grid.methods[panel])), 0.5f * (x0 + x1), y0 - 12, TextSize::large, kTextColor, Align::center);
  // Frame just outside the cells so that it never covers one.
  canvas.rect(x0 - 1, y0 - 1, x1 + 1, y0, kAxisColor);
  canvas.rect(x0 - 1, y1, x1 + 1, y1 + 1, kAxisColor);
  canvas.rect(x0 - 1, y0, x0, y1, kAxisColor);
  canvas.rect(x1, y0, x1 + 1, y1, kAxisColor);

  const float small = Font::instance().pixel_height(TextSize::small);
  for (int j = 0; j < l.columns; j += l.h_label_step) {
    const float x = l.cell_center(panel, 0, j).x;
    canvas.rect(x - 0.5f, y1 + 1, x + 0.5f, y1 + 1 + kTick, kAxisColor);
    canvas.text(log2_label(grid.h[j]), x, y1 + kTick + 4 + 0.5f * small, TextSize::small, kTextColor,
                Align::center);
  }
  canvas.text("log\u2082 h", 0.5f * (x0 + x1), y1 + kTick + 10 + 1.5f * small, TextSize::small, kTextColor,
              Align::center);
  if (panel != 0) return;  // the panels share the N axis
  for (int i = 0; i < l.rows; i += l.n_label_step) {
    const float y = l.cell_center(0, i, 0).y;
    canvas.rect(x0 - 1 - kTick, y - 0.5f, x0 - 1, y + 0.5f, kAxisColor);
    canvas.text(std::to_string(grid.n[i]), x0 - kTick - 4, y, TextSize::small, kTextColor, Align::right);
  }
  canvas.text("N", 10, 0.5f * (y0 + y1), TextSize::small, kTextColor);
}

void draw_legend(Canvas& canvas, const HeatmapLayout& l) {
  constexpr float kSwatch = 12;
  for (std::size_t i = 0; i < l.legend.size(); ++i) {
    const int column = static_cast<int>(i) % l.legend_columns;
    const int row = static_cast<int>(i) / l.legend_columns;
    const float x = float(l.legend_x + column * l.legend_column_width);
    const float y = float(l.legend_y + row * l.legend_row_height);
    canvas.rect(x, y, x + kSwatch, y + kSwatch, kAxisColor);  // outline keeps pale swatches visible
    canvas.rect(x + 1, y + 1, x + kSwatch - 1, y + kSwatch - 1, l.legend[i].color);
    canvas.text(l.legend[i].label, x + kSwatch + 6, y + 0.5f * kSwatch, TextSize::small, kTextColor);
  }
}

// A white-ringed dark dot in the cell's middle: readable on both ends of viridis.
void draw_outlier_dot(Canvas& canvas, const HeatmapLayout& l, float x, float y) {
  const Point centre{x + 0.5f * l.cell_width, y + 0.5f * l.cell_height};
  const float size = std::clamp(0.35f * std::min(l.cell_width, l.cell_height), 2.0f, 8.0f);
  canvas.line(centre, centre, size + 2, kWhite);
  canvas.line(centre, centre, size, kOutlierDotColor);
}

}  // namespace

std::optional<double> metric_value(const SweepCell& cell, HeatmapMetric metric) {
  if (cell.status != Status::converged) return std::nullopt;
  switch (metric) {
    case HeatmapMetric::iterations: return static_cast<double>(cell.iterations);
    case HeatmapMetric::rate:
      if (cell.rate && std::isfinite(*cell.rate)) return *cell.rate;
      return std::nullopt;
    case HeatmapMetric::residual:
      if (!std::isfinite(cell.residual)) return std::nullopt;
      return std::log10(std::max(std::abs(cell.residual), 1e-18));
  }
  return std::nullopt;
}

Color MetricScale::color(double value) const { return viridis(position(value)); }

bool rate_outlier(const SweepCell& cell) {
  const auto r = metric_value(cell, HeatmapMetric::rate);
  return r && (*r < kRateColorLo || *r > kRateColorHi);
}

MetricScale metric_scale(const HeatmapGrid& grid, HeatmapMetric metric) {
  if (metric == HeatmapMetric::rate) return {kRateColorLo, kRateColorHi};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const SweepCell* cell : grid.cells) {
    if (cell == nullptr) continue;
    if (const auto v = metric_value(*cell, metric)) {
      lo = std::min(lo, *v);
      hi = std::max(hi, *v);
    }
  }
  if (!(lo <= hi)) return {0, 1};  // no converged cell: any range will do
  if (lo == hi) return {lo - 1, hi + 1};
  return {lo, hi};
}

Color cell_color(const SweepCell& cell, HeatmapMetric metric, const MetricScale& scale) {
  if (cell.status != Status::converged) return status_color(cell.status);
  const auto value = metric_value(cell, metric);
  return value ? scale.color(*value) : kNoValueColor;
}

void draw_heatmap(Canvas& canvas, const HeatmapGrid& grid, const HeatmapLayout& l, HeatmapMetric metric) {
  const MetricScale scale = metric_scale(grid, metric);
  for (int panel = 0; panel < l.panels; ++panel) {
    for (int i = 0; i < l.rows; ++i) {
      for (int j = 0; j < l.columns; ++j) {
        const SweepCell* cell = grid.at(panel, i, j);
        if (cell == nullptr) continue;
        const float x = float(l.panel_x(panel) + j * l.cell_width);
        const float y = float(l.top + (l.rows - 1 - i) * l.cell_height);
        canvas.rect(x, y, x + l.cell_width, y + l.cell_height, cell_color(*cell, metric, scale));
        if (metric == HeatmapMetric::rate && rate_outlier(*cell)) draw_outlier_dot(canvas, l, x, y);
      }
    }
    draw_panel_axes(canvas, grid, l, panel);
  }
  draw_colorbar(canvas, l, metric, scale);
  draw_legend(canvas, l);
}

}  // namespace lienewton::render
