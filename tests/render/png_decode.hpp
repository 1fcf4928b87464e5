#pragma once
// Decodes a PNG back to pixels with libpng, independently of the encoder under test.
#include <cstdint>
#include <vector>

#include "render/color.hpp"

namespace lienewton::render::testing {

struct DecodedImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // top-down

  Color at(int x, int y) const;
  // Pixels in [x0, x1) x [y0, y1) that differ from the background.
  int count_not(Color background, int x0, int y0, int x1, int y1) const;
};

// Fails the current test (and returns an empty image) if the bytes are not a valid PNG.
DecodedImage decode_png(const std::vector<std::uint8_t>& png);

// Channel-wise |a - b| <= tolerance.
bool near(Color a, Color b, int tolerance);

}  // namespace lienewton::render::testing
