#include "render/line_chart_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "render/gl_context.hpp"
#include "render/options.hpp"
#include "render/painter.hpp"
#include "render/png.hpp"

namespace lienewton::render {
namespace {

constexpr Color kAxisColor{90, 90, 90, 255};
constexpr Color kGridColor{225, 225, 225, 255};
constexpr Color kMinorGridColor{242, 242, 242, 255};
constexpr float kTick = 4;
constexpr float kSwatch = 28;        // legend sample length
constexpr float kLabelSpacing = 70;  // least distance between two x tick labels, pixels
constexpr float kYLabelSpacing = 28;

double axis_coordinate(double v, AxisScale scale) { return scale == AxisScale::log ? std::log10(v) : v; }
double axis_value(double c, AxisScale scale) { return scale == AxisScale::log ? std::pow(10.0, c) : c; }

// Axis ends from the data range: a margin of 5% of the span, at least a tenth of a decade on a log axis
// and half a unit on a linear one.
std::pair<double, double> axis_range(double lo, double hi, AxisScale scale) {
  const double a = axis_coordinate(lo, scale), b = axis_coordinate(hi, scale);
  const double margin = std::max(0.05 * (b - a), scale == AxisScale::log ? 0.1 : 0.5);
  return {a - margin, b + margin};
}

std::vector<AxisTick> ticks_of(const ChartAxis& axis, double lo, double hi, float pixels, float spacing) {
  return axis.scale == AxisScale::log ? log_ticks(lo, hi, pixels, spacing)
                                      : linear_ticks(lo, hi, pixels, spacing, axis.min_step);
}

float legend_text_width(const LineChart& chart) {
  const Font& font = Font::instance();
  float w = chart.legend_title.empty() ? 0 : font.width(chart.legend_title, TextSize::small) - kSwatch - 6;
  for (const auto& s : chart.series) w = std::max(w, font.width(s.label, TextSize::small));
  return w;
}

void draw_axes(Canvas& canvas, const LineChart& chart, const LineChartLayout& l) {
  const float small = Font::instance().pixel_height(TextSize::small);
  for (const AxisTick& t : ticks_of(chart.x, l.x_lo, l.x_hi, l.right - l.left, kLabelSpacing)) {
    const float px = l.project(t.value, axis_value(l.y_lo, l.y_scale)).x;
    canvas.rect(px - 0.5f, l.top, px + 0.5f, l.bottom, t.labelled ? kGridColor : kMinorGridColor);
    if (!t.labelled) continue;
    canvas.rect(px - 0.5f, l.bottom, px + 0.5f, l.bottom + kTick, kAxisColor);
    canvas.text(tick_label(t.value, chart.x.unit), px, l.bottom + kTick + 4 + 0.5f * small, TextSize::small,
                kTextColor, Align::center);
  }
  for (const AxisTick& t : ticks_of(chart.y, l.y_lo, l.y_hi, l.bottom - l.top, kYLabelSpacing)) {
    const float py = l.project(axis_value(l.x_lo, l.x_scale), t.value).y;
    canvas.rect(l.left, py - 0.5f, l.right, py + 0.5f, t.labelled ? kGridColor : kMinorGridColor);
    if (!t.labelled) continue;
    canvas.rect(l.left - kTick, py - 0.5f, l.left, py + 0.5f, kAxisColor);
    canvas.text(tick_label(t.value, chart.y.unit), l.left - kTick - 4, py, TextSize::small, kTextColor, Align::right);
  }
  canvas.rect(l.left - 1, l.top - 1, l.right + 1, l.top, kAxisColor);
  canvas.rect(l.left - 1, l.bottom, l.right + 1, l.bottom + 1, kAxisColor);
  canvas.rect(l.left - 1, l.top, l.left, l.bottom, kAxisColor);
  canvas.rect(l.right, l.top, l.right + 1, l.bottom, kAxisColor);
  const float mid_x = 0.5f * (l.left + l.right);
  canvas.text(chart.title, mid_x, l.frame.y0 + 0.5f * (l.top - 14 - l.frame.y0), TextSize::large, kTextColor,
              Align::center);
  canvas.text(chart.x.label, mid_x, l.bottom + kTick + 12 + 1.5f * small, TextSize::small, kTextColor, Align::center);
  canvas.text(chart.y.label, l.frame.x0 + 8, l.top - 12, TextSize::small, kTextColor);
}

void draw_legend(Canvas& canvas, const LineChart& chart, const LineChartLayout& l) {
  const float x0 = l.legend_x, y0 = l.legend_y, x1 = x0 + l.legend_width;
  const float y1 = y0 + 8 + l.legend_row_height * static_cast<float>(chart.series.size() + l.legend_title_rows);
  canvas.rect(x0, y0, x1, y1, kAxisColor);
  canvas.rect(x0 + 1, y0 + 1, x1 - 1, y1 - 1, kWhite);
  if (l.legend_title_rows > 0) {
    canvas.text(chart.legend_title, x0 + 8, y0 + 4 + 0.5f * l.legend_row_height, TextSize::small, kTextColor);
  }
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const LineSeries& s = chart.series[i];
    const float y = l.legend_row_y(i);
    stroke_series(canvas, {{x0 + 8, y}, {x0 + 8 + kSwatch, y}}, s.style);
    draw_marker(canvas, {x0 + 8 + 0.5f * kSwatch, y}, s.style);
    canvas.text(s.label, x0 + 8 + kSwatch + 6, y, TextSize::small, kTextColor);
  }
}

}  // namespace

Point LineChartLayout::project(double x, double y) const {
  const double tx = (axis_coordinate(x, x_scale) - x_lo) / (x_hi - x_lo);
  const double ty = (axis_coordinate(y, y_scale) - y_lo) / (y_hi - y_lo);
  return {static_cast<float>(left + tx * (right - left)), static_cast<float>(bottom - ty * (bottom - top))};
}

