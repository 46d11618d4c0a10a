#pragma once
// Unsigned distance to a triangle mesh, O(1) per query. The one door to OpenVDB
// (docs/code-style.md point 5): a narrow-band distance grid plus a closest-triangle index
// grid. See docs/environment.md for the accuracy contract.
#include <atomic>
#include <memory>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

struct DistanceFieldOptions {
  double voxel_size = 1.6e-3;      // m, grid spacing h
  int band_voxels = 4;             // half-width of the narrow band, voxels
  double refine_below = 0;         // m; cells with a corner value below this are answered
                                   // exactly from the closest-triangle index; 0 = 1 voxel
  int exact_fallback_triangles = 512;  // beyond the band, meshes with at most this many
                                       // triangles are answered exactly by brute force
  const std::atomic<bool>* cancel = nullptr;  // set -> the build stops and throws Cancelled
};

struct DistanceFieldStats {
  size_t active_voxels = 0;
  size_t memory_bytes = 0;    // distance grid + index grid + the leaf table
  double build_seconds = 0;
};

struct ClosestPoint {
  double distance = 0;        // m
  Vec3 point = Vec3::Zero();  // closest point on the mesh (m); meaningful when face >= 0
  int face = -1;              // triangle index, -1 when only a bound is known
  bool exact = false;         // distance is exact (else: interpolated or a lower bound)
};

class DistanceField {
 public:
  // An empty mesh gives a field that is infinitely far from everything.
  DistanceField(const TriangleMesh& mesh, const DistanceFieldOptions& options);
  ~DistanceField();
  DistanceField(const DistanceField&) = delete;
  DistanceField& operator=(const DistanceField&) = delete;

  // Distance from p to the mesh, m. Exact in cells that reach within refine_below
  // of the surface, trilinear elsewhere inside
  // the band, and beyond it exact (small meshes) or a lower bound: the larger
  // of the band width and the distance to the mesh's bounding box.
  double distance(const Vec3& p) const;
  // Distance with the closest point when it can be known.
  ClosestPoint closest(const Vec3& p) const;
  // Unit gradient of the distance (points away from the mesh).
  Vec3 gradient(const Vec3& p) const;

  double voxel_size() const;  // m
  double band_width() const;  // m, distances below this come from the grid
  const DistanceFieldStats& stats() const;
  const TriangleMesh& mesh() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sheetgen
