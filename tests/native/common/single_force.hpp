#pragma once
// A sample scene as the tests written before the scenes had load envelopes
// read it: each box's mass at 9 g downward as its one case "design"
// (F = m * 9 * 9.81 N, to the mN, as the scene generator wrote it then), no
// envelope, no buckling or frequency check. Tests whose premise is that one
// static case (the hand-built webs of boxed_in and bulkhead_hole, the cost
// bound's corner library, the right-angle bay part against CalculiX) read the
// scenes through it.
#include <cmath>

#include "sheetgen/core/problem.hpp"

namespace sheetgen::test {

inline Problem single_force(Problem p) {
  for (Load& l : p.loads) {
    const double m = l.mass.value();  // every sample scene's box has a mass
    l.force = Vec3(0, 0, -std::round(m * 9.0 * 9.81 * 1000.0) / 1000.0);
    l.moment = Vec3::Zero();
    l.mass.reset();
    l.center_of_mass = l.center;
    l.inertia.setZero();
    l.cases = {LoadCase{"design", l.force, l.moment, {}}};
  }
  p.load_cases.reset();
  p.requirements.eigen_checks = false;
  p.requirements.min_frequency_hz.reset();
  return p;
}

}  // namespace sheetgen::test
