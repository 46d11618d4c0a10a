#pragma once
// One conforming triangle mesh over a sheet-metal part's tabs (docs/fem.md
// "Mesher"). Input: planar convex polygons in 3-D, m, where a child tab's root
// edge lies on (a sub-segment of) an edge of its parent - T-junctions. Every
// polygon edge is split at every polygon vertex that lies on it, so the two
// sides of a shared segment get the same nodes; each piece is sampled at the
// element size h, an equilateral lattice of spacing h fills the inside, and
// the constrained Delaunay triangulation of those points inside the sampled
// outline (delaunay_2d.hpp: CGAL, exact predicates) gives near-equilateral
// triangles.
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

struct PlateMeshOptions {
  // Target edge length h, m. <= 0 selects the default: the narrowest polygon
  // width / 4 (four elements across the narrowest tab), clamped to
  // [2 t, 20 mm] (finer than 2 t buys nothing for a Kirchhoff shell; 20 mm
  // keeps big base plates resolved).
  double element_size = 0;
  double thickness = 1.6e-3;  // m, t for the default size rule; polygon vertices closer than max(t/100, h/1000) are one point
  // m: points closer than this are one node; a vertex closer than this to an
  // edge splits the edge. Also the planarity tolerance (scaled by polygon size).
  double tolerance = 1e-7;
  // Laplacian smoothing passes over the interior lattice points (each followed
  // by a re-triangulation); they even out the band next to the boundary.
  int smoothing_passes = 2;
  // Graded refinement at fold ends (docs/fem.md "Graded fold ends"): where a
  // polygon vertex lies inside another polygon's edge (a fold that ends
  // inside its parent's edge, or a narrower flat extension) the outline has a
  // re-entrant corner whose singular field the uniform mesh under-resolves
  // (the part comes out stiff). Around such a point p the element size is
  // min(h, fold_end_element_size + fold_end_grading * |x - p|).
  bool grade_fold_ends = true;
  double fold_end_element_size = 0;  // m, size at the corner; <= 0: t / 4
  double fold_end_grading = 0.5;     // growth of the size per unit distance from the corner
};

struct PlateMesh {
  TriangleMesh mesh;                             // m; a polygon's triangles follow its vertex order (normal by the right-hand rule)
  std::vector<int> element_polygon;              // #F, index of the polygon each triangle lies in
  std::vector<std::vector<int>> fixed_point_nodes;  // per polygon, the node of each requested fixed point
  double element_size = 0;                       // m, h used
  std::vector<Vec3> fold_ends;                   // m, the graded corners (empty when grading is off)
};

// The default h of PlateMeshOptions for these polygons, m.
double default_element_size(const std::vector<std::vector<Vec3>>& polygons, double thickness);

// Meshes the polygons into one conforming mesh. fixed_points[k] (optional,
// m) are points inside polygon k that must become nodes (rivets). Throws
// FemError for a non-planar, non-convex or degenerate polygon, or a fixed
// point outside its polygon.
PlateMesh mesh_plates(const std::vector<std::vector<Vec3>>& polygons,
                      const std::vector<std::vector<Vec3>>& fixed_points = {}, const PlateMeshOptions& options = {});

// Nodes of `mesh` lying on the planar convex `polygon` (within `tolerance` m
// of its plane and inside its edges), e.g. the base-tab nodes under a load box.
std::vector<int> nodes_on_polygon(const TriangleMesh& mesh, const std::vector<Vec3>& polygon,
                                  double tolerance = 1e-7);

// Nodes of `mesh` within `tolerance` m of the segment [a, b], ordered along it.
std::vector<int> nodes_on_segment(const TriangleMesh& mesh, const Vec3& a, const Vec3& b, double tolerance = 1e-7);

}  // namespace sheetgen
