#include "render/colormap.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace lienewton::render
