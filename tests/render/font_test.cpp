#include <gtest/gtest.h>

#include <string>

#include "core/options.hpp"
#include "core/vocabulary.hpp"
#include "render/font.hpp"
#include "render/options.hpp"

namespace lienewton::render {
namespace {

TEST(Font, DecodesUtf8AndMarksMalformedBytes) {
  EXPECT_EQ(decode_utf8("log\u2082 h"), (std::u32string{U'l', U'o', U'g', U'\u2082', U' ', U'h'}));
  EXPECT_EQ(decode_utf8("\u2016f\u2016 \u2248 1\u00b7"), (std::u32string{0x2016, U'f', 0x2016, U' ', 0x2248, U' ', U'1', 0xB7}));
  EXPECT_EQ(decode_utf8("a\xE2\x82"), (std::u32string{U'a', 0xFFFD, 0xFFFD}));  // cut short
  EXPECT_EQ(decode_utf8("\xC0\xAF"), (std::u32string{0xFFFD, 0xFFFD}));         // overlong '/'
}

// The default font (DejaVu Sans) has every extra glyph; anything else falls back to '?'.
TEST(Font, HasTheMathematicalGlyphsAndFallsBackToAQuestionMark) {
  const Font& font = Font::instance();
  for (char32_t c : kExtraCodepoints) EXPECT_TRUE(font.has_glyph(c)) << std::hex << static_cast<unsigned>(c);
  EXPECT_FALSE(font.has_glyph(U'\u4e2d'));
  EXPECT_EQ(font.width("\u4e2d", TextSize::small), font.width("?", TextSize::small));
  // A subscript is its own glyph, narrower than the digit.
  EXPECT_LT(font.width("\u2082", TextSize::small), font.width("2", TextSize::small));
  EXPECT_EQ(font.width("log\u2082 h", TextSize::small),
            font.width("log", TextSize::small) + font.width("\u2082", TextSize::small) + font.width(" h", TextSize::small));
}

// The labels that PNG captions and legends print (a method's, an integrator's, a colour metric's) have a glyph
// for every character: "Crouch–Grossman" is not drawn as "Crouch?Grossman".
TEST(Font, EveryCaptionLabelIsDrawnWithItsOwnGlyphs) {
  const Font& font = Font::instance();
  const auto drawable = [&](std::string_view label) {
    for (char32_t c : decode_utf8(label))
      if (!font.has_glyph(c)) return false;
    return true;
  };
  for (Method m : kAllMethods) EXPECT_TRUE(drawable(words(m).label)) << words(m).label;
  for (Integrator i : kAllIntegrators) EXPECT_TRUE(drawable(words(i).label)) << words(i).label;
  for (Differential d : kAllDifferentials) EXPECT_TRUE(drawable(words(d).label)) << words(d).label;
  for (HeatmapMetric h : kAllHeatmapMetrics) EXPECT_TRUE(drawable(words(h).label)) << words(h).label;
}

}  // namespace
}  // namespace lienewton::render
