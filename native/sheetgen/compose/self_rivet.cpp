#include "sheetgen/compose/self_rivet.hpp"
#include "sheetgen/compose/edge_span.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "sheetgen/core/polygon_geometry.hpp"
#include "sheetgen/part/part.hpp"
#include "sheetgen/part/validity.hpp"

namespace sheetgen {

namespace {

int tree_distance(const Part& part, int i, int j) {
  std::vector<int> up_i;
  for (int k = i; k >= 0; k = part.tabs[k].parent) up_i.push_back(k);
  int steps = 0;
  for (int k = j; k >= 0; k = part.tabs[k].parent, ++steps) {
    auto it = std::find(up_i.begin(), up_i.end(), k);
    if (it != up_i.end()) return steps + static_cast<int>(it - up_i.begin());
  }
  return 1 << 20;
}

bool edge_has_child(const Part& part, int tab, int edge) {
  for (int c : part.children(tab))
    if (part.tabs[c].parent_edge == edge) return true;
  return false;
}

std::vector<Vec2> ccw(std::vector<Vec2> p) {
  if (signed_area(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}

}  // namespace

std::vector<VisiblePair> visible_edge_pairs(const Part& part, const RealisedPart& rp, double thickness, const SelfRivetOptions& o) {
  const double tolerance = o.coplanar_tolerance > 0 ? o.coplanar_tolerance : 1.5 * thickness;
  std::vector<FreeEdge> edges;
  for (const FreeEdge& e : rp.free_edges())
    if (!edge_has_child(part, e.tab, e.edge) && part.tabs[e.tab].riveted_to < 0) edges.push_back(e);
  std::vector<VisiblePair> pairs;
  for (size_t i = 0; i < edges.size(); ++i)
    for (size_t j = i + 1; j < edges.size(); ++j) {
      const FreeEdge& a = edges[i];
      const FreeEdge& b = edges[j];
      if (a.tab == b.tab) continue;
      const Vec3 na = rp.tabs[a.tab].normal, nb = rp.tabs[b.tab].normal;
      // Parent tabs in one plane: a gusset between them would be a flat patch, not a brace.
      if (na.cross(nb).norm() < std::sin(o.min_plane_angle) && std::abs((rp.tabs[b.tab].origin - rp.tabs[a.tab].origin).dot(na)) < tolerance)
        continue;
      // Plane through edge a and the farther endpoint of b.
      const Vec3 ea = a.b - a.a;
      const Vec3 pb = ((b.a - a.a).cross(ea).norm() > (b.b - a.a).cross(ea).norm()) ? b.a : b.b;
      Vec3 n = ea.cross(pb - a.a);
      if (n.norm() < 1e-12) continue;
      n.normalize();
      if (std::abs((b.a - a.a).dot(n)) > tolerance || std::abs((b.b - a.a).dot(n)) > tolerance) continue;
      if (n.cross(na).norm() < std::sin(o.min_plane_angle) || n.cross(nb).norm() < std::sin(o.min_plane_angle)) continue;
      VisiblePair p{a, b, n, tree_distance(part, a.tab, b.tab), (0.5 * (a.a + a.b) - 0.5 * (b.a + b.b)).norm()};
      pairs.push_back(p);
    }
  std::stable_sort(pairs.begin(), pairs.end(), [](const VisiblePair& x, const VisiblePair& y) {
    return x.tree_distance != y.tree_distance ? x.tree_distance > y.tree_distance : x.gap < y.gap;
  });
  if (static_cast<int>(pairs.size()) > o.max_pairs) pairs.resize(o.max_pairs);
  return pairs;
}

namespace {

// The 2-D frame of a pair's common plane: the origin at edge a's start, x along edge a.
struct PlaneFrame {
  Vec3 origin, ex, ey, n;  // n: unit normal of the plane
  Vec2 to2(const Vec3& p) const { return Vec2((p - origin).dot(ex), (p - origin).dot(ey)); }
  Vec3 to3(const Vec2& q) const { return origin + q.x() * ex + q.y() * ey; }
};

// What every step of gusset_plans reads: the part, the pair and its plane, the sheet rules.
struct GussetContext {
  const Part& part;
  const RealisedPart& rp;
  const VisiblePair& pair;
  const Problem& problem;
  const Manufacturing& mf;
  SheetSpec spec;
  PlaneFrame frame;
  double clearance;  // m, between a gusset and the other tab's edge: as check_validity, plus a margin
};

GussetContext gusset_context(const Part& part, const RealisedPart& rp, const VisiblePair& pair, const Problem& problem) {
  const Vec3 n = pair.plane_normal;
  const Vec3 ex = (pair.a.b - pair.a.a).normalized();
  const PlaneFrame frame{pair.a.a, ex, n.cross(ex), n};
  return {part, rp, pair, problem, problem.manufacturing, SheetSpec::from(problem), frame,
          problem.material.thickness + ValidityOptions{}.self_gap + 0.5e-3};
}

// One gusset's root on its edge and its direction in the common plane.
struct GussetSide {
  const FreeEdge* e;
  Vec3 dir;        // unit, along the edge (a -> b)
  Vec3 v;          // unit, in the plane, perpendicular to the edge, towards the other edge
  double theta3;   // rad
  double theta2;   // rad, skew leaning the gusset towards the other edge's middle
  double d, w;     // m, root offset and width
  double reach;    // m, along v, to the other edge's midpoint
};

// On a rivet flange's side edge, stop short of the rivet row: the gusset's
// bend zone and the relief notch beyond its root's end (t) must stay the
// edge distance from the row, which runs e from the far edge (docs/fem.md
// "Rivets"). Else the flange loses the rivet nearest the gusset, which is
// the one that carries the gusset's load into the structure. lo, hi: m along the edge.
void keep_clear_of_rivet_row(const GussetContext& g, const FreeEdge& e, double& lo, double& hi) {
  const RealisedTab& t = g.rp.tabs[e.tab];
  if (!(g.part.tabs[e.tab].rivet_area >= 0 && e.tab > 0 && t.corners.size() == 4)) return;
  const double reserve = 2.0 * g.mf.rivet_edge_distance + g.problem.material.thickness + 0.5e-3;
  auto to_far = [&](const Vec3& p) { return std::min((p - t.corners[2]).norm(), (p - t.corners[3]).norm()); };
  const double len = (e.b - e.a).norm();
  if (to_far(e.a) < 1e-6) lo = std::max(lo, reserve);
  else if (to_far(e.b) < 1e-6) hi = std::min(hi, len - reserve);
}

// The widest root a gusset on `e` towards `other` may have, square to its
// edge or leaning towards the other edge's middle; none when the fold is out
// of the bend limits or no minimum-width root fits.
std::optional<GussetSide> make_side(const GussetContext& g, const FreeEdge& e, const FreeEdge& other, bool lean_in) {
  const Manufacturing& mf = g.mf;
  const Vec3& n = g.frame.n;
  const Vec3 dir = (e.b - e.a).normalized();
  const Vec3 mo = 0.5 * (other.a + other.b) - 0.5 * (e.a + e.b);
  Vec3 v = mo - mo.dot(dir) * dir;
  v -= v.dot(n) * n;
  if (v.norm() < 1e-9) return std::nullopt;
  v.normalize();
  const RealisedTab& t = g.rp.tabs[e.tab];
  const Vec3 o = e.outward;  // in the tab's plane, away from it
  const double theta3 = std::atan2(v.dot(t.normal), v.dot(o));
  const double mag = std::abs(theta3);
  if (mag < mf.min_bend_angle || mag > mf.max_bend_angle) return std::nullopt;
  const double reach = mo.dot(v);
  if (!(reach > 0)) return std::nullopt;
  // Lean towards the other edge's middle (grammar: + leans towards the edge's end b).
  const double lean = lean_in ? std::clamp(std::atan2(mo.dot(dir), reach), -0.9 * mf.max_skew, 0.9 * mf.max_skew) : 0.0;
  // Keep clear of the bends at the edge's ends (their bend zones) and leave the
  // room a skewed root slides along its edge in the flat, dL tan(theta2)
  // (docs/manufacturing.md).
  const double margin = bend_zone_depth(theta3, g.spec) + std::abs(bend_length_change(theta3, g.spec) * std::tan(lean)) + 0.5e-3;
  const std::optional<EdgeSpan> span = free_edge_span(g.part, g.rp, e, theta3, margin, g.spec);
  if (!span) return std::nullopt;
  double lo = span->lo, hi = span->lo + span->width();
  keep_clear_of_rivet_row(g, e, lo, hi);
  const double w = hi - lo;
  if (w < mf.min_tab_width) return std::nullopt;
  return GussetSide{&e, dir, v, theta3, lean, lo, w, reach};
}

// The gusset quad of length l in the common plane: root [P0, P1] on the edge,
// sides along the leaning centre line; from `start` (m, square to the root as
// l is) on.
std::vector<Vec2> gusset_quad(const GussetContext& g, const GussetSide& s, double l, double start = 0.0) {
  const double f = std::min(1.0, start / l);
  const Vec3 p0 = s.e->a + s.d * s.dir, p1 = p0 + s.w * s.dir;
  const Vec3 side = l * (s.v + std::tan(s.theta2) * s.dir);
  const PlaneFrame& fr = g.frame;
  return ccw({fr.to2(p0 + f * side), fr.to2(p1 + f * side), fr.to2(p1 + side), fr.to2(p0 + side)});
}

// Its flat sheet, where a rivet may go: beyond the bend zone at its root.
std::vector<Vec2> gusset_flat_quad(const GussetContext& g, const GussetSide& s, double l) {
  return gusset_quad(g, s, l, bend_setback(s.theta3, g.spec));
}

// Each gusset lies in the common plane, which holds the other edge: the
// other tab leaves the plane along that edge, so the gusset must keep the
// sheets' clearance from it. Where two edges meet at an acute corner a
// gusset square to its edge would cross the other edge: give up width at
// the end nearer the other edge until it clears.
std::optional<GussetSide> clear_of(const GussetContext& g, GussetSide s, double l, const FreeEdge& other) {
  const PlaneFrame& fr = g.frame;
  const Vec2 q0 = fr.to2(other.a), q1 = fr.to2(other.b);
  auto distance = [&](const GussetSide& x) {
    const std::vector<Vec2> r = gusset_quad(g, x, l);
    double d = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < r.size(); ++k) d = std::min(d, segment_distance_2d(r[k], r[(k + 1) % r.size()], q0, q1));
    return d;
  };
  const Vec2 r0 = fr.to2(s.e->a + s.d * s.dir), r1 = fr.to2(s.e->a + (s.d + s.w) * s.dir);
  const bool from_start = segment_distance_2d(r0, r0, q0, q1) < segment_distance_2d(r1, r1, q0, q1);
  const double step = 2e-3;
  while (distance(s) < g.clearance) {
    s.w -= step;
    if (from_start) s.d += step;
    if (s.w < g.mf.min_tab_width) return std::nullopt;
  }
  return s;
}

// Rivets in the room the overlap leaves: its centre, plus up to two more each
// way along its longest extent at the pitch (m).
std::vector<Vec2> rivet_points(const std::vector<Vec2>& room, double pitch) {
  const Vec2 c = polygon_centroid(room);
  Vec2 lo = room[0], hi = room[0];
  for (const Vec2& q : room) { lo = lo.cwiseMin(q); hi = hi.cwiseMax(q); }
  std::vector<Vec2> rivets = {c};
  const Vec2 span = hi - lo;
  const int axis = span.x() > span.y() ? 0 : 1;
  const int extra = static_cast<int>(std::floor(span[axis] / pitch / 2));
  for (int k = 1; k <= std::min(extra, 2); ++k)
    for (int sgn : {-1, 1}) {
      Vec2 q = c;
      q[axis] += sgn * k * pitch;
      if (point_in_convex(q, room)) rivets.push_back(q);  // a slanted room's box reaches past it
    }
  return rivets;
}

// The part with the two gussets added, riveted to each other at `rivets` (in the plane's frame).
SelfRivetPlan make_plan(const GussetContext& g, const GussetSide& sa, double la, const GussetSide& sb, double lb,
                        const std::vector<Vec2>& rivets) {
  SelfRivetPlan plan;
  plan.part = g.part;
  auto add = [&](const GussetSide& s, double l) {
    TabParameters tp;
    tp.d = s.d;
    tp.w = s.w;
    tp.l = l;
    tp.theta2 = s.theta2;
    tp.theta3 = s.theta3;
    return plan.part.add_tab(s.e->tab, s.e->edge, tp);
  };
  plan.tab_a = add(sa, la);
  plan.tab_b = add(sb, lb);
  plan.part.tabs[plan.tab_a].riveted_to = plan.tab_b;
  plan.part.tabs[plan.tab_b].riveted_to = plan.tab_a;
  // Each gusset lies in the plane through its own edge (normal n); a rivet is a
  // point on each, joined through the thickness.
  const double off_b = (g.pair.b.a - g.frame.origin).dot(g.frame.n);
  for (const Vec2& q : rivets) {
    plan.rivets_a.push_back(g.frame.to3(q));
    plan.rivets_b.push_back(plan.rivets_a.back() + off_b * g.frame.n);
  }
  plan.added_area = sa.w * la + sb.w * lb;
  return plan;
}

// The gussets of one shape at lengths fa and fb of their reach: both clear of
// the other edge, overlapping, with room for a rivet on their flat sheets.
std::optional<SelfRivetPlan> gusset_plan(const GussetContext& g, const GussetSide& side_a, const GussetSide& side_b,
                                         double fa, double fb) {
  const Manufacturing& mf = g.mf;
  const double la = std::clamp(fa * side_a.reach, mf.min_tab_length, mf.max_tab_length);
  const double lb = std::clamp(fb * side_b.reach, mf.min_tab_length, mf.max_tab_length);
  const std::optional<GussetSide> fit_a = clear_of(g, side_a, la, g.pair.b), fit_b = clear_of(g, side_b, lb, g.pair.a);
  if (!fit_a || !fit_b) return std::nullopt;
  const std::vector<Vec2> overlap = clip_convex(gusset_quad(g, *fit_a, la), gusset_quad(g, *fit_b, lb));
  if (overlap.size() < 3) return std::nullopt;
  const std::vector<Vec2> flat_overlap = clip_convex(gusset_flat_quad(g, *fit_a, la), gusset_flat_quad(g, *fit_b, lb));
  if (flat_overlap.size() < 3) return std::nullopt;
  const std::vector<Vec2> room = inset_convex(ccw(flat_overlap), mf.rivet_edge_distance);
  if (room.size() < 3) return std::nullopt;
  return make_plan(g, *fit_a, la, *fit_b, lb, rivet_points(room, mf.rivet_pitch));
}

}  // namespace

std::vector<SelfRivetPlan> gusset_plans(const Part& part, const RealisedPart& rp, const VisiblePair& pair, const Problem& problem) {
  const GussetContext g = gusset_context(part, rp, pair, problem);
  // Straight gussets (square to their edges) and gussets leaning towards the
  // other edge's middle: which one fits depends on what lies between the edges.
  std::vector<std::pair<GussetSide, GussetSide>> shapes;
  for (bool lean_a : {false, true})
    for (bool lean_b : {false, true}) {
      const auto sa = make_side(g, pair.a, pair.b, lean_a), sb = make_side(g, pair.b, pair.a, lean_b);
      if (sa && sb) shapes.emplace_back(*sa, *sb);
    }
  std::vector<SelfRivetPlan> plans;
  const double fractions[] = {0.35, 0.5, 0.7, 1.0};
  for (const auto& [side_a, side_b] : shapes)
    for (double fa : fractions)
      for (double fb : fractions)
        if (std::optional<SelfRivetPlan> plan = gusset_plan(g, side_a, side_b, fa, fb)) plans.push_back(std::move(*plan));
  std::stable_sort(plans.begin(), plans.end(), [](const SelfRivetPlan& x, const SelfRivetPlan& y) { return x.added_area < y.added_area; });
  return plans;
}

namespace {

// The shortest side edge a square gusset of minimum width fits on: the
// gusset's bend zone kept from both ends (gusset_plans' margin, taken at the
// 90 deg a corner gusset has; steeper folds need more and are left to
// gusset_plans to refuse) and the tab's own root bend zone (free_edge_span). m.
double shortest_gusset_edge(const Part& part, const FreeEdge& e, const Manufacturing& mf, const SheetSpec& spec) {
  const double margin = bend_zone_depth(M_PI / 2, spec) + 0.5e-3;
  return mf.min_tab_width + 2 * margin + bend_setback(part.tabs[e.tab].params.theta3, spec) + 0.5e-3 + 1e-3;
}

// A side edge of a leaf tab that is neither the base nor riveted: its tab may grow.
bool growable(const Part& part, const FreeEdge& e) {
  const Tab& t = part.tabs[e.tab];
  return e.tab != 0 && (e.edge == kStartSideEdge || e.edge == kEndSideEdge) && part.children(e.tab).empty() &&
         t.riveted_to < 0;
}

double tab_area(const RealisedPart& r, int i) { return std::abs(signed_area(r.tabs[i].local)); }  // m^2

// The free edge of `realised` on the same tab and edge as `e`.
std::optional<FreeEdge> same_free_edge(const RealisedPart& realised, const FreeEdge& e) {
  for (const FreeEdge& f : realised.free_edges())
    if (f.tab == e.tab && f.edge == e.edge) return f;
  return std::nullopt;
}

}  // namespace

std::vector<SelfRivetPlan> lengthened_gusset_plans(const Part& part, const RealisedPart& rp, const VisiblePair& pair,
                                                   const Problem& problem) {
  const Manufacturing& mf = problem.manufacturing;
  const SheetSpec spec = SheetSpec::from(problem);
  auto shortest = [&](const FreeEdge& e) { return shortest_gusset_edge(part, e, mf, spec); };
  const bool short_a = pair.a.length < shortest(pair.a), short_b = pair.b.length < shortest(pair.b);
  if (!short_a && !short_b) return {};
  if ((short_a && !growable(part, pair.a)) || (short_b && !growable(part, pair.b))) return {};

  std::vector<SelfRivetPlan> out;
  for (double factor : {1.0, 1.2, 1.4, 1.7, 2.0, 2.5}) {
    Part grown = part;
    for (const FreeEdge* e : {&pair.a, &pair.b}) {
      if (e->length >= shortest(*e)) continue;
      // The side edge's length grows with l by 1/cos(theta2) (docs/grammar.md);
      // theta1 tilts the far edge about its midpoint and does not change that rate.
      TabParameters& tp = grown.tabs[e->tab].params;
      tp.l = std::min(mf.max_tab_length, tp.l + (factor * shortest(*e) - e->length) * std::cos(tp.theta2));
    }
    const RealisedPart grp = realise(grown);
    const std::optional<FreeEdge> a = same_free_edge(grp, pair.a), b = same_free_edge(grp, pair.b);
    if (!a || !b || grp.tabs[pair.a.tab].degenerate || grp.tabs[pair.b.tab].degenerate) continue;
    // A side edge grows along its own line, so the two edges stay in the common plane.
    VisiblePair grown_pair = pair;
    grown_pair.a = *a;
    grown_pair.b = *b;
    // m^2; the two tabs of a visible pair are distinct.
    const double extension = tab_area(grp, pair.a.tab) - tab_area(rp, pair.a.tab) + tab_area(grp, pair.b.tab) - tab_area(rp, pair.b.tab);
    for (SelfRivetPlan& plan : gusset_plans(grown, grp, grown_pair, problem)) {
      plan.added_area += extension;
      out.push_back(std::move(plan));
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const SelfRivetPlan& x, const SelfRivetPlan& y) { return x.added_area < y.added_area; });
  return out;
}

}  // namespace sheetgen
