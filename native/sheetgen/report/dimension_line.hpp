#pragma once
// A linear dimension on a drawing sheet (ISO 129-1): extension lines from the
// two measured points, a dimension line between them with filled arrowheads,
// the value above it (reading from the bottom or the right of the sheet).
// mm on the paper, y down; internal to the report (it draws with cairo).
#include <cairo.h>

#include <string>

namespace sheetgen::sheet {

struct DimensionStyle {
  double text_height = 3.5;   // mm, capitals of the value (ISO 129: 3.5 mm on A3)
  double arrow_length = 3.0;  // mm
  double arrow_width = 1.0;   // mm, at the arrow's base
  double gap = 1.0;           // mm between the measured point and the extension line's start
  double overshoot = 2.0;     // mm the extension lines run past the dimension line
};

// Dimensions the distance from p to q along the horizontal (horizontal = true,
// measuring |q.x - p.x|) or the vertical, with the dimension line `offset` mm
// from p (down or right for a positive offset) and `value` as its text.
void draw_dimension(cairo_t* cr, double px, double py, double qx, double qy, bool horizontal, double offset,
                    const std::string& value, const DimensionStyle& style = {});

}  // namespace sheetgen::sheet
