#pragma once
// Exact small-geometry kernels shared by the fields (refinement), the tests
// (brute-force references) and later the part validity checks.
#include <optional>
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

// Closest point to p on the triangle (a, b, c); exact, handles degenerate triangles.
Vec3 closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);  // m

// Closest point to p on the segment [a, b].
Vec3 closest_point_on_segment(const Vec3& p, const Vec3& a, const Vec3& b);

// Closest points of segments [p0,p1] and [q0,q1] (one pair when they are parallel).
struct SegmentPair {
  Vec3 on_first, on_second;
};
SegmentPair segment_segment_closest(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);
// Distance between segments [p0,p1] and [q0,q1], m.
double segment_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

// Ray (origin o, unit direction d) against triangle; the hit distance t >= t_min, or nothing.
std::optional<double> ray_triangle_intersect(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b,
                                             const Vec3& c, double t_min = 0.0);

// Planar polygon area by the vector area formula (works for any plane), m^2.
double polygon_area(const std::vector<Vec3>& polygon);

}  // namespace sheetgen
