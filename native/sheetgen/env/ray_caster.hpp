#pragma once
// Exact ray casts and closest-point queries against a set of triangle meshes.
// The one door to Embree (docs/code-style.md point 5). Embree works in single precision:
// hits are exact to about 1e-7 of the scene size.
#include <memory>
#include <optional>
#include <vector>

#include "sheetgen/core/triangle_mesh.hpp"

namespace sheetgen {

struct RayCasterHit {
  double distance = 0;          // m along the unit direction
  Vec3 point = Vec3::Zero();    // m
  Vec3 normal = Vec3::Zero();   // unit geometric normal (front = counter-clockwise side)
  int geometry = -1;            // index of the mesh in the constructor's list
  int face = -1;                // triangle index in that mesh
};

struct RayCasterClosest {
  double distance = 0;          // m; infinity when nothing lies within the radius
  Vec3 point = Vec3::Zero();
  int geometry = -1;
  int face = -1;
};

class RayCaster {
 public:
  // Builds one Embree scene (a BVH) over the meshes; they are copied.
  explicit RayCaster(const std::vector<const TriangleMesh*>& meshes);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // First hit along origin + s * direction for s in (t_min, t_max]; direction need not be unit.
  std::optional<RayCasterHit> first_hit(const Vec3& origin, const Vec3& direction, double t_max,
                                        double t_min = 0.0) const;
  // Closest point on any mesh within `radius` of p (Embree's rtcPointQuery).
  RayCasterClosest closest_point(const Vec3& p, double radius = std::numeric_limits<double>::infinity()) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sheetgen
