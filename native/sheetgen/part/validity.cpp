#include "sheetgen/part/validity.hpp"

#include <algorithm>
#include <cstdio>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/core/polygon_geometry.hpp"
#include "sheetgen/part/rivet_flange.hpp"

namespace sheetgen {

const char* to_string(ValidityReason r) {
  switch (r) {
    case ValidityReason::Ok: return "ok";
    case ValidityReason::DegenerateTab: return "degenerate_tab";
    case ValidityReason::RootOutsideParentEdge: return "root_outside_parent_edge";
    case ValidityReason::TabTooNarrow: return "tab_too_narrow";
    case ValidityReason::TabTooShort: return "tab_too_short";
    case ValidityReason::TabTooLong: return "tab_too_long";
    case ValidityReason::BendAngleTooSmall: return "bend_angle_too_small";
    case ValidityReason::BendAngleTooLarge: return "bend_angle_too_large";
    case ValidityReason::SkewTooLarge: return "skew_too_large";
    case ValidityReason::BendZonesOverlap: return "bend_zones_overlap";
    case ValidityReason::FlangeTooShort: return "flange_too_short";
    case ValidityReason::SelfIntersection: return "self_intersection";
    case ValidityReason::ObstacleCollision: return "obstacle_collision";
    case ValidityReason::BadRivetArea: return "bad_rivet_area";
    case ValidityReason::FlangeNotFlush: return "flange_not_flush";
    case ValidityReason::FlangeOffRivetArea: return "flange_off_rivet_area";
    case ValidityReason::NoRoomForRivet: return "no_room_for_rivet";
    case ValidityReason::FlatJunctionOutsideEdge: return "flat_junction_outside_edge";
    case ValidityReason::ReliefDoesNotFit: return "relief_does_not_fit";
    case ValidityReason::FlatPatternOverlap: return "flat_pattern_overlap";
    case ValidityReason::NoBendSequence: return "no_bend_sequence";
    case ValidityReason::PressBrake: return "press_brake";
  }
  return "unknown";
}

bool ValidityReport::has(ValidityReason r) const {
  for (const auto& v : violations)
    if (v.reason == r) return true;
  return false;
}

std::string ValidityReport::summary() const { return violations.empty() ? "valid" : violations.front().message; }

namespace {

std::string fmt(const char* f, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a, b, c);
  return buf;
}

std::string mm(double m) { return fmt("%.3f mm", m * 1e3); }
std::string deg(double r) { return fmt("%.3f deg", r * 180.0 / M_PI); }

struct Sink {
  ValidityReport& report;
  const ValidityOptions& options;
  // Returns true when the caller should stop.
  bool add(ValidityReason r, int tab, int other, double value, const std::string& msg) {
    report.violations.push_back({r, tab, other, value, msg});
    return options.stop_at_first;
  }
  bool done() const { return options.stop_at_first && !report.violations.empty(); }
};

bool involves(const ValidityOptions& o, int i) { return o.only_tab < 0 || o.only_tab == i; }

std::string tab_name(int i) { return i == 0 ? std::string("base tab") : "tab " + std::to_string(i); }

// Limits of one tab; returns true to stop.
bool tab_limits(const Part& part, const RealisedPart& rp, const SheetSpec& spec, int i, Sink& sink) {
  const Tab& tab = part.tabs[i];
  const TabParameters& p = tab.params;
  const Manufacturing& mf = spec.manufacturing;
  const double lt = sink.options.length_tolerance, at = sink.options.angle_tolerance;
  const std::string who = tab_name(i);
  if (rp.tabs[i].degenerate &&
      sink.add(ValidityReason::DegenerateTab, i, -1, p.theta1 + p.theta2,
               who + " is degenerate: its far edge cannot be built (w " + mm(p.w) + ", l " + mm(p.l) + ", theta1 + theta2 " +
                   deg(p.theta1 + p.theta2) + ")"))
    return true;
  const RealisedTab& par = rp.tabs[tab.parent];
  const int m = static_cast<int>(par.corners.size());
  const double edge_len = (par.corners[(tab.parent_edge + 1) % m] - par.corners[tab.parent_edge]).norm();
  if ((p.d < -lt || p.d + p.w > edge_len + lt) &&
      sink.add(ValidityReason::RootOutsideParentEdge, i, tab.parent, p.d < 0 ? p.d : p.d + p.w - edge_len,
               who + " root [" + mm(p.d) + ", " + mm(p.d + p.w) + "] leaves edge " + std::to_string(tab.parent_edge) +
                   " of " + tab_name(tab.parent) + " (length " + mm(edge_len) + ")"))
    return true;
  if (p.w < mf.min_tab_width - lt &&
      sink.add(ValidityReason::TabTooNarrow, i, -1, p.w,
               who + " width " + mm(p.w) + " is below the minimum tab width " + mm(mf.min_tab_width)))
    return true;
  if (tab.rivet_area >= 0) {
    if (p.l < mf.min_flange - lt &&
        sink.add(ValidityReason::FlangeTooShort, i, -1, p.l,
                 who + " is a rivet flange of length " + mm(p.l) + ", below the minimum flange " + mm(mf.min_flange)))
      return true;
  } else if (p.l < mf.min_tab_length - lt &&
             sink.add(ValidityReason::TabTooShort, i, -1, p.l,
                      who + " length " + mm(p.l) + " is below the minimum tab length " + mm(mf.min_tab_length))) {
    return true;
  }
  if (p.l > mf.max_tab_length + lt &&
      sink.add(ValidityReason::TabTooLong, i, -1, p.l,
               who + " length " + mm(p.l) + " is above the maximum tab length " + mm(mf.max_tab_length)))
    return true;
  const double a3 = std::abs(p.theta3);
  if (is_flat_extension(p) && !mf.flat_extensions &&
      sink.add(ValidityReason::BendAngleTooSmall, i, -1, p.theta3,
               who + " is a flat extension (bend 0 deg), which these manufacturing settings do not allow"))
    return true;
  if (!is_flat_extension(p) && a3 < mf.min_bend_angle - at &&
      sink.add(ValidityReason::BendAngleTooSmall, i, -1, p.theta3,
               who + " bend " + deg(p.theta3) + " is below the minimum bend angle " + deg(mf.min_bend_angle)))
    return true;
  if (a3 > mf.max_bend_angle + at &&
      sink.add(ValidityReason::BendAngleTooLarge, i, -1, p.theta3,
               who + " bend " + deg(p.theta3) + " is above the maximum bend angle " + deg(mf.max_bend_angle)))
    return true;
  const double skew = std::max(std::abs(p.theta1), std::abs(p.theta2));
  if (skew > mf.max_skew + at &&
      sink.add(ValidityReason::SkewTooLarge, i, -1, skew,
               who + " in-plane angle " + deg(skew) + " (|theta1| or |theta2|) is above the maximum skew " +
                   deg(mf.max_skew)))
    return true;
  return false;
}

// Children's bend zones must stay clear of this tab's own root bend zone.
bool bend_zone_room(const Part& part, const RealisedPart& rp, const SheetSpec& spec, int i, Sink& sink) {
  if (i == 0) return false;
  const RealisedTab& t = rp.tabs[i];
  const double sb = bend_setback(part.tabs[i].params.theta3, spec);
  for (int c : part.children(i)) {
    if (!involves(sink.options, i) && !involves(sink.options, c)) continue;
    const RealisedTab& ct = rp.tabs[c];
    const double sbc = bend_setback(part.tabs[c].params.theta3, spec);
    // Extent of the child's bend zone along this tab's y axis.
    const double reach = sbc * std::abs(t.normal.cross(ct.x_axis).dot(t.y_axis));
    for (const Vec3& q : {ct.bend_start(), ct.bend_end()}) {
      const double y = (q - t.origin).dot(t.y_axis);
      if (y - reach < sb - sink.options.length_tolerance &&
          sink.add(ValidityReason::BendZonesOverlap, c, i, y - reach - sb,
                   tab_name(c) + " bend zone reaches " + mm(sb - (y - reach)) + " into the root bend zone of " +
                       tab_name(i) + " (setback " + mm(sb) + ")"))
        return true;
    }
  }
  return false;
}

// The strip of tab i's sheet that child c's bend takes (m, in i's local frame,
// counter-clockwise): the root, swept SB of that bend into tab i.
std::vector<Vec2> parent_side_bend_strip(const Part& part, const RealisedPart& rp, const SheetSpec& spec, int i, int c) {
  const RealisedTab& t = rp.tabs[i];
  const auto local = [&](const Vec3& q) { return Vec2((q - t.origin).dot(t.x_axis), (q - t.origin).dot(t.y_axis)); };
  const Vec2 a = local(rp.tabs[c].bend_start()), b = local(rp.tabs[c].bend_end());
  Vec2 inward(-(b - a).y(), (b - a).x());
  inward.normalize();
  if ((polygon_centroid(t.local) - a).dot(inward) < 0) inward = -inward;
  const Vec2 depth = bend_setback(part.tabs[c].params.theta3, spec) * inward;
  std::vector<Vec2> strip = {a, b, b + depth, a + depth};
  if (signed_area(strip) < 0) std::reverse(strip.begin(), strip.end());
  return strip;
}

// Two bends on edges of tab i that share no corner (the two sides of a
// narrow tab) must leave flat sheet between them: where the strips each bend
// takes out of tab i overlap, the two bends would have to be one curve, which
// no press brake makes (docs/manufacturing.md "Bends side by side"). Bends
// on one edge, or on two edges meeting at a corner, are the ordinary case
// (reliefs, corner notches) and are not checked here.
bool sibling_bend_room(const Part& part, const RealisedPart& rp, const SheetSpec& spec, int i, Sink& sink) {
  std::vector<int> bent;
  for (int c : part.children(i))
    if (!is_flat_extension(part.tabs[c].params)) bent.push_back(c);
  const int n = part.edge_count(i);
  const double tol = sink.options.length_tolerance;
  for (size_t u = 0; u < bent.size(); ++u)
    for (size_t v = u + 1; v < bent.size(); ++v) {
      const int c1 = bent[u], c2 = bent[v];
      if (!involves(sink.options, c1) && !involves(sink.options, c2)) continue;
      const int gap = std::abs(part.tabs[c1].parent_edge - part.tabs[c2].parent_edge);
      if (gap == 0 || gap == 1 || gap == n - 1) continue;
      const std::vector<Vec2> overlap = clip_convex(inset_convex(parent_side_bend_strip(part, rp, spec, i, c1), tol),
                                                    inset_convex(parent_side_bend_strip(part, rp, spec, i, c2), tol));
      const double area = overlap.size() >= 3 ? signed_area(overlap) : 0.0;
      if (area > 0 && sink.add(ValidityReason::BendZonesOverlap, c2, c1, area,
                               tab_name(c2) + " bend zone overlaps the bend zone of " + tab_name(c1) + " across " +
                                   tab_name(i) + " (" + fmt("%.1f mm^2", area * 1e6) + ", no flat sheet between them)"))
        return true;
    }
  return false;
}

// Tabs that may touch: a tab and its parent (they share the bend), and a
// self-rivet pair (they overlap by design).
bool adjacent(const Part& part, int i, int j) {
  const Tab& a = part.tabs[i];
  const Tab& b = part.tabs[j];
  return a.parent == j || b.parent == i || a.riveted_to == j || b.riveted_to == i;
}

}  // namespace

