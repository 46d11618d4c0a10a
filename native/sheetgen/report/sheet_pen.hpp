#pragma once
// Text and lines on a drawing sheet, in millimetres on the paper (y down), on
// a cairo context whose user unit is the millimetre. Internal to the report:
// only its sources include cairo (docs/code-style.md point 5).
#include <cairo.h>

#include <initializer_list>
#include <string>

namespace sheetgen::sheet {

struct Ink {
  double r = 0, g = 0, b = 0;  // 0..1
};

constexpr Ink kBlack{0, 0, 0};
constexpr Ink kGrey{0.45, 0.45, 0.45};
constexpr Ink kUp{0.80, 0.0, 0.0};     // bend up: red, as on flat.dxf's BEND_UP layer
constexpr Ink kDown{0.0, 0.20, 0.85};  // bend down: blue, as on BEND_DOWN

// ISO 128 line widths, mm.
constexpr double kThick = 0.5;   // visible outlines, the frame
constexpr double kMedium = 0.35; // bend lines, holes
constexpr double kThin = 0.18;   // dimension and extension lines, centre marks, table rules

void set_ink(cairo_t* cr, Ink ink);

// The font (DejaVu Sans) sized so that a capital is cap_mm high.
void set_text_height(cairo_t* cr, double cap_mm, bool bold = false);
double text_width(cairo_t* cr, const std::string& s);  // mm, in the current font

// Draws s with the point (ax, ay) of its box at (x, y): ax 0 / 0.5 / 1 is the
// left / centre / right end, ay 0 / 0.5 / 1 the top / middle / foot of a
// capital; rotated by rotation_rad (counter-clockwise on the paper) about (x, y).
void draw_text(cairo_t* cr, double x, double y, const std::string& s, double ax, double ay, double rotation_rad = 0);

// Sets the text height to cap_mm, or smaller so that s fits max_width_mm.
void fit_text(cairo_t* cr, const std::string& s, double cap_mm, double max_width_mm, bool bold = false);

void draw_line(cairo_t* cr, double x0, double y0, double x1, double y1, double width_mm);

// A dash pattern in mm ({} = solid).
void set_dash(cairo_t* cr, std::initializer_list<double> on_off_mm);

}  // namespace sheetgen::sheet
