#include "sheetgen/fem/shell_element.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sheetgen/fem/dkmt_plate.hpp"
#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

// Plane-stress constitutive matrix, Pa.
Eigen::Matrix3d plane_stress(double E, double nu) {
  Eigen::Matrix3d D;
  const double c = E / (1.0 - nu * nu);
  D << c, c * nu, 0, c * nu, c, 0, 0, 0, c * (1.0 - nu) / 2.0;
  return D;
}

// Local DOF slots of the membrane (u, v, rz) and bending (w, rx, ry) parts.
constexpr int kMembraneSlot[3] = {0, 1, 5};
constexpr int kBendingSlot[3] = {2, 3, 4};

}  // namespace

ShellFrame shell_frame(const std::array<Vec3, 3>& nodes) {
  for (const Vec3& p : nodes) {
    if (!p.allFinite()) throw FemError("element node", "coordinate is not finite");
  }
  const Vec3 a = nodes[1] - nodes[0];
  const Vec3 b = nodes[2] - nodes[0];
  const Vec3 n = a.cross(b);
  const double longest2 = std::max({a.squaredNorm(), b.squaredNorm(), (nodes[2] - nodes[1]).squaredNorm()});
  const double area2 = n.norm();
  if (!(longest2 > 0) || area2 <= 1e-14 * longest2) {
    std::ostringstream s;
    s << "degenerate triangle (area " << 0.5 * area2 << " m^2, longest edge " << std::sqrt(longest2) << " m)";
    throw FemError("element", s.str());
  }
  ShellFrame f;
  const Vec3 ex = a.normalized();
  const Vec3 ez = n / area2;
  const Vec3 ey = ez.cross(ex);
  f.rotation.row(0) = ex.transpose();
  f.rotation.row(1) = ey.transpose();
  f.rotation.row(2) = ez.transpose();
  f.local_xy[0] = Vec2::Zero();
  f.local_xy[1] = Vec2(a.norm(), 0.0);
  f.local_xy[2] = Vec2(b.dot(ex), b.dot(ey));
  f.area = 0.5 * area2;
  return f;
}

