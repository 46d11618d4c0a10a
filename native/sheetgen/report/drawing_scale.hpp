#pragma once
// The scale of a drawing's view: the largest ISO 5455 reduction (1:1, 1:2,
// 1:5, 1:10, 1:20, 1:50, ... the 1-2-5 series) at which a part fits its box
// on the paper. A shop can then lay a rule on the print, and at 1:1 use it as a
// template. Enlargements (2:1, 5:1) are left out on purpose: a flat pattern is
// cut at 1:1, and a sheet that shows it larger invites measuring it wrong.
#include <string>

namespace sheetgen {

// Denominator n of the scale 1:n: the smallest n of 1, 2, 5, 10, 20, 50, ...
// with width_m * 1000 / n <= box_width_mm and height_m * 1000 / n <= box_height_mm.
// Throws std::invalid_argument when a size is negative or not finite, or a box
// side is not positive.
int drawing_scale_denominator(double width_m, double height_m, double box_width_mm, double box_height_mm);

// "1:1", "1:2", ...
std::string scale_label(int denominator);

}  // namespace sheetgen
