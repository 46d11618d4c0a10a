#pragma once
// The 2-D kernel of plate_mesher (docs/fem.md "Mesher"): the constrained
// Delaunay triangulation of one polygon with points inside it. CGAL's
// Constrained_Delaunay_triangulation_2 with exact predicates does the work;
// delaunay_2d.cpp is the only file that includes CGAL (docs/code-style.md 5),
// the rest of the code sees Vec2 and index triples.
#include <array>
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

struct PolygonTriangulation {
  std::vector<std::array<int, 3>> triangles;  // #T, counter-clockwise, indices into the points; all inside the outline
  std::vector<int> unused_points;             // ascending: points in no triangle (outside the outline)
};

// Triangulates the simple polygon `outline` (indices into `points`, in order
// around it, either orientation; #P points, any unit) with every point inside
// it as a vertex. Each outline segment is an edge of the result, split where
// a point lies exactly on it; apart from that the triangulation is Delaunay.
// Orientation and in-circle decisions are exact for the given doubles, so no
// triangle is inverted or flat and the triangles tile the outline exactly.
// Deterministic: exactly cocircular points are resolved by insertion order
// (CGAL's spatial sort, with a fixed seed). Throws FemError for fewer than 3
// outline points, an outline index out of range or repeated, a non-finite or
// duplicate point, or outline segments that cross.
PolygonTriangulation triangulate_polygon(const std::vector<Vec2>& points, const std::vector<int>& outline);

}  // namespace sheetgen
