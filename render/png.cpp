#include "render/png.hpp"

#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <stdexcept>
#include <string>

namespace lienewton::render {
namespace {

struct Sink {
  std::vector<std::uint8_t>* out;
};

void write_bytes(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<Sink*>(png_get_io_ptr(png));
  try {
    sink->out->insert(sink->out->end(), data, data + length);
  } catch (...) {
    png_error(png, "out of memory");  // longjmps back to encode_rows; no C++ exception crosses libpng
  }
}

void flush_nothing(png_structp) {}

// libpng reports errors by longjmp: this function holds only trivially destructible locals so that the
// jump skips no destructor. Returns nullptr on success, else libpng's message.
const char* encode_rows(png_bytepp rows, int width, int height, Sink* sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (png == nullptr) return "png_create_write_struct failed";
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    return "png_create_info_struct failed";
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return "libpng failed while encoding";
  }
  png_set_write_fn(png, sink, write_bytes, flush_nothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, PNG_COLOR_TYPE_RGB,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, Z_BEST_SPEED);
  // Sub shrinks flat runs of color (most of both scenes) at almost no cost; libpng picks per row.
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE | PNG_FILTER_SUB);
  png_set_rows(png, info, rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return nullptr;
}

}  // namespace

std::vector<std::uint8_t> encode_png(std::span<const std::uint8_t> rgb, int width, int height, RowOrder order) {
  if (width <= 0 || height <= 0 || rgb.size() != static_cast<std::size_t>(width) * height * 3) {
    throw std::invalid_argument("encode_png: " + std::to_string(rgb.size()) + " bytes is not " +
                                std::to_string(width) + "x" + std::to_string(height) + " RGB pixels");
  }
  const std::size_t stride = static_cast<std::size_t>(width) * 3;
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y) {
    const int source_row = order == RowOrder::bottom_up ? height - 1 - y : y;
    // libpng's row type is non-const but it only reads rows when writing.
    rows[static_cast<std::size_t>(y)] = const_cast<png_bytep>(rgb.data() + stride * source_row);
  }
  std::vector<std::uint8_t> out;
  out.reserve(rgb.size() / 8);
  Sink sink{&out};
  if (const char* error = encode_rows(rows.data(), width, height, &sink)) throw std::runtime_error(error);
  return out;
}

}  // namespace lienewton::render
