#include "sheetgen/part/flat_pattern.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sheetgen/core/geometry.hpp"
#include "sheetgen/core/polygon_geometry.hpp"

namespace sheetgen {

double FlatPattern::area() const { return signed_area(outline); }

double FlatPattern::relief_area() const {
  double a = 0;
  for (const auto& r : reliefs) a += std::abs(signed_area(r.polygon));
  return a;
}

namespace {

std::string mm(double m) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f mm", m * 1e3);
  return buf;
}

std::vector<Vec2> ccw(std::vector<Vec2> p) {
  if (signed_area(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}

struct Junction {
  int parent = -1, edge = -1;
  double a0 = 0, a1 = 0;     // m along the parent's flat edge from its start vertex
  double edge_length = 0;    // m
  Vec2 S = Vec2::Zero(), E = Vec2::UnitX(), V = Vec2::UnitY();  // edge start, direction, outward
  double depth = 0;          // relief depth, m
  bool flat = false;         // a flat extension: no bend, so no relief of its own
  // Relief decisions.
  bool start_relief = false, end_relief = false, merged_with_next = false;
};

// What the unfolding steps share. Only the first failure is kept: the later
// ones are usually its consequences.
struct Unfolding {
  FlatPattern fp;
  std::vector<Junction> junction;                      // per tab (unused for the base)
  std::vector<std::vector<std::vector<int>>> on_edge;  // children per (parent, edge), sorted along the edge
  double wr = 0;    // m, relief width
  double ct = 0;    // m, corner tolerance
  double kerf = 0;  // m

  void fail(ValidityReason r, int tab, const std::string& msg) {
    if (fp.status == ValidityReason::Ok) {
      fp.status = r;
      fp.tab = tab;
      fp.message = msg;
    }
  }
};

// In the base tab's flat coordinates.
Vec2 flat_point(const BaseTab& base, const Vec3& p) {
  const Vec3 r = p - base.origin;
  return Vec2(r.dot(base.x_axis), r.dot(base.y_axis));
}

Vec2 flat_direction(const BaseTab& base, const Vec3& v) { return Vec2(v.dot(base.x_axis), v.dot(base.y_axis)).normalized(); }

// Every tab unbent (theta3 = 0) and pushed away from its parent by its bend length change dL.
RealiseOptions unbent_options(const Part& part, const SheetSpec& spec) {
  const int n = part.size();
  RealiseOptions ro;
  ro.angles.assign(n, 0.0);
  ro.shifts.assign(n, 0.0);
  for (int i = 1; i < n; ++i) ro.shifts[i] = bend_length_change(part.tabs[i].params.theta3, spec);
  return ro;
}

// Tab i's flat piece, trimmed at (or extended to) its parent's edge line along its side lines.
void lay_flat_piece(Unfolding& u, const Part& part, const RealisedTab& ft, int i, double dL) {
  const TabParameters& p = part.tabs[i].params;
  FlatPiece& pc = u.fp.pieces[i];
  pc.tab = i;
  pc.parent = part.tabs[i].parent;
  pc.shift = dL;
  pc.x_axis = flat_direction(part.base, ft.x_axis);
  pc.y_axis = flat_direction(part.base, ft.y_axis);
  pc.origin = flat_point(part.base, ft.origin) - dL * pc.y_axis;  // P0 on the parent's flat edge line
  for (const Vec3& c : ft.corners) pc.sharp.push_back(flat_point(part.base, c));
  const double delta = -dL * std::tan(p.theta2);  // where the shifted side lines meet the parent's edge line
  const Vec2 J0 = pc.origin + delta * pc.x_axis, J1 = pc.origin + (p.w + delta) * pc.x_axis;
  pc.polygon = {J1, J0, pc.sharp[2], pc.sharp[3]};
  if (!((pc.sharp[2] - J0).dot(pc.y_axis) > 0 && (pc.sharp[3] - J0).dot(pc.y_axis) > 0) || signed_area(pc.polygon) <= 0)
    u.fail(ValidityReason::BendZonesOverlap, i,
           "tab " + std::to_string(i) + " is too short for its bend: the flat pattern shortens it by " + mm(-dL));
}

FlatBend flat_bend(const FlatPiece& pc, const TabParameters& p, const SheetSpec& spec) {
  const Vec2 J0 = pc.polygon[1], J1 = pc.polygon[0];
  FlatBend bd;
  bd.tab = pc.tab;
  bd.parent = pc.parent;
  bd.angle = p.theta3;
  bd.direction = p.theta3 >= 0 ? BendDirection::Up : BendDirection::Down;
  bd.length = p.w;
  bd.inside_radius = spec.manufacturing.bend_radius;
  bd.allowance = bend_allowance(p.theta3, spec);
  bd.setback = bend_setback(p.theta3, spec);
  bd.length_change = pc.shift;
  bd.centre_offset = 0.5 * bd.allowance - bd.setback;
  bd.root_a = J0;
  bd.root_b = J1;
  bd.outward = pc.y_axis;
  bd.a = J0 + bd.centre_offset * pc.y_axis;
  bd.b = J1 + bd.centre_offset * pc.y_axis;
  return bd;
}

// Where tab i's root [J0, J1] lies on its parent's flat edge.
void place_on_parent_edge(Unfolding& u, const Tab& tab, int i, const SheetSpec& spec) {
  const FlatPiece& pc = u.fp.pieces[i];
  const Vec2 J0 = pc.polygon[1], J1 = pc.polygon[0];
  const std::vector<Vec2>& Q = u.fp.pieces[tab.parent].polygon;
  const int m = static_cast<int>(Q.size());
  Junction& j = u.junction[i];
  j.parent = tab.parent;
  j.edge = tab.parent_edge;
  j.S = Q[tab.parent_edge];
  const Vec2 T = Q[(tab.parent_edge + 1) % m];
  j.edge_length = (T - j.S).norm();
  j.E = j.edge_length > 0 ? Vec2((T - j.S) / j.edge_length) : pc.x_axis;
  j.V = pc.y_axis;
  j.a0 = (J0 - j.S).dot(j.E);
  j.a1 = (J1 - j.S).dot(j.E);
  j.flat = is_flat_extension(tab.params);
  j.depth = j.flat ? 0.0 : bend_zone_depth(tab.params.theta3, spec);
  if (j.a0 < -u.ct || j.a1 > j.edge_length + u.ct)
    u.fail(ValidityReason::FlatJunctionOutsideEdge, i,
           "tab " + std::to_string(i) + " flat root [" + mm(j.a0) + ", " + mm(j.a1) + "] leaves the flat edge " +
               std::to_string(j.edge) + " of tab " + std::to_string(j.parent) + " (length " + mm(j.edge_length) +
               "); skewed tabs shift their flat root by dL tan(theta2)");
}

// Pieces, bends and junctions of every tab, parents first.
void lay_out_tabs(Unfolding& u, const Part& part, const SheetSpec& spec, const RealisedPart& flat3, const std::vector<double>& shifts) {
  const int n = part.size();
  u.fp.pieces.resize(n);
  FlatPiece& base = u.fp.pieces[0];
  base.tab = 0;
  base.polygon = part.base.outline;
  base.sharp = part.base.outline;
  u.junction.assign(n, Junction{});
  for (int i = 1; i < n; ++i) {
    lay_flat_piece(u, part, flat3.tabs[i], i, shifts[i]);
    if (!is_flat_extension(part.tabs[i].params)) u.fp.bends.push_back(flat_bend(u.fp.pieces[i], part.tabs[i].params, spec));
    place_on_parent_edge(u, part.tabs[i], i, spec);
  }
}

void sort_children_along_edges(Unfolding& u, const Part& part) {
  const int n = part.size();
  u.on_edge.assign(n, {});
  for (int i = 0; i < n; ++i) u.on_edge[i].resize(part.edge_count(i));
  for (int i = 1; i < n; ++i) u.on_edge[part.tabs[i].parent][part.tabs[i].parent_edge].push_back(i);
  for (auto& edges : u.on_edge)
    for (auto& list : edges)
      std::sort(list.begin(), list.end(), [&](int a, int b) { return u.junction[a].a0 < u.junction[b].a0; });
}

// Which ends of the k-th bend on a parent edge get a relief, and whether it shares one with the next bend.
void decide_reliefs(Unfolding& u, const std::vector<int>& list, size_t k) {
  const double wr = u.wr, ct = u.ct;
  Junction& j = u.junction[list[k]];
  const Junction* prev = k > 0 ? &u.junction[list[k - 1]] : nullptr;
  const Junction* next = k + 1 < list.size() ? &u.junction[list[k + 1]] : nullptr;
  const bool prev_merged = prev && prev->merged_with_next;
  if (j.a0 > ct && !prev_merged && !j.flat) {
    j.start_relief = true;
    const double room = prev ? j.a0 - prev->a1 - wr : j.a0;
    if (room < wr - ct)
      u.fail(ValidityReason::ReliefDoesNotFit, list[k],
             "tab " + std::to_string(list[k]) + " bend ends " + mm(j.a0) + " from the start of its parent edge: a relief needs " +
                 mm(wr) + " (or end the bend at the corner)");
  }
  if (j.a1 < j.edge_length - ct && !j.flat) {
    if (next && next->a0 - j.a1 < 2.0 * wr + u.kerf) {
      j.merged_with_next = true;
      const double gap = next->a0 - j.a1;
      if (gap < 0)
        u.fail(ValidityReason::FlatPatternOverlap, list[k + 1],
               "tabs " + std::to_string(list[k]) + " and " + std::to_string(list[k + 1]) + " overlap on their parent edge by " + mm(-gap));
      else if (gap < wr - ct)
        u.fail(ValidityReason::ReliefDoesNotFit, list[k + 1],
               "tabs " + std::to_string(list[k]) + " and " + std::to_string(list[k + 1]) + " leave a gap of " + mm(gap) +
                   " on their parent edge: the shared relief needs " + mm(wr));
    } else {
      j.end_relief = true;
      if (!next && j.edge_length - j.a1 < wr - ct)
        u.fail(ValidityReason::ReliefDoesNotFit, list[k],
               "tab " + std::to_string(list[k]) + " bend ends " + mm(j.edge_length - j.a1) +
                   " from the end of its parent edge: a relief needs " + mm(wr) + " (or end the bend at the corner)");
    }
  }
}

struct Notch {
  double from = 0, to = 0;  // m along the parent edge
  double depth = 0;         // m
  int other_tab = -1;       // the second sibling of a shared notch
};

void cut_relief(Unfolding& u, int parent, int tab, const Notch& n) {
  const Junction& j = u.junction[tab];
  FlatRelief r;
  r.parent = parent;
  r.tab = tab;
  r.other_tab = n.other_tab;
  r.width = n.to - n.from;
  r.depth = n.depth;
  const Vec2 a = j.S + n.from * j.E, b = j.S + n.to * j.E;
  r.polygon = ccw({a, b, b - n.depth * j.V, a - n.depth * j.V});
  for (const Vec2& q : r.polygon)
    if (!point_in_convex(q, u.fp.pieces[parent].polygon, 1e-9))
      u.fail(ValidityReason::ReliefDoesNotFit, tab,
             "the relief of tab " + std::to_string(tab) + " (depth " + mm(n.depth) + ") does not fit inside tab " +
                 std::to_string(parent));
  u.fp.reliefs.push_back(r);
}

void cut_reliefs_of(Unfolding& u, int parent, const std::vector<int>& list, size_t k) {
  const Junction& j = u.junction[list[k]];
  if (j.start_relief) cut_relief(u, parent, list[k], {j.a0 - u.wr, j.a0, j.depth, -1});
  if (j.end_relief) cut_relief(u, parent, list[k], {j.a1, j.a1 + u.wr, j.depth, -1});
  if (j.merged_with_next) {
    const Junction& next = u.junction[list[k + 1]];
    if (next.a0 > j.a1) cut_relief(u, parent, list[k], {j.a1, next.a0, std::max(j.depth, next.depth), list[k + 1]});
  }
}

// Walks the base boundary, splicing every child's boundary (with its relief
// notches) into its parent's edge.
class OutlineTracer {
 public:
  explicit OutlineTracer(Unfolding& u) : u_(u), out_(u.fp.outline), owner_(u.fp.outline_tab) {}

  void trace(const BaseTab& base) {
    for (int k = 0; k < static_cast<int>(base.outline.size()); ++k) {
      push(base.outline[k], 0);
      edge(0, k);
    }
    if (out_.size() > 1 && (out_.back() - out_.front()).norm() <= u_.ct) {
      out_.pop_back();
      owner_.pop_back();
    }
  }

 private:
  void push(const Vec2& q, int who) {
    if (!out_.empty() && (out_.back() - q).norm() <= u_.ct) {
      owner_.back() = who;
      return;
    }
    out_.push_back(q);
    owner_.push_back(who);
  }

  // A tab's free edges 1..3 (edge 0 is its root), with its own children on them.
  void tab(int c) {
    const std::vector<Vec2>& Q = u_.fp.pieces[c].polygon;
    for (int k = 1; k <= 3; ++k) {
      edge(c, k);
      if (k < 3) push(Q[k + 1], c);
    }
  }

  void edge(int p, int k) {
    const auto& list = u_.on_edge[p][k];
    const double wr = u_.wr;
    for (size_t idx = 0; idx < list.size(); ++idx) {
      const int c = list[idx];
      const Junction& j = u_.junction[c];
      const Vec2 J0 = j.S + j.a0 * j.E, J1 = j.S + j.a1 * j.E;
      if (j.start_relief) {
        const Vec2 r1 = J0 - wr * j.E;
        push(r1, p);
        push(r1 - j.depth * j.V, p);
        push(J0 - j.depth * j.V, p);
      }
      push(J0, c);
      tab(c);
      push(J1, p);
      if (j.end_relief) {
        push(J1 - j.depth * j.V, p);
        push(J1 + wr * j.E - j.depth * j.V, p);
        push(J1 + wr * j.E, p);
      } else if (j.merged_with_next) {
        const Junction& nj = u_.junction[list[idx + 1]];
        const double d = std::max(j.depth, nj.depth);
        push(J1 - d * j.V, p);
        push(nj.S + nj.a0 * nj.E - d * j.V, p);
      }
    }
  }

  const Unfolding& u_;
  std::vector<Vec2>& out_;
  std::vector<int>& owner_;
};

}  // namespace

FlatPattern unfold(const Part& part, const SheetSpec& spec, const FlatPatternOptions& opt) {
  Unfolding u;
  u.fp.frame = part.base;
  if (part.size() == 0) return u.fp;
  u.wr = opt.relief_width > 0 ? opt.relief_width : spec.thickness;
  u.ct = opt.corner_tolerance;
  u.kerf = spec.manufacturing.kerf;

  const RealiseOptions ro = unbent_options(part, spec);
  lay_out_tabs(u, part, spec, realise(part, ro), ro.shifts);
  sort_children_along_edges(u, part);
  for (int p = 0; p < part.size(); ++p)
    for (const auto& list : u.on_edge[p])
      for (size_t k = 0; k < list.size(); ++k) {
        decide_reliefs(u, list, k);
        cut_reliefs_of(u, p, list, k);
      }
  OutlineTracer(u).trace(part.base);
  return std::move(u.fp);
}

bool unfolds_cleanly(const Part& part, const SheetSpec& spec) {
  const FlatPattern flat = unfold(part, spec);
  return flat.ok() && check_flat_pattern(flat, spec).valid();
}

ValidityReport check_flat_pattern(const FlatPattern& flat, const SheetSpec& spec, const ValidityOptions& o) {
  ValidityReport report;
  if (!flat.ok()) {
    report.violations.push_back({flat.status, flat.tab, -1, 0, flat.message});
    if (o.stop_at_first) return report;
  }
  const auto& P = flat.outline;
  const int m = static_cast<int>(P.size());
  const double kerf = spec.manufacturing.kerf;
  std::vector<Eigen::AlignedBox2d> boxes(m);
  for (int i = 0; i < m; ++i) {
    boxes[i].extend(P[i]);
    boxes[i].extend(P[(i + 1) % m]);
  }
  for (int i = 0; i < m; ++i) {
    for (int j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;  // adjacent through the closing vertex
      if (boxes[i].exteriorDistance(boxes[j]) >= kerf) continue;
      const double d = segment_distance_2d(P[i], P[(i + 1) % m], P[j], P[(j + 1) % m]);
      if (d < kerf) {
        const int a = flat.outline_tab[i], b = flat.outline_tab[j];
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.3f mm", d * 1e3);
        report.violations.push_back({ValidityReason::FlatPatternOverlap, std::max(a, b), std::min(a, b), d,
                                     "the flat pattern of tab " + std::to_string(std::max(a, b)) + " comes " + buf +
                                         " from tab " + std::to_string(std::min(a, b)) + " (kerf " + mm(kerf) + ")"});
        if (o.stop_at_first) return report;
      }
    }
  }
  return report;
}

std::vector<FlatPieceTransform> fold_transforms(const FlatPattern& flat) {
  const int n = static_cast<int>(flat.pieces.size());
  std::vector<FlatPieceTransform> m(n);
  if (n == 0) return m;
  m[0].rotation.col(0) = flat.frame.x_axis;
  m[0].rotation.col(1) = flat.frame.y_axis;
  m[0].rotation.col(2) = flat.frame.normal();
  m[0].translation = flat.frame.origin;
  std::vector<const FlatBend*> bend_of(n, nullptr);
  for (const FlatBend& b : flat.bends) bend_of[b.tab] = &b;
  for (int i = 1; i < n; ++i) {  // parents come first
    const FlatPieceTransform& P = m[flat.pieces[i].parent];
    const FlatBend* b = bend_of[i];
    if (!b) {  // a flat extension lies in its parent's plane
      m[i] = P;
      continue;
    }
    const Vec2 E = (b->b - b->a).normalized();
    const Vec3 e3 = P.rotation * Vec3(E.x(), E.y(), 0);
    const Vec3 X0 = P.apply(b->a - b->centre_offset * b->outward);  // on the sharp fold line
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(b->angle, -e3).toRotationMatrix();
    const Vec2 unshift = -b->length_change * b->outward;
    // q -> rot * (R_p (q + unshift) + T_p - X0) + X0
    m[i].rotation = rot * P.rotation;
    m[i].translation = rot * (P.rotation * Vec3(unshift.x(), unshift.y(), 0) + P.translation - X0) + X0;
  }
  return m;
}

std::vector<std::vector<Vec3>> fold_flat_pattern(const FlatPattern& flat) {
  const std::vector<FlatPieceTransform> m = fold_transforms(flat);
  std::vector<std::vector<Vec3>> out(m.size());
  for (size_t i = 0; i < m.size(); ++i)
    for (const Vec2& q : flat.pieces[i].sharp) out[i].push_back(m[i].apply(q));
  return out;
}

double predicted_flat_area(const Part& part, const RealisedPart& rp, const FlatPattern& flat, const SheetSpec& spec) {
  double a = 0;
  for (const auto& t : rp.tabs) a += polygon_area(t.corners);
  for (int i = 1; i < part.size(); ++i) a += part.tabs[i].params.w * bend_length_change(part.tabs[i].params.theta3, spec);
  return a - flat.relief_area();
}

}  // namespace sheetgen
