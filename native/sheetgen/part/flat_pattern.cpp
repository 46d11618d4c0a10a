#include "sheetgen/part/flat_pattern.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

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

}  // namespace

FlatPattern unfold(const Part& part, const SheetSpec& spec, const FlatPatternOptions& opt) {
  FlatPattern fp;
  fp.frame = part.base;
  const int n = part.size();
  if (n == 0) return fp;
  const double wr = opt.relief_width > 0 ? opt.relief_width : spec.thickness;
  const double ct = opt.corner_tolerance;
  const double kerf = spec.manufacturing.kerf;
  auto fail = [&](ValidityReason r, int tab, const std::string& msg) {
    if (fp.status == ValidityReason::Ok) {
      fp.status = r;
      fp.tab = tab;
      fp.message = msg;
    }
  };

  RealiseOptions ro;
  ro.angles.assign(n, 0.0);
  ro.shifts.assign(n, 0.0);
  for (int i = 1; i < n; ++i) ro.shifts[i] = bend_length_change(part.tabs[i].params.theta3, spec);
  const RealisedPart flat3 = realise(part, ro);
  const BaseTab& base = part.base;
  auto to2 = [&](const Vec3& p) { const Vec3 r = p - base.origin; return Vec2(r.dot(base.x_axis), r.dot(base.y_axis)); };
  auto dir2 = [&](const Vec3& v) { return Vec2(v.dot(base.x_axis), v.dot(base.y_axis)).normalized(); };

  fp.pieces.resize(n);
  {
    FlatPiece& pc = fp.pieces[0];
    pc.tab = 0;
    pc.polygon = base.outline;
    pc.sharp = base.outline;
  }
  std::vector<Junction> junction(n);
  for (int i = 1; i < n; ++i) {
    const Tab& tab = part.tabs[i];
    const TabParameters& p = tab.params;
    const RealisedTab& ft = flat3.tabs[i];
    FlatPiece& pc = fp.pieces[i];
    const double dL = ro.shifts[i];
    pc.tab = i;
    pc.parent = tab.parent;
    pc.shift = dL;
    pc.x_axis = dir2(ft.x_axis);
    pc.y_axis = dir2(ft.y_axis);
    pc.origin = to2(ft.origin) - dL * pc.y_axis;  // P0 on the parent's flat edge line
    for (const Vec3& c : ft.corners) pc.sharp.push_back(to2(c));
    const double delta = -dL * std::tan(p.theta2);  // where the shifted side lines meet the parent's edge line
    const Vec2 J0 = pc.origin + delta * pc.x_axis, J1 = pc.origin + (p.w + delta) * pc.x_axis;
    pc.polygon = {J1, J0, pc.sharp[2], pc.sharp[3]};
    if (!((pc.sharp[2] - J0).dot(pc.y_axis) > 0 && (pc.sharp[3] - J0).dot(pc.y_axis) > 0) || signed_area(pc.polygon) <= 0)
      fail(ValidityReason::BendZonesOverlap, i,
           "tab " + std::to_string(i) + " is too short for its bend: the flat pattern shortens it by " + mm(-dL));

    if (!is_flat_extension(p)) {
      FlatBend bd;
      bd.tab = i;
      bd.parent = tab.parent;
      bd.angle = p.theta3;
      bd.direction = p.theta3 >= 0 ? BendDirection::Up : BendDirection::Down;
      bd.length = p.w;
      bd.inside_radius = spec.manufacturing.bend_radius;
      bd.allowance = bend_allowance(p.theta3, spec);
      bd.setback = bend_setback(p.theta3, spec);
      bd.length_change = dL;
      bd.centre_offset = 0.5 * bd.allowance - bd.setback;
      bd.root_a = J0;
      bd.root_b = J1;
      bd.outward = pc.y_axis;
      bd.a = J0 + bd.centre_offset * pc.y_axis;
      bd.b = J1 + bd.centre_offset * pc.y_axis;
      fp.bends.push_back(bd);
    }

    // Position on the parent's flat edge.
    const std::vector<Vec2>& Q = fp.pieces[tab.parent].polygon;
    const int m = static_cast<int>(Q.size());
    Junction& j = junction[i];
    j.parent = tab.parent;
    j.edge = tab.parent_edge;
    j.S = Q[tab.parent_edge];
    const Vec2 T = Q[(tab.parent_edge + 1) % m];
    j.edge_length = (T - j.S).norm();
    j.E = j.edge_length > 0 ? Vec2((T - j.S) / j.edge_length) : pc.x_axis;
    j.V = pc.y_axis;
    j.a0 = (J0 - j.S).dot(j.E);
    j.a1 = (J1 - j.S).dot(j.E);
    j.flat = is_flat_extension(p);
    j.depth = j.flat ? 0.0 : bend_zone_depth(p.theta3, spec);
    if (j.a0 < -ct || j.a1 > j.edge_length + ct)
      fail(ValidityReason::FlatJunctionOutsideEdge, i,
           "tab " + std::to_string(i) + " flat root [" + mm(j.a0) + ", " + mm(j.a1) + "] leaves the flat edge " +
               std::to_string(j.edge) + " of tab " + std::to_string(j.parent) + " (length " + mm(j.edge_length) +
               "); skewed tabs shift their flat root by dL tan(theta2)");
  }

  // Children per (parent, edge), sorted along the edge.
  std::vector<std::vector<std::vector<int>>> on_edge(n);
  for (int i = 0; i < n; ++i) on_edge[i].resize(part.edge_count(i));
  for (int i = 1; i < n; ++i) on_edge[part.tabs[i].parent][part.tabs[i].parent_edge].push_back(i);
  for (auto& edges : on_edge)
    for (auto& list : edges) std::sort(list.begin(), list.end(), [&](int a, int b) { return junction[a].a0 < junction[b].a0; });

  // Relief decisions and polygons.
  for (int p = 0; p < n; ++p) {
    for (auto& list : on_edge[p]) {
      for (size_t k = 0; k < list.size(); ++k) {
        Junction& j = junction[list[k]];
        const Junction* prev = k > 0 ? &junction[list[k - 1]] : nullptr;
        const Junction* next = k + 1 < list.size() ? &junction[list[k + 1]] : nullptr;
        const bool prev_merged = prev && prev->merged_with_next;
        if (j.a0 > ct && !prev_merged && !j.flat) {
          j.start_relief = true;
          const double room = prev ? j.a0 - prev->a1 - wr : j.a0;
          if (room < wr - ct)
            fail(ValidityReason::ReliefDoesNotFit, list[k],
                 "tab " + std::to_string(list[k]) + " bend ends " + mm(j.a0) + " from the start of its parent edge: a relief needs " +
                     mm(wr) + " (or end the bend at the corner)");
        }
        if (j.a1 < j.edge_length - ct && !j.flat) {
          if (next && next->a0 - j.a1 < 2.0 * wr + kerf) {
            j.merged_with_next = true;
            const double gap = next->a0 - j.a1;
            if (gap < 0)
              fail(ValidityReason::FlatPatternOverlap, list[k + 1],
                   "tabs " + std::to_string(list[k]) + " and " + std::to_string(list[k + 1]) + " overlap on their parent edge by " + mm(-gap));
            else if (gap < wr - ct)
              fail(ValidityReason::ReliefDoesNotFit, list[k + 1],
                   "tabs " + std::to_string(list[k]) + " and " + std::to_string(list[k + 1]) + " leave a gap of " + mm(gap) +
                       " on their parent edge: the shared relief needs " + mm(wr));
          } else {
            j.end_relief = true;
            if (!next && j.edge_length - j.a1 < wr - ct)
              fail(ValidityReason::ReliefDoesNotFit, list[k],
                   "tab " + std::to_string(list[k]) + " bend ends " + mm(j.edge_length - j.a1) +
                       " from the end of its parent edge: a relief needs " + mm(wr) + " (or end the bend at the corner)");
          }
        }
        auto add_relief = [&](double from, double to, double depth, int other) {
          FlatRelief r;
          r.parent = p;
          r.tab = list[k];
          r.other_tab = other;
          r.width = to - from;
          r.depth = depth;
          const Vec2 a = j.S + from * j.E, b = j.S + to * j.E;
          r.polygon = ccw({a, b, b - depth * j.V, a - depth * j.V});
          for (const Vec2& q : r.polygon)
            if (!point_in_convex(q, fp.pieces[p].polygon, 1e-9))
              fail(ValidityReason::ReliefDoesNotFit, list[k],
                   "the relief of tab " + std::to_string(list[k]) + " (depth " + mm(depth) + ") does not fit inside tab " +
                       std::to_string(p));
          fp.reliefs.push_back(r);
        };
        if (j.start_relief) add_relief(j.a0 - wr, j.a0, j.depth, -1);
        if (j.end_relief) add_relief(j.a1, j.a1 + wr, j.depth, -1);
        if (j.merged_with_next && next->a0 > j.a1) add_relief(j.a1, next->a0, std::max(j.depth, next->depth), list[k + 1]);
      }
    }
  }

  // Outline: walk the base boundary, splicing every child's boundary (with
  // its relief notches) into its parent's edge.
  std::vector<Vec2>& out = fp.outline;
  std::vector<int>& owner = fp.outline_tab;
  auto push = [&](const Vec2& q, int who) {
    if (!out.empty() && (out.back() - q).norm() <= ct) {
      owner.back() = who;
      return;
    }
    out.push_back(q);
    owner.push_back(who);
  };
  std::function<void(int, int)> emit_edge;
  auto emit_tab = [&](int c) {
    const std::vector<Vec2>& Q = fp.pieces[c].polygon;
    for (int k = 1; k <= 3; ++k) {
      emit_edge(c, k);
      if (k < 3) push(Q[k + 1], c);
    }
  };
  emit_edge = [&](int p, int k) {
    const auto& list = on_edge[p][k];
    for (size_t idx = 0; idx < list.size(); ++idx) {
      const int c = list[idx];
      const Junction& j = junction[c];
      const Vec2 J0 = j.S + j.a0 * j.E, J1 = j.S + j.a1 * j.E;
      if (j.start_relief) {
        const Vec2 r1 = J0 - wr * j.E;
        push(r1, p);
        push(r1 - j.depth * j.V, p);
        push(J0 - j.depth * j.V, p);
      }
      push(J0, c);
      emit_tab(c);
      push(J1, p);
      if (j.end_relief) {
        push(J1 - j.depth * j.V, p);
        push(J1 + wr * j.E - j.depth * j.V, p);
        push(J1 + wr * j.E, p);
      } else if (j.merged_with_next) {
        const Junction& nj = junction[list[idx + 1]];
        const double d = std::max(j.depth, nj.depth);
        push(J1 - d * j.V, p);
        push(nj.S + nj.a0 * nj.E - d * j.V, p);
      }
    }
  };
  for (int k = 0; k < static_cast<int>(base.outline.size()); ++k) {
    push(base.outline[k], 0);
    emit_edge(0, k);
  }
  if (out.size() > 1 && (out.back() - out.front()).norm() <= ct) {
    out.pop_back();
    owner.pop_back();
  }
  return fp;
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

std::vector<std::vector<Vec3>> fold_flat_pattern(const FlatPattern& flat) {
  const int n = static_cast<int>(flat.pieces.size());
  std::vector<Eigen::Matrix3d> R(n);
  std::vector<Vec3> T(n);
  std::vector<std::vector<Vec3>> out(n);
  if (n == 0) return out;
  R[0].col(0) = flat.frame.x_axis;
  R[0].col(1) = flat.frame.y_axis;
  R[0].col(2) = flat.frame.normal();
  T[0] = flat.frame.origin;
  auto apply = [&](int i, const Vec2& q) { return Vec3(R[i] * Vec3(q.x(), q.y(), 0) + T[i]); };
  std::vector<const FlatBend*> bend_of(n, nullptr);
  for (const FlatBend& b : flat.bends) bend_of[b.tab] = &b;
  for (int i = 1; i < n; ++i) {  // parents come first
    const int p = flat.pieces[i].parent;
    const FlatBend* b = bend_of[i];
    if (!b) {  // a flat extension lies in its parent's plane
      R[i] = R[p];
      T[i] = T[p];
      continue;
    }
    const Vec2 E = (b->b - b->a).normalized();
    const Vec3 e3 = R[p] * Vec3(E.x(), E.y(), 0);
    const Vec3 X0 = apply(p, b->a - b->centre_offset * b->outward);  // on the sharp fold line
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(b->angle, -e3).toRotationMatrix();
    const Vec2 unshift = -b->length_change * b->outward;
    // q -> rot * (R_p (q + unshift) + T_p - X0) + X0
    R[i] = rot * R[p];
    T[i] = rot * (R[p] * Vec3(unshift.x(), unshift.y(), 0) + T[p] - X0) + X0;
  }
  for (int i = 0; i < n; ++i)
    for (const Vec2& q : flat.pieces[i].sharp) out[i].push_back(apply(i, q));
  return out;
}

double predicted_flat_area(const Part& part, const RealisedPart& rp, const FlatPattern& flat, const SheetSpec& spec) {
  double a = 0;
  for (const auto& t : rp.tabs) a += polygon_area(t.corners);
  for (int i = 1; i < part.size(); ++i) a += part.tabs[i].params.w * bend_length_change(part.tabs[i].params.theta3, spec);
  return a - flat.relief_area();
}

}  // namespace sheetgen