ValidityReport check_limits(const Part& part, const RealisedPart& rp, const SheetSpec& spec, const ValidityOptions& o) {
  ValidityReport report;
  Sink sink{report, o};
  for (int i = 1; i < part.size(); ++i) {
    if (involves(o, i) && tab_limits(part, rp, spec, i, sink)) return report;
  }
  for (int i = 1; i < part.size(); ++i)
    if (bend_zone_room(part, rp, spec, i, sink)) return report;
  for (int i = 0; i < part.size(); ++i)
    if (sibling_bend_room(part, rp, spec, i, sink)) return report;
  return report;
}

ValidityReport check_self_intersection(const Part& part, const RealisedPart& rp, const SheetSpec& spec,
                                       const ValidityOptions& o) {
  ValidityReport report;
  Sink sink{report, o};
  const double need = spec.thickness + o.self_gap;
  const int n = part.size();
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (!involves(o, i) && !involves(o, j)) continue;
      if (adjacent(part, i, j)) continue;
      const RealisedTab& a = rp.tabs[i];
      const RealisedTab& b = rp.tabs[j];
      if (box_gap(a.box, b.box) >= need) continue;
      const double d = convex_polygon_distance(a.corners, a.normal, b.corners, b.normal, need);
      if (d < need && sink.add(ValidityReason::SelfIntersection, j, i, d,
                               tab_name(j) + " comes " + mm(d) + " from " + tab_name(i) + " (needs t + gap = " + mm(need) +
                                   ")"))
        return report;
    }
  }
  return report;
}

