#pragma once
// A triangle mesh in metres. Open surfaces are allowed (a floor may be one plane).
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products, quaternions: used wherever Vec3 is
#include <array>
#include <limits>
#include <vector>

namespace sheetgen {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;

struct TriangleMesh {
  std::vector<Vec3> vertices;                // #V, m
  std::vector<std::array<int, 3>> triangles; // #F by 3 vertex indices, counter-clockwise seen from the front

  double face_area(int f) const;             // m^2
  Vec3 face_normal(int f) const;             // unit; zero for a degenerate face
  double area() const;                       // m^2, sum over faces
  // True when every edge is shared by exactly two faces with opposite orientation.
  bool is_closed() const;
};

struct BoundingBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void extend(const Vec3& p) { min = min.cwiseMin(p); max = max.cwiseMax(p); }
  void extend(const BoundingBox& b) { min = min.cwiseMin(b.min); max = max.cwiseMax(b.max); }
  bool empty() const { return !(min.array() <= max.array()).all(); }
  Vec3 size() const { return empty() ? Vec3::Zero() : Vec3(max - min); }
  double diagonal() const { return size().norm(); }
  // Euclidean distance from p to the box (0 inside), m.
  double distance(const Vec3& p) const;
};

BoundingBox bounding_box(const TriangleMesh& mesh);
// The gap between two boxes, m (0 when they overlap): a lower bound on the
// distance between anything inside them, so a cheap test before an exact one.
double box_gap(const BoundingBox& a, const BoundingBox& b);

}  // namespace sheetgen
