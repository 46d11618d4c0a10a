#pragma once
// Web roots (our extension, docs/discovery.md "Web roots"): plates hung
// straight down from the base tab's edges before the chains start. Feelers
// that grow from a web's vertical side edges leave the load edge-on, as webs
// that carry the force in their own plane; feelers from the base edges leave
// flat, as plates that carry it across their thickness. Where the only way to
// a rivet area is a window or hole a few centimetres tall, a plate through it
// is 40-130 x too soft (docs/scenes.md) while a web through it is not.
//
// A web root is a library segment without a rivet flange (rivet_area = -1): a
// "structural" segment that composition only takes as the parent of segments
// grown from it.
#include <vector>

#include "sheetgen/discovery/feeler.hpp"
#include "sheetgen/discovery/segment_library.hpp"
#include "sheetgen/part/part.hpp"

namespace sheetgen {

class Environment;

struct WebRootOptions {
  // Deepest web (m); <= 0: the base tab's longest edge, so a web is at most
  // about square and adds at most a base's worth of material per edge.
  double max_depth = 0;
  // Corner insets tried at the end of each web (m, in order): the web starts
  // at its edge's first corner and stops this far before the second, so that
  // webs on adjacent edges keep t + gap apart and the bend has relief room.
  std::vector<double> corner_insets = {4.8e-3, 9.6e-3, 19.2e-3};
};

// One web per base edge whose downward cast (theta3 = -90 deg, away from the
// load) gives at least min_tab_length: length min(cast, max_depth), valid
// against the environment, the other webs and the flat pattern. `base` is a
// part holding only the base tab. The segments have rivet_area = -1, parent -1,
// one tab each, and no ids yet (SegmentLibrary::add gives them).
std::vector<Segment> make_web_roots(const Part& base, const Environment& env, const SheetSpec& spec,
                                    const FeelerPrior& prior, const WebRootOptions& options = {});

}  // namespace sheetgen
