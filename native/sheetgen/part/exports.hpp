#pragma once
// Exports of the manufacturing plan (docs/architecture.md "Manufacturing plan",
// docs/manufacturing.md): DXF R12 in millimetres for the laser, SVG of the same,
// bend table CSV, bent mid-surface OBJ (metres), part JSON (the tabs[] of
// sheetgen-result/1) and flat-pattern JSON. All writers return text; callers
// choose where it goes (write_text_file for files).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/rivet_holes.hpp"

namespace sheetgen {

struct DrawingOptions {
  std::vector<int> bend_order;  // bent tabs in bending order; empty = tab order. Numbers the bends 1..n
  double text_height = 3e-3;    // m, annotation text height
  double dash = 6e-3, gap = 3e-3;  // m, DASHED linetype pattern
};

// Bend number (1-based) of every bent tab under `bend_order` (index = tab; 0 for the base
// and for flat extensions, which have no bend).
std::vector<int> bend_numbers(const FlatPattern& flat, const std::vector<int>& bend_order);

// DXF R12 ($ACADVER AC1009), $INSUNITS 4 (mm). Layers: CUT (outline, a closed
// POLYLINE with the relief notches in it), BEND_UP / BEND_DOWN (bend centre
// lines, LINE with linetype DASHED), RIVET_HOLES / SELF_RIVET_HOLES (CIRCLE of
// the hole diameter per hole of `holes`), ANNOTATION (TEXT "B<n> UP|DOWN
// <angle>%%d" per bend, "S<n> AFTER B<k>" beside each self-rivet hole).
std::string flat_pattern_dxf(const FlatPattern& flat, const DrawingOptions& options = {},
                             const std::vector<RivetHole>& holes = {});
// SVG in millimetres (y up, flipped into SVG's y down), same layers as <g id=...>.
std::string flat_pattern_svg(const FlatPattern& flat, const DrawingOptions& options = {},
                             const std::vector<RivetHole>& holes = {});
// Header "label,kind,tab,other_tab,x_mm,y_mm,diameter_mm,after_bend,world_x_m,world_y_m,world_z_m";
// one row per hole: x_mm, y_mm in the drawings' coordinates (the outline's
// lower-left corner at 0, 0); kind "flange" or "self"; other_tab and
// after_bend empty for flange rivets (set when the part is installed).
std::string rivet_table_csv(const FlatPattern& flat, const std::vector<RivetHole>& holes);
// The press-brake tools of one bend (part/press_brake.hpp), for the bend table.
struct BendToolRow {
  int tab = -1;
  std::string punch, die;
  bool turned_over = false;  // the part turned over front to back in the press
};
// Header "order,angle_deg,direction,inside_radius_mm,length_mm,tab,punch,die,turned_over";
// one row per bend in bending order; angle_deg is |theta3|, direction UP or
// DOWN; punch, die and turned_over (yes/no) empty for a bend without tools.
std::string bend_table_csv(const FlatPattern& flat, const std::vector<int>& bend_order = {},
                           const std::vector<BendToolRow>& tools = {});
// Wavefront OBJ of the bent mid-surface in metres, one object "tab_<i>" per tab
// (an n-gon face, counter-clockwise seen from the sheet's top side).
std::string part_obj(const RealisedPart& realised);
// tabs[] for sheetgen-result/1: [{index, parent, parent_edge, rivet_area,
// parameters{d,w,l,theta1,theta2,theta3} (m, rad), corners [[x,y,z],...] (m),
// normal}], the base with parent -1 and its outline corners.
nlohmann::json part_json(const Part& part, const RealisedPart& realised);
// flat_pattern for sheetgen-result/1: {outline [[x,y],...] (m), bends[...], reliefs[...],
// holes[{label, kind, tab, other_tab, centre [x,y] (m), diameter (m), after_bend}], area_m2}.
nlohmann::json flat_pattern_json(const FlatPattern& flat, const std::vector<int>& bend_order = {},
                                 const std::vector<RivetHole>& holes = {});

// Writes text to a file; throws std::runtime_error naming the path on failure.
void write_text_file(const std::string& path, const std::string& text);

}  // namespace sheetgen
