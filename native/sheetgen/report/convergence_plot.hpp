#pragma once
// Convergence plot of one load's beam search (paper Fig. 8), written as a PNG.
// Three panels share the x axis (beam-search iteration or candidates
// evaluated): best flat-pattern area (cm²), its compliance (J) against the
// load's limit, and its margin of safety against the required one, with the
// feasible side of each limit shaded. A point where no valid part had been
// found yet carries no value; a grey cross on its panel's bottom edge marks it.
// Drawn with cairo, which only convergence_plot.cpp sees (docs/code-style.md point 5).
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

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
  std::string load;                                                        // shown in the title
  std::vector<ConvergencePoint> points;                                    // in search order
  double compliance_limit_J = std::numeric_limits<double>::quiet_NaN();    // J, dashed line when finite
  double min_margin_of_safety = std::numeric_limits<double>::quiet_NaN();  // -, dashed line when finite
};

enum class ConvergenceXAxis { Iteration, CandidatesEvaluated };

struct ConvergenceOptions {
  int width_px = 900;            // whole image, 320..8192
  int height_px = 1000;          // 360..8192
  ConvergenceXAxis x_axis = ConvergenceXAxis::Iteration;
  double font_size_px = 15;      // labels and tick labels, 6..72; the title is 1.5 times larger
  double line_width_px = 3;      // curves, (0, 50]
  double marker_radius_px = 6;   // points of the curves, 0..50
  int target_ticks = 5;          // about this many ticks per axis (1-2-5 steps), 2..20
};

// Where a panel's data area is on the image and which values its edges stand
// for: a value (x, y) lands at px_x = left_px + (x - x_min) / (x_max - x_min) *
// (right_px - left_px) and px_y = bottom_px - (y - y_min) / (y_max - y_min) *
// (bottom_px - top_px), in px from the image's top-left corner (pixel (i, j)
// covers [i, i+1) x [j, j+1)).
struct ConvergencePanel {
  std::string y_label;
  double left_px = 0, right_px = 0, top_px = 0, bottom_px = 0;
  double x_min = 0, x_max = 1, y_min = 0, y_max = 1;
  int plotted_points = 0;    // points drawn with a value (found and finite)
  int not_found_points = 0;  // points drawn as "nothing found yet"
};

struct ConvergencePlotLayout {
  int width_px = 0, height_px = 0;
  std::vector<ConvergencePanel> panels;  // area, compliance, margin of safety, top to bottom
};

struct ConvergenceColour {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const ConvergenceColour& o) const { return r == o.r && g == o.g && b == o.b; }
  bool operator!=(const ConvergenceColour& o) const { return !(*this == o); }
};

// What each thing is drawn in, so tests and callers can find it on the image.
struct ConvergenceColours {
  static constexpr ConvergenceColour area{31, 119, 180};
  static constexpr ConvergenceColour compliance{230, 110, 0};
  static constexpr ConvergenceColour margin{44, 150, 44};
  static constexpr ConvergenceColour limit{214, 39, 40};       // the dashed limit lines
  static constexpr ConvergenceColour feasible{226, 242, 226};  // the feasible side of a limit
  static constexpr ConvergenceColour not_found{150, 150, 150};
};

// Draws the plot and writes it to `path` as an 8-bit RGB PNG of
// width_px x height_px; returns where the panels were drawn. The PNG is
// written to a temporary file beside `path` and renamed over it on success, so
// `path` never holds half a picture. Throws std::invalid_argument naming the
// option when one is out of its range or the panels do not fit, and
// std::runtime_error naming `path` when it cannot be written.
ConvergencePlotLayout write_convergence_png(const ConvergenceHistory& history, const ConvergenceOptions& options,
                                            const std::string& path);

}  // namespace sheetgen
