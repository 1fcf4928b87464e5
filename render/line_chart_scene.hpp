#pragma once
// A log-log line chart: one colored polyline with square markers per series, decade (and 2, 5) ticks with
// labels and light grid lines, axis titles, a title and a legend. Used by bench/perf_plot.cpp for the
// time-per-iteration vs N figure of docs/performance.md.
#include <cstdint>
#include <string>
#include <vector>

#include "render/canvas.hpp"

namespace lienewton::render {

struct LineSeries {
  std::string label;
  Color color;
  std::vector<double> x, y;  // same length, all > 0 (log axes)
};

enum class AxisUnit { plain, seconds };  // seconds: tick labels as "10 us", "1 ms", "1 s"

struct LineChart {
  std::string title;
  std::string x_label, y_label;
  AxisUnit y_unit = AxisUnit::plain;
  std::vector<LineSeries> series;
};

// Where everything goes for a chart of a given size: the plot box and the decades it spans.
struct LineChartLayout {
  int width = 0, height = 0;
  float left = 0, top = 0, right = 0, bottom = 0;  // the plot box, pixels, top-down
  double log_x_lo = 0, log_x_hi = 1, log_y_lo = 0, log_y_hi = 1;  // log10 of the axis ends
  float legend_x = 0, legend_y = 0, legend_row_height = 0;
  Point project(double x, double y) const;  // data (x, y > 0) -> pixel centre
};

// Throws std::invalid_argument when there is no point, when x and y differ in length, or when a value is
// not finite and positive; width and height as Renderer's (validate_size, no automatic size).
LineChartLayout layout_line_chart(const LineChart& chart, int width, int height);
void draw_line_chart(Canvas& canvas, const LineChart& chart, const LineChartLayout& layout);

// The chart as a PNG, drawn on a GL context of its own (for command-line tools that draw one picture).
std::vector<std::uint8_t> line_chart_png(const LineChart& chart, int width, int height);

// Distinct series colors (Okabe-Ito), cycled.
Color series_color(std::size_t index);

}  // namespace lienewton::render
