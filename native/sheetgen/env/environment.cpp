#include "sheetgen/env/environment.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "sheetgen/env/distance_field.hpp"
#include "sheetgen/env/ray_caster.hpp"
#include "sheetgen/env/triangle_bvh.hpp"
#include "sheetgen/core/polygon_geometry.hpp"

namespace sheetgen {

namespace {

// Copies the listed faces of `src` into a compact mesh.
TriangleMesh submesh(const TriangleMesh& src, const std::vector<int>& faces) {
  TriangleMesh out;
  std::vector<int> remap(src.vertices.size(), -1);
  for (int f : faces) {
    std::array<int, 3> t;
    for (int k = 0; k < 3; ++k) {
      int& r = remap[src.triangles[f][k]];
      if (r < 0) {
        r = static_cast<int>(out.vertices.size());
        out.vertices.push_back(src.vertices[src.triangles[f][k]]);
      }
      t[k] = r;
    }
    out.triangles.push_back(t);
  }
  return out;
}

void append(TriangleMesh& dst, const TriangleMesh& src) {
  const int base = static_cast<int>(dst.vertices.size());
  dst.vertices.insert(dst.vertices.end(), src.vertices.begin(), src.vertices.end());
  for (const auto& t : src.triangles) dst.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

bool contains(const std::vector<int>& v, int x) { return std::find(v.begin(), v.end(), x) != v.end(); }

}  // namespace

Environment::Environment(const Problem& problem, const EnvironmentOptions& options) : problem_(problem) {
  for (const Load& load : problem_.loads) {
    LoadBox box;
    box.center = load.center;
    box.to_local = load.rotation.conjugate().toRotationMatrix();
    box.half = 0.5 * load.size;
    box.radius = box.half.norm();
    load_boxes_.push_back(box);
  }
  const BoundingBox bounds = problem_.bounds();
  const double diag = std::max(bounds.diagonal(), 1e-9);
  const double t = problem_.material.thickness;
  // Voxel: the sheet thickness, kept between diag/4096 (bounded grid size on
  // big scenes) and diag/256 (enough voxels across a tiny scene).
  double voxel = options.voxel_size > 0 ? options.voxel_size : std::max(diag / 4096.0, std::min(t, diag / 256.0));
  const double required = 0.5 * t + problem_.requirements.clearance;
  int band = options.band_voxels > 0 ? options.band_voxels : static_cast<int>(std::ceil(required / voxel)) + 3;
  if (options.voxel_size <= 0) {
    // Memory budget: a narrow band holds about area / h^2 * 2 band voxels (8 bytes
    // each with the index grid). Keep it under kMaxBandVoxels; a huge scene gets
    // coarser voxels (the contact test stays exact near surfaces, docs/environment.md).
    constexpr double kMaxBandVoxels = 4.0e7;  // ~320 MB of grids
    double area = 0;
    for (const auto& m : problem_.meshes) area += m.mesh.area();
    const double h_budget = std::sqrt(area * 2.0 * band / kMaxBandVoxels);
    if (h_budget > voxel) {
      voxel = h_budget;
      band = static_cast<int>(std::ceil(required / voxel)) + 3;
    }
  }
  DistanceFieldOptions fo;
  fo.voxel_size = voxel;
  fo.band_voxels = band;
  fo.cancel = options.cancel;

  // Split every environment mesh into its rivet-area faces and the rest.
  const int nra = static_cast<int>(problem_.rivet_areas.size());
  tag_rivet_faces();

  TriangleMesh obstacles, all_ra;
  for (size_t m = 0; m < problem_.meshes.size(); ++m) {
    std::vector<int> plain;
    for (int f = 0; f < static_cast<int>(face_rivet_area_[m].size()); ++f)
      if (face_rivet_area_[m][f] < 0) plain.push_back(f);
    append(obstacles, submesh(problem_.meshes[m].mesh, plain));
  }
  obstacles_ = std::make_shared<DistanceField>(obstacles, fo);
  for (int r = 0; r < nra; ++r) {
    const auto& ra = problem_.rivet_areas[r];
    TriangleMesh ram = submesh(problem_.meshes[ra.mesh].mesh, ra.faces);
    rivet_bounds_.push_back(bounding_box(ram));
    append(all_ra, ram);
    rivet_fields_.push_back(std::make_shared<DistanceField>(ram, fo));
  }
  all_rivet_areas_ = std::make_shared<DistanceField>(all_ra, fo);
  build_mesh_queries(options);
}

Environment::Environment(const Environment& base, const std::vector<EnvironmentMesh>& extra, const EnvironmentOptions& options)
    : problem_(base.problem_),
      obstacles_(base.obstacles_),
      rivet_fields_(base.rivet_fields_),
      all_rivet_areas_(base.all_rivet_areas_),
      rivet_bounds_(base.rivet_bounds_),
      added_fields_(base.added_fields_),
      added_bounds_(base.added_bounds_),
      load_boxes_(base.load_boxes_) {
  TriangleMesh added;
  for (const EnvironmentMesh& m : extra) {
    append(added, m.mesh);
    problem_.meshes.push_back(m);
  }
  if (!added.triangles.empty()) {
    DistanceFieldOptions fo;
    fo.voxel_size = base.obstacles_->voxel_size();
    fo.band_voxels = static_cast<int>(std::lround(base.obstacles_->band_width() / fo.voxel_size));
    // Beyond its band a field over a few hundred triangles would answer by
    // brute force (DistanceFieldOptions::exact_fallback_triangles); the
    // scene's obstacle field gives a lower bound there, and so does this one.
    fo.exact_fallback_triangles = 0;
    fo.cancel = options.cancel;
    added_bounds_.push_back(bounding_box(added));
    added_fields_.push_back(std::make_shared<DistanceField>(added, fo));
  }
  tag_rivet_faces();
  build_mesh_queries(options);
}

double Environment::added_distance(const Vec3& p, double below, int* nearest) const {
  double d = std::numeric_limits<double>::infinity();
  if (nearest) *nearest = -1;
  for (size_t k = 0; k < added_fields_.size(); ++k) {
    if (added_bounds_[k].distance(p) >= std::min(d, below)) continue;
    const double dk = added_fields_[k]->distance(p);
    if (dk < d) {
      d = dk;
      if (nearest) *nearest = static_cast<int>(k);
    }
  }
  return d;
}

void Environment::tag_rivet_faces() {
  face_rivet_area_.resize(problem_.meshes.size());
  for (size_t m = 0; m < problem_.meshes.size(); ++m) face_rivet_area_[m].assign(problem_.meshes[m].mesh.triangles.size(), -1);
  for (int r = 0; r < static_cast<int>(problem_.rivet_areas.size()); ++r)
    for (int f : problem_.rivet_areas[r].faces) face_rivet_area_[problem_.rivet_areas[r].mesh][f] = r;
}

void Environment::build_mesh_queries(const EnvironmentOptions& options) {
  // Ray caster: every environment mesh whole, then every load box.
  std::vector<TriangleMesh> boxes;
  for (const auto& l : problem_.loads) boxes.push_back(l.box_mesh());
  std::vector<const TriangleMesh*> geoms;
  for (const auto& m : problem_.meshes) geoms.push_back(&m.mesh);
  for (const auto& b : boxes) geoms.push_back(&b);
  rays_ = std::make_unique<RayCaster>(geoms);
  mesh_closed_.clear();
  for (const auto& m : problem_.meshes) mesh_closed_.push_back(m.mesh.is_closed() ? 1 : 0);

  std::vector<std::array<Vec3, 3>> tris;
  for (size_t m = 0; m < problem_.meshes.size(); ++m) {
    const TriangleMesh& mesh = problem_.meshes[m].mesh;
    for (size_t f = 0; f < mesh.triangles.size(); ++f) {
      const auto& t = mesh.triangles[f];
      tris.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
      triangle_rivet_area_.push_back(face_rivet_area_[m][f]);
      triangle_load_.push_back(-1);
    }
  }
  for (size_t l = 0; l < boxes.size(); ++l)
    for (const auto& t : boxes[l].triangles) {
      tris.push_back({boxes[l].vertices[t[0]], boxes[l].vertices[t[1]], boxes[l].vertices[t[2]]});
      triangle_rivet_area_.push_back(-1);
      triangle_load_.push_back(static_cast<int>(l));
    }
  triangles_ = std::make_unique<TriangleBvh>(std::move(tris));
  exact_contact_max_triangles_ = options.exact_contact_max_triangles;
}

bool Environment::inside_closed_obstacle(const Vec3& p) const {
  const int nm = static_cast<int>(problem_.meshes.size());
  if (std::none_of(mesh_closed_.begin(), mesh_closed_.end(), [](char c) { return c != 0; })) return false;
  // Odd directions, so a ray rarely runs exactly along an edge of axis-aligned geometry.
  const Vec3 dirs[3] = {Vec3(0.8017, 0.2673, 0.5345), Vec3(-0.3015, 0.9045, -0.3015), Vec3(0.2357, -0.2357, -0.9428)};
  int votes = 0;
  for (const Vec3& d : dirs) {
    std::vector<int> crossings(nm, 0);
    double from = 0;
    for (int step = 0; step < 10000; ++step) {
      auto hit = rays_->first_hit(p, d, std::numeric_limits<double>::infinity(), from);
      if (!hit) break;
      if (hit->geometry < nm) ++crossings[hit->geometry];
      from = hit->distance + 1e-7;
    }
    bool inside = false;
    for (int m = 0; m < nm; ++m) inside = inside || (mesh_closed_[m] && crossings[m] % 2 == 1);
    votes += inside;
  }
  return votes >= 2;
}

Environment::~Environment() = default;

double Environment::voxel_size() const { return obstacles_->voxel_size(); }

size_t Environment::field_memory_bytes() const {
  size_t bytes = obstacles_->stats().memory_bytes + all_rivet_areas_->stats().memory_bytes;
  for (const auto& f : rivet_fields_) bytes += f->stats().memory_bytes;
  for (const auto& f : added_fields_) bytes += f->stats().memory_bytes;
  return bytes;
}

const DistanceField& Environment::obstacle_field() const { return *obstacles_; }

double Environment::clearance(const Vec3& p) const { return distance_excluding(p, AllowedContacts{}); }

double Environment::clearance(const Vec3& p, const AllowedContacts& allowed) const { return distance_excluding(p, allowed); }

double Environment::distance_excluding(const Vec3& p, const AllowedContacts& allowed) const {
  double d = obstacles_->distance(p);
  if (!added_fields_.empty()) d = std::min(d, added_distance(p, d));
  if (!rivet_fields_.empty()) {
    if (allowed.rivet_areas.empty()) {
      d = std::min(d, all_rivet_areas_->distance(p));
    } else if (all_rivet_areas_->distance(p) < d) {
      // Some rivet area is nearer than the plain obstacles: ask the ones not allowed.
      for (int r = 0; r < static_cast<int>(rivet_fields_.size()); ++r) {
        if (contains(allowed.rivet_areas, r) || rivet_bounds_[r].distance(p) >= d) continue;
        d = std::min(d, rivet_fields_[r]->distance(p));
      }
    }
  }
  for (int l = 0; l < static_cast<int>(load_boxes_.size()); ++l) {
    const LoadBox& box = load_boxes_[l];
    // |p - c| - r is a lower bound of the distance to the box.
    if ((p - box.center).norm() - box.radius >= d || contains(allowed.loads, l)) continue;
    d = std::min(d, box.signed_distance(p));
  }
  return d;
}

double Environment::LoadBox::signed_distance(const Vec3& p) const {
  const Vec3 q = (to_local * (p - center)).cwiseAbs() - half;
  return q.cwiseMax(Vec3::Zero()).norm() + std::min(q.maxCoeff(), 0.0);
}

Vec3 Environment::clearance_gradient(const Vec3& p) const {
  // The gradient of a minimum is the gradient of the component that attains it.
  double best = obstacles_->distance(p);
  Vec3 g = obstacles_->gradient(p);
  int nearest = -1;
  const double da = added_distance(p, best, &nearest);
  if (nearest >= 0 && da < best) {
    best = da;
    g = added_fields_[nearest]->gradient(p);
  }
  if (!rivet_fields_.empty()) {
    const double d = all_rivet_areas_->distance(p);
    if (d < best) {
      best = d;
      g = all_rivet_areas_->gradient(p);
    }
  }
  for (const LoadBox& load : load_boxes_) {
    const double d = load.signed_distance(p);
    if (d < best) {
      best = d;
      // Central differences of the exact box distance (cheap and robust at edges).
      const double h = 1e-6 * std::max(1.0, 2 * load.radius);
      for (int k = 0; k < 3; ++k) {
        Vec3 e = Vec3::Zero();
        e[k] = h;
        g[k] = load.signed_distance(p + e) - load.signed_distance(p - e);
      }
      if (g.norm() > 0) g.normalize();
    }
  }
  return g;
}

double Environment::rivet_area_distance(int ra, const Vec3& p) const {
  if (ra < 0 || ra >= static_cast<int>(rivet_fields_.size())) throw std::out_of_range("rivet area index " + std::to_string(ra) + " is out of range");
  return rivet_fields_[ra]->distance(p);
}

int Environment::rivet_area_of_face(int mesh, int face) const {
  if (mesh < 0 || mesh >= static_cast<int>(face_rivet_area_.size())) return -1;
  if (face < 0 || face >= static_cast<int>(face_rivet_area_[mesh].size())) return -1;
  return face_rivet_area_[mesh][face];
}

std::optional<RayHit> Environment::cast_ray(const Vec3& origin, const Vec3& direction, double max_distance) const {
  auto h = rays_->first_hit(origin, direction, max_distance, 0.0);
  if (!h) return std::nullopt;
  RayHit hit;
  hit.distance = h->distance;
  hit.point = h->point;
  hit.normal = h->normal;
  hit.face = h->face;
  const int nm = static_cast<int>(problem_.meshes.size());
  if (h->geometry < nm) {
    hit.mesh = h->geometry;
    hit.rivet_area = face_rivet_area_[hit.mesh][hit.face];
  } else {
    hit.load = h->geometry - nm;
  }
  return hit;
}

std::optional<ContactResult> Environment::exact_polygon_contact(const std::vector<Vec3>& polygon, double required,
                                                              const AllowedContacts& allowed) const {
  if (exact_contact_max_triangles_ <= 0) return std::nullopt;
  const size_t m = polygon.size();
  Vec3 normal = Vec3::Zero();  // Newell's normal
  for (size_t k = 0; k < m; ++k) normal += polygon[k].cross(polygon[(k + 1) % m]);
  const double len = normal.norm();
  if (!(len > 0)) return std::nullopt;
  normal /= len;
  // A triangle whose box misses the polygon's box grown by `required` is
  // farther than `required` along some axis, so farther in space.
  BoundingBox near;
  for (const Vec3& p : polygon) near.extend(p);
  near.min.array() -= required;
  near.max.array() += required;
  thread_local std::vector<int> candidates;
  candidates.clear();
  if (!triangles_->overlapping(near, candidates, exact_contact_max_triangles_)) return std::nullopt;

  ContactResult result;
  result.exact = true;
  result.min_clearance = required;  // nothing outside the candidates is nearer
  result.worst_point = polygon.front();
  thread_local std::vector<Vec3> corners(3);
  for (int c : candidates) {
    const int load = triangle_load_[c], ra = triangle_rivet_area_[c];
    if (load >= 0 ? contains(allowed.loads, load) : (ra >= 0 && contains(allowed.rivet_areas, ra))) continue;
    const auto& tri = triangles_->triangle(c);
    corners.assign(tri.begin(), tri.end());
    Vec3 tn = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
    const double scale = std::max({(tri[1] - tri[0]).squaredNorm(), (tri[2] - tri[0]).squaredNorm(), (tri[2] - tri[1]).squaredNorm()});
    const double area2 = tn.norm();
    tn = area2 > 1e-12 * scale ? Vec3(tn / area2) : Vec3::Zero();  // a sliver counts by its edges
    const PolygonPair pair = convex_polygon_closest(polygon, normal, corners, tn, required);
    ++result.samples;
    if (pair.distance < result.min_clearance) {
      result.min_clearance = pair.distance;
      result.worst_point = pair.on_a;
    }
    if (pair.distance < required) {
      result.clear = false;
      return result;
    }
  }
  // A polygon wholly inside a load box meets none of its faces.
  for (int l = 0; l < static_cast<int>(load_boxes_.size()); ++l) {
    if (contains(allowed.loads, l)) continue;
    const double d = load_boxes_[l].signed_distance(polygon.front());
    if (d < 0) {
      result.clear = false;
      result.min_clearance = d;
      result.worst_point = polygon.front();
      return result;
    }
  }
  result.clear = true;
  return result;
}

ContactResult Environment::polygon_contact(const std::vector<Vec3>& polygon, double required, const AllowedContacts& allowed,
                                           double sample_spacing) const {
  if (polygon.size() >= 3)
    if (auto exact = exact_polygon_contact(polygon, required, allowed)) return *exact;
  ContactResult result;
  result.min_clearance = std::numeric_limits<double>::infinity();
  if (polygon.size() < 3) {
    for (const auto& p : polygon) {
      const double d = distance_excluding(p, allowed);
      ++result.samples;
      if (d < result.min_clearance) { result.min_clearance = d; result.worst_point = p; }
    }
    result.clear = result.min_clearance >= required;
    return result;
  }
  const double leaf = 0.5 * (sample_spacing > 0 ? sample_spacing : 0.5 * voxel_size());
  // Fan triangulation (tabs are convex), then recursive 4-way subdivision: a
  // triangle whose bounding sphere (centre c, radius r) satisfies d(c) >= required + r
  // is clear as a whole, because distance is 1-Lipschitz.
  struct Tri { Vec3 a, b, c; };
  std::vector<Tri> stack;
  for (size_t k = 1; k + 1 < polygon.size(); ++k) stack.push_back({polygon[0], polygon[k], polygon[k + 1]});
  while (!stack.empty()) {
    const Tri t = stack.back();
    stack.pop_back();
    const Vec3 c = (t.a + t.b + t.c) / 3.0;
    const double r = std::max({(t.a - c).norm(), (t.b - c).norm(), (t.c - c).norm()});
    const double d = distance_excluding(c, allowed);
    ++result.samples;
    if (d >= required + r) {
      if (d - r < result.min_clearance) { result.min_clearance = d - r; result.worst_point = c; }
      continue;
    }
    if (r <= leaf) {
      if (d < result.min_clearance) { result.min_clearance = d; result.worst_point = c; }
      if (d < required) {
        result.clear = false;
        return result;  // one violation decides; the caller wants a yes/no and where
      }
      continue;
    }
    const Vec3 ab = 0.5 * (t.a + t.b), bc = 0.5 * (t.b + t.c), ca = 0.5 * (t.c + t.a);
    stack.push_back({t.a, ab, ca});
    stack.push_back({ab, t.b, bc});
    stack.push_back({ca, bc, t.c});
    stack.push_back({ab, bc, ca});
  }
  result.clear = true;
  return result;
}

}  // namespace sheetgen
