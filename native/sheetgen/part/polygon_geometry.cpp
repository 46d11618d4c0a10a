#include "sheetgen/part/polygon_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

double point_convex_polygon_distance(const Vec3& p, const std::vector<Vec3>& poly, const Vec3& n) {
  const size_t m = poly.size();
  const double h = (p - poly[0]).dot(n);
  const Vec3 q = p - h * n;  // projection onto the plane
  bool inside = true;
  for (size_t i = 0; i < m && inside; ++i)
    if ((poly[(i + 1) % m] - poly[i]).cross(q - poly[i]).dot(n) < 0) inside = false;
  if (inside) return std::abs(h);
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < m; ++i) best = std::min(best, (closest_point_on_segment(p, poly[i], poly[(i + 1) % m]) - p).norm());
  return best;
}

namespace {
// Does segment [a, b] cross (or touch) the convex polygon?
bool segment_hits_polygon(const Vec3& a, const Vec3& b, const std::vector<Vec3>& poly, const Vec3& n) {
  const double ha = (a - poly[0]).dot(n), hb = (b - poly[0]).dot(n);
  if ((ha > 0 && hb > 0) || (ha < 0 && hb < 0)) return false;
  if (ha == hb) return false;  // in-plane: edge/edge and vertex tests cover it
  const Vec3 q = a + (ha / (ha - hb)) * (b - a);
  const size_t m = poly.size();
  for (size_t i = 0; i < m; ++i)
    if ((poly[(i + 1) % m] - poly[i]).cross(q - poly[i]).dot(n) < 0) return false;
  return true;
}
}  // namespace

double convex_polygon_distance(const std::vector<Vec3>& a, const Vec3& na, const std::vector<Vec3>& b, const Vec3& nb,
                               double stop_below) {
  const size_t ma = a.size(), mb = b.size();
  // Crossing: for convex planar polygons in general position, one polygon's
  // boundary pierces the other where they intersect.
  for (size_t i = 0; i < ma; ++i)
    if (segment_hits_polygon(a[i], a[(i + 1) % ma], b, nb)) return 0.0;
  for (size_t j = 0; j < mb; ++j)
    if (segment_hits_polygon(b[j], b[(j + 1) % mb], a, na)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  // Closest pair: edge-edge, or a vertex against the other polygon's face.
  for (size_t i = 0; i < ma; ++i) {
    best = std::min(best, point_convex_polygon_distance(a[i], b, nb));
    if (best < stop_below) return best;
  }
  for (size_t j = 0; j < mb; ++j) {
    best = std::min(best, point_convex_polygon_distance(b[j], a, na));
    if (best < stop_below) return best;
  }
  for (size_t i = 0; i < ma; ++i)
    for (size_t j = 0; j < mb; ++j) {
      best = std::min(best, segment_segment_distance(a[i], a[(i + 1) % ma], b[j], b[(j + 1) % mb]));
      if (best < stop_below) return best;
    }
  return best;
}

}  // namespace sheetgen
