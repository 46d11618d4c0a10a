#pragma once
// Feelers (paper Sec. 4): thin tabs (w = min_tab_width) whose parameters are
// drawn from a prior and whose length is CAST: rays leave the root edge along
// the tab's centre-line direction and the tab ends where the first obstacle
// (minus the clearance) or the volume bound is, or at l_max. A feeler whose
// rays hit a rivet area can try to fold a rivet flange flush onto it.
#include <cstdint>
#include <limits>
#include <optional>
#include <random>

#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

class Environment;

// Prior over one feeler tab and over the depth of a grown feeler chain.
// Every parameter is uniform on its range; the prior density cancels in the MH
// ratio because jumps and diffusions propose from it (docs/discovery.md).
struct FeelerPrior {
  double min_bend_angle = -1;   // rad, |theta3| >= this; < 0 = Manufacturing::min_bend_angle
  double max_bend_angle = -1;   // rad, |theta3| <= this; < 0 = Manufacturing::max_bend_angle (sign uniform)
  double max_skew = -1;         // rad, |theta1|, |theta2| <= this; < 0 = Manufacturing::max_skew
  double max_length = -1;       // m, l_max of a cast; < 0 = Manufacturing::max_tab_length
  double flat_probability = 0.25;  // share of feelers that continue their parent flat (theta3 = 0), when
                                   // Manufacturing::flat_extensions allows it (right-angle mode)
  double bounds_margin = 0.05;  // m, the volume bound is the problem's bounding box grown by this
  double far_edge_probability = 0.5;   // a grown chain continues on the far edge, else on a side (half each)
  double empty_probability = 0.15;     // a jump grows no tab at all (the reverse of growing on a bare edge)
  double continue_probability = 0.6;   // after each grown tab, grow one more
  int max_depth = 5;                   // tabs per grown chain
};

// Random numbers of one chain: a 64-bit Mersenne twister turned into doubles by
// hand, so the stream is the same on every standard library.
class ChainRng {
 public:
  explicit ChainRng(std::uint64_t seed) : engine_(seed) {}
  static std::uint64_t seed_for(std::uint64_t seed, int chain);  // splitmix64 of (seed, chain)
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }  // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  int index(int n) { return std::min(n - 1, static_cast<int>(uniform() * n)); }  // 0..n-1
 private:
  std::mt19937_64 engine_;
};

// The prior with every "< 0 = default" resolved from the sheet spec.
FeelerPrior resolve_prior(const FeelerPrior& prior, const SheetSpec& spec);

// Draws d (on an edge of length edge_length), theta1..3 from the prior; w = min_tab_width, l = 0.
// Returns nullopt when the edge is shorter than the feeler width.
std::optional<TabParameters> sample_feeler_parameters(const FeelerPrior& prior, const SheetSpec& spec,
                                                      double edge_length, ChainRng& rng);

// A rivet-area plane a flange can lie on: the hit face's plane, normal towards the feeler.
struct RivetPlane {
  int rivet_area = -1;
  Vec3 point = Vec3::Zero();   // m, on the face
  Vec3 normal = Vec3::UnitZ(); // unit, front side (where the flange lies, at t/2)
};

struct CastResult {
  double length = 0;            // m, perpendicular tab length l that keeps every ray clear
  bool hit = false;             // an obstacle (not the volume bound or l_max) limited it
  std::optional<RivetPlane> rivet;  // the middle ray (or else a side ray) hit a rivet area
};

// Casts tab `tab` of `part` (its d, w, theta1..3 set; l is ignored): `rays`
// rays from points spread across the root edge, along the tab's sides.
// `realised` must be realise(part) (any l for this tab).
CastResult cast_tab_length(const Part& part, const RealisedPart& realised, int tab, const Environment& env,
                           const SheetSpec& spec, const FeelerPrior& prior, int rays = 3);

// Makes tab `tab` reach `plane` and folds a rivet flange onto it: theta1 turns
// the far edge parallel to the plane, l puts the far edge at t/2 from it, and a
// flange (rivet_area = plane.rivet_area) on the far edge, as wide as the far
// edge, with theta3 making it parallel to the plane and length flange_length().
// If `flange` >= 0 that tab is reused (it must be the far-edge child of `tab`),
// otherwise a tab is appended. Of the two bend angles that lie in the plane the
// one closest to `preferred_theta3` is tried (NaN: smaller |theta3| first).
// Returns the flange index, or -1 when the geometry cannot be built within the
// manufacturing limits (no validity check against the environment here).
int attach_flange(Part& part, int tab, const RivetPlane& plane, const SheetSpec& spec, int flange = -1,
                  double preferred_theta3 = std::numeric_limits<double>::quiet_NaN(), bool other_solution = false);

// Length of a flange bent by theta3 that leaves room for one rivet row:
// max(min_flange, setback + 2 * rivet_edge_distance + 1 mm).
double flange_length(double theta3, const SheetSpec& spec);

}  // namespace sheetgen
