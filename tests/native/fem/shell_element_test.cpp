// Element-level invariants of the flat-shell triangle (OPT membrane + DKT).
#include "sheetgen/fem/shell_element.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "sheetgen/fem/dkmt_plate.hpp"
#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

Material test_material(double nu = 0.3) {
  Material m;
  m.youngs_modulus = 70e9;
  m.poisson_ratio = nu;
  m.thickness = 1.6e-3;
  return m;
}

// Eigenvalues of a free element: exactly six rigid-body modes (3 translations,
// 3 rotations) are zero; the other 12 are strictly positive. A coplanar patch
// without drilling stiffness would show a seventh zero (docs/fem.md "Reference values").
void expect_six_rigid_modes(const std::array<Vec3, 3>& x, double nu) {
  const Matrix18d K = shell_element_stiffness(x, test_material(nu));
  EXPECT_LT((K - K.transpose()).norm(), 1e-9 * K.norm());
  Eigen::SelfAdjointEigenSolver<Matrix18d> eig(K);
  const auto& ev = eig.eigenvalues();
  const double scale = ev.cwiseAbs().maxCoeff();
  int zeros = 0;
  for (int i = 0; i < 18; ++i) {
    if (std::abs(ev(i)) < 1e-10 * scale) ++zeros;
    else EXPECT_GT(ev(i), 0.0) << "eigenvalue " << i;
  }
  EXPECT_EQ(zeros, 6);
  // The seventh smallest stays well away from round-off.
  EXPECT_GT(ev(6), 1e-8 * scale);
}

TEST(ShellElement, SixZeroEigenvaluesEquilateral) {
  expect_six_rigid_modes({Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.005, 0.005 * std::sqrt(3.0), 0)}, 0.3);
}

TEST(ShellElement, SixZeroEigenvaluesSkewedAndRotatedIn3d) {
  // An obtuse triangle in a general plane, with nu = 0 (beta0 at its largest).
  expect_six_rigid_modes({Vec3(0.1, 0.2, 0.3), Vec3(0.13, 0.21, 0.29), Vec3(0.095, 0.215, 0.31)}, 0.0);
  expect_six_rigid_modes({Vec3(0.1, 0.2, 0.3), Vec3(0.13, 0.21, 0.29), Vec3(0.095, 0.215, 0.31)}, 0.33);
}

TEST(ShellElement, RigidRotationGivesNoForce) {
  // A small rigid rotation theta about an arbitrary axis: u = theta x x, rotations = theta.
  const std::array<Vec3, 3> x = {Vec3(0, 0, 0), Vec3(0.02, 0.001, 0.003), Vec3(0.004, 0.015, -0.002)};
  const Vec3 theta(0.3, -0.2, 0.5);
  Vector18d u;
  for (int a = 0; a < 3; ++a) {
    u.segment<3>(6 * a) = theta.cross(x[a]);
    u.segment<3>(6 * a + 3) = theta;
  }
  const Matrix18d K = shell_element_stiffness(x, test_material());
  EXPECT_LT((K * u).norm(), 1e-10 * K.norm() * u.norm());
  const ShellStress s = shell_element_stress(x, test_material(), u);
  EXPECT_LT(s.von_mises_top, 1e-13 * 70e9);  // Pa: zero to round-off of E |theta| ~ 4e10 Pa
}

TEST(ShellElement, ConstantCurvaturePatch) {
  // w = x^2 / 2 (rx = w,y = 0, ry = -w,x = -x): DKT reproduces it exactly, so
  // kappa_xx = -1 1/m everywhere and the fibre stress is sigma = z E/(1-nu^2) kappa.
  const std::array<Vec2, 3> xy = {Vec2(0, 0), Vec2(0.03, 0.002), Vec2(0.01, 0.02)};
  Vector9d ub;
  for (int a = 0; a < 3; ++a) ub.segment<3>(3 * a) << 0.5 * xy[a].x() * xy[a].x(), 0.0, -xy[a].x();
  for (double xi : {0.0, 0.2, 1.0 / 3}) {
    const Eigen::Vector3d k = dkt_curvature_matrix(xy, xi, 0.25) * ub;
    EXPECT_NEAR(k(0), -1.0, 1e-12);
    EXPECT_NEAR(k(1), 0.0, 1e-12);
    EXPECT_NEAR(k(2), 0.0, 1e-12);
  }
}

