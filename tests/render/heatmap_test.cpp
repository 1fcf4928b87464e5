#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "png_decode.hpp"
#include "shared_renderer.hpp"
#include "render/colormap.hpp"
#include "render/heatmap_scene.hpp"
#include "render/renderer.hpp"
#include "render/short_names.hpp"

namespace lienewton::render {
namespace {

using testing::decode_png;
using testing::DecodedImage;

SweepCell cell(Method method, int n, double h, Status status, int iterations, std::optional<double> rate,
               double residual) {
  SweepCell c;
  c.method = method;
  c.n = n;
  c.h = h;
  c.status = status;
  c.iterations = iterations;
  c.rate = rate;
  c.residual = residual;
  return c;
}

// Two methods x N in {2, 3} x h in {1/2, 1, 2}: iterations 3..7 where converged, three failure classes.
SweepResult tiny_sweep() {
  SweepResult sweep;
  const Method methods[] = {Method::newton_group, Method::fixed_point};
  const int ns[] = {2, 3};
  const double hs[] = {0.5, 1.0, 2.0};
  int k = 0;
  for (Method m : methods) {
    for (int n : ns) {
      for (double h : hs) {
        Status status = Status::converged;
        if (m == Method::fixed_point && h == 2.0) status = n == 2 ? Status::diverged : Status::max_iterations;
        if (m == Method::newton_group && n == 3 && h == 2.0) status = Status::left_log_domain;
        const std::optional<double> rate = k % 4 == 0 ? std::nullopt : std::optional<double>(1.0 + 0.25 * k);
        sweep.cells.push_back(cell(m, n, h, status, 3 + k % 5, rate, std::pow(10.0, -10 - k % 6)));
        ++k;
      }
    }
  }
  return sweep;
}

// Every drawn cell's centre pixel has exactly the color its value or status calls for.
void expect_cells_colored(const SweepResult& sweep, const HeatmapOptions& options) {
  const DecodedImage image = decode_png(testing::shared_renderer().heatmap_png(sweep, options));
  const HeatmapGrid grid = make_grid(sweep);
  const HeatmapLayout layout = layout_heatmap(grid, options.metric, options.width, options.height);
  ASSERT_EQ(image.width, layout.width);
  ASSERT_EQ(image.height, layout.height);
  const MetricScale scale = metric_scale(grid, options.metric);
  for (int p = 0; p < layout.panels; ++p) {
    for (int i = 0; i < layout.rows; ++i) {
      for (int j = 0; j < layout.columns; ++j) {
        const SweepCell& c = *grid.at(p, i, j);
        const auto value = metric_value(c, options.metric);
        const bool dotted = options.metric == HeatmapMetric::rate && rate_outlier(c);  // centre: the dot
        const Color expected = c.status != Status::converged ? status_color(c.status)
                               : dotted                       ? kOutlierDotColor
                               : value                        ? viridis(scale.position(*value))
                                                              : kNoValueColor;
        const Point center = layout.cell_center(p, i, j);
        const Color got = image.at(static_cast<int>(center.x), static_cast<int>(center.y));
        EXPECT_TRUE(testing::near(got, expected, 2))
            << "panel " << p << " n " << c.n << " h " << c.h << ": got " << int(got.r) << "," << int(got.g) << ","
            << int(got.b) << " expected " << int(expected.r) << "," << int(expected.g) << "," << int(expected.b);
      }
    }
  }
}

TEST(Heatmap, GridOrdersMethodsAsGivenAndNAndHAscending) {
  const SweepResult sweep = tiny_sweep();
  const HeatmapGrid grid = make_grid(sweep);
  ASSERT_EQ(grid.methods.size(), 2u);
  EXPECT_EQ(grid.methods[0], Method::newton_group);
  EXPECT_EQ(grid.n, (std::vector<int>{2, 3}));
  EXPECT_EQ(grid.h, (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_EQ(grid.at(1, 0, 2)->status, Status::diverged);
}

TEST(Heatmap, CellCentersAreLaidOutLog2HRightwardNUpward) {
  const SweepResult sweep = tiny_sweep();
  const HeatmapLayout layout = layout_heatmap(make_grid(sweep), HeatmapMetric::iterations, 0, 0);
  EXPECT_LT(layout.cell_center(0, 0, 0).x, layout.cell_center(0, 0, 1).x);
  EXPECT_GT(layout.cell_center(0, 0, 0).y, layout.cell_center(0, 1, 0).y);  // larger N is higher
  EXPECT_LT(layout.cell_center(0, 0, 2).x, layout.cell_center(1, 0, 0).x);  // panels side by side
}

TEST(Heatmap, IterationCellsMatchTheColormap) {
  expect_cells_colored(tiny_sweep(), {0, 0, HeatmapMetric::iterations});
}

TEST(Heatmap, RateCellsMatchTheColormapAndMissingRatesAreGray) {
  expect_cells_colored(tiny_sweep(), {0, 0, HeatmapMetric::rate});
}

TEST(Heatmap, ResidualCellsMatchTheColormapAtAGivenSize) {
  expect_cells_colored(tiny_sweep(), {512, 512, HeatmapMetric::residual});
}

// Rates are coloured on 0..3 whatever the grid holds, so 1 and 2 always look different; the tiny sweep's
// rates above 3 are outliers, drawn with a dot.
TEST(Heatmap, RateScaleIsFixedAndOutliersAreFlagged) {
  const SweepResult sweep = tiny_sweep();  // the grid points into it
  const HeatmapGrid grid = make_grid(sweep);
  const MetricScale scale = metric_scale(grid, HeatmapMetric::rate);
  EXPECT_EQ(scale.lo, kRateColorLo);
  EXPECT_EQ(scale.hi, kRateColorHi);
  int outliers = 0;
  for (const SweepCell* c : grid.cells) outliers += rate_outlier(*c);
  EXPECT_GT(outliers, 0);
  SweepCell c = *grid.cells.front();
  c.status = Status::converged;
  for (double r : {-0.01, 3.01, 266.86}) {
    c.rate = r;
    EXPECT_TRUE(rate_outlier(c)) << r;
  }
  for (double r : {0.0, 1.0, 2.0, 3.0}) {
    c.rate = r;
    EXPECT_FALSE(rate_outlier(c)) << r;
  }
}

TEST(Heatmap, IterationScaleSpansTheConvergedCells) {
  const SweepResult sweep = tiny_sweep();
  const MetricScale scale = metric_scale(make_grid(sweep), HeatmapMetric::iterations);
  EXPECT_EQ(scale.lo, 3);
  EXPECT_EQ(scale.hi, 7);
}

TEST(Heatmap, LabelsLegendAndColorbarAreDrawn) {
  const SweepResult sweep = tiny_sweep();
  const HeatmapOptions options{0, 0, HeatmapMetric::iterations};
  const DecodedImage image = decode_png(testing::shared_renderer().heatmap_png(sweep, options));
  const HeatmapLayout l = layout_heatmap(make_grid(sweep), options.metric, 0, 0);
  const int panels_bottom = l.top + l.panel_height();
  // Legend band below the axis labels, title band above the panels, N labels left, colorbar numbers right.
  EXPECT_GT(image.count_not(kWhite, 0, l.legend_y, l.width, l.height), 200);
  EXPECT_GT(image.count_not(kWhite, l.left, 0, l.panel_x(1), l.top - 2), 50);
  EXPECT_GT(image.count_not(kWhite, 0, l.top, l.left - 2, panels_bottom), 20);
  EXPECT_GT(image.count_not(kWhite, l.colorbar_x + l.colorbar_width + 2, l.top, l.width, panels_bottom), 20);
  EXPECT_GT(image.count_not(kWhite, l.left, panels_bottom + 2, l.panel_x(1), l.legend_y), 50);  // log2 h labels
  // Each legend swatch shows its color.
  for (std::size_t k = 0; k < l.legend.size(); ++k) {
    const int x = l.legend_x + static_cast<int>(k % l.legend_columns) * l.legend_column_width + 6;
    const int y = l.legend_y + static_cast<int>(k / l.legend_columns) * l.legend_row_height + 6;
    EXPECT_EQ(image.at(x, y), l.legend[k].color) << l.legend[k].label;
  }
}

// The legend names only what the map shows, each with its number of cells: the tiny sweep has one cell each of
// three failure classes and none of the other six.
TEST(Heatmap, LegendListsOnlyTheClassesInTheMapWithTheirCounts) {
  const SweepResult sweep = tiny_sweep();
  const HeatmapGrid grid = make_grid(sweep);
  std::vector<std::string> labels;
  for (const LegendEntry& e : legend_entries(grid, HeatmapMetric::iterations)) labels.push_back(e.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"max iterations (1)", "diverged (1)", "left log domain (1)"}));

  // Rates: converged cells without a rate and rates outside 0..3, counted here from the cells themselves.
  int no_rate = 0, outside = 0;
  for (const SweepCell& c : sweep.cells) {
    if (c.status != Status::converged) continue;
    no_rate += !c.rate;
    outside += c.rate && (*c.rate < 0 || *c.rate > 3);
  }
  ASSERT_GT(no_rate, 0);
  ASSERT_GT(outside, 0);
  labels.clear();
  for (const LegendEntry& e : legend_entries(grid, HeatmapMetric::rate)) labels.push_back(e.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"max iterations (1)", "diverged (1)", "left log domain (1)",
                                              "converged, no rate (" + std::to_string(no_rate) + ")",
                                              "dot: rate outside 0\u20133 (" + std::to_string(outside) + ")"}));

