// The series style table and the chart axes' ticks and labels.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <tuple>

#include "render/log_axis.hpp"
#include "render/series_style.hpp"
#include "render/short_names.hpp"

namespace lienewton::render {
namespace {

// A legend names the method and differential of an integrator that solves stages, and only its name for the
// explicit rkmk4, which uses neither.
TEST(SeriesName, AnExplicitIntegratorNamesNoMethod) {
  EXPECT_EQ(series_name(Integrator::rkmk4, Method::newton_group, Differential::exact), "RKMK4");
  EXPECT_EQ(series_name(Integrator::dirk_cg2, Method::newton_group, Differential::exact),
            std::string(short_name(Integrator::dirk_cg2)) + ", " + series_name(Method::newton_group, Differential::exact));
  EXPECT_EQ(series_name(Integrator::dirk_cg2, Method::fixed_point, Differential::exact),
            std::string(short_name(Integrator::dirk_cg2)) + ", " + std::string(short_name(Method::fixed_point)));
}

TEST(SeriesStyle, TwentyFourSeriesAreDistinct) {
  std::set<std::tuple<int, int, int, int, int>> seen;
  for (std::size_t i = 0; i < kDistinctSeriesStyles; ++i) {
    const SeriesStyle s = series_style(i);
    seen.emplace(s.color.r, s.color.g, s.color.b, static_cast<int>(s.dash), static_cast<int>(s.marker));
  }
  EXPECT_EQ(seen.size(), kDistinctSeriesStyles);
  // Neighbours differ in color and in marker, so that two adjacent legend rows never look alike.
  for (std::size_t i = 1; i < kDistinctSeriesStyles; ++i) {
    EXPECT_NE(series_style(i).color, series_style(i - 1).color) << i;
    EXPECT_NE(series_style(i).marker, series_style(i - 1).marker) << i;
  }
  // The first eight colors differ from each other, from white and from the text color.
  std::set<std::tuple<int, int, int>> colors;
  for (std::size_t i = 0; i < kSeriesColors; ++i) {
    const Color c = series_style(i).color;
    colors.emplace(c.r, c.g, c.b);
    EXPECT_NE(c, kWhite);
    EXPECT_NE(c, kTextColor);
  }
  EXPECT_EQ(colors.size(), kSeriesColors);
}

TEST(SeriesStyle, DashPatternsAlternateOnAndOff) {
  EXPECT_TRUE(dash_pattern(Dash::solid).empty());
  for (Dash d : {Dash::dashed, Dash::dotted}) {
    const auto p = dash_pattern(d);
    ASSERT_EQ(p.size() % 2, 0u);
    for (float len : p) EXPECT_GT(len, 0);
  }
}

std::vector<double> values(const std::vector<AxisTick>& ticks, bool labelled_only) {
  std::vector<double> v;
  for (const auto& t : ticks) {
    if (t.labelled || !labelled_only) v.push_back(t.value);
  }
  return v;
}

TEST(LogAxis, DecadesOnLongAxesWithLabelsThatFit) {
  // 1e-16 .. 1: 17 decades over 340 px leaves 20 px a decade; labels 70 px apart means every 5th decade.
  const auto ticks = log_ticks(-16, 0, 340, 70);
  EXPECT_EQ(ticks.size(), 17u);
  const std::vector<double> labelled = values(ticks, true);
  ASSERT_EQ(labelled.size(), 4u);  // 1e-15, 1e-10, 1e-5, 1
  EXPECT_DOUBLE_EQ(labelled[0], 1e-15);
  EXPECT_DOUBLE_EQ(labelled[3], 1.0);
  // Wide enough: every decade labelled.
  EXPECT_EQ(values(log_ticks(-3, 1, 800, 70), true).size(), 5u);
}

TEST(LogAxis, OneTwoFiveOnShortAxesAndFinerBelowThat) {
  const std::vector<double> v = values(log_ticks(-0.05, 1.05, 600, 40), true);
  const std::vector<double> expected = {1, 2, 5, 10};
  ASSERT_EQ(v.size(), expected.size());
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(v[i], expected[i], 1e-12);
  // Between 3 and 4.5 there is no 1, 2 or 5: ticks at 3 and 4.
  const std::vector<double> fine = values(log_ticks(std::log10(2.9), std::log10(4.5), 600, 40), true);
  ASSERT_EQ(fine.size(), 2u);
  EXPECT_NEAR(fine[0], 3, 1e-12);
  EXPECT_NEAR(fine[1], 4, 1e-12);
}

TEST(LinearAxis, RoundStepsAndIntegerCounts) {
  const std::vector<double> v = values(linear_ticks(-0.5, 10.5, 500, 50), true);
  const std::vector<double> expected = {0, 2, 4, 6, 8, 10};
  EXPECT_EQ(v, expected);
  // Counts: never a half step, however wide the axis.
  const std::vector<double> counts = values(linear_ticks(-0.5, 2.5, 900, 40, 1), true);
  EXPECT_EQ(counts, (std::vector<double>{0, 1, 2}));
}

TEST(TickLabel, ShortNumbersAndTimeUnits) {
  EXPECT_EQ(tick_label(1e-8, AxisUnit::plain), "1e-8");
  EXPECT_EQ(tick_label(2e6, AxisUnit::plain), "2e6");
  EXPECT_EQ(tick_label(0.01, AxisUnit::plain), "0.01");
  EXPECT_EQ(tick_label(100, AxisUnit::plain), "100");
  EXPECT_EQ(tick_label(1e-5, AxisUnit::seconds), "10 \u00b5s");
  EXPECT_EQ(tick_label(1.5e-3, AxisUnit::seconds), "1.5 ms");
  EXPECT_EQ(tick_label(2, AxisUnit::seconds), "2 s");
  EXPECT_EQ(tick_label(3e-9, AxisUnit::seconds), "3 ns");
}

}  // namespace
}  // namespace lienewton::render
