#pragma once
// Stiffening lips: short tabs bent 90 degrees along the free edges of a
// part's tabs, as a sheet-metal designer flanges the edges of a long plate.
// Our extension of the paper (docs/pipeline.md, "Stiffening lips"): the
// segments the discovery finds are plates, and a plate carrying the box in
// bending is 10-100x more compliant than the same plate with its long edges
// turned up into a channel (second moment of area ~ w t^3 vs ~ t h^2 w).
// Composition tries lips on candidates that miss their limits.
#include "sheetgen/core/problem.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/part.hpp"

namespace sheetgen {

struct LipOptions {
  double min_edge_length = 0.04;  // m, shorter free edges get no lip (a lip stiffens along its length)
  int max_lips = 8;               // per part, longest edges first
  double length_factor = 2.0;     // lip length tried first, in multiples of Manufacturing::min_tab_length (then 1x)
};

struct LipResult {
  Part part;              // the input part plus the lips
  int lips = 0;           // lips added
  double added_area = 0;  // m^2, of the lips (mid-surface, before bend allowances)
};

// Adds lips one by one to the free edges of non-base tabs that carry no child,
// no rivet flange and no gusset, longest edge first. A lip is kept only when
// the part stays valid against the environment and itself (check_validity on
// the new tab) and still unfolds without overlap; on a tab that already has a
// lip the same side is tried first (a channel). Deterministic.
LipResult add_stiffening_lips(const Part& part, const Environment& env, const Problem& problem, const LipOptions& options = {});

}  // namespace sheetgen
