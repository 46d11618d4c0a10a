#pragma once
// The manufacturing rules the compose tests build their hand-made parts to:
// bend radius 4 t and the flange, tab and rivet sizes that follow from it
// (the defaults of docs/architecture.md "Units and defaults", written out so the tests' geometry is explicit).
#include "sheetgen/core/problem.hpp"

namespace sheetgen::testing {

inline void set_sheet_rules(Problem& p) {
  const double t = p.material.thickness;
  Manufacturing& m = p.manufacturing;
  m.bend_radius = 4 * t;
  m.min_flange = 4 * t + m.bend_radius;
  m.min_tab_width = 10 * t;
  m.min_tab_length = 2 * m.bend_radius + 2 * t;
  m.rivet_diameter = 3.175e-3;
  m.rivet_edge_distance = 2 * m.rivet_diameter;
  m.rivet_pitch = 6 * m.rivet_diameter;
}

}  // namespace sheetgen::testing
