#include "sheetgen/report/dimension_line.hpp"

#include <cmath>

#include "sheetgen/report/sheet_pen.hpp"

namespace sheetgen::sheet {
namespace {

// A filled arrowhead with its tip at (x, y), pointing along (dx, dy) (unit).
void arrowhead(cairo_t* cr, double x, double y, double dx, double dy, const DimensionStyle& s) {
  const double bx = x - s.arrow_length * dx, by = y - s.arrow_length * dy;
  const double nx = -dy * s.arrow_width / 2, ny = dx * s.arrow_width / 2;
  cairo_move_to(cr, x, y);
  cairo_line_to(cr, bx + nx, by + ny);
  cairo_line_to(cr, bx - nx, by - ny);
  cairo_close_path(cr);
  cairo_fill(cr);
}

}  // namespace

void draw_dimension(cairo_t* cr, double px, double py, double qx, double qy, bool horizontal, double offset,
                    const std::string& value, const DimensionStyle& style) {
  set_ink(cr, kBlack);
  set_dash(cr, {});
  const double sign = offset >= 0 ? 1 : -1;
  if (horizontal) {
    const double y = py + offset;  // the dimension line
    draw_line(cr, px, py + sign * style.gap, px, y + sign * style.overshoot, kThin);
    draw_line(cr, qx, qy + sign * style.gap, qx, y + sign * style.overshoot, kThin);
    draw_line(cr, px, y, qx, y, kThin);
    const double d = qx >= px ? 1 : -1;
    arrowhead(cr, px, y, -d, 0, style);
    arrowhead(cr, qx, y, d, 0, style);
    set_text_height(cr, style.text_height);
    draw_text(cr, (px + qx) / 2, y - 1.0, value, 0.5, 1);
  } else {
    const double x = px + offset;
    draw_line(cr, px + sign * style.gap, py, x + sign * style.overshoot, py, kThin);
    draw_line(cr, qx + sign * style.gap, qy, x + sign * style.overshoot, qy, kThin);
    draw_line(cr, x, py, x, qy, kThin);
    const double d = qy >= py ? 1 : -1;
    arrowhead(cr, x, py, 0, -d, style);
    arrowhead(cr, x, qy, 0, d, style);
    set_text_height(cr, style.text_height);
    // Read from the right of the sheet: rotated a quarter turn counter-clockwise, left of the line.
    draw_text(cr, x - 1.0, (py + qy) / 2, value, 0.5, 1, M_PI / 2);
  }
}

}  // namespace sheetgen::sheet