Matrix9d opt_membrane_stiffness(const std::array<Vec2, 3>& xy, double E, double nu, double h,
                                const ShellElementOptions& options) {
  const double x1 = xy[0].x(), y1 = xy[0].y(), x2 = xy[1].x(), y2 = xy[1].y(), x3 = xy[2].x(), y3 = xy[2].y();
  const double x12 = x1 - x2, x21 = -x12, x23 = x2 - x3, x32 = -x23, x31 = x3 - x1, x13 = -x31;
  const double y12 = y1 - y2, y21 = -y12, y23 = y2 - y3, y32 = -y23, y31 = y3 - y1, y13 = -y31;
  const double A = 0.5 * (x21 * y31 - x31 * y21);
  const double ab = options.alpha_b;
  const double b0 = options.beta0 >= 0 ? options.beta0 : std::max(0.5 * (1.0 - 4.0 * nu * nu), 0.01);
  const Eigen::Matrix3d Em = plane_stress(E, nu);

  // Basic stiffness Kb = L Em L^T / (h A) with the force-lumping matrix L of
  // the ANDES template (Felippa 2003, Eq. 3.6); L carries the factor h/2.
  Eigen::Matrix<double, 9, 3> L;
  L << y23, 0, x32,                                                            //
      0, x32, y23,                                                             //
      ab * y23 * (y13 - y21) / 6, ab * x32 * (x31 - x12) / 6, ab * (x31 * y13 - x12 * y21) / 3,  //
      y31, 0, x13,                                                             //
      0, x13, y31,                                                             //
      ab * y31 * (y21 - y32) / 6, ab * x13 * (x12 - x23) / 6, ab * (x12 * y21 - x23 * y32) / 3,  //
      y12, 0, x21,                                                             //
      0, x21, y12,                                                             //
      ab * y12 * (y32 - y13) / 6, ab * x21 * (x23 - x31) / 6, ab * (x23 * y32 - x31 * y13) / 3;
  L *= h / 2.0;
  Matrix9d K = L * Em * L.transpose() / (h * A);

  // Higher-order stiffness from the natural deviatoric strains at the three
  // mid-side points (Felippa 2003, Eqs. 4.x): Te maps natural strains to
  // Cartesian ones, Q1..Q3 are the corner strain-rotation matrices built from
  // the OPT signature b1..b9 = (1, 2, 1, 0, 1, -1, -1, -1, -2).
  const double LL21 = x21 * x21 + y21 * y21, LL32 = x32 * x32 + y32 * y32, LL13 = x13 * x13 + y13 * y13;
  Eigen::Matrix3d Te;
  Te << y23 * y13 * LL21, y31 * y21 * LL32, y12 * y32 * LL13,  //
      x23 * x13 * LL21, x31 * x21 * LL32, x12 * x32 * LL13,    //
      (y23 * x31 + x32 * y13) * LL21, (y31 * x12 + x13 * y21) * LL32, (y12 * x23 + x21 * y32) * LL13;
  Te /= 4.0 * A * A;
  constexpr double b[10] = {0, 1, 2, 1, 0, 1, -1, -1, -1, -2};  // 1-based like the paper
  Eigen::Matrix3d Q1, Q2, Q3;
  Q1 << b[1] / LL21, b[2] / LL21, b[3] / LL21, b[4] / LL32, b[5] / LL32, b[6] / LL32, b[7] / LL13, b[8] / LL13,
      b[9] / LL13;
  Q2 << b[9] / LL21, b[7] / LL21, b[8] / LL21, b[3] / LL32, b[1] / LL32, b[2] / LL32, b[6] / LL13, b[4] / LL13,
      b[5] / LL13;
  Q3 << b[5] / LL21, b[6] / LL21, b[4] / LL21, b[8] / LL32, b[9] / LL32, b[7] / LL32, b[2] / LL13, b[3] / LL13,
      b[1] / LL13;
  Q1 *= 2.0 * A / 3.0;
  Q2 *= 2.0 * A / 3.0;
  Q3 *= 2.0 * A / 3.0;
  const Eigen::Matrix3d Q4 = 0.5 * (Q1 + Q2), Q5 = 0.5 * (Q2 + Q3), Q6 = 0.5 * (Q3 + Q1);
  const Eigen::Matrix3d Enat = Te.transpose() * Em * Te;
  const Eigen::Matrix3d Ktheta = (0.75 * b0 * h * A) * (Q4.transpose() * Enat * Q4 + Q5.transpose() * Enat * Q5 +
                                                        Q6.transpose() * Enat * Q6);
  // Hierarchical rotations: corner drilling rotation minus the CST mean rotation.
  Eigen::Matrix<double, 3, 9> Ttu;
  const double A4 = 4.0 * A;
  Ttu << x32, y32, A4, x13, y13, 0, x21, y21, 0,  //
      x32, y32, 0, x13, y13, A4, x21, y21, 0,     //
      x32, y32, 0, x13, y13, 0, x21, y21, A4;
  Ttu /= A4;
  K.noalias() += Ttu.transpose() * Ktheta * Ttu;
  return K;
}

