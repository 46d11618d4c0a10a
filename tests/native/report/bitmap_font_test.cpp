// Bitmap font: the characters the plots write exist, glyphs sit in their cell,
// UTF-8 decodes (including the superscript two of "cm²").
#include <gtest/gtest.h>

#include "sheetgen/report/bitmap_font.hpp"

namespace sheetgen {
namespace {

TEST(BitmapFont, HasEveryCharacterThePlotsUse) {
  const std::u32string needed = U"0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ .,:-+=_%()[]/\u00B2";
  for (char32_t c : needed) EXPECT_TRUE(font_has_glyph(c)) << static_cast<unsigned>(c);
  EXPECT_FALSE(font_has_glyph(U'\u20AC'));  // euro: not in the font
}

TEST(BitmapFont, GlyphsAreDistinctAndNonEmpty) {
  const std::u32string chars = U"0123456789abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ";
  for (size_t i = 0; i < chars.size(); ++i) {
    const Glyph& a = font_glyph(chars[i]);
    int lit = 0;
    for (int r = 0; r < BitmapFontMetrics::glyph_height_px; ++r) lit += __builtin_popcount(a.rows[r]);
    EXPECT_GT(lit, 4) << static_cast<char>(chars[i]);
    for (size_t j = i + 1; j < chars.size(); ++j)
      EXPECT_NE(a.rows, font_glyph(chars[j]).rows) << static_cast<char>(chars[i]) << " = " << static_cast<char>(chars[j]);
  }
}

TEST(BitmapFont, OnlyDescendersUseTheLowRows) {
  const std::u32string with = U"gjpqy,;_";
  for (char32_t c = 32; c < 127; ++c) {
    if (!font_has_glyph(c)) continue;
    const Glyph& g = font_glyph(c);
    const bool low = g.rows[7] || g.rows[8];
    EXPECT_EQ(low, with.find(c) != std::u32string::npos) << static_cast<char>(c);
  }
}

TEST(BitmapFont, MissingCharacterIsABox) {
  const Glyph& box = font_glyph(U'\u20AC');
  EXPECT_TRUE(box.lit(0, 0));
  EXPECT_TRUE(box.lit(4, 6));
  EXPECT_FALSE(box.lit(2, 3));
}

TEST(BitmapFont, DecodesUtf8) {
  EXPECT_EQ(decode_utf8("cm\xC2\xB2"), U"cm\u00B2");
  EXPECT_EQ(decode_utf8("a\xFF" "b"), U"a\uFFFD" "b");
  EXPECT_EQ(decode_utf8("\xC2"), U"\uFFFD");  // truncated sequence
  EXPECT_EQ(decode_utf8("\xE2\x82\xAC"), U"\u20AC");
}

}  // namespace
}  // namespace sheetgen
