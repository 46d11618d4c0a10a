#include "sheetgen/fem/geometric_stiffness.hpp"

namespace sheetgen {

Matrix18d shell_geometric_stiffness(const std::array<Vec3, 3>& nodes, const Eigen::Vector3d& N) {
  const ShellFrame frame = shell_frame(nodes);
  const auto& p = frame.local_xy;
  // Linear shape function gradients: dN_i/dx = (y_j - y_k) / 2A, dN_i/dy = (x_k - x_j) / 2A.
  Eigen::Matrix<double, 2, 3> G;
  for (int i = 0; i < 3; ++i) {
    const Vec2& pj = p[(i + 1) % 3];
    const Vec2& pk = p[(i + 2) % 3];
    G(0, i) = (pj.y() - pk.y()) / (2.0 * frame.area);
    G(1, i) = (pk.x() - pj.x()) / (2.0 * frame.area);
  }
  Eigen::Matrix2d S;
  S << N(0), N(2), N(2), N(1);
  const Eigen::Matrix3d k = frame.area * G.transpose() * S * G;
  Matrix18d Kg = Matrix18d::Zero();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int d = 0; d < 3; ++d) Kg(6 * a + d, 6 * b + d) = k(a, b);
  return Kg;
}

}  // namespace sheetgen
