#pragma once
// The FEM's global algebra (internal to the fem area): the reduced DOF map of
// supports and rigid links (u = T u_hat), and assembly of element matrices
// and load vectors through it. Statics, buckling and vibration share it.
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <vector>

#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Full DOF (6 per node) -> linear combination of reduced DOFs: u = T u_hat.
struct DofMap {
  std::vector<int> start;  // 6 #N + 1, CSR offsets into index/coef
  std::vector<int> index;  // reduced DOF
  std::vector<double> coef;
  std::vector<int> owner;  // #reduced: the node whose DOF each reduced DOF is (node by node, ascending)
  int reduced = 0;
};

DofMap build_dof_map(const ShellModel& m);

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// A 6 x 6 matrix on one node's DOFs (a rigid body's mass on its node).
struct NodalBlock {
  int node = -1;
  Matrix6d matrix = Matrix6d::Zero();
};

// The full DOF ids (6 per node) of a triangle's three nodes and of one node.
inline std::array<int, 18> element_dofs(const std::array<int, 3>& t) {
  std::array<int, 18> dofs;
  for (int a = 0; a < 18; ++a) dofs[a] = 6 * t[a / 6] + a % 6;
  return dofs;
}
inline std::array<int, 6> node_dofs(int node) {
  std::array<int, 6> dofs;
  for (int a = 0; a < 6; ++a) dofs[a] = 6 * node + a;
  return dofs;
}

// A_hat = T^T A T (lower triangle) of an 18 x 18 world-frame matrix per
// element plus nodal blocks. Added in place into the node-block pattern
// (node_block_pattern.hpp) when the map allows, else through triplets; both
// give the same matrix to the last bit.
SparseMatrix assemble_elements(const ShellModel& m, const DofMap& map,
                               const std::function<Matrix18d(int element)>& element_matrix,
                               const std::vector<NodalBlock>& nodal_blocks = {});

// The same through a triplet list and Eigen's setFromTriplets: the reference
// the in-place assembly is tested against, and its fallback.
SparseMatrix assemble_elements_by_triplets(const ShellModel& m, const DofMap& map,
                                           const std::function<Matrix18d(int element)>& element_matrix,
                                           const std::vector<NodalBlock>& nodal_blocks = {});

// The stiffness K_hat (lower triangle), N/m.
SparseMatrix assemble_stiffness(const ShellModel& m, const DofMap& map, const ShellElementOptions& element);

// f_hat = T^T f of nodal loads (N, N m).
Eigen::VectorXd assemble_load(const std::vector<NodalLoad>& loads, const DofMap& map, int n_nodes);

// u = T u_hat: per node (ux, uy, uz, rx, ry, rz).
std::vector<Vector6d> expand_displacements(const DofMap& map, const Eigen::VectorXd& uh, int n_nodes);

// y = A x for the lower triangle `A_lower` of a symmetric matrix.
Eigen::VectorXd symmetric_product(const SparseMatrix& A_lower, const Eigen::VectorXd& x);

}  // namespace sheetgen
