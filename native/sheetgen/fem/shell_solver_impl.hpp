#pragma once
// ShellSolver's state (internal to the fem area): the reduced DOF map and
// stiffness of the last model and its factorisation, which the static cases,
// the buckling and the vibration analyses of one part share.
#include <vector>

#include "sheetgen/fem/shell_assembly.hpp"
#include "sheetgen/fem/shell_model.hpp"
#include "sheetgen/fem/stiffness_factor.hpp"

namespace sheetgen {

// What K_hat and its DOF map are built from. The static cases, the buckling
// and the vibration of one part each call prepare() with the same model; when
// these inputs equal the last model's, the map, K_hat and its factor are the
// ones built then (compared exactly, not hashed, so a stale factor cannot be
// taken for a new model's).
struct StiffnessInputs {
  std::vector<Vec3> nodes;
  std::vector<std::array<int, 3>> triangles;
  std::vector<NodeSupport> supports;
  std::vector<RigidLink> rigid_links;
  Material material;
  ShellElementOptions element;
  ShellSolverBackend backend = ShellSolverBackend::kEigenSimplicialLdlt;
  double singular_pivot_ratio = 0;

  bool same(const ShellModel& m, const ShellSolveOptions& options) const;
  void keep(const ShellModel& m, const ShellSolveOptions& options);
};

struct ShellSolver::Impl {
  DofMap map;
  SparseMatrix stiffness;  // K_hat of the last model, lower triangle
  StiffnessFactor factor;
  bool prepared = false;   // map, stiffness and factor hold `inputs`' model
  StiffnessInputs inputs;

  // Builds the DOF map and K_hat and factors it; all three are kept when the
  // model's stiffness inputs repeat, and the numeric factorisation is skipped
  // when K_hat's values repeat. Fills timing's assemble/factor seconds and
  // pattern_reused.
  void prepare(const ShellModel& m, const ShellSolveOptions& options, ShellResult& timing);
  // Every case on one factorisation.
  std::vector<ShellResult> solve(const ShellModel& m, const std::vector<ShellLoadCase>& cases,
                                 const ShellSolveOptions& options);
};

}  // namespace sheetgen
