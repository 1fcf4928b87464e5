#pragma once
// How a chart tells its series apart: a color, a dash pattern and a marker per series. The table cycles
// colors (8), dashes (3, changing every 8 series) and markers (6) so that the first kDistinctSeriesStyles
// indices differ in at least one of the three, and neighbours differ in color and marker.
#include <cstddef>
#include <string_view>
#include <vector>

#include "render/canvas.hpp"

namespace lienewton::render {

enum class Dash { solid, dashed, dotted };
enum class Marker { circle, square, triangle_up, diamond, triangle_down, cross };

struct SeriesStyle {
  Color color;
  Dash dash = Dash::solid;
  Marker marker = Marker::square;
};

inline constexpr std::size_t kSeriesColors = 8;
inline constexpr std::size_t kDistinctSeriesStyles = 24;

SeriesStyle series_style(std::size_t index);
std::string_view to_string(Dash dash);      // "solid" | "dashed" | "dotted"
std::string_view to_string(Marker marker);  // "circle" | "square" | "triangle-up" | "diamond" | "triangle-down" | "cross"
// On/off lengths in pixels, starting with a dash (empty for solid).
std::vector<float> dash_pattern(Dash dash);

inline constexpr float kSeriesLineWidth = 2;
inline constexpr float kMarkerSize = 9;  // pixels across

// The polyline through points with the style's dash pattern, continuous across vertices.
void stroke_series(Canvas& canvas, const std::vector<Point>& points, const SeriesStyle& style,
                   float width = kSeriesLineWidth);
// The style's marker centred at p, size pixels across, filled with the style's color.
void draw_marker(Canvas& canvas, Point p, const SeriesStyle& style, float size = kMarkerSize);

}  // namespace lienewton::render
