#pragma once
// The drawing sheet of one part (docs/drawing.md): one PDF page a sheet-metal
// shop can quote from. The flat pattern at a stated ISO 5455 scale with its
// overall dimensions, bend lines (dashed, up/down, angle, order) and holes; the
// bend table; the rivet schedule; material, thickness, mass and flat area; the
// governing checks; a small shaded isometric view of the bent part; a title
// block. Drawn with cairo's PDF surface, which only the report's sources see
// (docs/code-style.md point 5). Everything here is plain data in SI units (m,
// rad, kg, J, Hz): the pipeline fills it from a result.json part entry.
#include <limits>
#include <string>
#include <vector>

namespace sheetgen {

struct SheetPoint {
  double x = 0, y = 0;  // m
};

struct SheetPoint3 {
  double x = 0, y = 0, z = 0;  // m, world
};

struct SheetBend {
  int number = 0;             // position in the bending order, 1-based
  int tab = -1;               // the tab this bend folds
  SheetPoint a, b;            // m, flat frame: centre line of the bend zone (a: root start; the tab lies right of a -> b)
  double angle = 0;           // rad, |theta3|
  bool up = true;             // the tab folds towards the viewer of the flat pattern (its top side)
  double inside_radius = 0;   // m
  double length = 0;          // m, along the bend line
  double allowance = 0;       // m, bend allowance BA
};

struct SheetHole {
  std::string label;          // "R<n>" (flange rivet) or "S<n>" (one sheet of a self-rivet)
  bool self_rivet = false;
  int tab = -1, other_tab = -1;  // the tab it is in; a self-rivet's other sheet (else -1)
  SheetPoint centre;          // m, flat frame
  double diameter = 0;        // m, of the hole
  int after_bend = 0;         // self-rivet: set after this bend (0: no bend needed)
};

struct SheetMaterial {
  std::string name;           // "" when the material is not a named default
  double thickness = 0;       // m
  double density = 0;         // kg/m^3
  double youngs_modulus = 0;  // Pa
  double yield_strength = 0;  // Pa
  double ultimate_strength = 0;  // Pa
};

// The governing checks of the part (docs/pipeline.md "Checks of a candidate").
// NaN: not known (an old result, or not analysed).
struct SheetChecks {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string stiffness_case, strength_case, buckling_case;  // the governing load case of each check ("" if none)
  double compliance = kNaN, compliance_limit = kNaN;          // J
  double margin_of_safety = kNaN, min_margin_of_safety = kNaN;  // -
  double safety_factor = kNaN;                                // -, in MS = F_ty / (SF sigma_vm) - 1
  bool eigen_checked = false;                                 // buckling and frequencies were computed
  double buckling_factor = kNaN;     // -, lowest over the cases; +inf: no case compresses the sheet
  double min_buckling_factor = kNaN;  // -, NaN: not required
  double frequency_hz = kNaN;         // Hz, first natural frequency
  double min_frequency_hz = kNaN;     // Hz, NaN: not required
};

struct DrawingSheetPart {
  std::string part_name;      // the load's name
  std::string problem_name;   // the problem as the title block names it
  std::string status;         // "valid" or what the part misses
  std::vector<SheetPoint> outline;   // m, flat frame, counter-clockwise: the one cut contour (reliefs included)
  std::vector<SheetBend> bends;      // any order; the table lists them by number
  std::vector<SheetHole> holes;
  std::vector<std::vector<SheetPoint3>> tabs;  // m, world: the bent mid-surface, one polygon per tab
  SheetMaterial material;
  double flat_area = 0;       // m^2, of the flat pattern (holes not subtracted)
  double mass = 0;            // kg
  double k_factor = 0;        // -
  double kerf = 0;            // m
  double rivet_diameter = 0;  // m, shank of the flange rivets (0: not known)
  SheetChecks checks;
};

enum class PaperSize { A3, A4 };

struct DrawingSheetOptions {
  PaperSize paper = PaperSize::A3;  // landscape; docs/drawing.md says why A3
  double text_height = 2.5e-3;      // m on paper, table and label capitals (ISO 3098's smallest common size), 1.8..5 mm
};

// Where things went on the page: mm from the page's top-left corner, y down.
struct DrawingSheetLayout {
  double page_width_mm = 0, page_height_mm = 0;
  int scale_denominator = 0;          // the flat pattern is drawn at 1:scale_denominator
  // The outline's bounding box on the page: the flat point (x, y) lands at
  // (flat_left_mm + (x - x_min) * 1000 / n, flat_bottom_mm - (y - y_min) * 1000 / n).
  double flat_left_mm = 0, flat_bottom_mm = 0, flat_width_mm = 0, flat_height_mm = 0;
  double extent_x_mm = 0, extent_y_mm = 0;  // the flat pattern's overall size, true mm (the dimension values)
  int bend_rows = 0, bend_rows_omitted = 0;   // rows of the bend table drawn / left to bends.csv
  int hole_rows = 0, hole_rows_omitted = 0;   // rows of the rivet schedule drawn / left to rivets.csv
};

// Draws the sheet and writes it to `path` as a one-page PDF (no creation date,
// so the same part gives the same bytes). Written to a temporary file beside
// `path` and renamed over it, so `path` never holds half a drawing. Throws
// std::invalid_argument naming the field when the part or the options cannot
// be drawn (no outline, a non-finite coordinate, an option out of range) and
// std::runtime_error naming `path` when it cannot be written.
DrawingSheetLayout write_drawing_pdf(const DrawingSheetPart& part, const DrawingSheetOptions& options,
                                     const std::string& path);

}  // namespace sheetgen
