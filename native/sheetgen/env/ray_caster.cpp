// The only translation unit that includes Embree.
#include "sheetgen/env/ray_caster.hpp"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sheetgen/core/geometry.hpp"

namespace sheetgen {

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<TriangleMesh> meshes;  // double-precision copies for exact closest points

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

struct ClosestQueryState {
  const std::vector<TriangleMesh>* meshes;
  Vec3 p;
  RayCasterClosest best;
};

// Called by Embree for every triangle whose bounds meet the query sphere.
bool closest_point_callback(RTCPointQueryFunctionArguments* args) {
  auto* state = static_cast<ClosestQueryState*>(args->userPtr);
  const TriangleMesh& mesh = (*state->meshes)[args->geomID];
  const auto& t = mesh.triangles[args->primID];
  const Vec3 q = closest_point_on_triangle(state->p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  const double d = (q - state->p).norm();
  if (d < state->best.distance) {
    state->best.distance = d;
    state->best.point = q;
    state->best.geometry = static_cast<int>(args->geomID);
    state->best.face = static_cast<int>(args->primID);
    // Shrinking the radius prunes the rest of the traversal.
    args->query->radius = static_cast<float>(d);
    return true;
  }
  return false;
}

}  // namespace

RayCaster::RayCaster(const std::vector<const TriangleMesh*>& meshes) : impl_(std::make_unique<Impl>()) {
  // No "threads=N": Embree built on TBB turns N into a process-wide
  // tbb::global_control, which would cap every parallel loop in sheetgen
  // (chains, composition) at N threads while the device lives.
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error("Embree: cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  impl_->meshes.reserve(meshes.size());
  for (size_t g = 0; g < meshes.size(); ++g) {
    impl_->meshes.push_back(*meshes[g]);
    const TriangleMesh& m = impl_->meshes.back();
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // An empty mesh still takes a geometry slot so that ids match list positions.
    const size_t nv = std::max<size_t>(m.vertices.size(), 1), nt = m.triangles.size();
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    for (size_t i = 0; i < m.vertices.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = static_cast<float>(m.vertices[i][k]);
    if (m.vertices.empty()) v[0] = v[1] = v[2] = 0.f;
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt));
    for (size_t f = 0; f < nt; ++f)
      for (int k = 0; k < 3; ++k) idx[3 * f + k] = static_cast<unsigned>(m.triangles[f][k]);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(impl_->scene, geom, static_cast<unsigned>(g));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  const RTCError err = rtcGetDeviceError(impl_->device);
  if (err != RTC_ERROR_NONE) throw std::runtime_error("Embree: scene build failed (error " + std::to_string(err) + ")");
}

RayCaster::~RayCaster() = default;

std::optional<RayCasterHit> RayCaster::first_hit(const Vec3& origin, const Vec3& direction, double t_max, double t_min) const {
  const double len = direction.norm();
  if (!(len > 0) || !(t_max > t_min)) return std::nullopt;
  const Vec3 d = direction / len;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin.x());
  rh.ray.org_y = static_cast<float>(origin.y());
  rh.ray.org_z = static_cast<float>(origin.z());
  rh.ray.dir_x = static_cast<float>(d.x());
  rh.ray.dir_y = static_cast<float>(d.y());
  rh.ray.dir_z = static_cast<float>(d.z());
  rh.ray.tnear = static_cast<float>(t_min);
  rh.ray.tfar = std::isfinite(t_max) ? static_cast<float>(t_max) : std::numeric_limits<float>::infinity();
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.time = 0.f;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  RayCasterHit hit;
  hit.geometry = static_cast<int>(rh.hit.geomID);
  hit.face = static_cast<int>(rh.hit.primID);
  const TriangleMesh& m = impl_->meshes[hit.geometry];
  // Refine the distance in double precision against the hit triangle.
  const auto& t = m.triangles[hit.face];
  const auto exact = ray_triangle_intersect(origin, d, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], -1e-9);
  hit.distance = exact ? *exact : static_cast<double>(rh.ray.tfar);
  hit.point = origin + hit.distance * d;
  hit.normal = m.face_normal(hit.face);
  return hit;
}

RayCasterClosest RayCaster::closest_point(const Vec3& p, double radius) const {
  ClosestQueryState state{&impl_->meshes, p, {}};
  state.best.distance = std::numeric_limits<double>::infinity();
  RTCPointQuery query;
  query.x = static_cast<float>(p.x());
  query.y = static_cast<float>(p.y());
  query.z = static_cast<float>(p.z());
  query.radius = std::isfinite(radius) ? static_cast<float>(radius) : std::numeric_limits<float>::infinity();
  query.time = 0.f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(impl_->scene, &query, &context, closest_point_callback, &state);
  if (state.best.distance > radius) state.best = RayCasterClosest{std::numeric_limits<double>::infinity(), Vec3::Zero(), -1, -1};
  return state.best;
}

}  // namespace sheetgen
