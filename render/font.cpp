#include "render/font.hpp"

#include <stb_truetype.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "render/render_unavailable.hpp"

namespace lienewton::render {
namespace {

constexpr float kSmallPixels = 13.0f;
constexpr float kLargePixels = 15.0f;
constexpr int kBandHeight = 120;  // each size is baked into its own band of atlas rows

std::vector<unsigned char> read_font_file(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes;
  if (in) bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw RenderUnavailable(std::string("cannot read the label font ") + path);
  return bytes;
}

}  // namespace

const Font& Font::instance() {
  static const Font font;  // a throwing initialiser is retried by the next caller
  return font;
}

Font::Font() : atlas_(static_cast<std::size_t>(kAtlasWidth) * kAtlasHeight, 0) {
  const std::vector<unsigned char> ttf = read_font_file(LIENEWTON_FONT_PATH);
  stbtt_fontinfo info;
  if (!stbtt_InitFont(&info, ttf.data(), stbtt_GetFontOffsetForIndex(ttf.data(), 0))) {
    throw RenderUnavailable(std::string("cannot parse the label font ") + LIENEWTON_FONT_PATH);
  }
  int cap_x0 = 0, cap_y0 = 0, cap_x1 = 0, cap_y1 = 0;
  stbtt_GetCodepointBox(&info, 'H', &cap_x0, &cap_y0, &cap_x1, &cap_y1);

  auto bake = [&](Face& face, float pixels, int band) {
    face.pixel_height = pixels;
    face.cap_height = static_cast<float>(cap_y1) * stbtt_ScaleForPixelHeight(&info, pixels);
    stbtt_bakedchar baked[kCharCount];
    unsigned char* band_pixels = atlas_.data() + static_cast<std::size_t>(band) * kBandHeight * kAtlasWidth;
    const int rows = stbtt_BakeFontBitmap(ttf.data(), 0, pixels, band_pixels, kAtlasWidth, kBandHeight, kFirstChar,
                                          kCharCount, baked);
    if (rows <= 0) throw RenderUnavailable("the label font does not fit its atlas");
    for (int i = 0; i < kCharCount; ++i) {
      const auto y_shift = static_cast<std::uint16_t>(band * kBandHeight);
      face.chars[i] = {baked[i].x0, static_cast<std::uint16_t>(baked[i].y0 + y_shift), baked[i].x1,
                       static_cast<std::uint16_t>(baked[i].y1 + y_shift), baked[i].xoff, baked[i].yoff,
                       baked[i].xadvance};
    }
  };
  bake(small_, kSmallPixels, 0);
  bake(large_, kLargePixels, 1);
  // The solid block sits in the corner below both bands.
  for (int y = kAtlasHeight - 4; y < kAtlasHeight; ++y) {
    for (int x = kAtlasWidth - 4; x < kAtlasWidth; ++x) atlas_[static_cast<std::size_t>(y) * kAtlasWidth + x] = 255;
  }
}

const Font::Baked& Font::glyph(const Face& face, char c) {
  const int index = static_cast<unsigned char>(c) - kFirstChar;
  return face.chars[(index >= 0 && index < kCharCount) ? index : '?' - kFirstChar];
}

float Font::pixel_height(TextSize size) const { return face(size).pixel_height; }
float Font::cap_height(TextSize size) const { return face(size).cap_height; }

float Font::width(std::string_view text, TextSize size) const {
  float w = 0;
  for (char c : text) w += glyph(face(size), c).xadvance;
  return w;
}

void Font::layout(std::string_view text, TextSize size, float x, float baseline, std::vector<GlyphQuad>& out) const {
  const Face& f = face(size);
  // Glyphs land on whole pixels so that each atlas texel maps to one pixel and stays crisp.
  float pen = std::round(x);
  const float base = std::round(baseline);
  for (char c : text) {
    const Baked& g = glyph(f, c);
    if (g.x1 > g.x0) {
      const float x0 = std::round(pen + g.xoff);
      const float y0 = std::round(base + g.yoff);
      out.push_back({x0, y0, x0 + (g.x1 - g.x0), y0 + (g.y1 - g.y0), float(g.x0) / kAtlasWidth,
                     float(g.y0) / kAtlasHeight, float(g.x1) / kAtlasWidth, float(g.y1) / kAtlasHeight});
    }
    pen += g.xadvance;
  }
}

}  // namespace lienewton::render
