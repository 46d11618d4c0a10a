#pragma once
// A load's STEP files (docs/cad.md): part.step, the bent solid, and
// flat.step, the flat pattern as a solid, from the load's manufacturing plan.
#include <string>

#include "sheetgen/cad/step_export.hpp"
#include "sheetgen/core/problem.hpp"
#include "sheetgen/pipeline/generate.hpp"

namespace sheetgen {

struct LoadStepOptions {
  // A bent solid OpenCASCADE cannot build or check (StepGeometryError) leaves
  // part.step out and says why in LoadStepReport::part_error instead of
  // throwing: a solve keeps its other files (docs/cad.md "When the solid fails").
  bool keep_going = false;
};

struct LoadStepReport {
  StepSolidReport part;    // the bent solid as written
  StepSolidReport flat;    // the flat solid as written
  std::string part_error;  // with keep_going: why part.step was not written, naming the file without its folder ("" when it was)
};

// Writes the load's part.step to `part_path` and, unless `flat_path` is empty,
// its flat.step (sheet thickness from the problem, product names the load).
// Each file is written under a temporary name and renamed; a failure throws
// std::runtime_error naming the path (StepGeometryError when the solid is at
// fault). InputError when the load has no valid part.
LoadStepReport write_load_step(const Problem& problem, const LoadOutcome& load, const std::string& part_path,
                               const std::string& flat_path, const LoadStepOptions& options = {});

// The same for the load named `load` of a run (the add-on's "Export STEP");
// InputError when the run has no such load.
LoadStepReport write_load_step(const Problem& problem, const GenerateResult& result, const std::string& load,
                               const std::string& part_path, const std::string& flat_path);

}  // namespace sheetgen
