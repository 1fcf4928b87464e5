#pragma once
// A line chart: a polyline with markers per series in its SeriesStyle, log or linear axes with ticks, light
// grid lines and labels, a title and a legend (inside the plot's top-left corner or in a column to its right).
// Used by the work-precision and residual scenes and by bench/perf_plot.cpp (docs/performance.md).
#include <cstdint>
#include <string>
#include <vector>

#include "render/canvas.hpp"
#include "render/log_axis.hpp"
#include "render/series_style.hpp"

namespace lienewton::render {

enum class AxisScale { log, linear };

struct ChartAxis {
  std::string label;
  AxisScale scale = AxisScale::log;
  AxisUnit unit = AxisUnit::plain;
  double min_step = 0;  // linear axes: the smallest tick step (1 for counts)
};

struct LineSeries {
  std::string label;
  SeriesStyle style;
  std::vector<double> x, y;  // same length; finite, and positive on a log axis; may be empty (legend only)
  // A small label beside each marker (e.g. its h), or none; a label that would cover one drawn before is left out.
  std::vector<std::string> point_labels;
  // Points drawn grey (marker and label), e.g. those a fitted order leaves out; empty: none.
  std::vector<bool> muted;
};

enum class LegendPlace { none, inside, right };

struct LineChart {
  std::string title;
  ChartAxis x, y;
  std::vector<LineSeries> series;
  std::string legend_title;  // drawn above the legend's rows when not empty
  LegendPlace legend = LegendPlace::inside;
};

// A rectangle in pixels, top-down.
struct Box {
  float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Where everything goes for a chart drawn in a frame: the plot box and the ends of its axes.
struct LineChartLayout {
  Box frame;
  float left = 0, top = 0, right = 0, bottom = 0;  // the plot box
  AxisScale x_scale = AxisScale::log, y_scale = AxisScale::log;
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;  // axis ends: log10 of the value on a log axis
  float legend_x = 0, legend_y = 0, legend_row_height = 0, legend_width = 0;
  int legend_title_rows = 0;
  Point project(double x, double y) const;  // data -> pixel centre
  float legend_row_y(std::size_t series) const;  // vertical middle of a series' legend row
};

// Throws std::invalid_argument when there is no point, when x and y differ in length, or when a value is
// not finite (or not positive on a log axis). The int form checks width and height as Renderer does.
LineChartLayout layout_line_chart(const LineChart& chart, Box frame);
LineChartLayout layout_line_chart(const LineChart& chart, int width, int height);
void draw_line_chart(Canvas& canvas, const LineChart& chart, const LineChartLayout& layout);

// The chart as a PNG, drawn on a GL context of its own (for command-line tools that draw one picture).
std::vector<std::uint8_t> line_chart_png(const LineChart& chart, int width, int height);

}  // namespace lienewton::render
