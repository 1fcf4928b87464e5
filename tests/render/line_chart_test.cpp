#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "png_decode.hpp"
#include "render/line_chart_scene.hpp"

namespace lienewton::render {
namespace {

using testing::decode_png;
using testing::DecodedImage;

// Two series on log-log axes, far enough apart that no marker touches another series' line.
LineChart two_series() {
  // Designated initializers rather than assignments: g++ 12 warns falsely (-Wrestrict) on string = "literal".
  LineChart chart{.title = "time per iteration",
                  .x = {.label = "N", .scale = AxisScale::log, .unit = AxisUnit::plain, .min_step = 0},
                  .y = {.label = "time", .scale = AxisScale::log, .unit = AxisUnit::seconds, .min_step = 0},
                  .series = {}, .legend_title = {}, .legend = LegendPlace::inside};
  chart.series.push_back({"exact", series_style(0), {3, 8, 16, 32, 64, 100}, {1e-6, 1e-5, 6e-5, 4e-4, 3e-3, 1.1e-2}, {}, {}});
  chart.series.push_back({"finite-difference", series_style(1), {3, 8, 16, 32, 64, 100},
                          {3e-6, 1e-3, 2e-2, 0.4, 2.0, 9.0}, {}, {}});
  return chart;
}

TEST(LineChart, MarkersSitAtTheProjectedPointsInTheirSeriesColor) {
  const LineChart chart = two_series();
  const DecodedImage image = decode_png(line_chart_png(chart, 640, 420));
  ASSERT_EQ(image.width, 640);
  ASSERT_EQ(image.height, 420);
  const LineChartLayout layout = layout_line_chart(chart, 640, 420);
  for (const LineSeries& s : chart.series) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const Point p = layout.project(s.x[i], s.y[i]);
      EXPECT_GE(p.x, layout.left);
      EXPECT_LE(p.x, layout.right);
      EXPECT_GE(p.y, layout.top);
      EXPECT_LE(p.y, layout.bottom);
      EXPECT_EQ(image.at(static_cast<int>(p.x), static_cast<int>(p.y)), s.style.color)
          << s.label << " point " << i << " at (" << p.x << ", " << p.y << ")";
    }
  }
}

TEST(LineChart, ProjectionIsLogarithmic) {
  const LineChartLayout layout = layout_line_chart(two_series(), 640, 420);
  // Equal ratios are equal distances on both axes.
  EXPECT_NEAR(layout.project(10, 1).x - layout.project(1, 1).x, layout.project(100, 1).x - layout.project(10, 1).x, 1e-3);
  // A linear axis: equal differences are equal distances.
  LineChart linear = two_series();
  linear.x.scale = AxisScale::linear;
  const LineChartLayout lin = layout_line_chart(linear, 640, 420);
  EXPECT_NEAR(lin.project(20, 1).x - lin.project(10, 1).x, lin.project(30, 1).x - lin.project(20, 1).x, 1e-3);
  EXPECT_NEAR(layout.project(10, 1e-4).y - layout.project(10, 1e-3).y,
              layout.project(10, 1e-3).y - layout.project(10, 1e-2).y, 1e-3);
  EXPECT_LT(layout.project(10, 1e-2).y, layout.project(10, 1e-3).y);  // larger values higher up
}

TEST(LineChart, LegendShowsEverySeries) {
  const LineChart chart = two_series();
  const DecodedImage image = decode_png(line_chart_png(chart, 640, 420));
  const LineChartLayout layout = layout_line_chart(chart, 640, 420);
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const int y = static_cast<int>(layout.legend_row_y(i));
    const int x = static_cast<int>(layout.legend_x + 8);
    // The line sample in the series' color, then its label (text pixels) to the right.
    EXPECT_GT(image.count_not(kWhite, x, y - 2, x + 28, y + 3), 20) << chart.series[i].label;
    const int label_x = x + 28 + 6;
    EXPECT_GT(image.count_not(kWhite, label_x, y - 6, label_x + 60, y + 6), 20) << chart.series[i].label;
  }
}

TEST(LineChart, RejectsValuesALogAxisCannotShow) {
  LineChart chart = two_series();
  chart.series[0].y[2] = 0.0;
  EXPECT_THROW(layout_line_chart(chart, 640, 420), std::invalid_argument);
  chart.series[0].y[2] = 1.0;
  chart.series[1].x.pop_back();
  EXPECT_THROW(layout_line_chart(chart, 640, 420), std::invalid_argument);
  EXPECT_THROW(layout_line_chart(LineChart{}, 640, 420), std::invalid_argument);
  EXPECT_THROW(layout_line_chart(two_series(), 10, 420), std::invalid_argument);
}

}  // namespace
}  // namespace lienewton::render
