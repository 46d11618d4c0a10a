#pragma once
// Press-brake feasibility of a bend sequence (docs/manufacturing.md "Press
// brake"): each bend is air-bent between a punch and a V-die; the part, in its
// partly bent state, must clear the tools and the machine through the whole
// stroke, each flange must be long enough to sit on the die, and the tools'
// angles must allow the bend. A tool set is a list of punches and dies; each
// bend gets the first punch and die that make it.
//
// The tool frame of a bend: Z along the bend line, Y up through the punch tip
// (the inside of the bend faces the punch), X across; the sheet's mid-surface
// passes through the origin at the bend line, and both flanges rise by half
// the current bend angle (air bending). Profiles are drawn from the sheet's
// surfaces: the punch tip touches the top surface (Y = t/2), the die's
// shoulders the bottom one (Y = -t/2).
#include <string>
#include <vector>

#include "sheetgen/core/press_brake_tooling.hpp"
#include "sheetgen/part/validity.hpp"

namespace sheetgen {

struct PunchTool {
  std::string name;
  // The cross-section as convex counter-clockwise pieces, m: x across the
  // bend, y up from the tip (0, 0). Piece 0 is the tip wedge, which the two
  // flanges of the bend touch by design (the tip angle governs them).
  std::vector<std::vector<Vec2>> pieces;
  double tip_angle = 0;  // rad, included angle of the tip wedge
  double height = 0;     // m, tip to the punch holder (the ram starts there)
};

struct DieTool {
  std::string name;
  double v_opening = 0;         // m, between the shoulders
  double angle = 0;             // rad, included angle of the V
  double height = 0;            // m, shoulders to the bed
  double width = 0;             // m, across the bend
  double min_flange_ratio = 0;  // the shortest flange that stays on the shoulders, as a share of v_opening
};

struct PressBrakeMachine {  // defaults: PressBrakeTooling's
  double ram_width = PressBrakeTooling{}.ram_width;      // m, across the bend: the ram and punch holder above the punch
  double bed_width = PressBrakeTooling{}.bed_width;      // m, across the bend: the bed and die holder below the die
  double open_height = PressBrakeTooling{}.open_height;  // m, bed to ram with the ram up (the daylight)
};

struct ToolSet {
  std::vector<PunchTool> punches;  // in the order they are tried
  std::vector<DieTool> dies;       // in the order they are tried
  PressBrakeMachine machine;
  double springback = PressBrakeTooling{}.springback;  // rad, overbend beyond the bend angle while under load
  double gap = 0.5e-3;                     // m, kept beyond t/2 between the sheet and a tool or the machine
  double max_step = 2.0 * M_PI / 180.0;    // rad, largest angle step between checked states of a stroke
  // Skip the states of a stroke in which a tab is provably clear of a tool
  // (docs/manufacturing.md "Press brake"): the same answers as checking every
  // state, which `false` does (the reference the tests compare with).
  bool skip_clear_states = true;
};

// The tools a problem describes (core/press_brake_tooling.hpp), drawn for
// sheet of the given thickness (m): the dies' openings scale with it.
ToolSet make_tool_set(const PressBrakeTooling& tooling, double thickness);

// make_tool_set of default_press_brake_tooling(). docs/manufacturing.md "Press
// brake" gives the figures and sources.
ToolSet standard_tool_set(double thickness);

struct BendTooling {
  int tab = -1;             // the bend (the tab bent onto its parent)
  int punch = -1, die = -1; // indices into the tool set
  bool flipped = false;     // the part turned over front to back (X mirrored)
};

struct PressBrakeResult {
  bool ok = false;
  std::vector<BendTooling> tooling;  // per bend of the order, while they succeed
  int failed_tab = -1;               // the bend no punch and die can make
  std::string message;               // why, for the nearest tool (empty when ok)
};

// Bend `k` with the other tabs at `angles` (rad, per tab; k's own is ignored):
// the first punch and die of `tools` that make it (ok), or why none does
// (the failure that got furthest).
struct BendToolChoice {
  bool ok = false;
  BendTooling tooling;
  std::string reason;
};
BendToolChoice choose_bend_tools(const Part& part, int k, const std::vector<double>& angles, const SheetSpec& spec,
                                 const ToolSet& tools);

// Checks `order` (every bent tab once, as check_bend_order takes it): for each
// bend, every punch and die of `tools` in order, the part as it is and turned
// over, until one makes the bend.
PressBrakeResult check_press_brake(const Part& part, const std::vector<int>& order, const SheetSpec& spec,
                                   const ToolSet& tools);

}  // namespace sheetgen