TEST(ShellElement, DkmtWithoutShearFlexibilityIsDkt) {
  // phi = 0 turns DKMT's edge condition into DKT's Kirchhoff condition, so our
  // area-coordinate construction must reproduce Batoz's explicit matrices.
  const std::array<Vec2, 3> xy = {Vec2(0, 0), Vec2(0.031, 0.004), Vec2(0.007, 0.022)};
  double worst = 0;
  for (const auto& p : {std::array<double, 2>{0, 0}, {1, 0}, {0, 1}, {0.2, 0.3}, {1.0 / 3, 1.0 / 3}}) {
    const Eigen::Matrix<double, 3, 9> a = dkmt_curvature_matrix(xy, {0, 0, 0}, p[0], p[1]);
    const Eigen::Matrix<double, 3, 9> b = dkt_curvature_matrix(xy, p[0], p[1]);
    worst = std::max(worst, (a - b).norm() / b.norm());
  }
  EXPECT_LT(worst, 1e-12);
  // And the stiffness of a thin sheet (t / L = 1e-4) is DKT's to O(phi).
  const Matrix9d thin = dkmt_bending_stiffness(xy, 70e9, 0.3, 3e-6, 5.0 / 6.0);
  const Matrix9d dkt = dkt_bending_stiffness(xy, 70e9, 0.3, 3e-6);
  EXPECT_LT((thin - dkt).norm(), 1e-6 * dkt.norm());
}

TEST(ShellElement, DkmtConstantCurvaturePatchHasNoShear) {
  // w = x^2 / 2 + x y, rotations from the Kirchhoff slopes: a thick element
  // (t = 10 mm on 20-30 mm edges, phi ~ 0.4) keeps kappa = (-1, 0, -2) exactly
  // and no shear strain, so pure bending costs no shear energy.
  const std::array<Vec2, 3> xy = {Vec2(0, 0), Vec2(0.03, 0.002), Vec2(0.01, 0.02)};
  const std::array<double, 3> phi = dkmt_shear_ratios(xy, 0.3, 0.01, 5.0 / 6.0);
  EXPECT_GT(phi[0], 0.1);
  Vector9d ub;
  for (int a = 0; a < 3; ++a) {
    const double x = xy[a].x(), y = xy[a].y();
    ub.segment<3>(3 * a) << 0.5 * x * x + x * y, x, -(x + y);  // rx = w,y, ry = -w,x
  }
  for (double xi : {0.0, 0.2, 1.0 / 3}) {
    const Eigen::Vector3d k = dkmt_curvature_matrix(xy, phi, xi, 0.25) * ub;
    EXPECT_NEAR(k(0), -1.0, 1e-12);
    EXPECT_NEAR(k(1), 0.0, 1e-12);
    EXPECT_NEAR(k(2), -2.0, 1e-12);
    EXPECT_LT((dkmt_shear_strain_matrix(xy, phi, xi, 0.25) * ub).norm(), 1e-14);
  }
}

TEST(ShellElement, ConstantStrainPatch) {
  // u = 1e-3 x (uniaxial strain), v = 0, drilling rz = (v,x - u,y)/2 = 0:
  // membrane stress E/(1-nu^2) * 1e-3 and nu times that across.
  const Material mat = test_material(0.3);
  const std::array<Vec3, 3> x = {Vec3(0, 0, 0), Vec3(0.02, 0.004, 0), Vec3(0.006, 0.017, 0)};
  Vector18d u = Vector18d::Zero();
  for (int a = 0; a < 3; ++a) u(6 * a) = 1e-3 * x[a].x();
  const ShellStress s = shell_element_stress(x, mat, u);
  const ShellFrame f = shell_frame(x);
  const Eigen::Matrix3d S = stress_to_world(f, s.top);
  const double c = mat.youngs_modulus / (1 - 0.09) * 1e-3;
  EXPECT_NEAR(S(0, 0), c, 1e-9 * c);
  EXPECT_NEAR(S(1, 1), 0.3 * c, 1e-9 * c);
  EXPECT_NEAR(S(0, 1), 0.0, 1e-9 * c);
  // Pure membrane: top and bottom agree.
  EXPECT_NEAR(s.von_mises_top, s.von_mises_bottom, 1e-9 * c);
}

TEST(ShellElement, DegenerateTriangleThrows) {
  EXPECT_THROW(shell_element_stiffness({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}, test_material()), FemError);
  EXPECT_THROW(shell_element_stiffness({Vec3(0, 0, 0), Vec3(NAN, 0, 0), Vec3(2, 1, 0)}, test_material()), FemError);
}

}  // namespace
}  // namespace sheetgen