  // A sweep that stopped early: the cells it lacks are counted as not computed.
  SweepResult stopped = tiny_sweep();
  stopped.cells.erase(stopped.cells.begin() + 1, stopped.cells.begin() + 3);
  const auto entries = legend_entries(make_grid(stopped), HeatmapMetric::iterations);
  ASSERT_FALSE(entries.empty());
  EXPECT_EQ(entries.back().label, "blank: not computed (2)");
}

// In the PNG: every legend swatch in its colour, nothing after the last entry, and no 4 x 4 block anywhere in
// the colour of a failure class the map does not hold (so no swatch of one either).
TEST(Heatmap, PngShowsNoSwatchOfAnAbsentClass) {
  const SweepResult sweep = tiny_sweep();
  const HeatmapOptions options{0, 0, HeatmapMetric::iterations};
  const DecodedImage image = decode_png(testing::shared_renderer().heatmap_png(sweep, options));
  const HeatmapLayout l = layout_heatmap(make_grid(sweep), options.metric, 0, 0);
  ASSERT_EQ(l.legend.size(), 3u);
  auto swatch_centre = [&](std::size_t k) {
    return std::pair{l.legend_x + static_cast<int>(k % l.legend_columns) * l.legend_column_width + 6,
                     l.legend_y + static_cast<int>(k / l.legend_columns) * l.legend_row_height + 6};
  };
  for (std::size_t k = 0; k < l.legend.size(); ++k) {
    const auto [x, y] = swatch_centre(k);
    EXPECT_EQ(image.at(x, y), l.legend[k].color) << l.legend[k].label;
  }
  const auto [after_x, after_y] = swatch_centre(l.legend.size());
  if (after_y < l.height) {
    EXPECT_EQ(image.count_not(kWhite, after_x - 6, after_y - 6, after_x + 6, after_y + 6), 0);
  }
  for (Status s : {Status::non_finite, Status::singular_differential, Status::stagnated, Status::off_branch,
                   Status::local_minimum, Status::no_descent, Status::cancelled}) {
    // A swatch or a cell is a solid block; single pixels of a grey can be antialiased text.
    const Color absent = status_color(s);
    int blocks = 0;
    for (int y = 0; y + 4 <= image.height; ++y)
      for (int x = 0; x + 4 <= image.width; ++x) blocks += image.count_not(absent, x, y, x + 4, y + 4) == 0;
    EXPECT_EQ(blocks, 0) << short_name(s);
  }
}