float LineChartLayout::legend_row_y(std::size_t series) const {
  return legend_y + 4 + legend_row_height * (static_cast<float>(series + legend_title_rows) + 0.5f);
}

LineChartLayout layout_line_chart(const LineChart& chart, Box frame) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double x_lo = kInf, x_hi = -kInf, y_lo = kInf, y_hi = -kInf;
  auto fits = [](double v, AxisScale scale) { return std::isfinite(v) && (scale == AxisScale::linear || v > 0); };
  for (const auto& s : chart.series) {
    if (s.x.size() != s.y.size()) throw std::invalid_argument("series '" + s.label + "': x and y differ in length");
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!fits(s.x[i], chart.x.scale) || !fits(s.y[i], chart.y.scale)) {
        throw std::invalid_argument("series '" + s.label + "': values must be finite, and positive on log axes");
      }
      x_lo = std::min(x_lo, s.x[i]), x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, s.y[i]), y_hi = std::max(y_hi, s.y[i]);
    }
  }
  if (!(x_lo <= x_hi)) throw std::invalid_argument("a line chart needs at least one point");
  LineChartLayout l;
  l.frame = frame;
  l.x_scale = chart.x.scale;
  l.y_scale = chart.y.scale;
  const float small = Font::instance().pixel_height(TextSize::small);
  l.legend_row_height = small + 7;
  l.legend_title_rows = chart.legend_title.empty() ? 0 : 1;
  l.legend_width = 8 + kSwatch + 6 + legend_text_width(chart) + 8;
  l.left = frame.x0 + 70;
  l.right = frame.x1 - 20;
  l.top = frame.y0 + 50;
  l.bottom = frame.y1 - (kTick + 24 + 2 * small);
  if (chart.legend == LegendPlace::right) {
    // The legend gets its column unless the plot would keep less than a third of the frame.
    l.right = std::max(l.left + (frame.x1 - frame.x0) / 3, frame.x1 - 16 - l.legend_width - 12);
    l.legend_x = l.right + 12;
    l.legend_y = l.top;
  } else {
    l.legend_x = l.left + 10;
    l.legend_y = l.top + 10;
  }
  l.right = std::max(l.right, l.left + 1);
  l.bottom = std::max(l.bottom, l.top + 1);
  std::tie(l.x_lo, l.x_hi) = axis_range(x_lo, x_hi, chart.x.scale);
  std::tie(l.y_lo, l.y_hi) = axis_range(y_lo, y_hi, chart.y.scale);
  return l;
}

LineChartLayout layout_line_chart(const LineChart& chart, int width, int height) {
  validate_size("width", width, false);
  validate_size("height", height, false);
  return layout_line_chart(chart, Box{0, 0, static_cast<float>(width), static_cast<float>(height)});
}

// The grey of muted points: light enough to read as "left out", dark enough on white.
constexpr Color kMutedGrey{154, 154, 154};

void draw_line_chart(Canvas& canvas, const LineChart& chart, const LineChartLayout& l) {
  draw_axes(canvas, chart, l);
  // All polylines first, then all markers, so that a marker's pixels are its series' color.
  for (const auto& s : chart.series) {
    std::vector<Point> points;
    for (std::size_t i = 0; i < s.x.size(); ++i) points.push_back(l.project(s.x[i], s.y[i]));
    stroke_series(canvas, points, s.style);
  }
  // A muted point keeps its series' marker shape in grey.
  const auto style_at = [](const LineSeries& s, std::size_t i) {
    SeriesStyle style = s.style;
    if (i < s.muted.size() && s.muted[i]) style.color = kMutedGrey;
    return style;
  };
  for (const auto& s : chart.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) draw_marker(canvas, l.project(s.x[i], s.y[i]), style_at(s, i));
  }
  std::vector<Box> labelled;  // coinciding series share their labels rather than print them over each other
  const float label_height = Font::instance().pixel_height(TextSize::small);
  for (const auto& s : chart.series) {
    for (std::size_t i = 0; i < s.point_labels.size() && i < s.x.size(); ++i) {
      const Point p = l.project(s.x[i], s.y[i]);
      const float w = Font::instance().width(s.point_labels[i], TextSize::small);
      const Box box{p.x - 0.5f * w, p.y - 9 - label_height, p.x + 0.5f * w, p.y - 9};
      const bool covers = std::any_of(labelled.begin(), labelled.end(), [&](const Box& b) {
        return box.x0 < b.x1 && b.x0 < box.x1 && box.y0 < b.y1 && b.y0 < box.y1;
      });
      if (covers) continue;
      labelled.push_back(box);
      canvas.text(s.point_labels[i], p.x, 0.5f * (box.y0 + box.y1), TextSize::small, style_at(s, i).color,
                  Align::center);
    }
  }
  if (chart.legend != LegendPlace::none) draw_legend(canvas, chart, l);
}

std::vector<std::uint8_t> line_chart_png(const LineChart& chart, int width, int height) {
  const LineChartLayout layout = layout_line_chart(chart, width, height);
  Canvas canvas(width, height, kWhite);
  draw_line_chart(canvas, chart, layout);
  set_rasterizer_threads(1);
  GlContext context;
  context.make_current();
  std::vector<std::uint8_t> rgb;
  {
    struct Release {
      GlContext& context;
      ~Release() { context.release(); }
    } release_on_exit{context};
    Painter painter(context);
    rgb = painter.paint(canvas);
  }
  return encode_png(rgb, width, height, RowOrder::bottom_up);
}

}  // namespace lienewton::render