namespace {

// The band of tab i within `depth` of its edge k (a bend line), as a half-plane
// in the tab's local frame: keep dot(n, x) >= c.
void strip_half_plane(const RealisedTab& t, const Vec3& a, const Vec3& b, double depth, Vec2& n, double& c) {
  const Vec2 la((a - t.origin).dot(t.x_axis), (a - t.origin).dot(t.y_axis));
  const Vec2 lb((b - t.origin).dot(t.x_axis), (b - t.origin).dot(t.y_axis));
  const Vec2 e = (lb - la).normalized();
  n = Vec2(-e.y(), e.x());
  // Orient towards the tab's centroid.
  Vec2 cen = Vec2::Zero();
  for (const auto& q : t.local) cen += q;
  cen /= static_cast<double>(t.local.size());
  if (n.dot(cen - la) < 0) n = -n;
  c = n.dot(la) + depth;
}

}  // namespace

ValidityReport check_environment(const Part& part, const RealisedPart& rp, const Environment& env,
                                 const ValidityOptions& o) {
  ValidityReport report;
  Sink sink{report, o};
  const Problem& problem = env.problem();
  const SheetSpec spec = SheetSpec::from(problem);
  const int n = part.size();
  // Rivet flanges first: their attachment is the more specific diagnosis.
  for (int i = 1; i < n; ++i) {
    if (part.tabs[i].rivet_area < 0 || !involves(o, i)) continue;
    const FlangeAttachment fa = check_rivet_flange(part, rp, i, problem, o);
    if (!fa.ok() && sink.add(fa.reason, i, -1, fa.covered_fraction, fa.message)) return report;
  }
  const double required = 0.5 * spec.thickness + spec.clearance;
  const int nra = static_cast<int>(problem.rivet_areas.size());
  const int nloads = static_cast<int>(problem.loads.size());
  auto own = [&](int i) {
    AllowedContacts a;
    if (i == 0) {
      if (part.load >= 0 && part.load < nloads) a.loads.push_back(part.load);
    } else if (part.tabs[i].rivet_area >= 0 && part.tabs[i].rivet_area < nra) {
      a.rivet_areas.push_back(part.tabs[i].rivet_area);
    }
    return a;
  };
  for (int i = 0; i < n; ++i) {
    if (!involves(o, i)) continue;
    const RealisedTab& t = rp.tabs[i];
    AllowedContacts allowed = own(i);
    // Neighbour contacts: near a bend line the sharp mid-surface model comes
    // within t/2 of what the tab across the bend may touch (the base's load,
    // a flange's rivet area). They are allowed inside the bend zone only.
    struct Band { Vec2 n; double c; };
    std::vector<Band> bands;
    AllowedContacts near = allowed;
    auto add_neighbour = [&](const AllowedContacts& other, const Vec3& a, const Vec3& b, double theta) {
      if (other.loads.empty() && other.rivet_areas.empty()) return;
      near.loads.insert(near.loads.end(), other.loads.begin(), other.loads.end());
      near.rivet_areas.insert(near.rivet_areas.end(), other.rivet_areas.begin(), other.rivet_areas.end());
      Band band;
      strip_half_plane(t, a, b, bend_zone_depth(theta, spec), band.n, band.c);
      bands.push_back(band);
    };
    if (i > 0) add_neighbour(own(part.tabs[i].parent), t.bend_start(), t.bend_end(), part.tabs[i].params.theta3);
    for (int c : part.children(i)) add_neighbour(own(c), rp.tabs[c].bend_start(), rp.tabs[c].bend_end(), part.tabs[c].params.theta3);

    const ContactResult full = env.polygon_contact(t.corners, required, near, o.contact_sample_spacing);
    ContactResult worst = full;
    if (full.clear && !bands.empty()) {
      std::vector<Vec2> local = t.local;
      for (const Band& b : bands) local = clip_half_plane(local, b.n, b.c);
      if (local.size() >= 3) {
        std::vector<Vec3> poly;
        for (const Vec2& q : local) poly.push_back(t.origin + q.x() * t.x_axis + q.y() * t.y_axis);
        worst = env.polygon_contact(poly, required, allowed, o.contact_sample_spacing);
      }
    }
    if (!worst.clear &&
        sink.add(ValidityReason::ObstacleCollision, i, -1, worst.min_clearance,
                 tab_name(i) + " comes " + mm(worst.min_clearance) + " from an obstacle near (" +
                     fmt("%.4f, %.4f, %.4f", worst.worst_point.x(), worst.worst_point.y(), worst.worst_point.z()) +
                     ") m; it needs t/2 + clearance = " + mm(required)))
      return report;
  }
  return report;
}

ValidityReport check_validity(const Part& part, const RealisedPart& rp, const SheetSpec& spec, const ValidityOptions& o) {
  ValidityReport report = check_limits(part, rp, spec, o);
  if (o.stop_at_first && !report.valid()) return report;
  ValidityReport self = check_self_intersection(part, rp, spec, o);
  report.violations.insert(report.violations.end(), self.violations.begin(), self.violations.end());
  return report;
}

ValidityReport check_validity(const Part& part, const RealisedPart& rp, const SheetSpec& spec, const Environment& env,
                              const ValidityOptions& o) {
  ValidityReport report = check_validity(part, rp, spec, o);
  if (o.stop_at_first && !report.valid()) return report;
  // The environment's part of the check reads the scene and the sheet's
  // lengths, which no grammar changes.
  ValidityReport e = check_environment(part, rp, env, o);
  report.violations.insert(report.violations.end(), e.violations.begin(), e.violations.end());
  return report;
}

ValidityReport check_validity(const Part& part, const RealisedPart& rp, const Environment& env, const ValidityOptions& o) {
  return check_validity(part, rp, SheetSpec::from(env.problem()), env, o);
}

}  // namespace sheetgen
