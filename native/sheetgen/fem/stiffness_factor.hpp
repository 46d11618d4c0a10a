#pragma once
// The factorisation of the reduced stiffness K_hat (internal to the fem area):
// the one door to CHOLMOD and Eigen's sparse LDL^T. Keeps the symbolic
// analysis while the sparsity pattern repeats (the same mesh with other
// values, e.g. another thickness). ShellSolver keeps the whole factor while
// the stiffness inputs repeat (statics, buckling and vibration of one part).
#include <Eigen/Core>
#include <memory>

#include "sheetgen/fem/shell_assembly.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

class StiffnessFactor {
 public:
  StiffnessFactor();
  ~StiffnessFactor();

  // Factors K (lower triangle). Reuses the symbolic analysis when the pattern
  // (the index arrays, compared exactly) repeats.
  // Throws FemError when K is singular: a pivot below singular_pivot_ratio
  // times its diagonal entry is a rigid-body mode or mechanism.
  struct Outcome {
    bool pattern_reused = false;
  };
  Outcome factorise(const SparseMatrix& K, ShellSolverBackend backend, double singular_pivot_ratio);

  // K^-1 F for each column of F (each load case). With the LDL^T backend the
  // answer is Eigen's SimplicialLDLT::solve to the last bit, with the factor
  // read once for all the columns rather than once per column.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& F) const;

  // With K = W W^T (W = P^T L D^1/2 of the LDL^T backend), in place:
  // x <- W^-1 x and y <- W^-T y, `work` a scratch vector of the same length
  // (in place because the Lanczos operator applies them about fifty times per
  // eigen solve, and need not allocate a vector each time).
  // The generalized eigenproblem K phi = lambda B phi becomes the standard
  // one (W^-1 B W^-T) psi = (1 / lambda) psi, phi = W^-T psi.
  // Requires the LDL^T backend (eigen analyses always factor with it).
  void half_solve(Eigen::VectorXd& x, Eigen::VectorXd& work) const;
  void half_solve_transpose(Eigen::VectorXd& y, Eigen::VectorXd& work) const;

  int symbolic_analyses() const;
  ShellSolverBackend backend() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sheetgen
