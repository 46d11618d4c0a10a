#pragma once
// The sheet most native tests use: Al 2024-T3, t = 1.6 mm, clearance 1 mm,
// with the defaults of docs/architecture.md for that thickness written out (R = 4t, min flange
// 4t + R, w_min = 10t, l_min = 2R + 2t, 5/32 in rivets at 2D edge distance and
// 6D pitch), so a test's closed-form numbers do not move with the defaults.
#include <cmath>

#include "sheetgen/part/part.hpp"

namespace sheetgen::fixtures {

inline Manufacturing aluminium_manufacturing_1_6mm() {
  Manufacturing m;
  m.bend_radius = 6.4e-3;
  m.k_factor = 0.45;
  m.kerf = 0.2e-3;
  m.min_flange = 12.8e-3;
  m.min_tab_width = 16e-3;
  m.min_tab_length = 16e-3;
  m.max_tab_length = 0.5;
  m.rivet_diameter = 3.96875e-3;  // 2t rounded up to 1/32 in
  m.rivet_edge_distance = 2 * m.rivet_diameter;
  m.rivet_pitch = 6 * m.rivet_diameter;
  return m;
}

inline SheetSpec aluminium_sheet_1_6mm() {
  SheetSpec s;
  s.thickness = 1.6e-3;
  s.clearance = 1e-3;
  s.manufacturing = aluminium_manufacturing_1_6mm();
  return s;
}

// The short names the tests use; one definition here so that test files can
// share a unity batch (tests/native/CMakeLists.txt).
inline constexpr double kDeg = M_PI / 180.0;
inline SheetSpec spec() { return aluminium_sheet_1_6mm(); }

// A size x size square base in z = 0 with its normal +z, from the origin.
inline Part square_base(double size = 0.04) {
  return make_base_part({Vec3(0, 0, 0), Vec3(size, 0, 0), Vec3(size, size, 0), Vec3(0, size, 0)}, Vec3::UnitZ());
}

}  // namespace sheetgen::fixtures
