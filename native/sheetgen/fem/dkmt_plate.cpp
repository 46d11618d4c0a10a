#include "sheetgen/fem/dkmt_plate.hpp"

namespace sheetgen {
namespace {

using Row9 = Eigen::Matrix<double, 1, 9>;
using Mat29 = Eigen::Matrix<double, 2, 9>;

// Edge k joins node kEdge[k][0] to kEdge[k][1]; it is the edge opposite node k.
constexpr int kEdge[3][2] = {{1, 2}, {2, 0}, {0, 1}};

// The kinematics shared by curvatures and shear strains: corner rotations as
// rows of the DOF vector, each edge's mid-side rotation and its constant
// tangential shear strain.
struct DkmtKinematics {
  std::array<Mat29, 3> beta_corner;  // beta_x = ry, beta_y = -rx
  std::array<Mat29, 3> beta_mid;     // at the mid-side of edge k
  std::array<Row9, 3> gamma_edge;    // tangential shear strain along edge k
  std::array<Vec2, 3> grad_l;        // gradients of the area coordinates, 1/m
  std::array<double, 3> length;      // m
  double area = 0;                   // m^2
};

DkmtKinematics kinematics(const std::array<Vec2, 3>& xy, const std::array<double, 3>& phi) {
  DkmtKinematics k;
  const double twoA = (xy[1].x() - xy[0].x()) * (xy[2].y() - xy[0].y()) -
                      (xy[2].x() - xy[0].x()) * (xy[1].y() - xy[0].y());
  k.area = 0.5 * twoA;
  for (int i = 0; i < 3; ++i) {
    const Vec2& a = xy[(i + 1) % 3];
    const Vec2& b = xy[(i + 2) % 3];
    k.grad_l[i] = Vec2(a.y() - b.y(), b.x() - a.x()) / twoA;
    k.beta_corner[i].setZero();
    k.beta_corner[i](0, 3 * i + 2) = 1.0;
    k.beta_corner[i](1, 3 * i + 1) = -1.0;
  }
  for (int e = 0; e < 3; ++e) {
    const int i = kEdge[e][0], j = kEdge[e][1];
    const Vec2 d = xy[j] - xy[i];
    const double L = d.norm();
    const Eigen::Vector2d s = d / L;
    const Mat29 mean = 0.5 * (k.beta_corner[i] + k.beta_corner[j]);
    Row9 X = s.transpose() * mean;  // s . (beta_i + beta_j) / 2
    X(3 * j) += 1.0 / L;
    X(3 * i) -= 1.0 / L;
    const Row9 dbeta = (-1.5 / (1.0 + phi[e])) * X;
    k.beta_mid[e] = mean + s * dbeta;
    k.gamma_edge[e] = (phi[e] / (1.0 + phi[e])) * X;
    k.length[e] = L;
  }
  return k;
}

Eigen::Matrix<double, 3, 9> curvature_matrix(const DkmtKinematics& k, double xi, double eta) {
  const double l[3] = {1.0 - xi - eta, xi, eta};
  // beta = sum N_i beta_i + sum N_k beta_mid_k over the six-node quadratic
  // triangle: N_i = l_i (2 l_i - 1), N_k = 4 l_i l_j.
  Mat29 dx = Mat29::Zero(), dy = Mat29::Zero();
  for (int i = 0; i < 3; ++i) {
    const Vec2 g = (4.0 * l[i] - 1.0) * k.grad_l[i];
    dx += g.x() * k.beta_corner[i];
    dy += g.y() * k.beta_corner[i];
  }
  for (int e = 0; e < 3; ++e) {
    const int i = kEdge[e][0], j = kEdge[e][1];
    const Vec2 g = 4.0 * (l[i] * k.grad_l[j] + l[j] * k.grad_l[i]);
    dx += g.x() * k.beta_mid[e];
    dy += g.y() * k.beta_mid[e];
  }
  Eigen::Matrix<double, 3, 9> B;
  B.row(0) = dx.row(0);
  B.row(1) = dy.row(1);
  B.row(2) = dy.row(0) + dx.row(1);
  return B;
}

Mat29 shear_strain_matrix(const DkmtKinematics& k, double xi, double eta) {
  const double l[3] = {1.0 - xi - eta, xi, eta};
  // gamma = sum_k (gamma_k L_k) W_k with the Whitney edge function
  // W_k = l_i grad l_j - l_j grad l_i, whose tangential integral is 1 along
  // edge k and 0 along the other two.
  Mat29 S = Mat29::Zero();
  for (int e = 0; e < 3; ++e) {
    const int i = kEdge[e][0], j = kEdge[e][1];
    const Eigen::Vector2d W = l[i] * k.grad_l[j] - l[j] * k.grad_l[i];
    S += (k.length[e] * W) * k.gamma_edge[e];
  }
  return S;
}

}  // namespace

std::array<double, 3> dkmt_shear_ratios(const std::array<Vec2, 3>& xy, double poisson_ratio, double thickness,
                                        double shear_correction) {
  std::array<double, 3> phi{};
  for (int e = 0; e < 3; ++e) {
    const double L = (xy[kEdge[e][1]] - xy[kEdge[e][0]]).norm();
    phi[e] = 2.0 / (shear_correction * (1.0 - poisson_ratio)) * (thickness / L) * (thickness / L);
  }
  return phi;
}

Eigen::Matrix<double, 3, 9> dkmt_curvature_matrix(const std::array<Vec2, 3>& xy, const std::array<double, 3>& phi,
                                                  double xi, double eta) {
  return curvature_matrix(kinematics(xy, phi), xi, eta);
}

Eigen::Matrix<double, 2, 9> dkmt_shear_strain_matrix(const std::array<Vec2, 3>& xy,
                                                     const std::array<double, 3>& phi, double xi, double eta) {
  return shear_strain_matrix(kinematics(xy, phi), xi, eta);
}

Eigen::Matrix<double, 9, 9> dkmt_bending_stiffness(const std::array<Vec2, 3>& xy, double E, double nu, double t,
                                                   double shear_correction) {
  const DkmtKinematics k = kinematics(xy, dkmt_shear_ratios(xy, nu, t, shear_correction));
  Eigen::Matrix3d Db;
  const double D = E * t * t * t / (12.0 * (1.0 - nu * nu));
  Db << D, nu * D, 0, nu * D, D, 0, 0, 0, 0.5 * (1.0 - nu) * D;
  const double Ds = shear_correction * E / (2.0 * (1.0 + nu)) * t;  // N/m
  // Curvatures and shear strains are linear: the 3-point rule is exact.
  constexpr double gp[3][2] = {{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};
  Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero();
  for (const auto& g : gp) {
    const Eigen::Matrix<double, 3, 9> B = curvature_matrix(k, g[0], g[1]);
    const Mat29 S = shear_strain_matrix(k, g[0], g[1]);
    K.noalias() += (k.area / 3.0) * (B.transpose() * Db * B + Ds * S.transpose() * S);
  }
  return K;
}

}  // namespace sheetgen
