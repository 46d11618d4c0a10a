#pragma once
// The bending part of the shell triangle with transverse shear: a Discrete
// Kirchhoff-Mindlin Triangle (DKMT, I. Katili, "A new discrete Kirchhoff-
// Mindlin element based on Mindlin-Reissner plate theory and assumed shear
// strain fields", IJNME 36 (1993) 1859-1883 and 1885-1908), docs/fem.md
// "Transverse shear".
//
// Why: DKT is a Kirchhoff plate. Next to a rivet footprint (radius ~2.5 t) and
// on short flanges the sheet's transverse shear is not negligible, and a
// Kirchhoff model of a riveted bracket is 2-6 % stiffer than CalculiX's S8R
// (docs/fem.md). DKMT keeps DKT's DOFs (w, rx, ry per node) and reduces to DKT
// exactly as t / L -> 0, so it does not lock.
//
// Construction (ours, in area coordinates, not Katili's explicit matrices):
//   rotations beta = (beta_x, beta_y) = (ry, -rx) at the corners, quadratic
//   over the triangle; the mid-side value of edge k (i -> j, length L, unit
//   tangent s) is (beta_i + beta_j) / 2 + s dbeta_k with
//     dbeta_k = -3 / (2 (1 + phi_k)) X_k,  X_k = (w_j - w_i) / L + s.(beta_i + beta_j) / 2,
//     phi_k = 2 / (kappa_s (1 - nu)) (t / L)^2,
//   which is the edge's shear equilibrium (D_s gamma_s = D beta_s,ss) with a
//   constant shear strain gamma_k = phi_k / (1 + phi_k) X_k along the edge;
//   phi = 0 is DKT's Kirchhoff condition on the edge. The shear strain field
//   is the lowest-order edge (Nedelec) field with those tangential values;
//   curvatures and shear strains are linear, so the 3-point rule is exact.
#include <Eigen/Core>
#include <array>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

// phi_k for the edges k = (1->2, 2->0, 0->1) of the triangle: the ratio of
// shear to bending flexibility over that edge. Zero thickness gives DKT.
std::array<double, 3> dkmt_shear_ratios(const std::array<Vec2, 3>& xy, double poisson_ratio, double thickness,
                                        double shear_correction);

// Curvatures kappa = B * (w, rx, ry)_0..2 at the area coordinates xi (of node 1)
// and eta (of node 2), in dkt_curvature_matrix's convention
// (beta_x,x, beta_y,y, beta_x,y + beta_y,x); with phi = 0 it equals DKT's matrix.
Eigen::Matrix<double, 3, 9> dkmt_curvature_matrix(const std::array<Vec2, 3>& xy, const std::array<double, 3>& phi,
                                                  double xi, double eta);

// Transverse shear strains gamma = (w,x + beta_x, w,y + beta_y) = S * (w, rx, ry)_0..2.
Eigen::Matrix<double, 2, 9> dkmt_shear_strain_matrix(const std::array<Vec2, 3>& xy,
                                                     const std::array<double, 3>& phi, double xi, double eta);

// 9 x 9 bending + transverse shear stiffness in the local frame, DOFs
// (w, rx, ry) per node. shear_correction is kappa_s (5/6 for a homogeneous plate).
Eigen::Matrix<double, 9, 9> dkmt_bending_stiffness(const std::array<Vec2, 3>& xy, double youngs_modulus,
                                                   double poisson_ratio, double thickness, double shear_correction);

}  // namespace sheetgen
