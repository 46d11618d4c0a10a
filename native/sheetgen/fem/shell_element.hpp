#pragma once
// A linear-elastic flat-shell triangle with 6 DOF per node, the element of the
// bracket FEM (docs/architecture.md "FEM", docs/fem.md).
//
//   membrane: Felippa's ANDES "optimal" triangle OPT with corner drilling
//             rotations (C. A. Felippa, "A study of optimal membrane triangles
//             with drilling freedoms", CMAME 192 (2003) 2125-2168). A plain CST
//             locks in in-plane bending, which is what flanges do.
//   bending:  with transverse shear, the Discrete Kirchhoff-Mindlin Triangle
//             DKMT (dkmt_plate.hpp; the default); without, the Discrete
//             Kirchhoff Triangle DKT (J.-L. Batoz, K.-J. Bathe, L.-W. Ho, "A
//             study of three-node triangular plate bending elements", IJNME 15
//             (1980) 1771-1812), which DKMT becomes as t / L -> 0.
//
// Node DOF order, global and local alike: (ux, uy, uz, rx, ry, rz), metres and
// radians; rotations are right-handed about the axes. An element vector or
// matrix lists node 0's six DOFs, then node 1's, then node 2's (18 in all).
#include <Eigen/Core>
#include <array>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

using Matrix18d = Eigen::Matrix<double, 18, 18>;
using Vector18d = Eigen::Matrix<double, 18, 1>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;
using Vector9d = Eigen::Matrix<double, 9, 1>;

struct ShellElementOptions {
  // OPT membrane: the basic-stiffness drilling parameter alpha_b of the ANDES
  // template; 3/2 is the optimal value of Felippa (2003), Table 2.
  double alpha_b = 1.5;
  // Higher-order stiffness scale beta_0; a negative value selects Felippa's
  // optimum for isotropic material, max(0.5 (1 - 4 nu^2), 0.01).
  double beta0 = -1.0;
  // Bending: DKMT (transverse shear, the default) or DKT (Kirchhoff). A
  // Kirchhoff model of a riveted bracket is 2-6 % stiffer than CalculiX's S8R
  // (docs/fem.md "Transverse shear").
  bool transverse_shear = true;
  double shear_correction = 5.0 / 6.0;  // kappa_s of a homogeneous plate
};

// The element's local frame: origin at node 0, x along edge 0->1, z along the
// normal of the vertex order (right-hand rule), y = z cross x. "Top" fibres
// are at z = +t/2, on the side the normal points to.
struct ShellFrame {
  Eigen::Matrix3d rotation;      // rows are the local x, y, z axes in world coordinates
  std::array<Vec2, 3> local_xy;  // m, node positions in the local frame (node 0 at the origin)
  double area = 0;               // m^2
};

// Throws FemError for a degenerate triangle (area below 1e-14 of its squared
// longest edge) or non-finite coordinates.
ShellFrame shell_frame(const std::array<Vec3, 3>& nodes);

// 9 x 9 OPT membrane stiffness in the local frame, DOFs (u, v, rz) per node. N/m.
Matrix9d opt_membrane_stiffness(const std::array<Vec2, 3>& xy, double youngs_modulus, double poisson_ratio,
                                double thickness, const ShellElementOptions& options = {});

// DKT curvatures kappa = B * (w, rx, ry)_0..2 at area coordinates (xi, eta) =
// (L2, L3): kappa = (beta_x,x, beta_y,y, beta_x,y + beta_y,x) with beta_x = -w,x,
// beta_y = -w,y (Kirchhoff), so a plate bent up into w = x^2/2 has kappa_xx = -1.
Eigen::Matrix<double, 3, 9> dkt_curvature_matrix(const std::array<Vec2, 3>& xy, double xi, double eta);

// 9 x 9 DKT bending stiffness in the local frame, DOFs (w, rx, ry) per node.
Matrix9d dkt_bending_stiffness(const std::array<Vec2, 3>& xy, double youngs_modulus, double poisson_ratio,
                               double thickness);

// 18 x 18 element stiffness in world coordinates (N/m, N/rad, N m/rad).
Matrix18d shell_element_stiffness(const std::array<Vec3, 3>& nodes, const Material& material,
                                  const ShellElementOptions& options = {});

// Stresses at the element centroid, in the local frame, Pa. Components are
// (sigma_xx, sigma_yy, tau_xy) of the plane-stress state at that fibre.
struct ShellStress {
  Eigen::Vector3d membrane = Eigen::Vector3d::Zero();  // mid-surface
  Eigen::Vector3d top = Eigen::Vector3d::Zero();       // z = +t/2: membrane + bending
  Eigen::Vector3d bottom = Eigen::Vector3d::Zero();    // z = -t/2: membrane - bending
  double von_mises_top = 0;                            // Pa
  double von_mises_bottom = 0;                         // Pa
};

// Plane-stress von Mises stress of (sxx, syy, txy), Pa.
double von_mises(const Eigen::Vector3d& stress);

// Centroid stresses from the element's 18 world-frame nodal displacements.
// (OPT's higher-order strains vanish at the centroid, so the membrane part is
// the basic constant strain; curvatures are evaluated at xi = eta = 1/3.)
ShellStress shell_element_stress(const std::array<Vec3, 3>& nodes, const Material& material,
                                 const Vector18d& displacements, const ShellElementOptions& options = {});

// What the centroid stresses take from the element alone, so that several load
// cases (or the buckling's membrane resultants) reuse it: the same stresses,
// bit for bit, as shell_element_stress of the nodes.
struct ShellStressOperator {
  Eigen::Matrix3d rotation;                    // world -> local frame
  Eigen::Matrix<double, 3, 9> membrane_strain;  // L^T: eps = L^T u_m / (2 A)
  double two_area = 0;                         // m^2
  Eigen::Matrix3d elasticity;                  // plane-stress D, Pa
  Eigen::Matrix<double, 3, 9> curvature;       // kappa = B u_b at the centroid (1/m per unit DOF)
  double thickness = 0;                        // m
};
// bending = false leaves `curvature` unset: for membrane_stress only.
ShellStressOperator shell_stress_operator(const std::array<Vec3, 3>& nodes, const Material& material,
                                          const ShellElementOptions& options = {}, bool bending = true);
ShellStress shell_element_stress(const ShellStressOperator& op, const Vector18d& displacements);
// The membrane stress alone (ShellStress::membrane), without the bending part.
Eigen::Vector3d membrane_stress(const ShellStressOperator& op, const Vector18d& displacements);

// A local-frame stress (sxx, syy, txy) as a 3 x 3 world tensor, Pa.
Eigen::Matrix3d stress_to_world(const ShellFrame& frame, const Eigen::Vector3d& stress);

}  // namespace sheetgen
