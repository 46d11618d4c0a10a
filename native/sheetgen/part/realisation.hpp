#pragma once
// Realisation: tab tree -> one 3-D polygon, frame and bend per tab. A pure
// function of the Part (no environment); cheap enough to call per MCMC move.
#include <optional>
#include <vector>

#include "sheetgen/part/part.hpp"

namespace sheetgen {

enum class BendDirection : std::uint8_t { Up, Down };  // Up: towards the parent's top normal (theta3 > 0)

struct RealisedTab {
  // World corners, m, counter-clockwise seen from `normal`.
  // Tab: [P1, P0, F0, F1] (edge k = corner k -> k+1, see TabEdge); base: its outline.
  std::vector<Vec3> corners;
  // Same corners in the tab's local frame, m: x along x_axis, y along y_axis from origin.
  std::vector<Vec2> local;
  // Local frame. Tab: origin P0, x_axis = parent edge direction e (P0 -> P1),
  // y_axis = in-plane unit perpendicular to the root pointing into the tab.
  // Because a tab leaves its parent on the right of the parent's
  // counter-clockwise edge, x_axis x y_axis = -normal for tabs (and +normal for the base).
  Vec3 origin = Vec3::Zero();
  Vec3 x_axis = Vec3::UnitX();
  Vec3 y_axis = Vec3::UnitY();
  Vec3 normal = Vec3::UnitZ();  // unit, the sheet's top side (continuous with the base's top across every bend)
  // The sharp mid-surface bend line to the parent (tabs only): P0 -> P1.
  double bend_angle = 0;   // rad, = theta3 (signed)
  BendDirection direction = BendDirection::Up;
  BoundingBox box;         // of the corners
  bool degenerate = false; // far edge not defined (cos(theta1 + theta2) <= 0) or a side of non-positive length
  Vec3 bend_start() const { return origin; }
  Vec3 bend_end() const { return corners.size() == 4 ? corners[0] : origin; }
};

struct FreeEdge {
  int tab = 0;
  int edge = 0;               // edge index in that tab's polygon
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();  // world, m; a -> b counter-clockwise (interior on the left seen from the top)
  Vec3 outward = Vec3::Zero();  // unit, in the tab's plane, away from the tab = (b - a) x normal / |b - a|
  double length = 0;          // m
};

struct RealisedPart {
  std::vector<RealisedTab> tabs;  // same indices as Part::tabs
  std::vector<FreeEdge> free_edges() const;  // base: all edges; tabs: edges 1, 2, 3
};

// Tab geometry in its local frame: [P1, P0, F0, F1] from (w, l, theta1, theta2),
// into `out` (resized to 4), which keeps its storage: no allocation when
// realise_into() refills a RealisedPart. `degenerate` is set when the far
// edge cannot be built.
void tab_local_corners_into(const TabParameters& p, std::vector<Vec2>& out, bool* degenerate = nullptr);

// Options for partial folds (bend-sequence sweeps) and flat layouts.
struct RealiseOptions {
  // Per-tab bend angle override (rad); empty = each tab's theta3. Index 0 is ignored.
  std::vector<double> angles;
  // Per-tab translation of the whole subtree along the tab's y_axis before
  // bending children (m); empty = none. The flat pattern uses the bend length change here.
  std::vector<double> shifts;
};

// Throws std::invalid_argument when the tree is malformed (parent after child,
// edge not free); geometric problems are reported by check_validity instead.
RealisedPart realise(const Part& part, const RealiseOptions& options = {});
// Same into an existing object (reuses its buffers; the fast path for the search).
void realise_into(const Part& part, RealisedPart& out, const RealiseOptions& options = {});
// The base and the tabs from it to `tab` only (its ancestors and itself),
// into `out`, sized for the whole part; its other tabs are left as they were.
// Each realised tab is what realise_into gives: a tab depends on its parent alone.
void realise_path_into(const Part& part, int tab, RealisedPart& out, const RealiseOptions& options = {});

}  // namespace sheetgen
