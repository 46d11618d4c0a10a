#include "sheetgen/core/polygon_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "sheetgen/core/geometry.hpp"

namespace sheetgen {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

double signed_area(const std::vector<Vec2>& p) {
  double s = 0;
  const size_t n = p.size();
  for (size_t i = 0; i < n; ++i) s += cross2(p[i], p[(i + 1) % n]);
  return 0.5 * s;
}

Vec2 polygon_centroid(const std::vector<Vec2>& p) {
  const size_t n = p.size();
  if (n == 0) return Vec2::Zero();
  // Relative to p[0] for accuracy far from the origin.
  double a = 0;
  Vec2 c = Vec2::Zero();
  for (size_t i = 0; i < n; ++i) {
    const Vec2 u = p[i] - p[0], v = p[(i + 1) % n] - p[0];
    const double k = cross2(u, v);
    a += k;
    c += k * (u + v);
  }
  if (std::abs(a) <= 0) {
    Vec2 m = Vec2::Zero();
    for (const auto& q : p) m += q;
    return m / static_cast<double>(n);
  }
  return p[0] + c / (3.0 * a);
}

std::vector<Vec2> clip_half_plane(const std::vector<Vec2>& poly, const Vec2& n, double c) {
  std::vector<Vec2> out;
  const size_t m = poly.size();
  if (m == 0) return out;
  out.reserve(m + 1);
  for (size_t i = 0; i < m; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % m];
    const double da = n.dot(a) - c, db = n.dot(b) - c;
    if (da >= 0) out.push_back(a);
    if ((da >= 0) != (db >= 0)) {
      const double s = da / (da - db);
      out.push_back(a + s * (b - a));
    }
  }
  return out;
}

std::vector<Vec2> clip_convex(const std::vector<Vec2>& subject, const std::vector<Vec2>& k) {
  std::vector<Vec2> out = subject;
  const size_t m = k.size();
  for (size_t i = 0; i < m && !out.empty(); ++i) {
    const Vec2 e = k[(i + 1) % m] - k[i];
    const Vec2 inward(-e.y(), e.x());  // left of a counter-clockwise edge
    out = clip_half_plane(out, inward, inward.dot(k[i]));
  }
  return out;
}

std::vector<Vec2> inset_convex(const std::vector<Vec2>& k, double distance) {
  std::vector<Vec2> out = k;
  const size_t m = k.size();
  for (size_t i = 0; i < m && !out.empty(); ++i) {
    const Vec2 e = k[(i + 1) % m] - k[i];
    const double len = e.norm();
    if (!(len > 0)) continue;
    const Vec2 inward = Vec2(-e.y(), e.x()) / len;
    out = clip_half_plane(out, inward, inward.dot(k[i]) + distance);
  }
  if (out.size() < 3 || signed_area(out) <= 0) out.clear();
  return out;
}

namespace {
double point_segment_distance_2d(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double s = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}
}  // namespace

double segment_distance_2d(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1) {
  const double d1 = cross2(p1 - p0, q0 - p0), d2 = cross2(p1 - p0, q1 - p0);
  const double d3 = cross2(q1 - q0, p0 - q0), d4 = cross2(q1 - q0, p1 - q0);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return 0.0;
  return std::min({point_segment_distance_2d(p0, q0, q1), point_segment_distance_2d(p1, q0, q1),
                   point_segment_distance_2d(q0, p0, p1), point_segment_distance_2d(q1, p0, p1)});
}

bool point_in_convex(const Vec2& p, const std::vector<Vec2>& k, double tol) {
  const size_t m = k.size();
  for (size_t i = 0; i < m; ++i) {
    const Vec2 e = k[(i + 1) % m] - k[i];
    const double len = e.norm();
    if (!(len > 0)) continue;
    if (cross2(e, p - k[i]) / len < -tol) return false;
  }
  return true;
}

