#pragma once
// Where everything of the convergence heatmap goes: one panel per method, side by side, with one cell per
// (N, log2 h); log2 h grows to the right, N upward. Coordinates are pixels, top-down (as in the PNG).
#include <string>
#include <vector>

#include "core/sweep.hpp"
#include "render/canvas.hpp"
#include "render/options.hpp"

namespace lienewton::render {

// The sweep's cells arranged by (method, N, h). Methods keep their first-appearance order, N and h ascend.
struct HeatmapGrid {
  std::vector<Method> methods;
  std::vector<int> n;
  std::vector<double> h;
  std::vector<const SweepCell*> cells;  // [method][n][h]; nullptr where the sweep has no such cell

  const SweepCell* at(int panel, int n_index, int h_index) const;
};

// Throws std::invalid_argument when the sweep is empty or has a non-positive or non-finite h.
HeatmapGrid make_grid(const SweepResult& sweep);
HeatmapGrid make_grid(SweepResult&&) = delete;  // the grid points into the sweep: it must outlive the grid

struct LegendEntry {
  std::string label;
  Color color;
};

struct HeatmapLayout {
  int width = 0, height = 0;
  int panels = 0, rows = 0, columns = 0;
  int left = 0, top = 0;                   // top-left corner of the first panel's cells
  int cell_width = 0, cell_height = 0;
  int panel_gap = 0;                       // between two panels' cell areas
  int h_label_step = 1, n_label_step = 1;  // label every k-th tick so that labels do not collide
  int colorbar_x = 0, colorbar_width = 0;  // spans the panels' height
  int legend_x = 0, legend_y = 0, legend_column_width = 0, legend_row_height = 0, legend_columns = 1;
  std::vector<LegendEntry> legend;

  int panel_x(int panel) const { return left + panel * (columns * cell_width + panel_gap); }
  int panel_width() const { return columns * cell_width; }
  int panel_height() const { return rows * cell_height; }
  // Centre of a cell; n_index 0 is the bottom row, h_index 0 the leftmost column.
  Point cell_center(int panel, int n_index, int h_index) const;
};

// width or height 0 chooses it from the grid (within [64, 4096]); cells shrink to fit a given size.
HeatmapLayout layout_heatmap(const HeatmapGrid& grid, HeatmapMetric metric, int width, int height);

// A number's leading '-' as the minus sign U+2212, as typeset.
std::string with_minus_sign(std::string number);
std::string log2_label(double h);  // "−3" for h = 1/8
// The colours the map shows beyond the colorbar, each with its number of cells: failure classes, converged
// cells without a metric value, rate outliers (a dot) and cells the sweep does not hold. Only those present.
std::vector<LegendEntry> legend_entries(const HeatmapGrid& grid, HeatmapMetric metric);
std::string metric_label(HeatmapMetric metric);

}  // namespace lienewton::render
