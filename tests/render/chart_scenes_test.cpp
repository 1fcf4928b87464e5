// The work-precision and residual figures, drawn through the renderer and read back pixel by pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <tuple>

#include "png_decode.hpp"
#include "render/residuals_scene.hpp"
#include "render/work_precision_scene.hpp"
#include "shared_renderer.hpp"

namespace lienewton::render {
namespace {

using testing::decode_png;
using testing::DecodedImage;
using testing::shared_renderer;

// count series: series i has error = 10^-i h^p and a time that falls with the error, over h = 2^-2 .. 2^-6.
WorkPrecisionResult synthetic_work_precision(std::size_t count) {
  WorkPrecisionResult r;
  for (std::size_t i = 0; i < count; ++i) {
    WorkPrecisionSeries s;
    s.choice = {kAllIntegrators[i % 2], kAllMethods[(i / 2) % 3], kAllDifferentials[(i / 6) % 4]};
    const double p = 1.0 + static_cast<double>(i % 2);
    for (int k = 2; k <= 6; ++k) {
      const double h = std::ldexp(1.0, -k);
      s.points.push_back({.h = h, .cpu_seconds = 1e-5 * std::ldexp(1.0, k) * (1 + 0.1 * i),
                          .error = std::pow(10.0, -0.3 * i) * std::pow(h, p), .status = Status::converged,
                          .iterations = 10, .substeps = 16, .drifts = {}, .in_fit = true, .excluded = {}});
    }
    s.fitted_order = p;
    r.series.push_back(s);
  }
  return r;
}

std::set<std::size_t> series_colors_present(const DecodedImage& image, int x0, int x1) {
  std::set<std::size_t> found;
  for (int y = 0; y < image.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      const Color c = image.at(x, y);
      for (std::size_t k = 0; k < kSeriesColors; ++k) {
        if (c == series_style(k).color) found.insert(k);
      }
    }
  }
  return found;
}

DecodedImage draw(const Figure& figure) { return decode_png(shared_renderer().figure_png(figure)); }

TEST(WorkPrecisionScene, OneStyledLinePerSeriesWithEveryColor) {
  for (std::size_t count : {3u, 8u, 24u}) {
    const Figure figure = work_precision_scene(synthetic_work_precision(count), "work-precision", 960, 640);
    const DecodedImage image = draw(figure);
    ASSERT_EQ(image.width, 960);
    ASSERT_EQ(image.height, 640);
    EXPECT_EQ(series_colors_present(image, 0, image.width).size(), std::min(count, kSeriesColors)) << count;
  }
}

TEST(WorkPrecisionScene, LinesJoinTheStepSizesInOrderAndMarkersSitOnThePoints) {
  const WorkPrecisionResult result = synthetic_work_precision(8);
  const Figure figure = work_precision_scene(result, "work-precision", 960, 640);
  const DecodedImage image = draw(figure);
  const LineChart& chart = figure.panels[0].chart;
  const LineChartLayout layout = layout_line_chart(chart, figure.panels[0].frame);
  // The first series is solid: the middle of each segment between neighbouring h is in its color; h descends.
  const LineSeries& first = chart.series[0];
  ASSERT_EQ(first.x.size(), 5u);
  EXPECT_EQ(first.x.front(), result.series[0].points.front().error);  // largest h first
  for (std::size_t k = 1; k < first.x.size(); ++k) {
    const Point a = layout.project(first.x[k - 1], first.y[k - 1]), b = layout.project(first.x[k], first.y[k]);
    const Point mid{0.5f * (a.x + b.x), 0.5f * (a.y + b.y)};
    EXPECT_EQ(image.at(static_cast<int>(mid.x), static_cast<int>(mid.y)), first.style.color) << k;
  }
  // Every marker's centre is its series' color (markers are drawn over all lines).
  for (const LineSeries& s : chart.series) {
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      const Point p = layout.project(s.x[k], s.y[k]);
      EXPECT_EQ(image.at(static_cast<int>(p.x), static_cast<int>(p.y)), s.style.color) << s.label << " " << k;
    }
  }
}

TEST(WorkPrecisionScene, LegendNamesEverySeriesWithItsFittedOrder) {
  WorkPrecisionResult result = synthetic_work_precision(24);
  result.series[5].fitted_order.reset();
  result.series[7].points[1].status = Status::max_iterations;
  const Figure figure = work_precision_scene(result, "work-precision", 1100, 700);
  const LineChart& chart = figure.panels[0].chart;
  EXPECT_EQ(chart.series[0].label, "Euler, Fixed point  p = 1.00");
  EXPECT_EQ(chart.series[3].label, "DIRK-CG2, Newton group, FD  p = 2.00");
  EXPECT_EQ(chart.series[5].label, "DIRK-CG2, Newton algebra, FD  p = -");
  EXPECT_EQ(chart.series[7].label, "DIRK-CG2, Fixed point  p = 2.00 (1 of 5 failed)");
  EXPECT_EQ(chart.series[7].x.size(), 4u);
  const DecodedImage image = draw(figure);
  const LineChartLayout layout = layout_line_chart(chart, figure.panels[0].frame);
  EXPECT_GT(layout.legend_x, layout.right);  // a column of its own, right of the plot
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const int y = static_cast<int>(layout.legend_row_y(i));
    const int x = static_cast<int>(layout.legend_x + 8);
    ASSERT_LT(y, image.height);
    // The marker in the middle of the sample, then the label's text pixels.
    EXPECT_EQ(image.at(x + 14, y), chart.series[i].style.color) << i;
    EXPECT_GT(image.count_not(kWhite, x + 34, y - 6, x + 120, y + 6), 30) << i;
  }
}

