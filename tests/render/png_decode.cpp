#include "png_decode.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cstdlib>

namespace lienewton::render::testing {

Color DecodedImage::at(int x, int y) const {
  const std::size_t i = (static_cast<std::size_t>(y) * width + x) * 3;
  return {rgb[i], rgb[i + 1], rgb[i + 2], 255};
}

int DecodedImage::count_not(Color background, int x0, int y0, int x1, int y1) const {
  int count = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) count += at(x, y) == background ? 0 : 1;
  }
  return count;
}

DecodedImage decode_png(const std::vector<std::uint8_t>& png) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, png.data(), png.size())) {
    ADD_FAILURE() << "not a PNG: " << image.message;
    return {};
  }
  image.format = PNG_FORMAT_RGB;
  DecodedImage decoded{static_cast<int>(image.width), static_cast<int>(image.height), {}};
  decoded.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, decoded.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << "PNG does not decode: " << image.message;
    png_image_free(&image);
    return {};
  }
  return decoded;
}

bool near(Color a, Color b, int tolerance) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance && std::abs(a.b - b.b) <= tolerance;
}

}  // namespace lienewton::render::testing
