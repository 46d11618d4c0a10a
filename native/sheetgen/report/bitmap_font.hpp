#pragma once
// A small built-in bitmap font (drawn for this project): 5 x 7 px capitals and
// digits, lower case with 2-row descenders, the punctuation plots need, and a
// superscript two so units can read "cm²". Cells are 5 px wide and 9 px tall
// (rows 0-6 above the baseline, 7-8 descenders); characters advance 6 px.
#include <array>
#include <cstdint>
#include <string>

namespace sheetgen {

struct BitmapFontMetrics {
  static constexpr int glyph_width_px = 5;
  static constexpr int glyph_height_px = 9;  // cell height, descenders included
  static constexpr int cap_height_px = 7;    // rows 0..6 sit on the baseline
  static constexpr int advance_px = 6;       // glyph plus one column of spacing
};

struct Glyph {
  std::array<std::uint8_t, BitmapFontMetrics::glyph_height_px> rows{};  // bit 4 = leftmost column
  bool lit(int column, int row) const { return (rows[row] >> (BitmapFontMetrics::glyph_width_px - 1 - column)) & 1; }
};

bool font_has_glyph(char32_t code_point);
// The glyph of a code point; a hollow box for one the font lacks, so a missing
// character shows instead of vanishing.
const Glyph& font_glyph(char32_t code_point);

// UTF-8 to code points; a malformed byte becomes U+FFFD (drawn as the box).
std::u32string decode_utf8(const std::string& text);

}  // namespace sheetgen
