#pragma once
// Labels are drawn from a glyph atlas baked once per process with stb_truetype from a TrueType font
// (DejaVu Sans by default, see LIENEWTON_FONT). Text is UTF-8: printable ASCII plus the few mathematical
// characters in kExtraCodepoints (sub- and superscript digits, ‖, −, ≈, dashes, ...); anything else prints as '?'.
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

namespace lienewton::render {

enum class TextSize { small, large };

struct GlyphQuad {
  float x0, y0, x1, y1;  // pixels, top-down
  float u0, v0, u1, v1;  // atlas texture coordinates
};

// Beyond ASCII, sorted: ² ³ µ · ¹ × π ᵀ ᵏ – — ‖ … ⁰ ⁴-⁹ ⁻ ₀-₉ ₙ − ≈ ≠ ≤ ≥.
inline constexpr char32_t kExtraCodepoints[] = {
    0x00B2, 0x00B3, 0x00B5, 0x00B7, 0x00B9, 0x00D7, 0x03C0, 0x1D40, 0x1D4F, 0x2013, 0x2014, 0x2016, 0x2026, 0x2070,
    0x2074, 0x2075, 0x2076, 0x2077, 0x2078, 0x2079, 0x207B, 0x2080, 0x2081, 0x2082, 0x2083, 0x2084, 0x2085, 0x2086,
    0x2087, 0x2088, 0x2089, 0x2099, 0x2212, 0x2248, 0x2260, 0x2264, 0x2265};

// The code points of UTF-8 text; a malformed byte becomes U+FFFD (which prints as '?').
std::u32string decode_utf8(std::string_view text);

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
  float em_size(TextSize size) const;     // the font size a vector copy (SVG) gives for the same glyph sizes
  float width(std::string_view text, TextSize size) const;
  // Whether the atlas holds a glyph of the font for c (else c prints as '?').
  bool has_glyph(char32_t c) const;
  // Appends one quad per visible glyph for text whose pen starts at (x, baseline).
  void layout(std::string_view text, TextSize size, float x, float baseline, std::vector<GlyphQuad>& out) const;

 private:
  static constexpr int kAtlasWidth = 512;
  static constexpr int kAtlasHeight = 256;
  static constexpr int kFirstChar = 32;
  static constexpr int kAsciiCount = 95;
  static constexpr int kGlyphCount = kAsciiCount + static_cast<int>(std::size(kExtraCodepoints));
  struct Baked {
    std::uint16_t x0, y0, x1, y1;
    float xoff, yoff, xadvance;
  };
  struct Face {
    float pixel_height = 0;
    float cap_height = 0;
    float em_size = 0;
    Baked chars[kGlyphCount];  // ASCII from kFirstChar, then kExtraCodepoints
  };
  Font();
  const Face& face(TextSize size) const { return size == TextSize::small ? small_ : large_; }
  // Index into Face::chars: c's glyph, or '?''s when the atlas or the font lacks c.
  int glyph_index(char32_t c) const;

  std::vector<std::uint8_t> atlas_;
  std::vector<bool> in_font_;  // per glyph index: the font has a glyph for it
  Face small_;
  Face large_;
};

}  // namespace lienewton::render
