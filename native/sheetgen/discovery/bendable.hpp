#pragma once
// Discovery's press-brake filter (docs/discovery.md "Press-brake filter"): a
// segment whose own bends the press brake's tools cannot make, with nothing
// but the base and its ancestors around it, is not offered to the library.
// Every part that contains it holds the same tabs and more material, so no
// part built on it is bendable either; left in, it takes a slot of its rivet
// area that a bendable segment could fill, and composition spends analyses
// finding out.
#include <string>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/discovery/segment_library.hpp"
#include "sheetgen/part/part.hpp"

namespace sheetgen {

struct BendableResult {
  bool ok = true;
  std::string message;  // when not ok: the bend no tool makes and why, or the flat / sequence problem
};

// Checks `base` + the ancestors of `segment` in `library` + `segment` with
// the problem's press-brake tools. Always ok when the problem does not
// require the press brake (manufacturing.press_brake_required).
BendableResult segment_bendable(const Problem& problem, const Part& base, const SegmentLibrary& library,
                                const Segment& segment);

}  // namespace sheetgen
