#include "sheetgen/core/triangle_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>
#include <unordered_map>

namespace sheetgen {

double TriangleMesh::face_area(int f) const {
  const auto& t = triangles[f];
  return 0.5 * (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]).norm();
}

Vec3 TriangleMesh::face_normal(int f) const {
  const auto& t = triangles[f];
  Vec3 n = (vertices[t[1]] - vertices[t[0]]).cross(vertices[t[2]] - vertices[t[0]]);
  double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

double TriangleMesh::area() const {
  double a = 0;
  for (int f = 0; f < static_cast<int>(triangles.size()); ++f) a += face_area(f);
  return a;
}

bool TriangleMesh::is_closed() const {
  if (triangles.empty()) return false;
  // Directed edge (a,b) must meet exactly one opposite edge (b,a).
  std::unordered_map<long long, int> directed;
  const long long n = static_cast<long long>(vertices.size());
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) ++directed[t[k] * n + t[(k + 1) % 3]];
  for (const auto& [key, count] : directed) {
    if (count != 1) return false;
    long long a = key / n, b = key % n;
    auto it = directed.find(b * n + a);
    if (it == directed.end() || it->second != 1) return false;
  }
  return true;
}

double BoundingBox::distance(const Vec3& p) const {
  if (empty()) return std::numeric_limits<double>::infinity();
  Vec3 d = (min - p).cwiseMax(p - max).cwiseMax(Vec3::Zero());
  return d.norm();
}

BoundingBox bounding_box(const TriangleMesh& mesh) {
  BoundingBox b;
  for (const auto& v : mesh.vertices) b.extend(v);
  return b;
}

double box_gap(const BoundingBox& a, const BoundingBox& b) {
  return (a.min - b.max).cwiseMax(b.min - a.max).cwiseMax(Vec3::Zero()).norm();
}

}  // namespace sheetgen
