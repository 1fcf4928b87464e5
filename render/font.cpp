#include "render/font.hpp"

#include <stb_truetype.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

#include "render/render_unavailable.hpp"

namespace lienewton::render {
namespace {

constexpr float kSmallPixels = 13.0f;
constexpr float kLargePixels = 15.0f;
constexpr int kSolidRows = 4;  // the solid block's rows at the bottom of the atlas, kept out of the packing

std::vector<unsigned char> read_font_file(const char* path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<unsigned char> bytes;
  if (in) bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (bytes.empty()) throw RenderUnavailable(std::string("cannot read the label font ") + path);
  return bytes;
}

// The length of the UTF-8 sequence a lead byte starts, 0 for a byte that cannot start one.
int sequence_length(unsigned char lead) {
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead < 0xE0) return 2;
  if (lead >= 0xE0 && lead < 0xF0) return 3;
  if (lead >= 0xF0 && lead < 0xF5) return 4;
  return 0;
}

}  // namespace

std::u32string decode_utf8(std::string_view text) {
  std::u32string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const int length = sequence_length(lead);
    bool valid = length > 0 && i + static_cast<std::size_t>(length) <= text.size();
    char32_t c = length == 1 ? lead : lead & (0x7F >> length);
    for (int k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
      valid = (next & 0xC0) == 0x80;
      c = (c << 6) | (next & 0x3F);
    }
    out.push_back(valid ? c : U'\uFFFD');
    i += valid ? static_cast<std::size_t>(length) : 1;
  }
  return out;
}

const Font& Font::instance() {
  static const Font font;  // a throwing initialiser is retried by the next caller
  return font;
}

Font::Font() : atlas_(static_cast<std::size_t>(kAtlasWidth) * kAtlasHeight, 0), in_font_(kGlyphCount, true) {
  std::vector<unsigned char> ttf = read_font_file(LIENEWTON_FONT_PATH);
  stbtt_fontinfo info;
  if (!stbtt_InitFont(&info, ttf.data(), stbtt_GetFontOffsetForIndex(ttf.data(), 0))) {
    throw RenderUnavailable(std::string("cannot parse the label font ") + LIENEWTON_FONT_PATH);
  }
  int cap_x0 = 0, cap_y0 = 0, cap_x1 = 0, cap_y1 = 0;
  stbtt_GetCodepointBox(&info, 'H', &cap_x0, &cap_y0, &cap_x1, &cap_y1);
  for (std::size_t k = 0; k < std::size(kExtraCodepoints); ++k) {
    in_font_[kAsciiCount + k] = stbtt_FindGlyphIndex(&info, static_cast<int>(kExtraCodepoints[k])) != 0;
  }

  // Both sizes, ASCII and the extra code points, packed into the rows above the solid block; one texel of
  // padding keeps neighbours from bleeding into a glyph.
  stbtt_pack_context pack;
  if (!stbtt_PackBegin(&pack, atlas_.data(), kAtlasWidth, kAtlasHeight - kSolidRows, kAtlasWidth, 1, nullptr)) {
    throw RenderUnavailable("cannot start packing the label font");
  }
  stbtt_PackSetOversampling(&pack, 1, 1);  // texel = pixel: glyphs are drawn on whole pixels, unscaled
  int extras[std::size(kExtraCodepoints)];
  std::copy(std::begin(kExtraCodepoints), std::end(kExtraCodepoints), extras);
  stbtt_packedchar packed[2][kGlyphCount];
  stbtt_pack_range ranges[4] = {};
  for (int s = 0; s < 2; ++s) {
    const float pixels = s == 0 ? kSmallPixels : kLargePixels;
    ranges[2 * s] = {pixels, kFirstChar, nullptr, kAsciiCount, packed[s], 0, 0};
    ranges[2 * s + 1] = {pixels, 0, extras, static_cast<int>(std::size(extras)), packed[s] + kAsciiCount, 0, 0};
  }
  const int ok = stbtt_PackFontRanges(&pack, ttf.data(), 0, ranges, 4);
  stbtt_PackEnd(&pack);
  if (!ok) throw RenderUnavailable("the label font does not fit its atlas");

  auto keep = [&](Face& face, float pixels, const stbtt_packedchar* chars) {
    face.pixel_height = pixels;
    face.cap_height = static_cast<float>(cap_y1) * stbtt_ScaleForPixelHeight(&info, pixels);
    face.em_size = stbtt_ScaleForPixelHeight(&info, pixels) / stbtt_ScaleForMappingEmToPixels(&info, 1);
    for (int i = 0; i < kGlyphCount; ++i) {
      const stbtt_packedchar& c = chars[i];
      face.chars[i] = {c.x0, c.y0, c.x1, c.y1, c.xoff, c.yoff, c.xadvance};
    }
  };
  keep(small_, kSmallPixels, packed[0]);
  keep(large_, kLargePixels, packed[1]);
  for (int y = kAtlasHeight - kSolidRows; y < kAtlasHeight; ++y) {
    for (int x = kAtlasWidth - 4; x < kAtlasWidth; ++x) atlas_[static_cast<std::size_t>(y) * kAtlasWidth + x] = 255;
  }
}

int Font::glyph_index(char32_t c) const {
  constexpr int kQuestionMark = '?' - kFirstChar;
  if (c >= kFirstChar && c < kFirstChar + kAsciiCount) return static_cast<int>(c) - kFirstChar;
  const auto* hit = std::lower_bound(std::begin(kExtraCodepoints), std::end(kExtraCodepoints), c);
  if (hit == std::end(kExtraCodepoints) || *hit != c) return kQuestionMark;
  const int index = kAsciiCount + static_cast<int>(hit - std::begin(kExtraCodepoints));
  return in_font_[static_cast<std::size_t>(index)] ? index : kQuestionMark;
}

bool Font::has_glyph(char32_t c) const { return c == U'?' || glyph_index(c) != '?' - kFirstChar; }

float Font::pixel_height(TextSize size) const { return face(size).pixel_height; }
float Font::cap_height(TextSize size) const { return face(size).cap_height; }
float Font::em_size(TextSize size) const { return face(size).em_size; }

float Font::width(std::string_view text, TextSize size) const {
  float w = 0;
  for (char32_t c : decode_utf8(text)) w += face(size).chars[glyph_index(c)].xadvance;
  return w;
}

void Font::layout(std::string_view text, TextSize size, float x, float baseline, std::vector<GlyphQuad>& out) const {
  const Face& f = face(size);
  // Glyphs land on whole pixels so that each atlas texel maps to one pixel and stays crisp.
  float pen = std::round(x);
  const float base = std::round(baseline);
  for (char32_t c : decode_utf8(text)) {
    const Baked& g = f.chars[glyph_index(c)];
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
