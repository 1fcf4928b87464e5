#pragma once
// The basin map picture: one square panel per method, a pixel per start y_0 = z exp(a B1 + b B2) (a to the
// right, b upward), in its root's hue shaded by iterations (light = few) or in its failure class' colour,
// with a legend of the roots and of the failure classes that occur. Titles, axes and legend are drawn on a
// Canvas; the panels' pixels are written straight into the painted image (fill_basin_panels), so a 512 x 512
// map costs no triangles.
#include <cstdint>
#include <string>
#include <vector>

#include "core/basins.hpp"
#include "render/canvas.hpp"

namespace lienewton::render {

// A hue per root id, apart from the failure colours (colormap.hpp) and from each other for the first ten;
// ids repeat their colour every kDistinctRootColors.
inline constexpr int kDistinctRootColors = 64;
Color root_color(int id);
// The most iterations mix this much black into a root's hue.
inline constexpr double kBasinDarkest = 0.6;

// Iteration counts of converged pixels, over every method: light at lo, dark at hi.
struct IterationShade {
  int lo = 0, hi = 0;
  Color shade(Color base, int iterations) const;
};
IterationShade iteration_shade(const BasinResult& map);

// The colour of one pixel.
Color basin_pixel_color(const BasinPixel& pixel, const IterationShade& shade);

struct BasinLegendEntry {
  std::string label;
  Color color;
};

struct BasinLayout {
  int width = 0, height = 0;
  int panels = 0, panel_size = 0;  // square panels of panel_size screen pixels
  int left = 0, top = 0, gap = 0;
  int legend_y = 0, legend_columns = 1, legend_column_width = 0, legend_row_height = 0;
  std::vector<BasinLegendEntry> legend;
  int panel_x(int panel) const { return left + panel * (panel_size + gap); }
};

// width/height 0: chosen from the map (panels of about the grid's size, within [160, 360] pixels).
// Throws std::invalid_argument when the map has no rows to draw.
BasinLayout layout_basins(const BasinResult& map, int width, int height);

// Titles (method, share converged, basins), axes with a and b ticks, frames and the legend.
void draw_basin_decorations(Canvas& canvas, const BasinResult& map, const BasinLayout& layout);

// Writes each panel's pixels into rgb (width x height x 3 bytes, rows bottom-up as the painter returns them).
// Each screen pixel shows the grid pixel under its centre.
void fill_basin_panels(std::vector<std::uint8_t>& rgb, const BasinResult& map, const BasinLayout& layout);

}  // namespace lienewton::render
