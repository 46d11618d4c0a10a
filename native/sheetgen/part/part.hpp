#pragma once
// The tab grammar (docs/architecture.md "Grammar", paper Sec. 3.2): a part is a tree of
// tabs. tabs[0] is the base tab (a convex polygon under the load); every other
// tab is a planar trapezoid leaving a free edge of its parent, described by six
// numbers (d, w, l, theta1, theta2, theta3). docs/grammar.md has the figure and
// the exact meaning and sign of every parameter.
//
// A Part is plain data (two small vectors) so the search can copy it freely.
#include <cstdint>
#include <string>
#include <vector>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

// Edge indices of a (non-base) tab polygon [P1, P0, F0, F1] (counter-clockwise
// seen from the tab's top normal). Edge k runs from corner k to corner k+1.
enum TabEdge : int {
  kRootEdge = 0,      // P1 -> P0, on the parent's edge; not free
  kStartSideEdge = 1, // P0 -> F0, the side leaving the root start
  kFarEdge = 2,       // F0 -> F1
  kEndSideEdge = 3,   // F1 -> P1, the side coming back to the root end
};

struct TabParameters {
  double d = 0;       // m, root start P0 = A + d*e, A the parent edge's start vertex, e its unit direction
  double w = 0;       // m, root width: P1 = P0 + w*e
  double l = 0;       // m, perpendicular distance from the root line to the far-edge midpoint
  double theta1 = 0;  // rad, in-plane rotation of the far edge about its midpoint; + moves F1 (the B-side far corner) away from the root
  double theta2 = 0;  // rad, in-plane skew; + leans the tab towards the parent edge's end vertex B
  double theta3 = 0;  // rad, bend out of the parent plane; + folds towards the parent's top normal ("up")
};

// theta3 = 0: the tab continues its parent's plane and is not bent (a flat
// extension, Manufacturing::flat_extensions). It has no bend line, no bend
// zone and no relief, and is not counted as a bend.
inline bool is_flat_extension(const TabParameters& p) { return p.theta3 == 0.0; }

struct Tab {
  int parent = -1;        // index into Part::tabs; -1 only for tabs[0] (the base)
  int parent_edge = -1;   // edge of the parent polygon (base: 0..n-1; tab: kStartSideEdge, kFarEdge, kEndSideEdge)
  TabParameters params;   // unused for the base
  int rivet_area = -1;    // >= 0: a rivet flange lying flush on Problem::rivet_areas[rivet_area]
  int tag = -1;           // free for callers (e.g. segment id in discovery); ignored by this library
  // >= 0: a self-rivet tab lying flush on (overlapping) that tab, riveted to it
  // (paper Sec. 5.2). The pair may touch: self-intersection and bend-sequence
  // checks skip it.
  int riveted_to = -1;
};

// The base tab's plane and outline. normal = x_axis x y_axis is the sheet's top
// side (towards the load); the outline is convex and counter-clockwise seen from it.
struct BaseTab {
  Vec3 origin = Vec3::Zero();   // m, world
  Vec3 x_axis = Vec3::UnitX();  // unit
  Vec3 y_axis = Vec3::UnitY();  // unit, orthogonal to x_axis
  std::vector<Vec2> outline;    // #n >= 3, m in (x_axis, y_axis) coordinates
  Vec3 normal() const { return x_axis.cross(y_axis); }
  Vec3 to_world(const Vec2& q) const { return origin + q.x() * x_axis + q.y() * y_axis; }
};

struct Part {
  int load = -1;           // index into Problem::loads the base tab carries (allowed contact), -1 = none
  BaseTab base;
  std::vector<Tab> tabs;   // tabs[0] = base; a parent always comes before its children

  int size() const { return static_cast<int>(tabs.size()); }
  // Appends a tab and returns its index. Throws std::invalid_argument when the
  // parent or edge index is out of range (the geometry is checked by check_validity).
  int add_tab(int parent, int parent_edge, const TabParameters& params, int rivet_area = -1);
  // Number of edges of tab i's polygon (base: outline size; tab: 4).
  int edge_count(int i) const { return i == 0 ? static_cast<int>(base.outline.size()) : 4; }
  bool is_free_edge(int i, int edge) const { return i == 0 ? (edge >= 0 && edge < edge_count(0)) : (edge >= 1 && edge <= 3); }
  std::vector<int> children(int i) const;  // in index order
  int depth(int i) const;                  // base 0, its children 1, ...
  int bend_count() const;                  // non-base tabs that are bent (flat extensions are not)
};

// Part with only a base tab: the load's bottom face moved t/2 down along the
// load's -z (so the sheet's top surface touches the box), top normal = load +z.
Part make_base_part(const Load& load, int load_index, double thickness);
// Part with a given base polygon (world, m, planar, convex, counter-clockwise
// about `normal`). Throws std::invalid_argument when it is not.
Part make_base_part(const std::vector<Vec3>& polygon, const Vec3& normal, int load_index = -1);

// Everything the part checks and plans need from a Problem, in SI units.
struct SheetSpec {
  double thickness = 1.6e-3;   // m
  double clearance = 1.0e-3;   // m, beyond t/2 (Requirements::clearance)
  Manufacturing manufacturing; // must have its defaults filled (load_problem does)
  static SheetSpec from(const Problem& problem);
};

// Bend geometry of the sharp mid-surface model (docs/manufacturing.md):
// setback SB = tan(|theta|/2) (R + t/2), allowance BA = |theta| (R + K t),
// flat length change per bend dL = BA - 2 SB (<= 0 for K <= 1/2).
double bend_setback(double theta, const SheetSpec& spec);     // m
double bend_allowance(double theta, const SheetSpec& spec);   // m
double bend_length_change(double theta, const SheetSpec& spec);  // m
// Depth of the bend zone measured into the parent from the sharp line:
// max(R + t, SB + t/2). Used for relief depth and contact allowances.
double bend_zone_depth(double theta, const SheetSpec& spec);  // m

}  // namespace sheetgen