// Ink rows [top, bottom] of the columns [x0, x1) within rows [y0, y1): pixels clearly darker than white.
std::pair<int, int> ink_rows(const DecodedImage& image, int x0, int x1, int y0, int y1) {
  int top = y1, bottom = y0 - 1;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      const Color c = image.at(x, y);
      if (std::min({c.r, c.g, c.b}) < 160) top = std::min(top, y), bottom = std::max(bottom, y);
    }
  }
  return {top, bottom};
}

// The h axis reads "log₂ h" with a real subscript two: a small glyph down at the baseline, at most 2/3 as tall
// as the h (an ASCII "log2 h", or a '?' for a missing glyph, would be about as tall as the h).
TEST(Heatmap, AxisTitleWritesTheSubscriptTwoBelowTheBaseline) {
  const SweepResult sweep = tiny_sweep();
  const DecodedImage image = decode_png(testing::shared_renderer().heatmap_png(sweep, {0, 0, HeatmapMetric::iterations}));
  const HeatmapLayout l = layout_heatmap(make_grid(sweep), HeatmapMetric::iterations, 0, 0);
  const Font& font = Font::instance();
  const std::string title = "log\u2082 h";
  // Where draw_panel_axes puts the first panel's title: centred under the panel, its capitals' middle at y.
  const float centre = l.panel_x(0) + 0.5f * l.panel_width();
  const float y = l.top + l.panel_height() + 4 + 10 + 1.5f * font.pixel_height(TextSize::small);
  const int pen = static_cast<int>(std::round(centre - 0.5f * font.width(title, TextSize::small)));
  const int baseline = static_cast<int>(std::round(y + 0.5f * font.cap_height(TextSize::small)));
  auto span = [&](std::string_view before, std::string_view through) {
    return std::pair{pen + static_cast<int>(std::ceil(font.width(before, TextSize::small))),
                     pen + static_cast<int>(std::floor(font.width(through, TextSize::small)))};
  };
  const auto [two_x0, two_x1] = span("log", "log\u2082");
  const auto [h_x0, h_x1] = span("log\u2082 ", title);
  const int y0 = baseline - 16, y1 = baseline + 6;
  const auto [two_top, two_bottom] = ink_rows(image, two_x0, two_x1, y0, y1);
  const auto [h_top, h_bottom] = ink_rows(image, h_x0, h_x1, y0, y1);
  ASSERT_LE(h_top, h_bottom) << "no h at the expected place";
  ASSERT_LE(two_top, two_bottom) << "no subscript at the expected place";
  EXPECT_EQ(h_bottom, baseline - 1);  // the h stands on the baseline
  EXPECT_GE(two_bottom, h_bottom);    // the subscript reaches down to it
  EXPECT_LE(3 * (two_bottom - two_top + 1), 2 * (h_bottom - h_top + 1));  // at most 2/3 of the h's height
}

