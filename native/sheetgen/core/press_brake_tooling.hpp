#pragma once
// The press brake a part is checked against, as the problem file describes it
// (`manufacturing.press_brake_tools`, docs/problem-format.md): its punches, its
// V-dies and the machine around them, in sizes. part/press_brake.hpp draws the
// tool profiles from these sizes and checks each bend on them; the defaults
// and their sources are in docs/manufacturing.md "Press brake".
#include <cmath>
#include <string>
#include <vector>

namespace sheetgen {

class JsonNode;

enum class PunchKind {
  Straight,   // a tip wedge, then a straight body
  Gooseneck,  // a tip wedge, a column, and a head reaching back over a throat that takes a return flange
};

struct PunchSpec {
  std::string name;                         // empty: "<kind> <tip angle> deg", with the height when not 120 mm
  PunchKind kind = PunchKind::Straight;
  double tip_angle = 30.0 * M_PI / 180.0;   // rad, included angle of the tip
  double height = 0.120;                    // m, tip to the punch holder (the ram starts there)
  double body_width = 0.020;                // m, straight punch: the body above the wedge
  double throat_bottom = 0.012;             // m above the tip, gooseneck: where the throat starts
  double throat_top = 0.080;                // m above the tip, gooseneck: where the head starts
};

struct DieSpec {
  std::string name;                         // empty: "V<opening mm> <angle> deg"
  double v_opening = 0;                     // m; 0: v_per_thickness x t, at least the tooling's min_v_opening
  double v_per_thickness = 8;               // V / t when v_opening is 0
  double angle = 85.0 * M_PI / 180.0;       // rad, included angle of the V
  double height = 0.060;                    // m, shoulders to the bed
  double width = 0;                         // m across the bend; 0: 3 V, at least 30 mm
  double min_flange_ratio = 0.7;            // the shortest flange that stays on the shoulders, x V
};

struct PressBrakeTooling {
  std::vector<PunchSpec> punches;           // tried in this order
  std::vector<DieSpec> dies;                // tried in this order
  double open_height = 0.42;                // m, bed to ram with the ram up (the daylight)
  double ram_width = 0.06;                  // m across the bend: the ram and punch holder above the punch
  double bed_width = 0.10;                  // m across the bend: the bed and die holder below the die
  double springback = 3.0 * M_PI / 180.0;   // rad, overbend beyond the bend angle while under load
  double min_v_opening = 4e-3;              // m, the smallest V-die made
};

// The standard tool set (docs/manufacturing.md "Press brake"): a straight and a
// gooseneck punch 120 mm high, a straight punch 180 mm high for boxes, 85 deg
// V-dies of 8, 6, 10 and 12 t and a 30 deg die of 8 t, on the machine above.
PressBrakeTooling default_press_brake_tooling();

// The die's opening for sheet of thickness t, m.
double die_opening(const PressBrakeTooling& tooling, const DieSpec& die, double thickness);

// Reads `press_brake_tools` (an object) into `tooling`: a list given replaces
// the default list, a size left out keeps its default. Throws InputError
// naming the field.
void parse_press_brake_tooling(const JsonNode& node, PressBrakeTooling& tooling);

}  // namespace sheetgen
