#pragma once
// The environment a part lives in: every obstacle, every rivet area, every load
// box, and the fast queries the search asks of them. OpenVDB and Embree stay
// behind DistanceField and RayCaster; this header includes neither.
#include <atomic>
#include <memory>
#include <optional>
#include <vector>

#include "sheetgen/core/problem.hpp"

namespace sheetgen {

class DistanceField;
class RayCaster;
class TriangleBvh;

struct EnvironmentOptions {
  double voxel_size = 0;  // m; 0 = auto: clamp(t, diag/4096, diag/256), see docs/environment.md
  int band_voxels = 0;    // half-width of the narrow band, voxels; 0 = auto (clearance need + 3)
  const std::atomic<bool>* cancel = nullptr;  // set during the build -> the constructor throws Cancelled
  // polygon_contact measures a tab's clearance exactly (polygon against every
  // triangle near it) when at most this many triangles come near its box;
  // beyond, it samples the distance fields (docs/environment.md "Exact tab
  // clearance"). 0: always sample.
  int exact_contact_max_triangles = 4096;
};

// Obstacles a polygon may touch without counting as a collision: its own rivet
// area (a rivet flange lying on it) and its own load (the base tab under it).
struct AllowedContacts {
  std::vector<int> rivet_areas;  // indices into Problem::rivet_areas
  std::vector<int> loads;        // indices into Problem::loads
};

struct RayHit {
  double distance = 0;     // m along the unit direction
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();  // unit geometric normal of the face hit
  int mesh = -1;           // environment mesh index, or -1 for a load box
  int face = -1;           // face index in that mesh (or in the box mesh)
  int load = -1;           // load index when a load box was hit
  int rivet_area = -1;     // rivet area the face belongs to, or -1
};

struct ContactResult {
  bool clear = true;          // every point keeps >= required clearance from non-allowed obstacles
  double min_clearance = 0;   // m, smallest clearance found on the polygon (lower bound where clear)
  Vec3 worst_point = Vec3::Zero();
  int samples = 0;            // field queries spent (sampled), or triangles measured (exact)
  bool exact = false;         // measured against the triangles, not sampled on the fields
};

class Environment {
 public:
  explicit Environment(const Problem& problem, const EnvironmentOptions& options = {});
  // `base` with more obstacles: `extra` (the parts made for earlier loads of
  // the problem) appended to its meshes, never rivet areas. Shares every
  // distance field of `base` (the static scene's grids are built once per
  // problem, not once per load) and builds one field over `extra` alone, with
  // base's voxel size and band; rays and the triangle tree are rebuilt over
  // all meshes (docs/environment.md "Obstacles added later").
  Environment(const Environment& base, const std::vector<EnvironmentMesh>& extra, const EnvironmentOptions& options = {});
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

  const Problem& problem() const { return problem_; }
  double voxel_size() const;  // m, of the clearance field
  // Bytes held by the distance fields' grids (obstacles, each rivet area, their
  // union, the added obstacles): the bulk of an environment's memory.
  size_t field_memory_bytes() const;

  // Distance from p to the nearest obstacle of any kind (environment faces,
  // rivet areas, load boxes), m; negative only inside a load box.
  double clearance(const Vec3& p) const;
  // Same, ignoring the allowed contacts.
  double clearance(const Vec3& p, const AllowedContacts& allowed) const;
  // Unit direction of steepest increase of clearance(p) (away from the nearest obstacle).
  Vec3 clearance_gradient(const Vec3& p) const;

  // Distance from p to rivet area `ra`, m (exact near it; see docs/environment.md).
  double rivet_area_distance(int ra, const Vec3& p) const;
  int rivet_area_count() const { return static_cast<int>(problem_.rivet_areas.size()); }
  // Rivet area of a face of environment mesh `mesh`, or -1.
  int rivet_area_of_face(int mesh, int face) const;
  // The field of the plain obstacles (environment faces outside rivet areas), for benchmarks and diagnostics.
  const DistanceField& obstacle_field() const;

  // Is p inside a closed (watertight) environment mesh? Ray parity, majority of
  // three directions. The clearance field is unsigned (docs/environment.md), so
  // a point deep inside a solid looks "far from everything" to it; a load box
  // placed inside a cabinet is caught here.
  bool inside_closed_obstacle(const Vec3& p) const;

  // First obstacle hit along the ray o + s d, 0 < s <= max_distance (d need not be unit).
  std::optional<RayHit> cast_ray(const Vec3& origin, const Vec3& direction, double max_distance) const;

  // Is a planar convex polygon (a tab's mid-surface, m) at least `required` m from
  // every obstacle except the allowed contacts? Exact where few triangles come
  // near it (EnvironmentOptions::exact_contact_max_triangles); else sampled on
  // the distance fields, conservative to `sample_spacing` (m, 0 = voxel/2).
  ContactResult polygon_contact(const std::vector<Vec3>& polygon, double required,
                                const AllowedContacts& allowed, double sample_spacing = 0) const;

 private:
  double distance_excluding(const Vec3& p, const AllowedContacts& allowed) const;
  // The exact test, or nothing when too many triangles come near the polygon.
  std::optional<ContactResult> exact_polygon_contact(const std::vector<Vec3>& polygon, double required,
                                                     const AllowedContacts& allowed) const;

  // Rays, the triangle tree and the per-mesh tables over every mesh of problem_.
  void build_mesh_queries(const EnvironmentOptions& options);
  // face_rivet_area_ for every mesh of problem_.
  void tag_rivet_faces();
  // Distance to the obstacles added by the second constructor (infinity when
  // none or all farther than `below`), m; `nearest` gets the field attaining it (-1: none).
  double added_distance(const Vec3& p, double below, int* nearest = nullptr) const;

  Problem problem_;
  std::shared_ptr<const DistanceField> obstacles_;                  // environment faces that are not rivet areas
  std::vector<std::shared_ptr<const DistanceField>> rivet_fields_;  // one per rivet area
  std::shared_ptr<const DistanceField> all_rivet_areas_;            // union, for quick rejection
  std::vector<BoundingBox> rivet_bounds_;
  // Obstacles added after the scene (parts of earlier loads), one field per
  // addition with its mesh's box; answered beyond their band by a lower bound
  // like obstacles_.
  std::vector<std::shared_ptr<const DistanceField>> added_fields_;
  std::vector<BoundingBox> added_bounds_;
  // The load boxes, prepared for the clearance queries (the hot path of the
  // discovery in scenes with many loads): rotation as a matrix, and a bounding
  // sphere to skip boxes farther than the nearest obstacle found so far.
  struct LoadBox {
    Vec3 center = Vec3::Zero();
    Eigen::Matrix3d to_local = Eigen::Matrix3d::Identity();  // world -> box frame
    Vec3 half = Vec3::Zero();                                  // m, half size
    double radius = 0;                                         // m, half diagonal
    double signed_distance(const Vec3& p) const;               // m, = Load::signed_distance
  };
  std::vector<LoadBox> load_boxes_;
  std::unique_ptr<RayCaster> rays_;
  std::vector<std::vector<int>> face_rivet_area_;  // [mesh][face] -> rivet area or -1
  std::vector<char> mesh_closed_;                    // per environment mesh: watertight
  // Every environment face and every load box's faces, for the exact contact
  // test; per triangle its rivet area and its load (-1 when none).
  std::unique_ptr<TriangleBvh> triangles_;
  std::vector<int> triangle_rivet_area_, triangle_load_;
  int exact_contact_max_triangles_ = 4096;
};

}  // namespace sheetgen
