#include "render/colormap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <tuple>

#include "png_decode.hpp"

namespace lienewton::render {
namespace {

TEST(Colormap, ViridisMatchesMatplotlibAtKnownPoints) {
  // Entries 0, 128 and 255 of matplotlib's viridis table, times 255.
  EXPECT_TRUE(testing::near(viridis(0.0), {68, 1, 84, 255}, 4));
  EXPECT_TRUE(testing::near(viridis(128.0 / 255.0), {33, 145, 140, 255}, 4));
  EXPECT_TRUE(testing::near(viridis(1.0), {253, 231, 37, 255}, 4));
}

TEST(Colormap, ViridisClampsAndTreatsNanAsLow) {
  EXPECT_EQ(viridis(-3.0), viridis(0.0));
  EXPECT_EQ(viridis(7.0), viridis(1.0));
  EXPECT_EQ(viridis(std::nan("")), viridis(0.0));
}

TEST(Colormap, EveryFailureClassHasItsOwnColor) {
  std::set<std::tuple<int, int, int>> seen;
  for (Status status : kAllStatuses) {
    if (status == Status::converged) continue;
    const Color c = status_color(status);
    EXPECT_TRUE(seen.insert({c.r, c.g, c.b}).second) << to_string(status);
    EXPECT_NE(c, kNoValueColor);
    EXPECT_NE(c, kWhite);
  }
}

// CIELAB (D65) of an sRGB colour: distances there are roughly what the eye sees.
std::array<double, 3> lab(Color c) {
  auto linear = [](std::uint8_t u) {
    const double v = u / 255.0;
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  };
  const double r = linear(c.r), g = linear(c.g), b = linear(c.b);
  const double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
  return {116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
}

double distance(Color a, Color b) {
  const auto p = lab(a), q = lab(b);
  return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

// A failure must not read as a converged cell's iteration count: each failure colour stays a clearly visible
// distance (CIELAB 25; a just-noticeable difference is about 2.3) from every shade of the converged ramp.
TEST(Colormap, FailureColorsLieOffTheConvergedRamp) {
  for (Status status : kAllStatuses) {
    if (status == Status::converged) continue;
    double nearest = 1e9;
    for (int i = 0; i < 256; ++i) nearest = std::min(nearest, distance(status_color(status), viridis(i / 255.0)));
    EXPECT_GE(nearest, 25.0) << to_string(status);
  }
  EXPECT_GE([] {
    double nearest = 1e9;
    for (int i = 0; i < 256; ++i) nearest = std::min(nearest, distance(kNoValueColor, viridis(i / 255.0)));
    return nearest;
  }(), 25.0);
}

}  // namespace
}  // namespace lienewton::render
