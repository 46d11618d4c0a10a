#pragma once
// Rivet positions on a rivet flange (docs/fem.md "Rivets"): one row parallel
// to the flange's far edge, at the edge distance from it, at the pitch,
// centred, keeping the edge distance from every other edge and from the
// flange's bend zones too. The points
// are handed to mesh_plates() as fixed points so each rivet is a node; the
// FEM clamps those nodes (rivet flange) or ties them (self-rivet).
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

struct RivetLayoutOptions {
  double thickness = 1.6e-3;  // m, sheet t for the default diameter
  // Rivet diameter d, m; <= 0: 2 t rounded up to 1/32 in, at least 1/8 in
  // (Manufacturing defaults in problem.hpp; 3.175 mm for t = 1.6 mm).
  double diameter = 0;
  double edge_distance = 0;  // m, centre to any edge; <= 0: 2 d (MIL-HDBK-5 practice)
  double pitch = 0;          // m, centre to centre; <= 0: 6 d
  // Radius of the clamped footprint around each rivet, m; <= 0: d (a
  // universal head is about 2 d across, MS20470). The footprint is a ring of
  // footprint_points points that become nodes; clamping (or tying) the ring
  // with the centre makes a rivet a small rigid patch of fixed size, whose
  // stiffness converges under refinement - a single clamped node does not
  // (the membrane field of a point support is log-singular).
  double footprint_radius = 0;
  int footprint_points = 6;
};

struct RivetLayout {
  std::vector<Vec3> points;  // m, rivet centres on the polygon
  std::vector<std::vector<Vec3>> footprints;  // per rivet: its centre, then the ring, m
  double footprint_radius = 0;  // m, value used
  double diameter = 0;       // m, values used
  double edge_distance = 0;  // m
  double pitch = 0;          // m

  // Centres and rings of all rivets, in order: the fixed points for mesh_plates().
  std::vector<Vec3> all_points() const;
};

// The rivet diameter `options` gives, m (its default when diameter <= 0).
double rivet_diameter(const RivetLayoutOptions& options);

// A rivet's footprint on a sheet: `centre`, then `points` points on the circle
// of `radius` (m) about it in the plane normal to `normal` (unit).
std::vector<Vec3> rivet_footprint(const Vec3& centre, const Vec3& normal, double radius, int points);

// polygon: planar convex, m; far_edge: index i of the edge from vertex i to
// vertex i+1. keep_out: convex polygons in the flange's plane (m) where the
// sheet is not flat, the bend zones and relief notches of the flange's bends:
// every rivet keeps the edge distance from them too, as from a cut edge. The
// row may then fall into pieces; each gets its own rivets at the pitch.
// Throws FemError when the flange cannot hold one rivet at the edge distance.
RivetLayout layout_rivets(const std::vector<Vec3>& polygon, int far_edge, const RivetLayoutOptions& options = {},
                          const std::vector<std::vector<Vec3>>& keep_out = {});

}  // namespace sheetgen
