#pragma once
// 2-D Delaunay triangulation (Bowyer-Watson with triangle adjacency and a
// walking point location), the kernel of plate_mesher. The convex hull of the
// points is triangulated; hull points that are collinear stay on the hull, so
// the boundary of a convex polygon sampled along its edges is kept edge by edge.
#include <array>
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

// Triangles (counter-clockwise) of the Delaunay triangulation of `points`
// (#P, any unit). Deterministic. Cocircular points are handled but any of
// their valid triangulations may come out; a caller that wants a clean choice
// perturbs them first (plate_mesher does). Duplicate points are an error
// (FemError). Exactly collinear hull points give no triangle; hull points
// inside the hull by round-off give slivers the caller may drop.
std::vector<std::array<int, 3>> delaunay_triangulation(const std::vector<Vec2>& points);

}  // namespace sheetgen