Vec3 closest_point_on_convex_polygon(const Vec3& p, const std::vector<Vec3>& poly, const Vec3& n) {
  const size_t m = poly.size();
  const Vec3 q = p - (p - poly[0]).dot(n) * n;  // projection onto the plane
  bool inside = true;
  for (size_t i = 0; i < m && inside; ++i)
    if ((poly[(i + 1) % m] - poly[i]).cross(q - poly[i]).dot(n) < 0) inside = false;
  if (inside) return q;
  Vec3 best = poly[0];
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < m; ++i) {
    const Vec3 c = closest_point_on_segment(p, poly[i], poly[(i + 1) % m]);
    const double d = (c - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

double point_convex_polygon_distance(const Vec3& p, const std::vector<Vec3>& poly, const Vec3& n) {
  return (closest_point_on_convex_polygon(p, poly, n) - p).norm();
}

namespace {
// Where segment [a, b] crosses (or touches) the convex polygon, if it does.
std::optional<Vec3> segment_polygon_crossing(const Vec3& a, const Vec3& b, const std::vector<Vec3>& poly, const Vec3& n) {
  const double ha = (a - poly[0]).dot(n), hb = (b - poly[0]).dot(n);
  if ((ha > 0 && hb > 0) || (ha < 0 && hb < 0)) return std::nullopt;
  if (ha == hb) return std::nullopt;  // in-plane: edge/edge and vertex tests cover it
  const Vec3 q = a + (ha / (ha - hb)) * (b - a);
  const size_t m = poly.size();
  for (size_t i = 0; i < m; ++i)
    if ((poly[(i + 1) % m] - poly[i]).cross(q - poly[i]).dot(n) < 0) return std::nullopt;
  return q;
}
}  // namespace

PolygonPair convex_polygon_closest(const std::vector<Vec3>& a, const Vec3& na, const std::vector<Vec3>& b, const Vec3& nb,
                                   double stop_below) {
  const size_t ma = a.size(), mb = b.size();
  // A zero normal marks a polygon without area (a degenerate mesh triangle):
  // its points are all on its edges, so only the edge tests apply to it.
  const bool a_has_face = na.squaredNorm() > 0.25, b_has_face = nb.squaredNorm() > 0.25;
  // Crossing: for convex planar polygons in general position, one polygon's
  // boundary pierces the other where they intersect.
  if (b_has_face)
    for (size_t i = 0; i < ma; ++i)
      if (auto q = segment_polygon_crossing(a[i], a[(i + 1) % ma], b, nb)) return {0.0, *q};
  if (a_has_face)
    for (size_t j = 0; j < mb; ++j)
      if (auto q = segment_polygon_crossing(b[j], b[(j + 1) % mb], a, na)) return {0.0, *q};
  PolygonPair best{std::numeric_limits<double>::infinity(), a.front()};
  auto consider = [&](const Vec3& on_a, const Vec3& on_b) {
    const double d = (on_a - on_b).norm();
    if (d < best.distance) best = {d, on_a};
    return best.distance < stop_below;
  };
  // Closest pair: edge-edge, or a vertex against the other polygon's face.
  if (b_has_face)
    for (size_t i = 0; i < ma; ++i)
      if (consider(a[i], closest_point_on_convex_polygon(a[i], b, nb))) return best;
  if (a_has_face)
    for (size_t j = 0; j < mb; ++j)
      if (consider(closest_point_on_convex_polygon(b[j], a, na), b[j])) return best;
  for (size_t i = 0; i < ma; ++i)
    for (size_t j = 0; j < mb; ++j) {
      const SegmentPair c = segment_segment_closest(a[i], a[(i + 1) % ma], b[j], b[(j + 1) % mb]);
      if (consider(c.on_first, c.on_second)) return best;
    }
  return best;
}

double convex_polygon_distance(const std::vector<Vec3>& a, const Vec3& na, const std::vector<Vec3>& b, const Vec3& nb,
                               double stop_below) {
  return convex_polygon_closest(a, na, b, nb, stop_below).distance;
}

}  // namespace sheetgen
