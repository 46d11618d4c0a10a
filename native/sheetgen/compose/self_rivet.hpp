#pragma once
// Self-riveting (paper Sec. 5.2, Fig. 6 and 9; docs/architecture.md
// "Composition"): two free edges are *visible* to each other when their four
// endpoints lie in one plane and their tabs do not. A gusset joins them: a tab
// from each edge bent into that plane, long enough that the two overlap,
// riveted where they overlap. The FEM ties the two sheets at the rivets.
#include <vector>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

struct SelfRivetOptions {
  // m, endpoints this close to the common plane count as in it. Two riveted
  // sheets lie one on the other, their mid-surfaces a thickness apart, so an
  // offset of up to 1.5 t is what a real gusset absorbs; 0 = 1.5 t.
  double coplanar_tolerance = 0;
  double min_plane_angle = 10.0 * M_PI / 180.0;  // rad, the common plane must differ from both tabs' planes
  int max_pairs = 6;                   // visible pairs tried per part, most promising first
};

struct VisiblePair {
  FreeEdge a, b;
  Vec3 plane_normal = Vec3::UnitZ();   // unit, of the common plane
  int tree_distance = 0;               // tabs between the two along the part tree
  double gap = 0;                      // m, between the edge midpoints
};

struct SelfRivetPlan {
  Part part;                  // the input part plus the two gusset tabs (riveted_to set on both)
  int tab_a = -1, tab_b = -1; // indices of the gusset tabs
  std::vector<Vec3> rivets_a, rivets_b;  // m, each rivet on gusset a and on gusset b (up to 1.5 t apart)
  double added_area = 0;      // m^2, of the two gusset tabs
};

// The visibility graph's edges, most promising first: tabs far apart in the
// tree (a compliant edge joined to a stiff one), then short gaps.
std::vector<VisiblePair> visible_edge_pairs(const Part& part, const RealisedPart& realised, double thickness,
                                           const SelfRivetOptions& options = {});

// Gussets for one pair, lightest first; each within the tab limits and with
// room for at least one rivet in the overlap. Validity against the
// environment is the caller's (check_validity) job.
std::vector<SelfRivetPlan> gusset_plans(const Part& part, const RealisedPart& realised, const VisiblePair& pair,
                                        const Problem& problem);

// Gussets for a pair whose edge is too short for one: the side edge of a leaf
// tab (a minimum-length rivet flange is 6 mm long) has no room for a gusset
// root between the bend zones at its ends. That tab is lengthened along its
// side edge, to the shortest length a minimum-width gusset fits and to twice
// that, and gusset_plans is run on the lengthened part. added_area counts the
// extension too. Empty when neither edge is short or a short one cannot grow
// (the base, a tab with children or a self-rivet tab).
std::vector<SelfRivetPlan> lengthened_gusset_plans(const Part& part, const RealisedPart& realised, const VisiblePair& pair,
                                                   const Problem& problem);

}  // namespace sheetgen