// Against tolerance (DiffEqDevTools' chart): markers labelled with each run's tolerance, along decreasing
// tolerance whatever the points' order, and no fitted order in the legend.
TEST(WorkPrecisionScene, AgainstToleranceMarkersAreLabelledWithTheTolerance) {
  WorkPrecisionResult result = synthetic_work_precision(2);
  for (auto& s : result.series) {
    s.fitted_order.reset();
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      s.points[k].tolerance = std::pow(10.0, -4.0 - 2.0 * static_cast<double>(k));
      s.points[k].in_fit = false;
    }
  }
  std::reverse(result.series[1].points.begin(), result.series[1].points.end());
  const Figure figure = work_precision_scene(result, "work-precision", 960, 640);
  const LineChart& chart = figure.panels[0].chart;
  const std::vector<std::string> labels{"1e-4", "1e-6", "1e-8", "1e-10", "1e-12"};
  EXPECT_EQ(chart.series[0].point_labels, labels);
  EXPECT_EQ(chart.series[1].point_labels, labels);
  EXPECT_EQ(chart.series[0].label, "Euler, Fixed point");
  EXPECT_NE(chart.legend_title.find("tolerance"), std::string::npos);
  EXPECT_GT(draw(figure).width, 0);
}

TEST(WorkPrecisionScene, RefusesWhatItCannotDraw) {
  WorkPrecisionResult failed = synthetic_work_precision(2);
  for (auto& s : failed.series) {
    for (auto& p : s.points) p.status = Status::diverged;
  }
  EXPECT_THROW(work_precision_scene(failed, "t", 640, 480), std::invalid_argument);
  EXPECT_THROW(work_precision_scene(synthetic_work_precision(2), "t", 8000, 480), std::invalid_argument);
}

// Newton-like runs: residual squares each iteration; run i costs (i + 1) times as much per iteration.
std::vector<ResidualRun> synthetic_runs(std::size_t count) {
  std::vector<ResidualRun> runs;
  for (std::size_t i = 0; i < count; ++i) {
    ResidualRun run{.method = kAllMethods[1 + i % 2], .differential = kAllDifferentials[(i / 2) % 4],
                    .status = Status::converged, .cpu_seconds = {}, .residual = {}};
    double r = 0.5;
    for (int n = 0; n <= 5; ++n, r = r * r) {
      run.cpu_seconds.push_back(2e-6 * (n + 1) * (i + 1));
      run.residual.push_back(r);
    }
    runs.push_back(run);
  }
  return runs;
}

TEST(ResidualsScene, TimePanelBesideIterationPanelEachWithEverySeries) {
  const std::vector<ResidualRun> runs = synthetic_runs(6);
  const Figure figure = residuals_scene(runs, "residual against solver CPU time", 1200, 520);
  ASSERT_EQ(figure.panels.size(), 2u);
  const DecodedImage image = draw(figure);
  const int split = static_cast<int>(figure.panels[0].frame.x1);
  EXPECT_EQ(series_colors_present(image, 0, split).size(), 6u);
  EXPECT_EQ(series_colors_present(image, split, image.width).size(), 6u);
  // The six runs share one curve against n, but they lie apart against time: each run's last marker shows.
  const LineChart& by_time = figure.panels[0].chart;
  const LineChartLayout time_layout = layout_line_chart(by_time, figure.panels[0].frame);
  for (const LineSeries& s : by_time.series) {
    const Point p = time_layout.project(s.x.back(), s.y.back());
    EXPECT_EQ(image.at(static_cast<int>(p.x), static_cast<int>(p.y)), s.style.color);
  }
  const LineChart& by_iteration = figure.panels[1].chart;
  EXPECT_EQ(by_iteration.series[0].label, "Newton group, FD: 5 it, 12 \u00b5s");
  EXPECT_EQ(by_iteration.x.scale, AxisScale::linear);
}

TEST(ResidualsScene, FailedRunsSayHowAndZeroResidualsAreLeftOut) {
  std::vector<ResidualRun> runs = synthetic_runs(2);
  runs[1].status = Status::max_iterations;
  runs[0].residual.back() = 0.0;
  const Figure figure = residuals_scene(runs, "t", 800, 400);
  EXPECT_EQ(figure.panels[1].chart.series[1].label, "Newton algebra, FD: max_iterations after 5 it");
  EXPECT_EQ(figure.panels[0].chart.series[0].x.size(), 5u);
  runs[0].cpu_seconds.pop_back();
  EXPECT_THROW(residuals_scene(runs, "t", 800, 400), std::invalid_argument);
}

}  // namespace
}  // namespace lienewton::render
