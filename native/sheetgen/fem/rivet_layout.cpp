#include "sheetgen/fem/rivet_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "sheetgen/core/polygon_geometry.hpp"
#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {

double rivet_diameter(const RivetLayoutOptions& options) {
  constexpr double inch = 0.0254;
  return options.diameter > 0 ? options.diameter
                              : std::max(inch / 8.0, std::ceil(2.0 * options.thickness / (inch / 32.0) - 1e-9) * inch / 32.0);
}

std::vector<Vec3> rivet_footprint(const Vec3& centre, const Vec3& normal, double radius, int points) {
  // Any in-plane unit pair: the ring's phase does not matter.
  const Vec3 u = (std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(normal).normalized();
  const Vec3 v = normal.cross(u);
  std::vector<Vec3> fp = {centre};
  for (int k = 0; k < points; ++k) {
    const double a = 2.0 * M_PI * k / points;
    fp.push_back(centre + radius * (std::cos(a) * u + std::sin(a) * v));
  }
  return fp;
}

namespace {

// The s-interval (lo, hi) on the line origin + s d where the distance to the
// convex polygon `zone` is below `e`; empty (lo > hi) when the line keeps e.
// The distance to a convex set is convex along a line: golden-section search
// for its minimum, then bisection on each side.
std::pair<double, double> too_close(const Vec3& origin, const Vec3& d, const std::vector<Vec3>& zone, const Vec3& normal,
                                    double e, double s_min, double s_max) {
  auto dist = [&](double s) { return point_convex_polygon_distance(origin + s * d, zone, normal); };
  double a = s_min, b = s_max;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 80 && b - a > 1e-9; ++it) {
    const double c = b - g * (b - a), f = a + g * (b - a);
    if (dist(c) < dist(f)) b = f;
    else a = c;
  }
  const double s_star = 0.5 * (a + b);
  if (dist(s_star) >= e) return {1.0, 0.0};
  auto edge_of = [&](double inside, double outside) {  // dist(inside) < e <= dist(outside)
    for (int it = 0; it < 60; ++it) {
      const double m = 0.5 * (inside + outside);
      (dist(m) < e ? inside : outside) = m;
    }
    return outside;
  };
  const double lo = dist(s_min) < e ? s_min : edge_of(s_star, s_min);
  const double hi = dist(s_max) < e ? s_max : edge_of(s_star, s_max);
  return {lo, hi};
}

}  // namespace

RivetLayout layout_rivets(const std::vector<Vec3>& polygon, int far_edge, const RivetLayoutOptions& options,
                          const std::vector<std::vector<Vec3>>& keep_out) {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) throw FemError("rivet flange", "polygon has fewer than 3 vertices");
  if (far_edge < 0 || far_edge >= n) throw FemError("rivet flange", "far edge index out of range");
  RivetLayout out;
  out.diameter = rivet_diameter(options);
  out.edge_distance = options.edge_distance > 0 ? options.edge_distance : 2.0 * out.diameter;
  out.pitch = options.pitch > 0 ? options.pitch : 6.0 * out.diameter;
  const double e = out.edge_distance;

  Vec3 normal = Vec3::Zero();  // Newell: the right-hand normal of the vertex order
  for (int i = 0; i < n; ++i) normal += polygon[i].cross(polygon[(i + 1) % n]);
  if (!(normal.norm() > 0)) throw FemError("rivet flange", "polygon is degenerate");
  normal.normalize();
  const Vec3 a = polygon[far_edge], b = polygon[(far_edge + 1) % n];
  if (!((b - a).norm() > 0)) throw FemError("rivet flange", "far edge has zero length");
  const Vec3 d = (b - a).normalized();
  // In-plane inward normal of edge (p, q) of a polygon ordered counter-clockwise about `normal`.
  auto inward = [&](const Vec3& p, const Vec3& q) { return normal.cross((q - p).normalized()); };
  const Vec3 origin = a + e * inward(a, b);
  // Keep e from every other edge: n_j . (origin + s d - p_j) >= e, an interval in s.
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    if (j == far_edge) continue;
    const Vec3 p = polygon[j], q = polygon[(j + 1) % n];
    if (!((q - p).norm() > 0)) continue;
    const Vec3 m = inward(p, q);
    const double g0 = m.dot(origin - p) - e, slope = m.dot(d);
    if (std::abs(slope) < 1e-12) {
      if (g0 < -1e-12) throw FemError("rivet flange", "too narrow for a rivet row at the edge distance");
      continue;
    }
    const double s = -g0 / slope;
    if (slope > 0) lo = std::max(lo, s);
    else hi = std::min(hi, s);
  }
  if (!(hi >= lo - 1e-12) || !std::isfinite(lo) || !std::isfinite(hi))
    throw FemError("rivet flange", "too small for one rivet at edge distance " + std::to_string(e * 1e3) + " mm");
  // The row on flat sheet only: the pieces of [lo, hi] that keep e from every keep-out zone.
  std::vector<std::pair<double, double>> pieces = {{lo, std::max(lo, hi)}};
  for (const auto& zone : keep_out) {
    if (zone.size() < 3) continue;
    const auto [x0, x1] = too_close(origin, d, zone, normal, e, lo - 1.0, hi + 1.0);
    if (x0 > x1) continue;
    std::vector<std::pair<double, double>> kept;
    for (const auto& [p0, p1] : pieces) {
      if (x1 <= p0 || x0 >= p1) {  // open exclusion: a rivet exactly e away is fine
        kept.emplace_back(p0, p1);
        continue;
      }
      if (x0 > p0) kept.emplace_back(p0, x0);
      if (x1 < p1) kept.emplace_back(x1, p1);
    }
    pieces = std::move(kept);
  }
  if (pieces.empty())
    throw FemError("rivet flange", "has no flat sheet for one rivet at edge distance " + std::to_string(e * 1e3) +
                                       " mm: bend zones take it");
  out.footprint_radius = options.footprint_radius > 0 ? options.footprint_radius : out.diameter;
  if (out.footprint_radius > e) throw FemError("rivet layout", "footprint radius exceeds the edge distance");
  const Vec3 side = normal.cross(d);  // in-plane, perpendicular to the row
  // Each piece holds floor(span / p) + 1 rivets at exactly the pitch, centred in it.
  for (const auto& [p0, p1] : pieces) {
    const int count = static_cast<int>(std::floor((p1 - p0) / out.pitch + 1e-9)) + 1;
    const double mid = 0.5 * (p0 + p1);
    for (int i = 0; i < count; ++i) {
      const Vec3 c = origin + (mid + (i - 0.5 * (count - 1)) * out.pitch) * d;
      out.points.push_back(c);
      std::vector<Vec3> fp = {c};
      for (int k = 0; k < options.footprint_points; ++k) {
        const double ang = 2.0 * M_PI * k / options.footprint_points;
        fp.push_back(c + out.footprint_radius * (std::cos(ang) * d + std::sin(ang) * side));
      }
      out.footprints.push_back(fp);
    }
  }
  return out;
}

std::vector<Vec3> RivetLayout::all_points() const {
  std::vector<Vec3> all;
  for (const auto& fp : footprints) all.insert(all.end(), fp.begin(), fp.end());
  return all;
}

}  // namespace sheetgen
