#pragma once
// A part checked over its load's whole envelope (docs/fem.md "Envelope
// analysis"): every static case on one factorisation, linear buckling of each
// case that compresses the sheet, and the first natural frequencies with the
// box's mass - what a stress engineer checks before signing the bracket.
#include <limits>
#include <string>
#include <vector>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/fem/shell_model.hpp"
#include "sheetgen/structure/envelope_result.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {

struct EnvelopeOptions {
  bool buckling = true;   // the eigen solve of every compressive case
  int frequencies = 3;    // natural frequencies wanted (0: none)
  bool keep_mode_shapes = false;  // the governing buckling mode and the first vibration mode, per node
  // Skip buckling and frequencies when a static case already fails (stiffness
  // or strength): the search's cheap checks first, the eigen solves only on
  // parts that pass them.
  bool eigen_only_if_static_passes = false;
};

// Builds the part model of load `load_index` (its cases and box mass from the
// problem) and analyses it. `solver` (optional) keeps the factorisations.
// Throws FemError when the model cannot be built or solved.
EnvelopeResult analyse_part_envelope(const Problem& problem, int load_index, const PlateGeometry& geometry,
                                     const PartModelOptions& model_options = {},
                                     const EnvelopeOptions& options = {}, ShellSolver* solver = nullptr);

// The same on a built model (its model.cases() and point masses).
EnvelopeResult analyse_envelope(const Problem& problem, const PartModel& part, const EnvelopeOptions& options,
                                const ShellElementOptions& element, ShellSolver& solver);

}  // namespace sheetgen
