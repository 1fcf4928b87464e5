#include "render/heatmap_layout.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "render/colormap.hpp"
#include "render/heatmap_scene.hpp"
#include "render/short_names.hpp"

namespace lienewton::render {
namespace {

constexpr int kMargin = 10;
constexpr int kPanelGap = 26;
constexpr int kTick = 4;
constexpr int kSwatch = 12;
constexpr int kColorbarGap = 24;
constexpr int kColorbarWidth = 14;
constexpr int kAutoCellMin = 12;
constexpr int kAutoCellMax = 40;

int text_width(std::string_view text, TextSize size) {
  return static_cast<int>(std::ceil(Font::instance().width(text, size)));
}

int line_height(TextSize size) { return static_cast<int>(std::ceil(Font::instance().pixel_height(size))); }

int ceil_div(int a, int b) { return (a + b - 1) / b; }

}  // namespace

const SweepCell* HeatmapGrid::at(int panel, int n_index, int h_index) const {
  return cells[(static_cast<std::size_t>(panel) * n.size() + n_index) * h.size() + h_index];
}

HeatmapGrid make_grid(const SweepResult& sweep) {
  if (sweep.cells.empty()) throw std::invalid_argument("sweep has no cells to draw");
  HeatmapGrid grid;
  for (const SweepCell& cell : sweep.cells) {
    if (!(cell.h > 0) || !std::isfinite(cell.h)) throw std::invalid_argument("sweep cell with a non-positive h");
    if (std::find(grid.methods.begin(), grid.methods.end(), cell.method) == grid.methods.end()) {
      grid.methods.push_back(cell.method);
    }
    grid.n.push_back(cell.n);
    grid.h.push_back(cell.h);
  }
  std::sort(grid.n.begin(), grid.n.end());
  grid.n.erase(std::unique(grid.n.begin(), grid.n.end()), grid.n.end());
  std::sort(grid.h.begin(), grid.h.end());
  grid.h.erase(std::unique(grid.h.begin(), grid.h.end()), grid.h.end());
  grid.cells.assign(grid.methods.size() * grid.n.size() * grid.h.size(), nullptr);
  auto index_of = [](const auto& values, const auto& value) {
    return static_cast<std::size_t>(std::lower_bound(values.begin(), values.end(), value) - values.begin());
  };
  for (const SweepCell& cell : sweep.cells) {
    const auto m = static_cast<std::size_t>(std::find(grid.methods.begin(), grid.methods.end(), cell.method) -
                                            grid.methods.begin());
    grid.cells[(m * grid.n.size() + index_of(grid.n, cell.n)) * grid.h.size() + index_of(grid.h, cell.h)] = &cell;
  }
  return grid;
}

Point HeatmapLayout::cell_center(int panel, int n_index, int h_index) const {
  return {panel_x(panel) + (h_index + 0.5f) * cell_width, top + (rows - n_index - 0.5f) * cell_height};
}

std::string with_minus_sign(std::string number) {
  if (!number.empty() && number.front() == '-') number.replace(0, 1, "\u2212");
  return number;
}

std::string log2_label(double h) {
  const double e = std::log2(h);
  char text[32];
  if (std::abs(e - std::round(e)) < 1e-9) {
    std::snprintf(text, sizeof text, "%d", static_cast<int>(std::lround(e)));
  } else {
    std::snprintf(text, sizeof text, "%.3g", e);
  }
  return with_minus_sign(text);
}

std::string metric_label(HeatmapMetric metric) {
  return metric == HeatmapMetric::residual ? "log\u2081\u2080 \u2016f\u2016" : std::string(to_string(metric));
}

std::vector<LegendEntry> legend_entries(const HeatmapGrid& grid, HeatmapMetric metric) {
  std::size_t by_status[std::size(kAllStatuses)] = {};
  int missing = 0, no_value = 0, outliers = 0;
  for (const SweepCell* cell : grid.cells) {
    if (cell == nullptr) {
      ++missing;
      continue;
    }
    ++by_status[static_cast<std::size_t>(std::find(std::begin(kAllStatuses), std::end(kAllStatuses), cell->status) -
                                         std::begin(kAllStatuses))];
    if (cell->status != Status::converged) continue;
    no_value += !metric_value(*cell, metric);
    outliers += metric == HeatmapMetric::rate && rate_outlier(*cell);
  }
  std::vector<LegendEntry> legend;
  auto add = [&](std::string label, long count, Color color) {
    if (count > 0) legend.push_back({label.append(" (").append(std::to_string(count)).append(")"), color});
  };
  for (std::size_t k = 0; k < std::size(kAllStatuses); ++k) {
    if (kAllStatuses[k] != Status::converged) {
      add(std::string(short_name(kAllStatuses[k])), static_cast<long>(by_status[k]), status_color(kAllStatuses[k]));
    }
  }
  add("converged, no " + std::string(to_string(metric)), no_value, kNoValueColor);
  add("dot: rate outside 0\u20133", outliers, kOutlierDotColor);
  add("blank: not computed", missing, kWhite);
  return legend;
}

HeatmapLayout layout_heatmap(const HeatmapGrid& grid, HeatmapMetric metric, int width, int height) {
  HeatmapLayout l;
  l.panels = static_cast<int>(grid.methods.size());
  l.rows = static_cast<int>(grid.n.size());
  l.columns = static_cast<int>(grid.h.size());
  const int small = line_height(TextSize::small);
  const int large = line_height(TextSize::large);

  int n_label_width = 0;
  for (int n : grid.n) n_label_width = std::max(n_label_width, text_width(std::to_string(n), TextSize::small));
  int h_label_width = 0;
  for (double h : grid.h) h_label_width = std::max(h_label_width, text_width(log2_label(h), TextSize::small));

  l.legend = legend_entries(grid, metric);
  int legend_label_width = 0;
  for (const LegendEntry& entry : l.legend) {
    legend_label_width = std::max(legend_label_width, text_width(entry.label, TextSize::small));
  }
  l.legend_column_width = kSwatch + 6 + legend_label_width + 16;
  l.legend_row_height = small + 5;

  // Horizontal: [N title][N labels][tick][panels with gaps][gap][colorbar][tick labels or title]
  l.left = kMargin + text_width("N", TextSize::small) + 8 + n_label_width + kTick + 3;
  l.panel_gap = kPanelGap;
  const int colorbar_text = std::max(text_width("\u221200.0", TextSize::small) + kTick + 4,
                                     text_width(metric_label(metric), TextSize::small) - kColorbarWidth);
  const int right = kColorbarGap + kColorbarWidth + colorbar_text + kMargin;
  l.colorbar_width = kColorbarWidth;
  // Vertical: [title][panels][tick][h labels][h title][legend]
  l.top = kMargin + large + 8;
  const int below_panels = kTick + 4 + small + 6 + small + 12;

  const int fixed_width = l.left + (l.panels - 1) * l.panel_gap + right;
  const int cell_columns = l.panels * l.columns;
  if (width == 0 || height == 0) {
    // Square cells sized so that a typical grid fills about 600 pixels across.
    const int cell = std::clamp(600 / std::max(cell_columns, l.rows), kAutoCellMin, kAutoCellMax);
    l.cell_width = cell;
    l.cell_height = std::max(cell, small);  // tall enough to label every N
  }
  if (width == 0) {
    width = fixed_width + cell_columns * l.cell_width;
    width = std::max(width, 2 * kMargin + 2 * l.legend_column_width);
    width = std::clamp(width, kMinImageSize, kMaxImageSize);
  }
  l.cell_width = std::max(1, (width - fixed_width) / cell_columns);
  l.legend_x = kMargin;
  l.legend_columns = std::max(1, (width - 2 * kMargin) / l.legend_column_width);
  const int legend_rows = ceil_div(static_cast<int>(l.legend.size()), l.legend_columns);
  const int fixed_height = l.top + below_panels + legend_rows * l.legend_row_height + kMargin;
  if (height == 0) height = std::clamp(fixed_height + l.rows * l.cell_height, kMinImageSize, kMaxImageSize);
  l.cell_height = std::max(1, (height - fixed_height) / l.rows);
  l.width = width;
  l.height = height;

  l.colorbar_x = l.panel_x(l.panels - 1) + l.panel_width() + kColorbarGap;
  l.legend_y = l.top + l.panel_height() + below_panels;
  l.h_label_step = ceil_div(h_label_width + 6, l.cell_width);
  l.n_label_step = ceil_div(small, l.cell_height);
  return l;
}

}  // namespace lienewton::render