Eigen::Matrix<double, 3, 9> dkt_curvature_matrix(const std::array<Vec2, 3>& xy, double xi, double eta) {
  const double x1 = xy[0].x(), y1 = xy[0].y(), x2 = xy[1].x(), y2 = xy[1].y(), x3 = xy[2].x(), y3 = xy[2].y();
  const double x23 = x2 - x3, x31 = x3 - x1, x12 = x1 - x2;
  const double y23 = y2 - y3, y31 = y3 - y1, y12 = y1 - y2;
  const double l23 = x23 * x23 + y23 * y23, l31 = x31 * x31 + y31 * y31, l12 = x12 * x12 + y12 * y12;
  // Batoz et al. (1980), Eqs. (B) of the appendix: side k = 4, 5, 6 is 23, 31, 12.
  const double P4 = -6 * x23 / l23, P5 = -6 * x31 / l31, P6 = -6 * x12 / l12;
  const double t4 = -6 * y23 / l23, t5 = -6 * y31 / l31, t6 = -6 * y12 / l12;
  const double q4 = 3 * x23 * y23 / l23, q5 = 3 * x31 * y31 / l31, q6 = 3 * x12 * y12 / l12;
  const double r4 = 3 * y23 * y23 / l23, r5 = 3 * y31 * y31 / l31, r6 = 3 * y12 * y12 / l12;
  const double a = 1 - 2 * xi, c = 1 - 2 * eta;

  Vector9d Hx_xi, Hy_xi, Hx_eta, Hy_eta;
  Hx_xi << P6 * a + (P5 - P6) * eta, q6 * a - (q5 + q6) * eta, -4 + 6 * (xi + eta) + r6 * a - eta * (r5 + r6),
      -P6 * a + eta * (P4 + P6), q6 * a - eta * (q6 - q4), -2 + 6 * xi + r6 * a + eta * (r4 - r6),
      -eta * (P5 + P4), eta * (q4 - q5), -eta * (r5 - r4);
  Hy_xi << t6 * a + eta * (t5 - t6), 1 + r6 * a - eta * (r5 + r6), -q6 * a + eta * (q5 + q6),
      -t6 * a + eta * (t4 + t6), -1 + r6 * a + eta * (r4 - r6), -q6 * a - eta * (q4 - q6), -eta * (t4 + t5),
      eta * (r4 - r5), -eta * (q4 - q5);
  Hx_eta << -P5 * c - xi * (P6 - P5), q5 * c - xi * (q5 + q6), -4 + 6 * (xi + eta) + r5 * c - xi * (r5 + r6),
      xi * (P4 + P6), xi * (q4 - q6), -xi * (r6 - r4), P5 * c - xi * (P4 + P5), q5 * c + xi * (q4 - q5),
      -2 + 6 * eta + r5 * c + xi * (r4 - r5);
  Hy_eta << -t5 * c - xi * (t6 - t5), 1 + r5 * c - xi * (r5 + r6), -q5 * c + xi * (q5 + q6), xi * (t4 + t6),
      xi * (r4 - r6), -xi * (q4 - q6), t5 * c - xi * (t4 + t5), -1 + r5 * c + xi * (r4 - r5),
      -q5 * c - xi * (q4 - q5);

  const double twoA = x31 * y12 - x12 * y31;
  Eigen::Matrix<double, 3, 9> B;
  B.row(0) = (y31 * Hx_xi + y12 * Hx_eta).transpose();
  B.row(1) = (-x31 * Hy_xi - x12 * Hy_eta).transpose();
  B.row(2) = (-x31 * Hx_xi - x12 * Hx_eta + y31 * Hy_xi + y12 * Hy_eta).transpose();
  return B / twoA;
}

