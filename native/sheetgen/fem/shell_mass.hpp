#pragma once
// Mass matrices of the vibration analysis (vibration.hpp, docs/fem.md
// "Natural frequencies"): the sheet's elements and rigid bodies on a node.
#include <Eigen/Core>
#include <array>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/core/triangle_mesh.hpp"
#include "sheetgen/fem/shell_element.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen {

// 18 x 18 world-frame mass of a flat triangle (kg; kg m^2 on rotations):
// translations consistent with linear interpolation, rho t A / 12 [2 1 1; 1 2
// 1; 1 1 2] on each component (the same in any frame); rotations lumped, the
// plate's rotary inertia rho t^3 / 12 A / 3 per node on each axis (isotropic,
// so frame-free; it is 1e-6 of the translational mass for 1.6 mm sheet and
// only keeps the matrix free of arbitrary zeros).
Matrix18d shell_element_mass(const std::array<Vec3, 3>& nodes, const Material& material);

// 6 x 6 mass of a rigid body about its node, DOFs (u, theta): with r the
// centre of mass relative to the node and J its inertia about the centre,
//   [ m I       -m [r]x           ]
//   [ m [r]x    J - m [r]x [r]x   ]   ([r]x the cross-product matrix),
// the kinetic energy of v_c = v + theta' x r and spin theta'.
Eigen::Matrix<double, 6, 6> rigid_body_mass(const PointMass& body);

}  // namespace sheetgen
