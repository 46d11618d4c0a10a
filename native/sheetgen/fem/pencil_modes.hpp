#pragma once
// The generalized eigenproblem K phi = lambda B phi of buckling (B = -K_G) and
// vibration (B = M, lambda = omega^2) on K's factor (internal to the fem area).
#include <Eigen/Core>
#include <vector>

#include "sheetgen/fem/lanczos.hpp"
#include "sheetgen/fem/shell_assembly.hpp"
#include "sheetgen/fem/stiffness_factor.hpp"

namespace sheetgen {

struct PencilModes {
  std::vector<double> lambdas;        // the smallest positive eigenvalues, ascending
  std::vector<Eigen::VectorXd> modes;  // per eigenvalue, reduced DOFs, phi^T B phi = 1
  int operations = 0;                  // Lanczos operator products
};

// With K = W W^T (factor, LDL^T backend) the pencil is the standard problem
// S psi = mu psi, S = W^-1 B W^-T, mu = 1 / lambda, phi = W^-T psi: the
// shift-invert transform at shift 0, so the smallest lambda are S's largest,
// best separated eigenvalues, and B need not be definite (K_G is not).
// Returns up to `count` pairs with lambda > 0 (fewer when S has fewer
// positive eigenvalues: a buckling case whose compression cannot buckle).
// A reduced mode as nodal (ux, uy, uz, rx, ry, rz), scaled to a largest translation of 1.
std::vector<Vector6d> expand_unit_mode(const DofMap& map, const Eigen::VectorXd& phi, int n_nodes);

PencilModes lowest_positive_modes(const StiffnessFactor& factor, const SparseMatrix& B_lower, int count,
                                  LanczosOptions options, const char* what);

// The eigenvalue of smallest magnitude of each sign, from one Lanczos run over
// both ends of S's spectrum: `positive` holds the lowest lambda > 0, and
// `negative` the |lambda| of the lambda < 0 nearest zero, which is the lowest
// positive eigenvalue of the pencil with -B (buckling: the opposite load).
// Either holds nothing when the pencil has no eigenvalue of that sign.
struct PencilBothSigns {
  PencilModes positive;
  PencilModes negative;
};
PencilBothSigns lowest_modes_of_both_signs(const StiffnessFactor& factor, const SparseMatrix& B_lower,
                                           LanczosOptions options, const char* what);

}  // namespace sheetgen
