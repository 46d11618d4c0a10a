#pragma once
// Linear buckling of a shell model under one static load case (docs/fem.md
// "Buckling"): the lowest load factors lambda > 0 with (K + lambda K_G) phi = 0,
// K_G the geometric stiffness of the case's membrane stress state.
#include <limits>
#include <string>
#include <vector>

#include "sheetgen/fem/lanczos.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

struct BucklingOptions {
  int modes = 1;             // buckling factors wanted
  double tolerance = LanczosOptions{}.tolerance;  // Lanczos relative residual (why 1e-6: lanczos.hpp)
  int max_restarts = LanczosOptions{}.max_restarts;
  // The case is "in compression", and gets the eigen solve, when some
  // element's smaller principal membrane resultant is below -this times the
  // largest principal resultant magnitude of the model: compression above
  // round-off. Without it no load factor can buckle the sheet (factor +inf).
  double compression_threshold = 1e-6;
};

struct BucklingResult {
  std::string case_name;
  bool compressed = false;          // the case compresses part of the sheet
  std::vector<double> factors;      // -, load multipliers lambda, ascending, all > 0
  // Per factor, #N (ux, uy, uz, rx, ry, rz), scaled to a largest translation of 1.
  std::vector<std::vector<Vector6d>> mode_shapes;
  int operations = 0;               // Lanczos operator products (each two triangular solves)
  double seconds = 0;               // wall clock, geometric stiffness to modes

  // The lowest factor; +inf when the case cannot buckle the part.
  double factor() const { return factors.empty() ? std::numeric_limits<double>::infinity() : factors.front(); }
};

// The buckling factors of `reference`, a static result of `model` (from
// solver.solve or solve_cases). Reuses the solver's factorisation of K when
// it holds this model's (always with the LDL^T backend: the transform needs
// its D). Throws FemError on a bad model or a Lanczos failure.
BucklingResult analyse_buckling(ShellSolver& solver, const ShellModel& model, const ShellResult& reference,
                                const ShellSolveOptions& solve_options = {}, const BucklingOptions& options = {});

// `reference` and the opposite load (-reference, the same magnitude) from one
// Lanczos run over both ends of the pencil's spectrum: `first` is what
// analyse_buckling(reference) gives, `second` what it gives for the negated
// static result. Each holds at most one factor (options.modes is not used);
// an envelope's opposite cases (left and right, forward and rearward, down and
// up) scale `second` by the ratio of their magnitudes, since K_G is linear in
// the load.
struct BucklingPair {
  BucklingResult first;
  BucklingResult second;
};
BucklingPair analyse_buckling_both_ways(ShellSolver& solver, const ShellModel& model, const ShellResult& reference,
                                        const ShellSolveOptions& solve_options = {}, const BucklingOptions& options = {});

}  // namespace sheetgen
