#include "sheetgen/core/geometry.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace sheetgen {

Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab = b - a;
  double len2 = ab.squaredNorm();
  if (len2 <= 0) return a;
  double s = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + s * ab;
}

// Voronoi-region walk over the triangle's vertices, edges and face
// (the classic barycentric formulation; each branch is one feature region).
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  // A (near-)degenerate triangle first: with collinear corners the region
  // tests below see products that cancel to rounding noise, and may pick a
  // sub-edge (a to c) when the point is nearest to the rest of the line.
  const double scale = std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()});
  if (!(ab.cross(ac).norm() > 1e-12 * scale)) {
    Vec3 best = closest_point_on_segment(p, a, b);
    for (const Vec3& q : {closest_point_on_segment(p, b, c), closest_point_on_segment(p, c, a)})
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return best;
  }
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double den = d1 - d3;
    return den > 0 ? Vec3(a + (d1 / den) * ab) : a;
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double den = d2 - d6;
    return den > 0 ? Vec3(a + (d2 / den) * ac) : a;
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double den = (d4 - d3) + (d5 - d6);
    return den > 0 ? Vec3(b + ((d4 - d3) / den) * (c - b)) : b;
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) {
    // Degenerate (zero-area) triangle: the closest of its three edges.
    Vec3 best = closest_point_on_segment(p, a, b);
    for (const Vec3& q : {closest_point_on_segment(p, b, c), closest_point_on_segment(p, c, a)})
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return best;
  }
  const double v = vb / sum, w = vc / sum;
  return a + v * ab + w * ac;
}

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (closest_point_on_triangle(p, a, b, c) - p).norm();
}

SegmentPair segment_segment_closest(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return {p0, q0};
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), den = a * e - b * b;
      s = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return {p0 + s * d1, q0 + t * d2};
}

double segment_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const SegmentPair c = segment_segment_closest(p0, p1, q0, q1);
  return (c.on_first - c.on_second).norm();
}

std::optional<double> ray_triangle_intersect(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                             const Vec3& c, double t_min) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 pv = d.cross(e2);
  const double det = e1.dot(pv);
  if (std::abs(det) < 1e-300) return std::nullopt;
  const double inv = 1.0 / det;
  const Vec3 tv = o - a;
  const double u = tv.dot(pv) * inv;
  if (u < 0 || u > 1) return std::nullopt;
  const Vec3 qv = tv.cross(e1);
  const double v = d.dot(qv) * inv;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = e2.dot(qv) * inv;
  if (t < t_min) return std::nullopt;
  return t;
}

double polygon_area(const std::vector<Vec3>& polygon) {
  Vec3 s = Vec3::Zero();
  for (size_t i = 0; i < polygon.size(); ++i) s += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  return 0.5 * s.norm();
}

}  // namespace sheetgen
