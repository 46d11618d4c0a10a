#include "sheetgen/report/sheet_pen.hpp"

#include <vector>

namespace sheetgen::sheet {

void set_ink(cairo_t* cr, Ink ink) { cairo_set_source_rgb(cr, ink.r, ink.g, ink.b); }

void set_text_height(cairo_t* cr, double cap_mm, bool bold) {
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  // DejaVu Sans' capitals are 0.729 em high (its OS/2 sCapHeight, 1493 of 2048 units).
  cairo_set_font_size(cr, cap_mm / 0.729);
}

double text_width(cairo_t* cr, const std::string& s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

void draw_text(cairo_t* cr, double x, double y, const std::string& s, double ax, double ay, double rotation_rad) {
  cairo_matrix_t font;
  cairo_get_font_matrix(cr, &font);
  const double cap = 0.729 * font.yy;  // the font size is font.yy mm
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, -rotation_rad);  // the paper's y points down: counter-clockwise is a negative cairo angle
  cairo_move_to(cr, -ax * text_width(cr, s), (1 - ay) * cap);
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

void fit_text(cairo_t* cr, const std::string& s, double cap_mm, double max_width_mm, bool bold) {
  set_text_height(cr, cap_mm, bold);
  const double w = text_width(cr, s);
  if (w > max_width_mm) set_text_height(cr, cap_mm * max_width_mm / w, bold);
}

void draw_line(cairo_t* cr, double x0, double y0, double x1, double y1, double width_mm) {
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  cairo_set_line_width(cr, width_mm);
  cairo_stroke(cr);
}

void set_dash(cairo_t* cr, std::initializer_list<double> on_off_mm) {
  const std::vector<double> d(on_off_mm);
  cairo_set_dash(cr, d.empty() ? nullptr : d.data(), static_cast<int>(d.size()), 0);
}

}  // namespace sheetgen::sheet
