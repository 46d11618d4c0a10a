#pragma once
// ShellSolver's state (internal to the fem area): the reduced DOF map and
// stiffness of the last model and its factorisation, which the static cases,
// the buckling and the vibration analyses of one part share.
#include <vector>

#include "sheetgen/fem/shell_assembly.hpp"
#include "sheetgen/fem/shell_model.hpp"
#include "sheetgen/fem/stiffness_factor.hpp"

namespace sheetgen {

struct ShellSolver::Impl {
  DofMap map;
  SparseMatrix stiffness;  // K_hat of the last model, lower triangle
  StiffnessFactor factor;

  // Builds the DOF map and K_hat and factors it (skipped when K_hat repeats);
  // fills timing's assemble/factor seconds and pattern_reused.
  void prepare(const ShellModel& m, const ShellSolveOptions& options, ShellResult& timing);
  // Every case on one factorisation.
  std::vector<ShellResult> solve(const ShellModel& m, const std::vector<ShellLoadCase>& cases,
                                 const ShellSolveOptions& options);
};

}  // namespace sheetgen
