#include "render/line_chart_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>

#include "render/gl_context.hpp"
#include "render/options.hpp"
#include "render/painter.hpp"
#include "render/png.hpp"

namespace lienewton::render {
namespace {

constexpr Color kAxisColor{90, 90, 90, 255};
constexpr Color kGridColor{225, 225, 225, 255};
constexpr float kTick = 4;
constexpr float kMarker = 7;      // side of a marker square, pixels
constexpr float kLineWidth = 2;
constexpr float kSwatch = 22;     // legend line sample length

// Ticks on a log axis: every decade; also 2 and 5 times a decade when the axis spans at most two decades.
std::vector<double> log_ticks(double log_lo, double log_hi) {
  const bool fine = log_hi - log_lo <= 2.0 + 1e-9;
  std::vector<double> ticks;
  for (int e = static_cast<int>(std::floor(log_lo)); e <= static_cast<int>(std::ceil(log_hi)); ++e) {
    for (double m : {1.0, 2.0, 5.0}) {
      if (m != 1.0 && !fine) continue;
      const double l = e + std::log10(m);
      if (l >= log_lo - 1e-9 && l <= log_hi + 1e-9) ticks.push_back(m * std::pow(10.0, e));
    }
  }
  return ticks;
}

std::string axis_label(double value, AxisUnit unit) {
  char text[32];
  if (unit == AxisUnit::seconds) {
    static constexpr struct {
      double scale;
      const char* suffix;
    } kUnits[] = {{1.0, "s"}, {1e-3, "ms"}, {1e-6, "us"}, {1e-9, "ns"}};
    for (const auto& u : kUnits) {
      if (value >= u.scale * (1 - 1e-9) || u.scale == 1e-9) {
        std::snprintf(text, sizeof text, "%g %s", value / u.scale, u.suffix);
        return text;
      }
    }
  }
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Axis ends: the data range widened by a margin of 5% of its (log) span, at least a tenth of a decade.
std::pair<double, double> log_range(double lo, double hi) {
  double a = std::log10(lo), b = std::log10(hi);
  const double margin = std::max(0.05 * (b - a), 0.1);
  return {a - margin, b + margin};
}

void draw_axes(Canvas& canvas, const LineChart& chart, const LineChartLayout& l) {
  const float small = Font::instance().pixel_height(TextSize::small);
  for (double x : log_ticks(l.log_x_lo, l.log_x_hi)) {
    const float px = l.project(x, std::pow(10.0, l.log_y_lo)).x;
    canvas.rect(px - 0.5f, l.top, px + 0.5f, l.bottom, kGridColor);
    canvas.rect(px - 0.5f, l.bottom, px + 0.5f, l.bottom + kTick, kAxisColor);
    canvas.text(axis_label(x, AxisUnit::plain), px, l.bottom + kTick + 4 + 0.5f * small, TextSize::small,
                kTextColor, Align::center);
  }
  for (double y : log_ticks(l.log_y_lo, l.log_y_hi)) {
    const float py = l.project(std::pow(10.0, l.log_x_lo), y).y;
    canvas.rect(l.left, py - 0.5f, l.right, py + 0.5f, kGridColor);
    canvas.rect(l.left - kTick, py - 0.5f, l.left, py + 0.5f, kAxisColor);
    canvas.text(axis_label(y, chart.y_unit), l.left - kTick - 4, py, TextSize::small, kTextColor, Align::right);
  }
  canvas.rect(l.left - 1, l.top - 1, l.right + 1, l.top, kAxisColor);
  canvas.rect(l.left - 1, l.bottom, l.right + 1, l.bottom + 1, kAxisColor);
  canvas.rect(l.left - 1, l.top, l.left, l.bottom, kAxisColor);
  canvas.rect(l.right, l.top, l.right + 1, l.bottom, kAxisColor);
  const float mid_x = 0.5f * (l.left + l.right);
  canvas.text(chart.title, mid_x, 0.5f * l.top, TextSize::large, kTextColor, Align::center);
  canvas.text(chart.x_label, mid_x, l.bottom + kTick + 12 + 1.5f * small, TextSize::small, kTextColor,
              Align::center);
  canvas.text(chart.y_label, 8, l.top - 14, TextSize::small, kTextColor);
}

void draw_legend(Canvas& canvas, const LineChart& chart, const LineChartLayout& l) {
  float text_width = 0;
  for (const auto& s : chart.series) text_width = std::max(text_width, Font::instance().width(s.label, TextSize::small));
  const float x0 = l.legend_x, y0 = l.legend_y;
  const float x1 = x0 + 8 + kSwatch + 6 + text_width + 8;
  const float y1 = y0 + 4 + l.legend_row_height * chart.series.size() + 4;
  canvas.rect(x0, y0, x1, y1, kAxisColor);
  canvas.rect(x0 + 1, y0 + 1, x1 - 1, y1 - 1, kWhite);
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const LineSeries& s = chart.series[i];
    const float y = y0 + 4 + l.legend_row_height * (i + 0.5f);
    canvas.line({x0 + 8, y}, {x0 + 8 + kSwatch, y}, kLineWidth, s.color);
    const float mx = x0 + 8 + 0.5f * kSwatch;
    canvas.rect(mx - 0.5f * kMarker, y - 0.5f * kMarker, mx + 0.5f * kMarker, y + 0.5f * kMarker, s.color);
    canvas.text(s.label, x0 + 8 + kSwatch + 6, y, TextSize::small, kTextColor);
  }
}

}  // namespace

Point LineChartLayout::project(double x, double y) const {
  const double tx = (std::log10(x) - log_x_lo) / (log_x_hi - log_x_lo);
  const double ty = (std::log10(y) - log_y_lo) / (log_y_hi - log_y_lo);
  return {static_cast<float>(left + tx * (right - left)), static_cast<float>(bottom - ty * (bottom - top))};
}

LineChartLayout layout_line_chart(const LineChart& chart, int width, int height) {
  validate_size("width", width, false);
  validate_size("height", height, false);
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = 0, y_lo = x_lo, y_hi = 0;
  for (const auto& s : chart.series) {
    if (s.x.size() != s.y.size()) throw std::invalid_argument("series '" + s.label + "': x and y differ in length");
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!(std::isfinite(s.x[i]) && s.x[i] > 0 && std::isfinite(s.y[i]) && s.y[i] > 0)) {
        throw std::invalid_argument("series '" + s.label + "': values must be finite and positive on log axes");
      }
      x_lo = std::min(x_lo, s.x[i]), x_hi = std::max(x_hi, s.x[i]);
      y_lo = std::min(y_lo, s.y[i]), y_hi = std::max(y_hi, s.y[i]);
    }
  }
  if (!(x_lo <= x_hi)) throw std::invalid_argument("a line chart needs at least one point");
  LineChartLayout l;
  l.width = width;
  l.height = height;
  const float small = Font::instance().pixel_height(TextSize::small);
  l.left = 70;
  l.right = static_cast<float>(width) - 20;
  l.top = 50;
  l.bottom = static_cast<float>(height) - (kTick + 24 + 2 * small);
  std::tie(l.log_x_lo, l.log_x_hi) = log_range(x_lo, x_hi);
  std::tie(l.log_y_lo, l.log_y_hi) = log_range(y_lo, y_hi);
  l.legend_x = l.left + 10;
  l.legend_y = l.top + 10;
  l.legend_row_height = small + 8;
  return l;
}

void draw_line_chart(Canvas& canvas, const LineChart& chart, const LineChartLayout& l) {
  draw_axes(canvas, chart, l);
  // All polylines first, then all markers, so that a marker's pixels are its series' color.
  for (const auto& s : chart.series) {
    for (std::size_t i = 1; i < s.x.size(); ++i) {
      canvas.line(l.project(s.x[i - 1], s.y[i - 1]), l.project(s.x[i], s.y[i]), kLineWidth, s.color);
    }
  }
  for (const auto& s : chart.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const Point p = l.project(s.x[i], s.y[i]);
      canvas.rect(p.x - 0.5f * kMarker, p.y - 0.5f * kMarker, p.x + 0.5f * kMarker, p.y + 0.5f * kMarker, s.color);
    }
  }
  draw_legend(canvas, chart, l);
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

Color series_color(std::size_t index) {
  static constexpr Color kColors[] = {{0, 114, 178, 255},  {213, 94, 0, 255},   {0, 158, 115, 255},
                                      {204, 121, 167, 255}, {230, 159, 0, 255}, {86, 180, 233, 255}};
  return kColors[index % std::size(kColors)];
}

}  // namespace lienewton::render
