#include "sheetgen/fem/shell_mass.hpp"

namespace sheetgen {

Matrix18d shell_element_mass(const std::array<Vec3, 3>& nodes, const Material& material) {
  const ShellFrame frame = shell_frame(nodes);
  const double t = material.thickness;
  const double m = material.density * t * frame.area;  // kg
  const double rotary = m * t * t / 12.0 / 3.0;          // kg m^2 per node
  Matrix18d M = Matrix18d::Zero();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b)
      for (int d = 0; d < 3; ++d) M(6 * a + d, 6 * b + d) = m / 12.0 * (a == b ? 2.0 : 1.0);
    for (int d = 3; d < 6; ++d) M(6 * a + d, 6 * a + d) = rotary;
  }
  return M;
}

Eigen::Matrix<double, 6, 6> rigid_body_mass(const PointMass& body) {
  Eigen::Matrix3d rx;
  const Vec3& r = body.offset;
  rx << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  Eigen::Matrix<double, 6, 6> M;
  M.topLeftCorner<3, 3>() = body.mass * Eigen::Matrix3d::Identity();
  M.topRightCorner<3, 3>() = -body.mass * rx;
  M.bottomLeftCorner<3, 3>() = body.mass * rx;
  M.bottomRightCorner<3, 3>() = body.inertia - body.mass * rx * rx;
  return M;
}

}  // namespace sheetgen
