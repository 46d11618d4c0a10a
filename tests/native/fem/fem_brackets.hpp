#pragma once
// Bracket models shared by the CalculiX comparison test and bench/fem_bench.cpp:
// the L-bracket of docs/fem.md "Reference values" and a three-tab bracket (a base plate under a
// rigid load box, a leg bent down from it, a rivet flange bent out from the
// leg and clamped at its rivet points), both meshed by the plate mesher.
#include <vector>

#include "sheetgen/fem/plate_mesher.hpp"
#include "sheetgen/fem/rivet_layout.hpp"
#include "sheetgen/fem/shell_model.hpp"

namespace sheetgen::test {

inline Material bracket_material(double nu) {
  Material m;  // Al 2024-T3 1.6 mm (docs/architecture.md "FEM") with the given nu
  m.youngs_modulus = 73.1e9;
  m.poisson_ratio = nu;
  m.thickness = 1.6e-3;
  return m;
}

// L-bracket: leg 1 (z = 0, 50 x 20 mm) clamped at x = 0, leg 2 (x = 50 mm,
// 30 mm high); 1 N along x spread over the top edge; load_node = top middle.
inline ShellModel l_bracket_model(double h) {
  const std::vector<Vec3> leg1 = {Vec3(0, 0, 0), Vec3(0.05, 0, 0), Vec3(0.05, 0.02, 0), Vec3(0, 0.02, 0)};
  const std::vector<Vec3> leg2 = {Vec3(0.05, 0, 0), Vec3(0.05, 0, 0.03), Vec3(0.05, 0.02, 0.03), Vec3(0.05, 0.02, 0)};
  PlateMeshOptions opt;
  opt.element_size = h;
  const PlateMesh pm = mesh_plates({leg1, leg2}, {}, opt);
  ShellModel m;
  m.material = bracket_material(0.0);
  m.nodes = pm.mesh.vertices;
  m.triangles = pm.mesh.triangles;
  for (int n : nodes_on_segment(pm.mesh, leg1[0], leg1[3])) m.clamp(n);
  const std::vector<int> top = nodes_on_segment(pm.mesh, leg2[1], leg2[2]);
  for (size_t k = 0; k < top.size(); ++k)
    m.add_load(top[k], Vec3((k == 0 || k + 1 == top.size() ? 0.5 : 1.0) / (top.size() - 1), 0, 0));
  m.load_node = top[top.size() / 2];
  return m;
}

// Three-tab bracket, sizes in m scaled by `scale` (1 = base 60 x 40 mm, leg
// 50 mm, flange 25 mm). Rivets by the default layout rule on the flange's far
// edge; each rivet clamps its footprint (centre + ring of radius d).
// The load box (30 x 20 x 30 mm) sits on the base; its centroid node carries
// F = (30, 10, -100) N and M = (0.5, -0.3, 0.2) N m.
inline ShellModel three_tab_bracket_model(double h, double scale = 1.0) {
  const double s = scale;
  const std::vector<Vec3> base = {Vec3(0, 0, 0), Vec3(0.06 * s, 0, 0), Vec3(0.06 * s, 0.04 * s, 0),
                                  Vec3(0, 0.04 * s, 0)};
  const std::vector<Vec3> leg = {Vec3(0.06 * s, 0, 0), Vec3(0.06 * s, 0, -0.05 * s), Vec3(0.06 * s, 0.04 * s, -0.05 * s),
                                 Vec3(0.06 * s, 0.04 * s, 0)};
  const std::vector<Vec3> flange = {Vec3(0.06 * s, 0, -0.05 * s), Vec3(0.085 * s, 0, -0.05 * s),
                                    Vec3(0.085 * s, 0.04 * s, -0.05 * s), Vec3(0.06 * s, 0.04 * s, -0.05 * s)};
  RivetLayoutOptions ro;
  ro.thickness = 1.6e-3;
  const RivetLayout rivets = layout_rivets(flange, 1, ro);  // far edge x = 85 mm
  PlateMeshOptions opt;
  opt.element_size = h;
  const PlateMesh pm = mesh_plates({base, leg, flange}, {{}, {}, rivets.all_points()}, opt);
  ShellModel m;
  m.material = bracket_material(0.33);
  m.nodes = pm.mesh.vertices;
  m.triangles = pm.mesh.triangles;
  for (int n : pm.fixed_point_nodes[2]) m.clamp(n);
  const double bx0 = 0.015 * s, bx1 = 0.045 * s, by0 = 0.01 * s, by1 = 0.03 * s;
  const std::vector<Vec3> box_bottom = {Vec3(bx0, by0, 0), Vec3(bx1, by0, 0), Vec3(bx1, by1, 0), Vec3(bx0, by1, 0)};
  RigidLink box;
  box.master = m.add_node(Vec3(0.5 * (bx0 + bx1), 0.5 * (by0 + by1), 0.015 * s));
  box.slaves = nodes_on_polygon(pm.mesh, box_bottom, 1e-9);
  m.rigid_links.push_back(box);
  m.add_load(box.master, Vec3(30, 10, -100), Vec3(0.5, -0.3, 0.2));
  m.load_node = box.master;
  return m;
}

}  // namespace sheetgen::test
