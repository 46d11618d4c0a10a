#include "sheetgen/report/isometric_view.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace sheetgen {
namespace {

using V = std::array<double, 3>;

V vec(const SheetPoint3& p) { return {p.x, p.y, p.z}; }
double dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V unit(const V& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? V{a[0] / n, a[1] / n, a[2] / n} : V{0, 0, 0};
}

// Newell's normal of a polygon times its area (twice): its length is the area's.
V area_normal(const std::vector<SheetPoint3>& poly) {
  V n{0, 0, 0};
  for (size_t i = 0; i < poly.size(); ++i) {
    const V a = vec(poly[i]), b = vec(poly[(i + 1) % poly.size()]);
    n = {n[0] + (a[1] - b[1]) * (a[2] + b[2]), n[1] + (a[2] - b[2]) * (a[0] + b[0]),
         n[2] + (a[0] - b[0]) * (a[1] + b[1])};
  }
  return {n[0] / 2, n[1] / 2, n[2] / 2};
}

// How face-on the sheet is seen along `view`: sum of |n . view| * area.
double visible_area(const std::vector<std::vector<SheetPoint3>>& tabs, const V& view) {
  double s = 0;
  for (const auto& t : tabs)
    if (t.size() >= 3) s += std::abs(dot(area_normal(t), view));
  return s;
}

void set_axes(IsometricView& v, const V& view) {
  const V r = unit(cross(view, V{0, 0, 1}));  // horizontal on the picture
  const V u = cross(r, view);                 // world z points up the picture
  for (int k = 0; k < 3; ++k) {
    v.view[k] = view[k];
    v.right[k] = r[k];
    v.up[k] = u[k];
  }
}

}  // namespace

SheetPoint IsometricView::project(const SheetPoint3& p) const {
  const V q = vec(p);
  return {dot(q, V{right[0], right[1], right[2]}), dot(q, V{up[0], up[1], up[2]})};
}

double IsometricView::depth(const SheetPoint3& p) const { return dot(vec(p), V{view[0], view[1], view[2]}); }

IsometricView isometric_view(const std::vector<std::vector<SheetPoint3>>& tabs) {
  const double s = 1 / std::sqrt(3.0);
  const V diagonals[4] = {{-s, -s, -s}, {s, -s, -s}, {s, s, -s}, {-s, s, -s}};  // looking from (+1,+1), (-1,+1), ...
  V best = diagonals[0];
  double best_area = -1;
  for (const V& d : diagonals) {
    const double a = visible_area(tabs, d);
    if (a > best_area * (1 + 1e-9)) best = d, best_area = a;
  }
  IsometricView v;
  set_axes(v, best);
  const V light = unit(V{-0.3 * best[0] + 0.4 * v.up[0] - 0.5 * v.right[0], -0.3 * best[1] + 0.4 * v.up[1] - 0.5 * v.right[1],
                         -0.3 * best[2] + 0.4 * v.up[2] - 0.5 * v.right[2]});  // from the upper left, behind the viewer
  const double inf = std::numeric_limits<double>::infinity();
  v.min = {inf, inf};
  v.max = {-inf, -inf};
  for (size_t i = 0; i < tabs.size(); ++i) {
    if (tabs[i].size() < 3) continue;
    IsometricFace f;
    f.tab = static_cast<int>(i);
    SheetPoint3 c;
    for (const SheetPoint3& p : tabs[i]) {
      const SheetPoint q = v.project(p);
      f.polygon.push_back(q);
      v.min = {std::min(v.min.x, q.x), std::min(v.min.y, q.y)};
      v.max = {std::max(v.max.x, q.x), std::max(v.max.y, q.y)};
      c = {c.x + p.x / tabs[i].size(), c.y + p.y / tabs[i].size(), c.z + p.z / tabs[i].size()};
    }
    f.depth = v.depth(c);
    f.shade = 0.45 + 0.5 * std::abs(dot(unit(area_normal(tabs[i])), light));  // a sheet is lit from either side
    v.faces.push_back(f);
  }
  std::stable_sort(v.faces.begin(), v.faces.end(),
                   [](const IsometricFace& a, const IsometricFace& b) { return a.depth > b.depth; });
  if (v.faces.empty()) v.min = v.max = {0, 0};
  return v;
}

}  // namespace sheetgen
