#include "render/basin_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "render/colormap.hpp"
#include "render/options.hpp"
#include "render/short_names.hpp"

namespace lienewton::render {
namespace {

constexpr int kMargin = 10;
constexpr int kGap = 28;
constexpr int kTick = 4;
constexpr int kSwatch = 12;
constexpr int kMaxRootEntries = 12;  // legend entries for roots; the rest are summed up in one line
constexpr Color kAxisColor{90, 90, 90, 255};

// Blues, greens, purples and yellows: the failure colours are reds, oranges, pinks, browns and greys.
constexpr Color kRootPalette[] = {{31, 119, 180, 255}, {44, 160, 44, 255},  {148, 103, 189, 255}, {188, 189, 34, 255},
                                  {23, 190, 207, 255}, {255, 217, 47, 255}, {102, 102, 255, 255}, {27, 120, 80, 255},
                                  {90, 60, 160, 255},  {150, 210, 90, 255}};

int text_width(std::string_view text, TextSize size) {
  return static_cast<int>(std::ceil(Font::instance().width(text, size)));
}
int line_height(TextSize size) { return static_cast<int>(std::ceil(Font::instance().pixel_height(size))); }

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

// HSV with s, v in [0, 1] and h in degrees.
Color hsv(double h, double s, double v) {
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h / 60.0, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  if (h < 60) r = c, g = x;
  else if (h < 120) r = x, g = c;
  else if (h < 180) g = c, b = x;
  else if (h < 240) g = x, b = c;
  else if (h < 300) r = x, b = c;
  else r = c, b = x;
  auto byte = [&](double t) { return static_cast<std::uint8_t>(std::lround(255 * (t + m))); };
  return {byte(r), byte(g), byte(b), 255};
}

std::vector<BasinLegendEntry> legend_entries(const BasinResult& map) {
  std::vector<BasinLegendEntry> legend;
  const int roots = static_cast<int>(map.roots.size());
  for (int k = 0; k < std::min(roots, kMaxRootEntries); ++k) {
    const BasinRoot& root = map.roots[static_cast<std::size_t>(k)];
    std::string text("root ");  // appended: GCC 12 reports a false -Wrestrict on "..." + std::string
    text.append(std::to_string(k)).append(format(", \u2016log z\u207b\u00b9y\u2016 = %.3g", root.distance_from_z));
    legend.push_back({text, root_color(k)});
  }
  if (roots > kMaxRootEntries)
    legend.push_back({std::string("+").append(std::to_string(roots - kMaxRootEntries)).append(" more roots"),
                      root_color(kMaxRootEntries)});
  for (Status status : kAllStatuses) {
    if (status == Status::converged) continue;
    const auto index = static_cast<std::size_t>(std::find(std::begin(kAllStatuses), std::end(kAllStatuses), status) -
                                                std::begin(kAllStatuses));
    long pixels = 0;  // over every method's panel
    for (const BasinMethodSummary& s : map.methods) pixels += static_cast<long>(s.status_counts[index]);
    if (pixels > 0) {
      legend.push_back({std::string(short_name(status)).append(" (").append(std::to_string(pixels)).append(")"),
                        status_color(status)});
    }
  }
  return legend;
}

void frame(Canvas& canvas, float x0, float y0, float x1, float y1) {
  canvas.rect(x0 - 1, y0 - 1, x1 + 1, y0, kAxisColor);
  canvas.rect(x0 - 1, y1, x1 + 1, y1 + 1, kAxisColor);
  canvas.rect(x0 - 1, y0, x0, y1, kAxisColor);
  canvas.rect(x1, y0, x1 + 1, y1, kAxisColor);
}

}  // namespace

Color root_color(int id) {
  id = ((id % kDistinctRootColors) + kDistinctRootColors) % kDistinctRootColors;
  if (id < static_cast<int>(std::size(kRootPalette))) return kRootPalette[id];
  // Further roots: golden-angle hues within 170..290 degrees and 60..110 (blues-purples, greens-yellows).
  const double t = std::fmod(id * 0.618033988749895, 1.0);
  const double hue = t < 0.5 ? 60 + 100 * t : 170 + 240 * (t - 0.5);
  return hsv(hue, 0.75, 0.55 + 0.35 * std::fmod(id * 0.381966, 1.0));
}

Color IterationShade::shade(Color base, int iterations) const {
  const double t = hi > lo ? static_cast<double>(iterations - lo) / (hi - lo) : 0.0;
  return mix(base, kBlack, kBasinDarkest * std::clamp(t, 0.0, 1.0));
}

IterationShade iteration_shade(const BasinResult& map) {
  IterationShade s{std::numeric_limits<int>::max(), 0};
  for (const BasinRow& row : map.rows)
    for (const auto& pixels : row.pixels)
      for (const BasinPixel& p : pixels)
        if (p.status == Status::converged) s.lo = std::min(s.lo, p.iterations), s.hi = std::max(s.hi, p.iterations);
  if (s.lo > s.hi) s.lo = s.hi = 0;
  return s;
}

Color basin_pixel_color(const BasinPixel& pixel, const IterationShade& shade) {
  if (pixel.status != Status::converged) return status_color(pixel.status);
  return shade.shade(root_color(pixel.root), pixel.iterations);
}

BasinLayout layout_basins(const BasinResult& map, int width, int height) {
  if (map.rows.empty() || map.methods.empty()) throw std::invalid_argument("the basin map has no rows to draw");
  BasinLayout l;
  l.panels = static_cast<int>(map.methods.size());
  const int small = line_height(TextSize::small), large = line_height(TextSize::large);
  l.legend = legend_entries(map);
  int label = 0;
  for (const auto& e : l.legend) label = std::max(label, text_width(e.label, TextSize::small));
  l.legend_column_width = kSwatch + 6 + label + 16;
  l.legend_row_height = small + 5;
  // Horizontal: [b title][b ticks][panels with gaps][margin or half a tick]; vertical: [title][subtitle][panels][a ticks][a
  // title][shade note][legend].
  const int tick_width = text_width("-0.00", TextSize::small);
  // Neighbouring panels' end ticks (r of one, -r of the next) are centred on their edges: the gap holds both.
  l.gap = std::max(kGap, tick_width + 8);
  l.left = kMargin + text_width("b", TextSize::small) + 8 + tick_width + kTick + 3;
  l.top = kMargin + large + 6 + small + 8;
  const int below = kTick + 4 + small + 6 + small + 10 + small + 10;
  // The last panel's end tick is centred on its right edge too: the right margin holds half of it.
  const int right = std::max(kMargin, tick_width / 2 + 4);
  const int fixed_width = l.left + (l.panels - 1) * l.gap + right;
  const int grid = static_cast<int>(map.grid.axis.size());
  auto legend_rows = [&](int w) {
    const int columns = std::max(1, (w - 2 * kMargin) / l.legend_column_width);
    return (static_cast<int>(l.legend.size()) + columns - 1) / columns;
  };
  if (width == 0) {
    l.panel_size = std::clamp(grid, 160, 360);
    width = std::clamp(fixed_width + l.panels * l.panel_size, kMinImageSize, kMaxImageSize);
    width = std::max(width, std::min(kMaxImageSize, 2 * kMargin + l.legend_column_width));
  }
  l.panel_size = std::max(1, (width - fixed_width) / l.panels);
  if (height == 0) {
    height = std::clamp(l.top + l.panel_size + below + legend_rows(width) * l.legend_row_height + kMargin,
                        kMinImageSize, kMaxImageSize);
  }
  l.panel_size = std::max(1, std::min(l.panel_size, height - l.top - below - legend_rows(width) * l.legend_row_height -
                                                        kMargin));
  l.width = width;
  l.height = height;
  l.legend_columns = std::max(1, (width - 2 * kMargin) / l.legend_column_width);
  l.legend_y = l.top + l.panel_size + below;
  return l;
}

void draw_basin_decorations(Canvas& canvas, const BasinResult& map, const BasinLayout& l) {
  const float small = Font::instance().pixel_height(TextSize::small);
  const double radius = map.grid.radius;
  const float y0 = float(l.top), y1 = float(l.top + l.panel_size);
  for (int p = 0; p < l.panels; ++p) {
    const BasinMethodSummary& s = map.methods[static_cast<std::size_t>(p)];
    const float x0 = float(l.panel_x(p)), x1 = x0 + float(l.panel_size);
    const float mid = 0.5f * (x0 + x1);
    canvas.text(short_name(s.method), mid, float(kMargin) + 0.5f * Font::instance().pixel_height(TextSize::large),
                TextSize::large, kTextColor, Align::center);
    canvas.text(format("%.1f%% converged, ", 100 * s.converged_fraction)
                    .append(std::to_string(s.basins))
                    .append(s.basins == 1 ? " basin" : " basins"),
                mid, y0 - 8 - 0.5f * small, TextSize::small, kTextColor, Align::center);
    frame(canvas, x0, y0, x1, y1);
    for (double v : {-radius, 0.0, radius}) {
      const float x = x0 + float((v + radius) / (2 * radius)) * l.panel_size;
      canvas.rect(x - 0.5f, y1 + 1, x + 0.5f, y1 + 1 + kTick, kAxisColor);
      canvas.text(format("%.3g", v), x, y1 + kTick + 4 + 0.5f * small, TextSize::small, kTextColor, Align::center);
    }
    canvas.text("a (along B1)", mid, y1 + kTick + 10 + 1.5f * small, TextSize::small, kTextColor, Align::center);
    if (p != 0) continue;
    for (double v : {-radius, 0.0, radius}) {
      const float y = y1 - float((v + radius) / (2 * radius)) * l.panel_size;
      canvas.rect(x0 - 1 - kTick, y - 0.5f, x0 - 1, y + 0.5f, kAxisColor);
      canvas.text(format("%.3g", v), x0 - kTick - 4, y, TextSize::small, kTextColor, Align::right);
    }
    canvas.text("b", float(kMargin), 0.5f * (y0 + y1), TextSize::small, kTextColor);
  }
  const IterationShade shade = iteration_shade(map);
  canvas.text(std::string("shade: iterations to converge, light ")
                  .append(std::to_string(shade.lo))
                  .append(" .. dark ")
                  .append(std::to_string(shade.hi)),
              float(kMargin), float(l.legend_y) - 10 - 0.5f * small, TextSize::small, kTextColor);
  for (std::size_t i = 0; i < l.legend.size(); ++i) {
    const int column = static_cast<int>(i) % l.legend_columns, row = static_cast<int>(i) / l.legend_columns;
    const float x = float(kMargin + column * l.legend_column_width), y = float(l.legend_y + row * l.legend_row_height);
    canvas.rect(x, y, x + kSwatch, y + kSwatch, kAxisColor);
    canvas.rect(x + 1, y + 1, x + kSwatch - 1, y + kSwatch - 1, l.legend[i].color);
    canvas.text(l.legend[i].label, x + kSwatch + 6, y + 0.5f * kSwatch, TextSize::small, kTextColor);
  }
}

void fill_basin_panels(std::vector<std::uint8_t>& rgb, const BasinResult& map, const BasinLayout& l) {
  const IterationShade shade = iteration_shade(map);
  const int grid = static_cast<int>(map.grid.axis.size());
  for (int p = 0; p < l.panels; ++p) {
    for (int sy = 0; sy < l.panel_size; ++sy) {
      // Screen row sy (top-down) shows grid row `row` (b grows upward); rows a cancelled map lacks stay blank.
      const int row = grid - 1 - std::min(grid - 1, (2 * sy + 1) * grid / (2 * l.panel_size));
      if (row >= static_cast<int>(map.rows.size())) continue;
      const auto& pixels = map.rows[static_cast<std::size_t>(row)].pixels[static_cast<std::size_t>(p)];
      const int image_row = l.height - 1 - (l.top + sy);  // bottom-up
      std::uint8_t* out = rgb.data() + (static_cast<std::size_t>(image_row) * l.width + l.panel_x(p)) * 3;
      for (int sx = 0; sx < l.panel_size; ++sx, out += 3) {
        const int column = std::min(grid - 1, (2 * sx + 1) * grid / (2 * l.panel_size));
        const Color c = basin_pixel_color(pixels[static_cast<std::size_t>(column)], shade);
        out[0] = c.r;
        out[1] = c.g;
        out[2] = c.b;
      }
    }
  }
}

}  // namespace lienewton::render
