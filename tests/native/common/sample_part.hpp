#pragma once
// The exports tests' sample part (its DXF is also what tests/python/test_part_dxf.py reads).
#include <cmath>

#include "sheetgen/part/part.hpp"

namespace sheetgen::fixtures {

// Base 60 x 60 mm; A up 90 on edge 0 with D down 90 on A's far edge; B down 45
// on edge 2; C up 120 on edge 1. Four bends: UP 90, DOWN 90, DOWN 45, UP 120.
inline Part four_bend_sample() {
  const double deg = M_PI / 180.0;
  Part p = make_base_part({Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.06, 0), Vec3(0, 0.06, 0)}, Vec3::UnitZ());
  const int a = p.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, 90 * deg});
  p.add_tab(a, kFarEdge, {0.002, 0.016, 0.02, 0, 0, -90 * deg});
  p.add_tab(0, 2, {0.02, 0.02, 0.025, 0, 0, -45 * deg});
  p.add_tab(0, 1, {0.02, 0.02, 0.02, 0, 0, 120 * deg});
  return p;
}

}  // namespace sheetgen::fixtures
