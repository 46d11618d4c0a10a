#pragma once
// A pixel canvas for simple charts: thick and dashed lines, filled rectangles,
// markers and bitmap-font text (bitmap_font.hpp), no anti-aliasing, so a test
// can predict every pixel. Coordinates are in px, x to the right and y down
// from the top-left corner; pixel (i, j) covers [i, i+1) x [j, j+1), so its
// centre is (i + 0.5, j + 0.5). Drawing outside the canvas is clipped.
#include <string>

#include "sheetgen/report/rgb_image.hpp"

namespace sheetgen {

struct LineStyle {
  double thickness_px = 1.0;  // pixels whose centre lies within thickness/2 of the segment are painted
  double dash_px = 0.0;       // > 0: dashed, painted dash_px then gap_px along the line
  double gap_px = 0.0;
};

enum class MarkerShape { FilledCircle, HollowCircle, Cross, FilledSquare };

enum class HAlign { Left, Center, Right };
enum class VAlign { Top, Middle, Bottom };  // Bottom = baseline-free cell bottom (descenders included)

struct TextStyle {
  int scale = 1;              // each font pixel becomes scale x scale px
  HAlign h_align = HAlign::Left;
  VAlign v_align = VAlign::Top;
  bool vertical = false;      // rotated 90 deg counter-clockwise (reads bottom to top); alignment applies to the rotated box
};

class RasterCanvas {
 public:
  // Throws std::invalid_argument naming the field unless 1 <= width_px, height_px <= 65536.
  RasterCanvas(int width_px, int height_px, Rgb background);

  int width_px() const { return image_.width_px; }
  int height_px() const { return image_.height_px; }
  const RgbImage& image() const { return image_; }

  void set_pixel(int x, int y, Rgb colour);
  // Pixels x0 <= i < x1, y0 <= j < y1.
  void fill_rect(int x0, int y0, int x1, int y1, Rgb colour);
  void line(double x0, double y0, double x1, double y1, Rgb colour, const LineStyle& style = {});
  // Centred on (x, y); radius_px is the circle radius or the half side of the square and cross.
  void marker(double x, double y, MarkerShape shape, double radius_px, Rgb colour);
  // Text anchored at (x, y) by the style's alignment; '\n' is not interpreted.
  void text(int x, int y, const std::string& utf8, Rgb colour, const TextStyle& style = {});

  // Size of text's box before rotation: advance * n - 1 spacing column, times scale; 9 rows times scale.
  static int text_width_px(const std::string& utf8, int scale = 1);
  static int text_height_px(int scale = 1);

 private:
  void solid_line(double x0, double y0, double x1, double y1, Rgb colour, double thickness_px);
  RgbImage image_;
};

}  // namespace sheetgen
