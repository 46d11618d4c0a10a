#pragma once
// STEP solids of a part for CAD (docs/cad.md): the bent part (`part.step`) and
// its flat pattern (`flat.step`), both solids of the sheet thickness in
// millimetres, AP214. Both are built from the flat pattern alone (outline with
// its relief notches, bend zones, rivet and self-rivet holes), so they agree
// with flat.dxf by construction: the flat solid is the outline extruded by t,
// and the bent solid is the same sheet with every bend zone laid on a true
// cylinder of inside radius R. OpenCASCADE is reached only from
// step_export.cpp (docs/code-style.md point 5).
#include <stdexcept>
#include <string>
#include <vector>

#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/rivet_holes.hpp"

namespace sheetgen {

// The solid could not be built or did not pass OpenCASCADE's check (as
// opposed to a file that could not be written, a plain std::runtime_error).
class StepGeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StepExportOptions {
  double thickness = 1.6e-3;    // m, sheet thickness t (SheetSpec::thickness)
  std::string product = "part";  // the STEP product name a CAD tree shows
  // m, the sewing tolerance that joins the bend faces to the flat faces:
  // well below the kerf (0.2 mm), the least real gap between two cut edges,
  // and above the wrap's round-off (docs/cad.md "Sewing").
  double sewing_tolerance = 1e-5;
};

// What was built, measured on the solid before writing (mm, the file's unit).
struct StepSolidReport {
  int solids = 0;               // 1 when the model is one solid
  bool valid = false;           // OpenCASCADE's BRepCheck of the solid
  double volume_mm3 = 0;
  int faces = 0;
  int bend_faces = 0;           // cylindrical faces of radius R or R + t (2 per bend)
  int hole_faces = 0;           // cylindrical faces of any other radius: the hole walls (docs/cad.md "Holes")
  double box_min_mm[3] = {0, 0, 0}, box_max_mm[3] = {0, 0, 0};  // axis-aligned bounding box
};

// The bent solid in world coordinates (mm): every piece of sheet outside the
// bend zones moved rigidly onto its tab's plane, every bend zone wrapped onto
// the cylinder of mid radius R + t/2 (arc length along the neutral fibre =
// the flat length, as the bend allowance defines it), then thickened by t/2
// on both sides of that mid-surface. Throws std::invalid_argument when the
// flat pattern is not ok and StepGeometryError when OpenCASCADE cannot build
// or check the solid (naming the step).
StepSolidReport bent_part_solid_report(const FlatPattern& flat, const std::vector<RivetHole>& holes,
                                       const StepExportOptions& options = {});

// Writes the bent solid as STEP (AP214, mm) to `path`: written under a
// temporary name beside it and renamed, so a failure leaves no file. Throws
// std::runtime_error whose message names the path when it cannot be written.
StepSolidReport write_part_step(const std::string& path, const FlatPattern& flat, const std::vector<RivetHole>& holes,
                                const StepExportOptions& options = {});

// Writes the flat pattern as a STEP solid: the outline of flat.dxf with its
// holes, in flat.dxf's coordinates (mm, the outline's bounding box starting at
// x = y = 0), from z = 0 (the sheet's bottom) to z = t (its top side, the side
// the drawings show). Same failure behaviour as write_part_step.
StepSolidReport write_flat_step(const std::string& path, const FlatPattern& flat, const std::vector<RivetHole>& holes,
                                const StepExportOptions& options = {});

}  // namespace sheetgen
