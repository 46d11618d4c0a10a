#pragma once
// The hat bracket of the structure tests: a 10 cm cube load 15 cm above a
// floor (one rivet area), a base under it, two legs down and two flanges on
// the floor.
#include <cmath>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/part/part.hpp"

namespace sheetgen::test {

// A 10 cm cube load whose bottom is 15 cm above a floor; the floor is one rivet area.
inline Problem bracket_problem() {
  Problem p;
  p.source = "<test>";
  EnvironmentMesh floor;
  floor.name = "floor";
  floor.mesh.vertices = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
  floor.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  p.meshes.push_back(floor);
  p.rivet_areas.push_back(RivetAreaSpec{"floor", 0, {0, 1}, 4.0});
  Load l;
  l.name = "box";
  l.center = Vec3(0, 0, 0.2);
  l.size = Vec3(0.1, 0.1, 0.1);
  l.force = Vec3(30, 0, -350);
  l.moment = Vec3(0, 2, 0);
  p.loads.push_back(l);
  const double t = p.material.thickness;
  p.manufacturing.bend_radius = 4 * t;
  p.manufacturing.rivet_diameter = 3.175e-3;
  p.manufacturing.rivet_edge_distance = 2 * 3.175e-3;
  p.manufacturing.rivet_pitch = 6 * 3.175e-3;
  return p;
}

// Base under the box; from its -x and +x edges a leg folds down to the floor
// and a flange folds flat onto it (a "hat" bracket: two legs, two flanges).
inline Part hat_part(const Problem& p) {
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  const double zb = 0.15 - 0.5 * p.material.thickness;  // base mid-surface height
  for (int edge : {1, 3}) {
    TabParameters leg{0.0, 0.1, zb - 0.5 * p.material.thickness, 0, 0, -M_PI / 2};
    const int l = part.add_tab(0, edge, leg);
    TabParameters flange{0.0, 0.1, 0.03, 0, 0, M_PI / 2};
    part.add_tab(l, kFarEdge, flange, 0);
  }
  return part;
}

}  // namespace sheetgen::test
