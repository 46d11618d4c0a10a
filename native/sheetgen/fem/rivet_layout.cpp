#include "sheetgen/fem/rivet_layout.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

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

RivetLayout layout_rivets(const std::vector<Vec3>& polygon, int far_edge, const RivetLayoutOptions& options,
                          const std::vector<double>& edge_setback) {
  const int n = static_cast<int>(polygon.size());
  if (n < 3) throw FemError("rivet flange", "polygon has fewer than 3 vertices");
  if (far_edge < 0 || far_edge >= n) throw FemError("rivet flange", "far edge index out of range");
  RivetLayout out;
  out.diameter = rivet_diameter(options);
  out.edge_distance = options.edge_distance > 0 ? options.edge_distance : 2.0 * out.diameter;
  out.pitch = options.pitch > 0 ? options.pitch : 6.0 * out.diameter;
  const double e = out.edge_distance;
  if (!edge_setback.empty() && static_cast<int>(edge_setback.size()) != n)
    throw FemError("rivet flange", "has " + std::to_string(n) + " edges but " + std::to_string(edge_setback.size()) +
                                       " edge setbacks");
  // Distance a rivet keeps from edge j: the edge distance, beyond the bend zone when the edge is a bend.
  auto keep = [&](int j) { return e + (edge_setback.empty() ? 0.0 : std::max(0.0, edge_setback[j])); };

  Vec3 normal = Vec3::Zero();  // Newell: the right-hand normal of the vertex order
  for (int i = 0; i < n; ++i) normal += polygon[i].cross(polygon[(i + 1) % n]);
  if (!(normal.norm() > 0)) throw FemError("rivet flange", "polygon is degenerate");
  normal.normalize();
  const Vec3 a = polygon[far_edge], b = polygon[(far_edge + 1) % n];
  if (!((b - a).norm() > 0)) throw FemError("rivet flange", "far edge has zero length");
  const Vec3 d = (b - a).normalized();
  // In-plane inward normal of edge (p, q) of a polygon ordered counter-clockwise about `normal`.
  auto inward = [&](const Vec3& p, const Vec3& q) { return normal.cross((q - p).normalized()); };
  const Vec3 origin = a + keep(far_edge) * inward(a, b);
  // Keep keep(j) from every other edge: n_j . (origin + s d - p_j) >= keep(j), an interval in s.
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  for (int j = 0; j < n; ++j) {
    if (j == far_edge) continue;
    const Vec3 p = polygon[j], q = polygon[(j + 1) % n];
    if (!((q - p).norm() > 0)) continue;
    const Vec3 m = inward(p, q);
    const double g0 = m.dot(origin - p) - keep(j), slope = m.dot(d);
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
  const double span = std::max(0.0, hi - lo);
  const int count = static_cast<int>(std::floor(span / out.pitch + 1e-9)) + 1;
  const double mid = 0.5 * (lo + hi);
  out.footprint_radius = options.footprint_radius > 0 ? options.footprint_radius : out.diameter;
  if (out.footprint_radius > e) throw FemError("rivet layout", "footprint radius exceeds the edge distance");
  const Vec3 side = normal.cross(d);  // in-plane, perpendicular to the row
  for (int i = 0; i < count; ++i) {
    const Vec3 c = origin + (mid + (i - 0.5 * (count - 1)) * out.pitch) * d;
    out.points.push_back(c);
    std::vector<Vec3> fp = {c};
    for (int k = 0; k < options.footprint_points; ++k) {
      const double a = 2.0 * M_PI * k / options.footprint_points;
      fp.push_back(c + out.footprint_radius * (std::cos(a) * d + std::sin(a) * side));
    }
    out.footprints.push_back(fp);
  }
  return out;
}

std::vector<Vec3> RivetLayout::all_points() const {
  std::vector<Vec3> all;
  for (const auto& fp : footprints) all.insert(all.end(), fp.begin(), fp.end());
  return all;
}

}  // namespace sheetgen
