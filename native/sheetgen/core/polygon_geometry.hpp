#pragma once
// Small exact kernels on convex planar polygons used by validity, flat pattern,
// bend-sequence and environment clearance checks. Polygons are corner lists, implicitly closed.
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

// ---- 2-D (m)
double cross2(const Vec2& a, const Vec2& b);
double signed_area(const std::vector<Vec2>& polygon);  // m^2, > 0 counter-clockwise
Vec2 polygon_centroid(const std::vector<Vec2>& polygon);
// Keeps the part of a convex polygon where dot(n, x) >= c (Sutherland-Hodgman, one plane).
std::vector<Vec2> clip_half_plane(const std::vector<Vec2>& polygon, const Vec2& n, double c);
// Intersection of a polygon with a convex counter-clockwise polygon.
std::vector<Vec2> clip_convex(const std::vector<Vec2>& subject, const std::vector<Vec2>& convex_ccw);
// Convex counter-clockwise polygon moved inwards by `distance` on every edge (may be empty).
std::vector<Vec2> inset_convex(const std::vector<Vec2>& convex_ccw, double distance);
double segment_distance_2d(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1);  // m, 0 when crossing
bool point_in_convex(const Vec2& p, const std::vector<Vec2>& convex_ccw, double tolerance = 0);

// ---- 3-D (m)
// Closest point to p on a convex planar polygon with unit normal n, and its distance, m.
Vec3 closest_point_on_convex_polygon(const Vec3& p, const std::vector<Vec3>& polygon, const Vec3& n);
double point_convex_polygon_distance(const Vec3& p, const std::vector<Vec3>& polygon, const Vec3& n);
// Closest approach of two convex planar polygons: the distance (0 when they
// touch or cross) and a point of `a` where it is attained. A zero normal marks
// a polygon without area (a degenerate triangle: only its edges count).
// `stop_below`: may return any pair closer than stop_below as soon as one is found.
struct PolygonPair {
  double distance = 0;  // m
  Vec3 on_a = Vec3::Zero();
};
PolygonPair convex_polygon_closest(const std::vector<Vec3>& a, const Vec3& na, const std::vector<Vec3>& b, const Vec3& nb,
                                   double stop_below = 0);
// Distance between two convex planar polygons (0 when they touch or cross).
// `stop_below`: may return any value < stop_below as soon as one is found.
double convex_polygon_distance(const std::vector<Vec3>& a, const Vec3& na, const std::vector<Vec3>& b, const Vec3& nb,
                               double stop_below = 0);

}  // namespace sheetgen
