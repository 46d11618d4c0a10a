#pragma once
// One call for the end of the pipeline (docs/architecture.md "Manufacturing plan"): flat
// pattern + reliefs, flat overlap check with the kerf, bend sequence; and the
// per-load files of the CLI contract (flat.dxf, flat.svg, bends.csv, part.obj).
#include <string>

#include "sheetgen/part/bend_sequence.hpp"
#include "sheetgen/part/exports.hpp"
#include "sheetgen/part/flat_pattern.hpp"

namespace sheetgen {

struct ManufacturingPlanOptions {
  FlatPatternOptions flat;
  BendSequenceOptions bends;
  ValidityOptions validity;  // stop_at_first etc. for the flat overlap check
  bool plan_bends_when_flat_fails = false;  // skip the (costlier) bend search when the flat pattern is already invalid
};

struct ManufacturingPlan {
  ValidityReason status = ValidityReason::Ok;  // first problem found, in the order flat -> overlap -> bend sequence
  std::string message;
  FlatPattern flat;
  ValidityReport flat_report;  // unfold status + outline overlap
  BendSequenceResult sequence; // order (tab indices) when ok
  // Rivet and self-rivet holes; the rivets come from the FEM's layout, so the
  // caller fills them (set_rivet_holes) once the part is analysed. Empty: the drawings show none.
  std::vector<RivetHole> holes;
  bool ok() const { return status == ValidityReason::Ok; }
};

ManufacturingPlan plan_manufacturing(const Part& part, const SheetSpec& spec, const ManufacturingPlanOptions& options = {});

// Fills plan.holes: the rivets mapped into the flat pattern, self-rivets
// numbered against the plan's bending order.
void set_rivet_holes(ManufacturingPlan& plan, const RealisedPart& realised, const std::vector<PlacedRivet>& flange_rivets,
                     const std::vector<PlacedSelfRivet>& self_rivets, const RivetHoleOptions& options);

// Writes DIR/flat.dxf, DIR/flat.svg (both with the plan's holes), DIR/bends.csv
// (bending order when the plan has one, tab order otherwise), DIR/rivets.csv
// and DIR/part.obj; creates DIR. Throws std::runtime_error naming the file on failure.
void write_manufacturing_files(const std::string& dir, const RealisedPart& realised, const ManufacturingPlan& plan,
                               const DrawingOptions& drawing = {});

}  // namespace sheetgen
