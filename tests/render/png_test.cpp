#include "render/png.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "png_decode.hpp"

namespace lienewton::render {
namespace {

// A 5x3 image whose every pixel is distinct, so a flip or a stride error shows.
std::vector<std::uint8_t> gradient(int width, int height) {
  std::vector<std::uint8_t> rgb;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      rgb.push_back(static_cast<std::uint8_t>(40 * x));
      rgb.push_back(static_cast<std::uint8_t>(80 * y));
      rgb.push_back(static_cast<std::uint8_t>(7 * x + 11 * y));
    }
  }
  return rgb;
}

TEST(Png, TopDownRoundTrips) {
  const auto rgb = gradient(5, 3);
  const auto decoded = testing::decode_png(encode_png(rgb, 5, 3, RowOrder::top_down));
  ASSERT_EQ(decoded.width, 5);
  ASSERT_EQ(decoded.height, 3);
  EXPECT_EQ(decoded.rgb, rgb);
}

TEST(Png, BottomUpRowsAreFlipped) {
  const auto rgb = gradient(5, 3);
  const auto decoded = testing::decode_png(encode_png(rgb, 5, 3, RowOrder::bottom_up));
  ASSERT_EQ(decoded.height, 3);
  // The first stored row (GL's bottom) is the PNG's last.
  EXPECT_EQ(decoded.at(2, 2), (Color{80, 0, 14, 255}));
  EXPECT_EQ(decoded.at(2, 0), (Color{80, 160, 36, 255}));
}

TEST(Png, SizeMismatchThrows) {
  const auto rgb = gradient(5, 3);
  EXPECT_THROW(encode_png(rgb, 5, 4, RowOrder::top_down), std::invalid_argument);
  EXPECT_THROW(encode_png(rgb, 0, 3, RowOrder::top_down), std::invalid_argument);
}

}  // namespace
}  // namespace lienewton::render
