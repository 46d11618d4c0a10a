#pragma once
// Conservative advancement, shared by the bend-sequence sweeps and the
// press-brake strokes (docs/manufacturing.md "Bend sequence").
#include <cmath>

namespace sheetgen {

// How many states after this one a tab moving at most `per_state` (m) per
// state stays clear with `margin` (m) to spare, at most `steps`. A part per
// million of the motion is kept back for rounding; a margin or motion that
// gives no number (0 / 0) skips nothing.
inline int clear_states(double margin, double per_state, int steps) {
  const double states = margin / (per_state * (1 + 1e-6));
  if (!(states >= 0)) return 0;
  return states >= steps ? steps : static_cast<int>(std::floor(states));
}

}  // namespace sheetgen