TEST(Heatmap, MetricNamesParse) {
  EXPECT_EQ(heatmap_metric_from_string("iterations"), HeatmapMetric::iterations);
  EXPECT_EQ(heatmap_metric_from_string("rate"), HeatmapMetric::rate);
  EXPECT_EQ(heatmap_metric_from_string("residual"), HeatmapMetric::residual);
  EXPECT_FALSE(heatmap_metric_from_string("Rate"));
}

TEST(Heatmap, EmptySweepIsRejected) {
  EXPECT_THROW(testing::shared_renderer().heatmap_png(SweepResult{}, HeatmapOptions{}), std::invalid_argument);
}

// The PNG speaks the dashboard's words, not the API's: no "max_iterations" or "newton-group" in a legend.
TEST(Heatmap, LegendAndTitlesUseWordsNotApiNames) {
  std::vector<std::string> names;
  for (Status s : kAllStatuses) names.emplace_back(short_name(s));
  for (Method m : kAllMethods) names.emplace_back(short_name(m));
  for (Differential d : kAllDifferentials) names.emplace_back(short_name(d));
  for (Integrator i : kAllIntegrators) names.emplace_back(short_name(i));
  for (const std::string& word : names) {
    EXPECT_EQ(word.find('_'), std::string::npos) << word;
    EXPECT_FALSE(word.empty());
    for (char ch : word) EXPECT_LT(static_cast<unsigned char>(ch), 128) << word;  // the render font is ASCII
  }
  EXPECT_EQ(short_name(Status::max_iterations), "max iterations");
  EXPECT_EQ(short_name(Method::newton_group), "Newton group");
}

}  // namespace
}  // namespace lienewton::render
