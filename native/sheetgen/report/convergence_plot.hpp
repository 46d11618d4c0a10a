#pragma once
// Convergence plot of one load's beam search (paper Fig. 8): three panels
// sharing the x axis (beam-search iteration or candidates evaluated) -- best
// flat-pattern area (cm²), its compliance (J) against the load's limit, and its
// margin of safety against the required one. Points where no valid part had
// been found yet are not plotted as values; a grey cross on each panel's
// bottom edge marks them.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sheetgen/report/rgb_image.hpp"

namespace sheetgen {

struct ConvergencePoint {
  int iteration = 0;            // beam-search level (segments per candidate)
  int evaluated = 0;            // candidates evaluated so far
  bool found = false;           // a valid part exists so far; the values below are meaningless otherwise
  double best_area_m2 = 0;      // m², flat-pattern area of the best part so far
  double compliance_J = 0;      // J, of the best part so far
  double margin_of_safety = 0;  // -, of the best part so far
};

struct ConvergenceHistory {
  std::string load;                                                     // shown in the title
  std::vector<ConvergencePoint> points;                                 // in search order
  double compliance_limit_J = std::numeric_limits<double>::quiet_NaN();  // dashed line when finite
  double min_margin_of_safety = std::numeric_limits<double>::quiet_NaN();  // dashed line when finite
};

enum class ConvergenceXAxis { Iteration, CandidatesEvaluated };

struct ConvergencePlotOptions {
  int width_px = 900;             // whole image
  int height_px = 1000;
  ConvergenceXAxis x_axis = ConvergenceXAxis::Iteration;
  int font_scale = 2;             // px per font pixel for labels and ticks (the font is 5 x 7)
  int title_font_scale = 3;       // px per font pixel for the title
  double line_thickness_px = 3;   // curves
  double marker_radius_px = 6;    // points of the curves
  int target_ticks = 5;           // about this many ticks per axis (1-2-5 steps)
};

// Where a panel's data area is on the image and which values its edges stand
// for: a value (x, y) lands at px_x = left_px + (x - x_min) / (x_max - x_min) *
// (right_px - left_px) and px_y = bottom_px - (y - y_min) / (y_max - y_min) *
// (bottom_px - top_px), in the canvas convention of raster_canvas.hpp.
struct ConvergencePanel {
  std::string y_label;
  double left_px = 0, right_px = 0, top_px = 0, bottom_px = 0;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  int plotted_points = 0;   // points drawn with a value (found and finite)
  int not_found_points = 0; // points drawn as "nothing found yet"
};

struct ConvergencePlot {
  RgbImage image;
  std::vector<ConvergencePanel> panels;  // area, compliance, margin of safety, top to bottom
};

// Colours, so tests and callers can find what was drawn.
struct ConvergencePlotColours {
  static constexpr Rgb area{31, 119, 180};
  static constexpr Rgb compliance{230, 110, 0};
  static constexpr Rgb margin{44, 150, 44};
  static constexpr Rgb limit{214, 39, 40};
  static constexpr Rgb not_found{150, 150, 150};
};

// Throws std::invalid_argument naming the option when the size is below 320 x 360
// px or above 8192 on a side, a font scale is outside 1..8, or target_ticks outside 2..20.
ConvergencePlot draw_convergence_plot(const ConvergenceHistory& history, const ConvergencePlotOptions& options = {});

}  // namespace sheetgen
