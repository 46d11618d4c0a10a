#pragma once
// Natural frequencies of a shell model with rigid masses (docs/fem.md
// "Natural frequencies"): the lowest omega with (K - omega^2 M) phi = 0, M the
// sheet's mass (density x thickness) plus each PointMass's rigid-body mass.
#include <string>
#include <vector>

#include "sheetgen/fem/lanczos.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

struct VibrationOptions {
  int modes = 3;             // frequencies wanted
  double tolerance = LanczosOptions{}.tolerance;  // Lanczos relative residual (why 1e-6: lanczos.hpp)
  int max_restarts = LanczosOptions{}.max_restarts;
};

struct VibrationResult {
  std::vector<double> frequencies_hz;  // ascending
  // Per frequency, #N (ux, uy, uz, rx, ry, rz), scaled to a largest translation of 1.
  std::vector<std::vector<Vector6d>> mode_shapes;
  double sheet_mass = 0;               // kg, density x thickness x area
  double point_mass = 0;               // kg, sum of model.point_masses
  int operations = 0;                  // Lanczos operator products
  double seconds = 0;                  // wall clock, mass matrix to modes
};

// Reuses the solver's factorisation of K when it holds this model's. Throws
// FemError on a bad model (a density or point mass that is not > 0), a
// mechanism (K singular: a mode at 0 Hz) or a Lanczos failure.
VibrationResult analyse_vibration(ShellSolver& solver, const ShellModel& model,
                                  const ShellSolveOptions& solve_options = {}, const VibrationOptions& options = {});

}  // namespace sheetgen
