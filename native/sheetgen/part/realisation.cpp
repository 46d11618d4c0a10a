#include "sheetgen/part/realisation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sheetgen {

void tab_local_corners_into(const TabParameters& p, std::vector<Vec2>& c, bool* degenerate) {
  // Centre line from the root midpoint, skewed by theta2; the far edge passes
  // through M1 (perpendicular distance l from the root) with direction
  // (cos theta1, sin theta1) and ends on the two side lines, which are parallel
  // to the centre line. Half far-edge length h = w cos(theta2) / (2 cos(theta1 + theta2)).
  const double c12 = std::cos(p.theta1 + p.theta2);
  const double t2 = std::tan(p.theta2);
  const Vec2 m1(0.5 * p.w + p.l * t2, p.l);
  const Vec2 f(std::cos(p.theta1), std::sin(p.theta1));
  bool bad = !(c12 > 1e-9) || !(p.w > 0) || !(p.l > 0) || !(std::abs(std::cos(p.theta2)) > 1e-9);
  const double h = bad ? 0.5 * p.w : p.w * std::cos(p.theta2) / (2.0 * c12);
  c.resize(4);
  c[0] = Vec2(p.w, 0);
  c[1] = Vec2(0, 0);
  c[2] = m1 - h * f;
  c[3] = m1 + h * f;
  if (!(c[2].y() > 0) || !(c[3].y() > 0)) bad = true;
  if (degenerate) *degenerate = bad;
}

std::vector<FreeEdge> RealisedPart::free_edges() const {
  std::vector<FreeEdge> out;
  for (int i = 0; i < static_cast<int>(tabs.size()); ++i) {
    const RealisedTab& t = tabs[i];
    const int n = static_cast<int>(t.corners.size());
    for (int k = (i == 0 ? 0 : 1); k < (i == 0 ? n : 4); ++k) {
      FreeEdge e;
      e.tab = i;
      e.edge = k;
      e.a = t.corners[k];
      e.b = t.corners[(k + 1) % n];
      const Vec3 ab = e.b - e.a;
      e.length = ab.norm();
      e.outward = e.length > 0 ? Vec3(ab.cross(t.normal) / e.length) : Vec3::Zero();
      out.push_back(e);
    }
  }
  return out;
}

namespace {
void set_box(RealisedTab& t) {
  t.box = BoundingBox();
  for (const Vec3& p : t.corners) t.box.extend(p);
}

// The base tab into out.tabs[0].
void realise_base(const Part& part, RealisedPart& out) {
  RealisedTab& b = out.tabs[0];
  const BaseTab& base = part.base;
  b.local = base.outline;
  b.corners.resize(base.outline.size());
  for (size_t k = 0; k < base.outline.size(); ++k) b.corners[k] = base.to_world(base.outline[k]);
  b.origin = base.origin;
  b.x_axis = base.x_axis;
  b.y_axis = base.y_axis;
  b.normal = base.normal();
  b.bend_angle = 0;
  b.direction = BendDirection::Up;
  b.degenerate = base.outline.size() < 3;
  set_box(b);
}

// Tab i into out.tabs[i], from its parent's realised corners and frame.
void realise_tab(const Part& part, int i, RealisedPart& out, const RealiseOptions& options) {
  const Tab& tab = part.tabs[i];
  if (tab.parent < 0 || tab.parent >= i)
    throw std::invalid_argument("realise: tab " + std::to_string(i) + " has parent " + std::to_string(tab.parent) +
                                " (must be an earlier tab)");
  if (!part.is_free_edge(tab.parent, tab.parent_edge))
    throw std::invalid_argument("realise: tab " + std::to_string(i) + " names edge " + std::to_string(tab.parent_edge) +
                                " of tab " + std::to_string(tab.parent) + ", which is not a free edge");
  const RealisedTab& par = out.tabs[tab.parent];
  RealisedTab& t = out.tabs[i];
  const int m = static_cast<int>(par.corners.size());
  const Vec3& A = par.corners[tab.parent_edge];
  const Vec3& B = par.corners[(tab.parent_edge + 1) % m];
  const Vec3 ab = B - A;
  const double len = ab.norm();
  const Vec3 e = len > 0 ? Vec3(ab / len) : par.x_axis;
  const Vec3 np = par.normal;
  const Vec3 o = e.cross(np);  // in the parent's plane, away from the parent
  const double th = options.angles.empty() ? tab.params.theta3 : options.angles[i];
  const double c = std::cos(th), s = std::sin(th);
  const Vec3 v = c * o + s * np;
  const double shift = options.shifts.empty() ? 0.0 : options.shifts[i];
  t.origin = A + tab.params.d * e + shift * v;
  t.x_axis = e;
  t.y_axis = v;
  t.normal = c * np - s * o;
  t.bend_angle = th;
  t.direction = tab.params.theta3 >= 0 ? BendDirection::Up : BendDirection::Down;
  tab_local_corners_into(tab.params, t.local, &t.degenerate);  // in place: realise_into runs in every bend sweep
  t.corners.resize(4);
  for (int k = 0; k < 4; ++k) t.corners[k] = t.origin + t.local[k].x() * e + t.local[k].y() * v;
  set_box(t);
}

}  // namespace

void realise_into(const Part& part, RealisedPart& out, const RealiseOptions& options) {
  const int n = part.size();
  out.tabs.resize(n);
  if (n == 0) return;
  realise_base(part, out);
  for (int i = 1; i < n; ++i) realise_tab(part, i, out, options);
}

void realise_path_into(const Part& part, int tab, RealisedPart& out, const RealiseOptions& options) {
  if (tab < 0 || tab >= part.size()) throw std::invalid_argument("realise: no tab " + std::to_string(tab));
  out.tabs.resize(part.size());
  realise_base(part, out);
  int path[64], depth = 0;
  for (int i = tab; i > 0; i = part.tabs[i].parent) {
    if (part.tabs[i].parent < 0 || part.tabs[i].parent >= i || depth == 64) {
      realise_into(part, out, options);  // malformed or very deep: the whole part, which names the problem
      return;
    }
    path[depth++] = i;
  }
  while (depth > 0) realise_tab(part, path[--depth], out, options);
}

RealisedPart realise(const Part& part, const RealiseOptions& options) {
  RealisedPart r;
  realise_into(part, r, options);
  return r;
}

}  // namespace sheetgen
