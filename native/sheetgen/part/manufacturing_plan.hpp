#pragma once
// One call for the end of the pipeline (docs/architecture.md "Manufacturing plan"): flat
// pattern + reliefs, flat overlap check with the kerf, bend sequence; and the
// per-load files of the CLI contract (flat.dxf, flat.svg, bends.csv, part.obj).
#include <string>

#include "sheetgen/part/bend_sequence.hpp"
#include "sheetgen/part/exports.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/press_brake.hpp"

namespace sheetgen {

struct ManufacturingPlanOptions {
  FlatPatternOptions flat;
  BendSequenceOptions bends;
  ValidityOptions validity;  // stop_at_first etc. for the flat overlap check
  bool plan_bends_when_flat_fails = false;  // skip the (costlier) bend search when the flat pattern is already invalid
  // Check the bend sequence on the press-brake tools below
  // (plan_press_brake): plan.press, and the tools in bends.csv.
  bool press_brake = false;
  PressBrakeTooling press_brake_tools = default_press_brake_tooling();
  int press_brake_sweeps = 200;  // budget of plan_press_brake's order search
};

struct ManufacturingPlan {
  ValidityReason status = ValidityReason::Ok;  // first problem found, in the order flat -> overlap -> bend sequence
  std::string message;
  FlatPattern flat;
  ValidityReport flat_report;  // unfold status + outline overlap
  BendSequenceResult sequence; // order (tab indices) when ok
  bool press_checked = false;  // options.press_brake and a bend sequence to check
  ToolSet tools;               // the tool set checked against
  PressBrakeResult press;      // the tools of each bend, or the bend no tool makes
  // Rivet and self-rivet holes; the rivets come from the FEM's layout, so the
  // caller fills them (set_rivet_holes) once the part is analysed. Empty: the drawings show none.
  std::vector<RivetHole> holes;
  bool ok() const { return status == ValidityReason::Ok; }
};

ManufacturingPlan plan_manufacturing(const Part& part, const SheetSpec& spec, const ManufacturingPlanOptions& options = {});

// The order search's budget when a search checks many parts (composition's
// candidates, discovery's segments): a quarter of the answer's
// (ManufacturingPlanOptions::press_brake_sweeps), because the search pays it on
// every part it checks; the part-only order is checked first and passes for
// most parts.
constexpr int kSearchPressBrakeSweeps = 50;

// The press-brake step of a plan whose bend sequence is ok: `tooling` drawn
// for the sheet (plan.tools), and plan.press. The part-only order is kept when the tools
// make each of its bends; otherwise the bend-sequence search runs again, taking
// a bend next only when a tool makes it, within `sweeps` sweeps, and its order
// replaces the part-only one when it finds one. When neither works, plan.press
// names the bend no tool makes and why; plan.status is left as it is (the
// caller decides whether that makes the part invalid).
void plan_press_brake(ManufacturingPlan& plan, const Part& part, const SheetSpec& spec,
                      const PressBrakeTooling& tooling, const BendSequenceOptions& bends, int sweeps);

// Fills plan.holes: the rivets mapped into the flat pattern, self-rivets
// numbered against the plan's bending order.
void set_rivet_holes(ManufacturingPlan& plan, const RealisedPart& realised, const std::vector<PlacedRivet>& flange_rivets,
                     const std::vector<PlacedSelfRivet>& self_rivets, const RivetHoleOptions& options);

// The plan's press-brake tools per bend, for bends.csv (empty when unchecked).
std::vector<BendToolRow> bend_tool_rows(const ManufacturingPlan& plan);

// Writes DIR/flat.dxf, DIR/flat.svg (both with the plan's holes), DIR/bends.csv
// (bending order when the plan has one, tab order otherwise; the tools when
// the plan has them), DIR/rivets.csv
// and DIR/part.obj; creates DIR. Throws std::runtime_error naming the file on failure.
void write_manufacturing_files(const std::string& dir, const RealisedPart& realised, const ManufacturingPlan& plan,
                               const DrawingOptions& drawing = {});

}  // namespace sheetgen
