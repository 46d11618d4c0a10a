// Raster canvas: which pixels a line, a dash pattern, a marker, a rectangle and
// text paint, counted against the geometry (pixel centres within thickness/2).
#include <gtest/gtest.h>

#include "sheetgen/report/raster_canvas.hpp"

namespace sheetgen {
namespace {

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kInk{10, 20, 30};

int count(const RasterCanvas& c, Rgb colour) {
  int n = 0;
  for (int y = 0; y < c.height_px(); ++y)
    for (int x = 0; x < c.width_px(); ++x) n += c.image().at(x, y) == colour;
  return n;
}

TEST(RasterCanvas, OnePixelLineThroughPixelCentresPaintsOneRow) {
  RasterCanvas c(40, 30, kWhite);
  c.line(2.5, 10.5, 20.5, 10.5, kInk);
  EXPECT_EQ(count(c, kInk), 19);  // x = 2..20 of row 10
  for (int x = 2; x <= 20; ++x) EXPECT_EQ(c.image().at(x, 10), kInk) << x;
  EXPECT_EQ(c.image().at(1, 10), kWhite);
  EXPECT_EQ(c.image().at(21, 10), kWhite);
}

TEST(RasterCanvas, ThickLinePaintsThicknessRows) {
  RasterCanvas c(40, 40, kWhite);
  c.line(5.5, 20.5, 30.5, 20.5, kInk, {5.0});
  // Rows whose centre is within 2.5 px of y = 20.5: 18..22.
  for (int y = 15; y <= 25; ++y) EXPECT_EQ(c.image().at(15, y) == kInk, y >= 18 && y <= 22) << y;
  // A vertical thick line is the transpose.
  RasterCanvas v(40, 40, kWhite);
  v.line(20.5, 5.5, 20.5, 30.5, kInk, {5.0});
  for (int x = 15; x <= 25; ++x) EXPECT_EQ(v.image().at(x, 15) == kInk, x >= 18 && x <= 22) << x;
}

TEST(RasterCanvas, DiagonalLineHasNoHoles) {
  RasterCanvas c(50, 50, kWhite);
  c.line(0.5, 0.5, 40.5, 30.5, kInk);
  // Every column the segment crosses has a painted pixel within a pixel of the line.
  for (int x = 0; x <= 40; ++x) {
    const double y = 0.5 + (x + 0.5 - 0.5) * 30.0 / 40.0;
    bool hit = false;
    for (int j = static_cast<int>(y) - 1; j <= static_cast<int>(y) + 1; ++j) hit = hit || (j >= 0 && c.image().at(x, j) == kInk);
    EXPECT_TRUE(hit) << x;
  }
}

TEST(RasterCanvas, DashedLineFollowsThePattern) {
  RasterCanvas c(120, 12, kWhite);
  c.line(0.5, 5.5, 100.5, 5.5, kInk, {1.0, 6.0, 4.0});
  // Dash k spans x = 10k .. 10k + 6 (centres within half a pixel of [10k + 0.5, 10k + 6.5]).
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(c.image().at(10 * k + 3, 5), kInk) << k;
    EXPECT_EQ(c.image().at(10 * k + 8, 5), kWhite) << k;
  }
  EXPECT_EQ(count(c, kInk), 10 * 7);  // ten dashes of 7 px
}

TEST(RasterCanvas, FillRectIsHalfOpenAndClipped) {
  RasterCanvas c(10, 10, kWhite);
  c.fill_rect(-5, -5, 3, 2, kInk);
  EXPECT_EQ(count(c, kInk), 6);
  c.fill_rect(8, 8, 20, 20, kInk);
  EXPECT_EQ(count(c, kInk), 10);
}

TEST(RasterCanvas, FilledCircleCountsLatticePoints) {
  RasterCanvas c(30, 30, kWhite);
  c.marker(10.5, 10.5, MarkerShape::FilledCircle, 3.0, kInk);
  EXPECT_EQ(count(c, kInk), 29);  // integer (i, j) with i^2 + j^2 <= 9 (Gauss circle problem, r = 3)
  RasterCanvas h(30, 30, kWhite);
  h.marker(10.5, 10.5, MarkerShape::HollowCircle, 5.0, kInk);
  EXPECT_EQ(h.image().at(10, 10), kWhite);  // hollow
  EXPECT_EQ(h.image().at(15, 10), kInk);    // on the ring
}

TEST(RasterCanvas, TextPaintsTheGlyphsInsideItsBox) {
  RasterCanvas c(60, 30, kWhite);
  c.text(3, 4, "1", kInk);
  // '1' is "..#.. .##.. ..#.." in its top rows.
  EXPECT_EQ(c.image().at(3 + 2, 4 + 0), kInk);
  EXPECT_EQ(c.image().at(3 + 1, 4 + 0), kWhite);
  EXPECT_EQ(c.image().at(3 + 1, 4 + 1), kInk);
  EXPECT_EQ(c.image().at(3 + 2, 4 + 2), kInk);

  RasterCanvas s(80, 40, kWhite);
  const int w = RasterCanvas::text_width_px("0.5", 2), h = RasterCanvas::text_height_px(2);
  EXPECT_EQ(w, (3 * 6 - 1) * 2);
  EXPECT_EQ(h, 18);
  s.text(5, 6, "0.5", kInk, {2});
  int min_x = 1000, max_x = -1, min_y = 1000, max_y = -1;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 80; ++x)
      if (s.image().at(x, y) == kInk) {
        min_x = std::min(min_x, x), max_x = std::max(max_x, x);
        min_y = std::min(min_y, y), max_y = std::max(max_y, y);
      }
  EXPECT_EQ(min_x, 5);          // '0' has its left column lit
  EXPECT_EQ(max_x, 5 + w - 1);  // '5' has its right column lit (top row "#####")
  EXPECT_EQ(min_y, 6);
  EXPECT_EQ(max_y, 6 + 7 * 2 - 1);  // no descenders: 7 rows of 2 px
}

TEST(RasterCanvas, AlignmentMovesTheBox) {
  RasterCanvas c(60, 30, kWhite);
  c.text(30, 20, "-", kInk, {1, HAlign::Right, VAlign::Bottom});
  // '-' is row 3, columns 1..3 of a 5 x 9 box ending at (30, 20).
  for (int x = 26; x <= 28; ++x) EXPECT_EQ(c.image().at(x, 20 - 9 + 3), kInk) << x;
  EXPECT_EQ(count(c, kInk), 3);
}

TEST(RasterCanvas, VerticalTextReadsBottomToTop) {
  RasterCanvas c(30, 30, kWhite);
  TextStyle st;
  st.vertical = true;
  c.text(0, 0, "AB", kInk, st);
  // Box 9 wide, 11 tall. 'A' row 0 ".###." lies in column 0, its columns 1..3 at y = 11 - 2 .. 11 - 4.
  EXPECT_EQ(c.image().at(0, 9), kInk);
  EXPECT_EQ(c.image().at(0, 8), kInk);
  EXPECT_EQ(c.image().at(0, 7), kInk);
  EXPECT_EQ(c.image().at(0, 10), kWhite);
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 30; ++x)
      if (c.image().at(x, y) == kInk) {
        EXPECT_LT(x, 9);
        EXPECT_LT(y, 11);
      }
}

TEST(RasterCanvas, RefusesABadSize) {
  EXPECT_THROW(RasterCanvas(0, 10, kWhite), std::invalid_argument);
  EXPECT_THROW(RasterCanvas(10, 70000, kWhite), std::invalid_argument);
}

}  // namespace
}  // namespace sheetgen
