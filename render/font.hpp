#pragma once
// Labels are drawn from a glyph atlas baked once per process with stb_truetype from a TrueType font
// (DejaVu Sans by default, see LIENEWTON_FONT). Printable ASCII only; anything else prints as '?'.
#include <cstdint>
#include <string_view>
#include <vector>

namespace lienewton::render {

enum class TextSize { small, large };

struct GlyphQuad {
  float x0, y0, x1, y1;  // pixels, top-down
  float u0, v0, u1, v1;  // atlas texture coordinates
};

class Font {
 public:
  // The process-wide font; throws RenderUnavailable if the font file cannot be read or parsed.
  static const Font& instance();

  int atlas_width() const { return kAtlasWidth; }
  int atlas_height() const { return kAtlasHeight; }
  const std::vector<std::uint8_t>& atlas() const { return atlas_; }  // one coverage byte per texel
  // Texture coordinates of a fully covered texel block: solid shapes sample it, so one shader draws all.
  float solid_u() const { return (kAtlasWidth - 2.0f) / kAtlasWidth; }
  float solid_v() const { return (kAtlasHeight - 2.0f) / kAtlasHeight; }

  float pixel_height(TextSize size) const;
  float cap_height(TextSize size) const;  // height of 'H' above the baseline, for centering
  float width(std::string_view text, TextSize size) const;
  // Appends one quad per visible glyph for text whose pen starts at (x, baseline).
  void layout(std::string_view text, TextSize size, float x, float baseline, std::vector<GlyphQuad>& out) const;

 private:
  static constexpr int kAtlasWidth = 512;
  static constexpr int kAtlasHeight = 256;
  static constexpr int kFirstChar = 32;
  static constexpr int kCharCount = 95;
  struct Baked {
    std::uint16_t x0, y0, x1, y1;
    float xoff, yoff, xadvance;
  };
  struct Face {
    float pixel_height = 0;
    float cap_height = 0;
    Baked chars[kCharCount];
  };
  Font();
  const Face& face(TextSize size) const { return size == TextSize::small ? small_ : large_; }
  static const Baked& glyph(const Face& face, char c);

  std::vector<std::uint8_t> atlas_;
  Face small_;
  Face large_;
};

}  // namespace lienewton::render
