#pragma once
// The leg of the compose tests (stiffening lips, sizing): a box 0.25 m above a
// floor, pushed along +x; the part is the base under the box, a 100 mm wide
// leg bent 90 deg down from the base's -x edge, and a flange as wide as the
// leg bent back onto the floor. The force works the leg in bending across its
// plane.
#include <cmath>

#include "../common/scene_fixture.hpp"
#include "sheet_rules.hpp"
#include "sheetgen/core/problem.hpp"
#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen::testing {

struct LegOnFloor {
  Problem problem;
  Part part;
};

// force_x: N along +x on the box.
inline LegOnFloor leg_on_floor(double force_x) {
  LegOnFloor f;
  Problem& p = f.problem;
  p.source = "<test>";
  EnvironmentMesh floor;
  floor.name = "floor";
  floor.mesh = testing_scenes::rectangle(-0.5, 0.5, -0.5, 0.5, 0.0);  // normal +z
  p.meshes.push_back(floor);
  p.rivet_areas.push_back(RivetAreaSpec{"floor", 0, {0, 1}, 1.0});
  Load l;
  l.name = "box";
  l.center = Vec3(0, 0, 0.28);
  l.size = Vec3(0.1, 0.1, 0.06);
  l.force = Vec3(force_x, 0, 0);
  p.loads.push_back(l);
  set_sheet_rules(p);
  const double t = p.material.thickness;
  f.part = make_base_part(l, 0, t);
  const double z_base = realise(f.part).tabs[0].corners[0].z();
  // Base edge 3 is the -x side (docs/grammar.md); theta3 = -90 deg folds down.
  // The leg ends where the flange's mid-surface lies t/2 above the floor.
  const int leg = f.part.add_tab(0, 3, TabParameters{0.0, 0.1, z_base - 0.5 * t, 0, 0, -M_PI / 2});
  f.part.add_tab(leg, 2, TabParameters{0.0, 0.1, 0.03, 0, 0, M_PI / 2}, 0);
  return f;
}

}  // namespace sheetgen::testing
