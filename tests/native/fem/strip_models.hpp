#pragma once
// Strips and plates for the closed-form buckling and vibration tests: a flat
// strip along x (length L, width b) meshed ns x nt, and a square plate.
#include <vector>

#include "fem_test_models.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen::test {

struct Strip {
  ShellModel model;
  std::vector<std::vector<int>> grid;  // [i along x][j along y]
  double length = 0.2, width = 0.01;   // m
};

// Al 2024-T3 1.6 mm with Poisson's ratio nu (0 makes the plate a beam: D = EI / b).
inline Material strip_material(double nu) {
  Material m;
  m.youngs_modulus = 73.1e9;
  m.poisson_ratio = nu;
  m.density = 2780;
  m.thickness = 1.6e-3;
  return m;
}

inline Strip strip(int ns, int nt, double nu = 0.0, double length = 0.2, double width = 0.01) {
  Strip s;
  s.length = length;
  s.width = width;
  s.model.material = strip_material(nu);
  GridBuilder g(s.model);
  s.grid = g.flat(Vec3::Zero(), Vec3(length, 0, 0), Vec3(0, width, 0), ns, nt);
  return s;
}

// Consistent nodal shares of a total force spread evenly along a grid edge.
inline void add_edge_force(ShellModel& m, const std::vector<int>& edge_nodes, const Vec3& total) {
  const double cells = static_cast<double>(edge_nodes.size() - 1);
  for (size_t k = 0; k < edge_nodes.size(); ++k) {
    const double share = (k == 0 || k + 1 == edge_nodes.size() ? 0.5 : 1.0) / cells;
    m.add_load(edge_nodes[k], total * share);
  }
}

}  // namespace sheetgen::test
