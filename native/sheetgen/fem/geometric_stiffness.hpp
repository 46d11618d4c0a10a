#pragma once
// The geometric (initial-stress) stiffness of a flat shell triangle, for linear
// buckling (buckling.hpp, docs/fem.md "Buckling").
#include <Eigen/Core>
#include <array>

#include "sheetgen/core/triangle_mesh.hpp"
#include "sheetgen/fem/shell_element.hpp"

namespace sheetgen {

// 18 x 18 world-frame geometric stiffness of a triangle carrying the constant
// membrane stress resultants N = (Nxx, Nyy, Nxy) (N/m; the element's local
// frame, shell_frame()): the second variation of the membrane work,
//   K_G = A G^T [Nxx Nxy; Nxy Nyy] G   for each translation component,
// with G the gradients of the linear shape functions. The same 3 x 3 block
// acts on ux, uy and uz, so it is the same in any frame; rotations get none.
// Compression (negative N) makes it negative: (K + lambda K_G) phi = 0 at the
// buckling load factor lambda.
Matrix18d shell_geometric_stiffness(const std::array<Vec3, 3>& nodes, const Eigen::Vector3d& membrane_resultant);

}  // namespace sheetgen
