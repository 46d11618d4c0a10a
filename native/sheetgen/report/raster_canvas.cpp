#include "sheetgen/report/raster_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sheetgen/report/bitmap_font.hpp"

namespace sheetgen {
namespace {

constexpr int kMaxSidePx = 1 << 16;

// Squared distance from point p to segment ab, all in px.
double distance2_to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const double qx = ax + t * dx - px, qy = ay + t * dy - py;
  return qx * qx + qy * qy;
}

}  // namespace

RasterCanvas::RasterCanvas(int width_px, int height_px, Rgb background) {
  if (width_px < 1 || width_px > kMaxSidePx)
    throw std::invalid_argument("RasterCanvas: width_px " + std::to_string(width_px) + " is not in 1..65536");
  if (height_px < 1 || height_px > kMaxSidePx)
    throw std::invalid_argument("RasterCanvas: height_px " + std::to_string(height_px) + " is not in 1..65536");
  image_ = RgbImage(width_px, height_px, background);
}

void RasterCanvas::set_pixel(int x, int y, Rgb colour) {
  if (image_.contains(x, y)) image_.set(x, y, colour);
}

void RasterCanvas::fill_rect(int x0, int y0, int x1, int y1, Rgb colour) {
  x0 = std::max(x0, 0);
  y0 = std::max(y0, 0);
  x1 = std::min(x1, image_.width_px);
  y1 = std::min(y1, image_.height_px);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) image_.set(x, y, colour);
}

void RasterCanvas::solid_line(double x0, double y0, double x1, double y1, Rgb colour, double thickness_px) {
  const double half = std::max(thickness_px, 0.0) / 2.0;
  // Half a pixel at least, so a 1 px line through pixel centres leaves no holes.
  const double r = std::max(half, 0.5);
  const double r2 = r * r + 1e-9;
  const int xa = static_cast<int>(std::floor(std::min(x0, x1) - r)), xb = static_cast<int>(std::ceil(std::max(x0, x1) + r));
  const int ya = static_cast<int>(std::floor(std::min(y0, y1) - r)), yb = static_cast<int>(std::ceil(std::max(y0, y1) + r));
  for (int y = std::max(ya, 0); y <= std::min(yb, image_.height_px - 1); ++y)
    for (int x = std::max(xa, 0); x <= std::min(xb, image_.width_px - 1); ++x)
      if (distance2_to_segment(x + 0.5, y + 0.5, x0, y0, x1, y1) <= r2) image_.set(x, y, colour);
}

void RasterCanvas::line(double x0, double y0, double x1, double y1, Rgb colour, const LineStyle& style) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return;
  if (style.dash_px <= 0) {
    solid_line(x0, y0, x1, y1, colour, style.thickness_px);
    return;
  }
  const double length = std::hypot(x1 - x0, y1 - y0);
  if (length == 0) {
    solid_line(x0, y0, x1, y1, colour, style.thickness_px);
    return;
  }
  const double period = style.dash_px + std::max(style.gap_px, 0.0);
  for (double s = 0; s < length; s += period) {
    const double e = std::min(s + style.dash_px, length);
    const double ts = s / length, te = e / length;
    solid_line(x0 + ts * (x1 - x0), y0 + ts * (y1 - y0), x0 + te * (x1 - x0), y0 + te * (y1 - y0), colour,
               style.thickness_px);
  }
}

void RasterCanvas::marker(double x, double y, MarkerShape shape, double radius_px, Rgb colour) {
  if (!std::isfinite(x) || !std::isfinite(y) || radius_px <= 0) return;
  const double r = radius_px;
  switch (shape) {
    case MarkerShape::FilledCircle:
    case MarkerShape::HollowCircle: {
      const double inner = shape == MarkerShape::HollowCircle ? std::max(r - 1.5, 0.0) : -1.0;
      for (int j = static_cast<int>(std::floor(y - r)); j <= static_cast<int>(std::ceil(y + r)); ++j)
        for (int i = static_cast<int>(std::floor(x - r)); i <= static_cast<int>(std::ceil(x + r)); ++i) {
          const double d = std::hypot(i + 0.5 - x, j + 0.5 - y);
          if (d <= r && d >= inner) set_pixel(i, j, colour);
        }
      break;
    }
    case MarkerShape::FilledSquare:
      fill_rect(static_cast<int>(std::lround(x - r)), static_cast<int>(std::lround(y - r)),
                static_cast<int>(std::lround(x + r)), static_cast<int>(std::lround(y + r)), colour);
      break;
    case MarkerShape::Cross: {
      const LineStyle thick{2.0};
      line(x - r, y - r, x + r, y + r, colour, thick);
      line(x - r, y + r, x + r, y - r, colour, thick);
      break;
    }
  }
}

int RasterCanvas::text_width_px(const std::string& utf8, int scale) {
  const size_t n = decode_utf8(utf8).size();
  if (n == 0) return 0;
  return (static_cast<int>(n) * BitmapFontMetrics::advance_px - 1) * std::max(scale, 1);
}

int RasterCanvas::text_height_px(int scale) { return BitmapFontMetrics::glyph_height_px * std::max(scale, 1); }

void RasterCanvas::text(int x, int y, const std::string& utf8, Rgb colour, const TextStyle& style) {
  const int s = std::max(style.scale, 1);
  const std::u32string cps = decode_utf8(utf8);
  const int w = text_width_px(utf8, s), h = text_height_px(s);
  // The box as it appears on the canvas (rotated when vertical).
  const int box_w = style.vertical ? h : w, box_h = style.vertical ? w : h;
  int left = x, top = y;
  if (style.h_align == HAlign::Center) left = x - box_w / 2;
  if (style.h_align == HAlign::Right) left = x - box_w;
  if (style.v_align == VAlign::Middle) top = y - box_h / 2;
  if (style.v_align == VAlign::Bottom) top = y - box_h;
  for (size_t k = 0; k < cps.size(); ++k) {
    const Glyph& g = font_glyph(cps[k]);
    const int pen = static_cast<int>(k) * BitmapFontMetrics::advance_px;  // font px along the text
    for (int row = 0; row < BitmapFontMetrics::glyph_height_px; ++row)
      for (int col = 0; col < BitmapFontMetrics::glyph_width_px; ++col) {
        if (!g.lit(col, row)) continue;
        const int u = pen + col, v = row;  // font px in the unrotated text box
        // Rotated counter-clockwise: the text's x runs up the canvas, its rows run right.
        const int px = style.vertical ? left + v * s : left + u * s;
        const int py = style.vertical ? top + (w - (u + 1) * s) : top + v * s;
        fill_rect(px, py, px + s, py + s, colour);
      }
  }
}

}  // namespace sheetgen
