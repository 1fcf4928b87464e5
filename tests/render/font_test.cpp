#include <gtest/gtest.h>

#include "render/font.hpp"

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

}  // namespace
}  // namespace lienewton::render
