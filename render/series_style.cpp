#include "render/series_style.hpp"

#include <cmath>

namespace lienewton::render {
namespace {

// Okabe-Ito's colour-blind-safe set, with its yellow darkened to read on white, and black last.
constexpr Color kColors[kSeriesColors] = {{0, 114, 178, 255},   {213, 94, 0, 255},    {0, 158, 115, 255},
                                          {204, 121, 167, 255}, {230, 159, 0, 255},   {86, 180, 233, 255},
                                          {150, 130, 0, 255},   {0, 0, 0, 255}};
constexpr Dash kDashes[] = {Dash::solid, Dash::dashed, Dash::dotted};
constexpr Marker kMarkers[] = {Marker::circle, Marker::square, Marker::triangle_up,
                               Marker::diamond, Marker::triangle_down, Marker::cross};

Point along(Point a, Point b, float t) { return {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}; }

}  // namespace

SeriesStyle series_style(std::size_t index) {
  return {kColors[index % kSeriesColors], kDashes[(index / kSeriesColors) % std::size(kDashes)],
          kMarkers[index % std::size(kMarkers)]};
}

std::string_view to_string(Dash dash) {
  switch (dash) {
    case Dash::solid: return "solid";
    case Dash::dashed: return "dashed";
    case Dash::dotted: return "dotted";
  }
  return "solid";
}

std::string_view to_string(Marker marker) {
  switch (marker) {
    case Marker::circle: return "circle";
    case Marker::square: return "square";
    case Marker::triangle_up: return "triangle-up";
    case Marker::diamond: return "diamond";
    case Marker::triangle_down: return "triangle-down";
    case Marker::cross: return "cross";
  }
  return "square";
}

std::vector<float> dash_pattern(Dash dash) {
  switch (dash) {
    case Dash::solid: return {};
    case Dash::dashed: return {9, 5};
    case Dash::dotted: return {2, 5};
  }
  return {};
}

void stroke_series(Canvas& canvas, const std::vector<Point>& points, const SeriesStyle& style, float width) {
  const std::vector<float> pattern = dash_pattern(style.dash);
  if (pattern.empty()) {
    for (std::size_t i = 1; i < points.size(); ++i) canvas.line(points[i - 1], points[i], width, style.color);
    return;
  }
  // Walk the polyline by arc length; phase is the position inside the current on/off entry.
  std::size_t entry = 0;
  float phase = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Point a = points[i - 1], b = points[i];
    const float length = std::hypot(b.x - a.x, b.y - a.y);
    float done = 0;
    while (done < length) {
      const float step = std::min(pattern[entry] - phase, length - done);
      if (entry % 2 == 0) canvas.line(along(a, b, done / length), along(a, b, (done + step) / length), width, style.color);
      done += step;
      phase += step;
      if (phase >= pattern[entry]) {
        phase = 0;
        entry = (entry + 1) % pattern.size();
      }
    }
  }
}

void draw_marker(Canvas& canvas, Point p, const SeriesStyle& style, float size) {
  const float r = 0.5f * size;
  const Color c = style.color;
  switch (style.marker) {
    case Marker::circle: canvas.line(p, p, size, c); break;  // a zero-length capsule is a disc
    case Marker::square: canvas.rect(p.x - 0.8f * r, p.y - 0.8f * r, p.x + 0.8f * r, p.y + 0.8f * r, c); break;
    case Marker::triangle_up: canvas.triangle({p.x, p.y - r}, {p.x + r, p.y + 0.8f * r}, {p.x - r, p.y + 0.8f * r}, c); break;
    case Marker::triangle_down: canvas.triangle({p.x, p.y + r}, {p.x - r, p.y - 0.8f * r}, {p.x + r, p.y - 0.8f * r}, c); break;
    case Marker::diamond:
      canvas.triangle({p.x, p.y - r}, {p.x + r, p.y}, {p.x, p.y + r}, c);
      canvas.triangle({p.x, p.y - r}, {p.x, p.y + r}, {p.x - r, p.y}, c);
      break;
    case Marker::cross:
      canvas.line({p.x - 0.75f * r, p.y - 0.75f * r}, {p.x + 0.75f * r, p.y + 0.75f * r}, 2.5f, c);
      canvas.line({p.x - 0.75f * r, p.y + 0.75f * r}, {p.x + 0.75f * r, p.y - 0.75f * r}, 2.5f, c);
      break;
  }
}

}  // namespace lienewton::render
