#pragma once
// Meshes shared by the environment tests and benchmarks.
#include <cmath>
#include <map>
#include <random>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen::testing {

// Closed icosphere of the given radius (m) and subdivision level (20 * 4^level triangles).
inline TriangleMesh icosphere(double radius, int level, const Vec3& centre = Vec3::Zero()) {
  TriangleMesh m;
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  const double raw[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                             {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  for (const auto& r : raw) m.vertices.push_back(Vec3(r[0], r[1], r[2]).normalized());
  m.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      return mid[key] = static_cast<int>(m.vertices.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& t : m.triangles) {
      int a = midpoint(t[0], t[1]), b = midpoint(t[1], t[2]), c = midpoint(t[2], t[0]);
      next.push_back({t[0], a, c});
      next.push_back({t[1], b, a});
      next.push_back({t[2], c, b});
      next.push_back({a, b, c});
    }
    m.triangles = next;
  }
  for (auto& v : m.vertices) v = centre + radius * v;
  return m;
}

// Open square plane of side `size` (m) through `centre` with unit normal n, n x n cells.
inline TriangleMesh plane(const Vec3& centre, const Vec3& normal, double size, int cells) {
  TriangleMesh m;
  const Vec3 n = normal.normalized();
  const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i)
      m.vertices.push_back(centre + size * ((i / double(cells) - 0.5) * u + (j / double(cells) - 0.5) * v));
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      int a = j * (cells + 1) + i, b = a + 1, c = a + cells + 2, d = a + cells + 1;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  return m;
}

// A random point on the mesh surface (area-weighted by rejection on triangle index is fine for tests).
inline Vec3 random_surface_point(const TriangleMesh& m, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, static_cast<int>(m.triangles.size()) - 1);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const auto& t = m.triangles[pick(rng)];
  double a = u01(rng), b = u01(rng);
  if (a + b > 1) { a = 1 - a; b = 1 - b; }
  return m.vertices[t[0]] + a * (m.vertices[t[1]] - m.vertices[t[0]]) + b * (m.vertices[t[2]] - m.vertices[t[0]]);
}

// Faces of plane(..., cells) in the block of cells [from, to) x [from, to) (two triangles per cell).
inline std::vector<int> plane_cell_block(int cells, int from, int to) {
  std::vector<int> faces;
  for (int j = from; j < to; ++j)
    for (int i = from; i < to; ++i) {
      faces.push_back(2 * (j * cells + i));
      faces.push_back(2 * (j * cells + i) + 1);
    }
  return faces;
}

inline Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Vec3 v(n(rng), n(rng), n(rng));
  return v.normalized();
}

}  // namespace sheetgen::testing