Matrix9d dkt_bending_stiffness(const std::array<Vec2, 3>& xy, double E, double nu, double h) {
  const double x1 = xy[0].x(), y1 = xy[0].y(), x2 = xy[1].x(), y2 = xy[1].y(), x3 = xy[2].x(), y3 = xy[2].y();
  const double A = 0.5 * ((x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1));
  const Eigen::Matrix3d Db = plane_stress(E, nu) * (h * h * h / 12.0);
  // Curvatures are linear, so the 3-point interior rule (degree 2) is exact.
  constexpr double gp[3][2] = {{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
  Matrix9d K = Matrix9d::Zero();
  for (const auto& g : gp) {
    const Eigen::Matrix<double, 3, 9> B = dkt_curvature_matrix(xy, g[0], g[1]);
    K.noalias() += (A / 3.0) * B.transpose() * Db * B;
  }
  return K;
}

Matrix18d shell_element_stiffness(const std::array<Vec3, 3>& nodes, const Material& material,
                                  const ShellElementOptions& options) {
  const ShellFrame f = shell_frame(nodes);
  const double E = material.youngs_modulus, nu = material.poisson_ratio, h = material.thickness;
  const Matrix9d Km = opt_membrane_stiffness(f.local_xy, E, nu, h, options);
  const Matrix9d Kb = options.transverse_shear
                          ? dkmt_bending_stiffness(f.local_xy, E, nu, h, options.shear_correction)
                          : dkt_bending_stiffness(f.local_xy, E, nu, h);
  Matrix18d Kl = Matrix18d::Zero();
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < 3; ++i)
      for (int b = 0; b < 3; ++b)
        for (int j = 0; j < 3; ++j) {
          Kl(6 * a + kMembraneSlot[i], 6 * b + kMembraneSlot[j]) = Km(3 * a + i, 3 * b + j);
          Kl(6 * a + kBendingSlot[i], 6 * b + kBendingSlot[j]) = Kb(3 * a + i, 3 * b + j);
        }
  // K_world = T^T K_local T with T = diag(R, ..., R); done per 3 x 3 block.
  const Eigen::Matrix3d& R = f.rotation;
  Matrix18d Kg;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      Kg.block<3, 3>(3 * a, 3 * b).noalias() = R.transpose() * Kl.block<3, 3>(3 * a, 3 * b) * R;
  return Kg;
}

double von_mises(const Eigen::Vector3d& s) {
  return std::sqrt(std::max(0.0, s(0) * s(0) - s(0) * s(1) + s(1) * s(1) + 3.0 * s(2) * s(2)));
}

ShellStressOperator shell_stress_operator(const std::array<Vec3, 3>& nodes, const Material& material,
                                          const ShellElementOptions& options, bool bending) {
  const ShellFrame f = shell_frame(nodes);
  const double nu = material.poisson_ratio;
  ShellStressOperator op;
  op.rotation = f.rotation;
  op.two_area = 2.0 * f.area;
  op.thickness = material.thickness;
  const auto& xy = f.local_xy;
  const double x1 = xy[0].x(), y1 = xy[0].y(), x2 = xy[1].x(), y2 = xy[1].y(), x3 = xy[2].x(), y3 = xy[2].y();
  const double ab = options.alpha_b;
  const double x12 = x1 - x2, x21 = -x12, x23 = x2 - x3, x32 = -x23, x31 = x3 - x1, x13 = -x31;
  const double y12 = y1 - y2, y21 = -y12, y23 = y2 - y3, y32 = -y23, y31 = y3 - y1, y13 = -y31;
  // Basic (constant) membrane strain eps = L^T u / (h A) with the same L as the
  // stiffness; OPT's higher-order strains sum to zero at the centroid.
  op.membrane_strain << y23, 0, ab * y23 * (y13 - y21) / 6, y31, 0, ab * y31 * (y21 - y32) / 6, y12, 0,
      ab * y12 * (y32 - y13) / 6,  //
      0, x32, ab * x32 * (x31 - x12) / 6, 0, x13, ab * x13 * (x12 - x23) / 6, 0, x21, ab * x21 * (x23 - x31) / 6,  //
      x32, y23, ab * (x31 * y13 - x12 * y21) / 3, x13, y31, ab * (x12 * y21 - x23 * y32) / 3, x21, y12,
      ab * (x23 * y32 - x31 * y13) / 3;
  op.elasticity = plane_stress(material.youngs_modulus, nu);
  if (!bending) return op;  // the curvature matrix is most of the cost
  op.curvature = options.transverse_shear ? dkmt_curvature_matrix(xy, dkmt_shear_ratios(xy, nu, material.thickness,
                                                                                          options.shear_correction),
                                                                  1.0 / 3, 1.0 / 3)
                                          : dkt_curvature_matrix(xy, 1.0 / 3, 1.0 / 3);
  return op;
}

namespace {
// The element's membrane (u, v, rz) and bending (w, rx, ry) DOFs in its local frame.
void local_dofs(const ShellStressOperator& op, const Vector18d& u, Vector9d& um, Vector9d& ub) {
  for (int a = 0; a < 3; ++a) {
    const Eigen::Vector3d t = op.rotation * u.segment<3>(6 * a);
    const Eigen::Vector3d r = op.rotation * u.segment<3>(6 * a + 3);
    um.segment<3>(3 * a) << t(0), t(1), r(2);
    ub.segment<3>(3 * a) << t(2), r(0), r(1);
  }
}
}  // namespace

Eigen::Vector3d membrane_stress(const ShellStressOperator& op, const Vector18d& u) {
  Vector9d um, ub;
  local_dofs(op, u, um, ub);
  const Eigen::Vector3d eps = op.membrane_strain * um / op.two_area;
  return op.elasticity * eps;
}

ShellStress shell_element_stress(const ShellStressOperator& op, const Vector18d& u) {
  Vector9d um, ub;
  local_dofs(op, u, um, ub);
  const Eigen::Vector3d eps = op.membrane_strain * um / op.two_area;
  const Eigen::Vector3d kappa = op.curvature * ub;
  ShellStress s;
  s.membrane = op.elasticity * eps;
  const Eigen::Vector3d bending = (0.5 * op.thickness) * (op.elasticity * kappa);  // sigma(z) = z D kappa at z = t/2
  s.top = s.membrane + bending;
  s.bottom = s.membrane - bending;
  s.von_mises_top = von_mises(s.top);
  s.von_mises_bottom = von_mises(s.bottom);
  return s;
}

ShellStress shell_element_stress(const std::array<Vec3, 3>& nodes, const Material& material,
                                 const Vector18d& u, const ShellElementOptions& options) {
  return shell_element_stress(shell_stress_operator(nodes, material, options), u);
}

Eigen::Matrix3d stress_to_world(const ShellFrame& frame, const Eigen::Vector3d& s) {
  Eigen::Matrix3d local = Eigen::Matrix3d::Zero();
  local << s(0), s(2), 0, s(2), s(1), 0, 0, 0, 0;
  return frame.rotation.transpose() * local * frame.rotation;
}

}  // namespace sheetgen
