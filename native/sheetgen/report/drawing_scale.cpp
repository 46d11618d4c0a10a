#include "sheetgen/report/drawing_scale.hpp"

#include <cmath>
#include <stdexcept>

namespace sheetgen {

int drawing_scale_denominator(double width_m, double height_m, double box_width_mm, double box_height_mm) {
  if (!(std::isfinite(width_m) && width_m >= 0 && std::isfinite(height_m) && height_m >= 0))
    throw std::invalid_argument("drawing scale: the part's size " + std::to_string(width_m) + " x " +
                                std::to_string(height_m) + " m is not a finite non-negative size");
  if (!(box_width_mm > 0 && box_height_mm > 0 && std::isfinite(box_width_mm) && std::isfinite(box_height_mm)))
    throw std::invalid_argument("drawing scale: the view box " + std::to_string(box_width_mm) + " x " +
                                std::to_string(box_height_mm) + " mm has no room");
  const int steps[] = {1, 2, 5};
  for (long decade = 1; decade <= 100000000L; decade *= 10)
    for (int s : steps) {
      const long n = s * decade;
      if (width_m * 1e3 / n <= box_width_mm && height_m * 1e3 / n <= box_height_mm) return static_cast<int>(n);
    }
  throw std::invalid_argument("drawing scale: a part of " + std::to_string(width_m) + " x " + std::to_string(height_m) +
                              " m does not fit the view at 1:500000000");
}

std::string scale_label(int denominator) { return "1:" + std::to_string(denominator); }

}  // namespace sheetgen
