#include "sheetgen/part/rivet_flange.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "sheetgen/core/polygon_geometry.hpp"

namespace sheetgen {

namespace {

std::vector<Vec2> ccw(std::vector<Vec2> p) {
  if (signed_area(p) < 0) std::reverse(p.begin(), p.end());
  return p;
}

std::string num(const char* f, double a, double b = 0) {
  char buf[200];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

// The rivet area tab `who` names, or null (with out.reason and out.message set)
// when it or its mesh does not exist.
const RivetAreaSpec* named_rivet_area(int ra, const Problem& problem, const std::string& who, FlangeAttachment& out) {
  if (ra < 0 || ra >= static_cast<int>(problem.rivet_areas.size())) {
    out.reason = ValidityReason::BadRivetArea;
    out.message = who + " names rivet area " + std::to_string(ra) + ", which does not exist";
    return nullptr;
  }
  const RivetAreaSpec& area = problem.rivet_areas[ra];
  if (area.mesh < 0 || area.mesh >= static_cast<int>(problem.meshes.size())) {
    out.reason = ValidityReason::BadRivetArea;
    out.message = "rivet area " + area.name + " names a mesh that does not exist";
    return nullptr;
  }
  return &area;
}

// The flange as the faces of a rivet area are measured against it.
struct FlangeProbe {
  explicit FlangeProbe(const RealisedTab& tab) : t(tab) {}
  const RealisedTab& t;
  std::vector<Vec2> flange;      // tab frame, counter-clockwise, m
  double flange_area = 0;        // m^2
  double half = 0;               // m, t/2: where a flush face lies
  double near = 0;               // m, faces farther than this are not "under" the flange
  double cos_tol = 0;            // cosine of the flush angle tolerance
  double distance_tolerance = 0; // m
  BoundingBox box;               // the tab's, grown by `near`
};

FlangeProbe flange_probe(const RealisedTab& t, const SheetSpec& spec, const ValidityOptions& o) {
  FlangeProbe p(t);
  p.half = 0.5 * spec.thickness;
  p.flange = ccw(t.local);
  p.flange_area = signed_area(p.flange);
  p.cos_tol = std::cos(o.flush_angle_tolerance);
  p.near = p.half + 2.0 * spec.thickness + o.flush_distance_tolerance;
  p.distance_tolerance = o.flush_distance_tolerance;
  p.box = t.box;
  p.box.min -= Vec3::Constant(p.near);
  p.box.max += Vec3::Constant(p.near);
  return p;
}

// A face under the flange: how much of the flange it covers and how far from
// the flange's mid-surface it lies.
struct FaceUnder {
  double area = 0;            // m^2 of the flange over the face
  double smin = 0, smax = 0;  // m, range of distances from the face, seen from the flange's side
  double cos_angle = 0;       // |cosine| between the face's and the flange's normals
};

std::optional<FaceUnder> face_under_flange(const FlangeProbe& p, const TriangleMesh& mesh, int f) {
  const RealisedTab& t = p.t;
  const auto& tri = mesh.triangles[f];
  const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
  BoundingBox fb;
  fb.extend(a);
  fb.extend(b);
  fb.extend(c);
  if ((fb.min.array() > p.box.max.array()).any() || (fb.max.array() < p.box.min.array()).any()) return std::nullopt;
  const Vec3 nf = mesh.face_normal(f);
  if (nf.squaredNorm() == 0) return std::nullopt;
  std::vector<Vec2> tri2;
  for (const Vec3* q : {&a, &b, &c}) tri2.emplace_back((*q - t.origin).dot(t.x_axis), (*q - t.origin).dot(t.y_axis));
  tri2 = ccw(tri2);
  const std::vector<Vec2> common = clip_convex(p.flange, tri2);
  if (common.size() < 3) return std::nullopt;
  FaceUnder u;
  u.area = signed_area(common);
  if (!(u.area > 1e-12 * p.flange_area)) return std::nullopt;
  u.smin = std::numeric_limits<double>::infinity();
  u.smax = -u.smin;
  for (const Vec2& q : common) {
    const Vec3 Q = t.origin + q.x() * t.x_axis + q.y() * t.y_axis;
    const double s = (Q - a).dot(nf);
    u.smin = std::min(u.smin, s);
    u.smax = std::max(u.smax, s);
  }
  // A face's winding says nothing about which side is free: a bulkhead or
  // a shelf drawn as one sheet may face either way (Blender does not care),
  // and a rivet area is used from the side the part comes from. Measure
  // from the flange's side; a flange inside a solid fails the clearance of
  // the path that would have to reach it.
  if (u.smin + u.smax < 0) {
    const double lo = -u.smax;
    u.smax = -u.smin;
    u.smin = lo;
  }
  // a face far behind or in front
  if (std::abs(u.smin) > p.near && std::abs(u.smax) > p.near && u.smin * u.smax > 0) return std::nullopt;
  u.cos_angle = std::abs(nf.dot(t.normal));
  return u;
}

struct Coverage {
  double covered = 0;                  // m^2 of the flange over flush faces
  int bad_face = -1;                   // the first face under the flange that is not flush
  double bad_angle = 0, bad_dist = 0;  // rad, m: its angle and its distance farthest from t/2
};

// Also records the largest angle and flush distance error in `out`.
Coverage measure_coverage(const FlangeProbe& p, const TriangleMesh& mesh, const std::vector<int>& faces, FlangeAttachment& out) {
  Coverage c;
  for (int f : faces) {
    const std::optional<FaceUnder> u = face_under_flange(p, mesh, f);
    if (!u) continue;
    const double ang = std::acos(std::clamp(u->cos_angle, 0.0, 1.0));
    out.max_angle = std::max(out.max_angle, ang);
    const double derr = std::max(std::abs(u->smin - p.half), std::abs(u->smax - p.half));
    if (u->cos_angle < p.cos_tol || derr > p.distance_tolerance) {
      if (c.bad_face < 0) {
        c.bad_face = f;
        c.bad_angle = ang;
        c.bad_dist = std::abs(u->smin - p.half) > std::abs(u->smax - p.half) ? u->smin : u->smax;
      }
      continue;
    }
    out.max_distance_error = std::max(out.max_distance_error, derr);
    c.covered += u->area;
  }
  return c;
}

}  // namespace

FlangeAttachment check_rivet_flange(const Part& part, const RealisedPart& rp, int i, const Problem& problem,
                                    const ValidityOptions& o) {
  FlangeAttachment out;
  const std::string who = "tab " + std::to_string(i);
  const RivetAreaSpec* area = named_rivet_area(part.tabs[i].rivet_area, problem, who, out);
  if (!area) return out;
  const SheetSpec spec = SheetSpec::from(problem);
  const FlangeProbe probe = flange_probe(rp.tabs[i], spec, o);
  const Coverage c = measure_coverage(probe, problem.meshes[area->mesh].mesh, area->faces, out);
  out.covered_fraction = probe.flange_area > 0 ? c.covered / probe.flange_area : 0;
  if (c.bad_face >= 0) {
    out.reason = ValidityReason::FlangeNotFlush;
    out.message = who + " is not flush on rivet area " + area->name + ": face " + std::to_string(c.bad_face) + " is at " +
                  num("%.3f mm (needs t/2 = %.3f mm)", c.bad_dist * 1e3, probe.half * 1e3) + " and " +
                  num("%.3f deg from parallel", c.bad_angle * 180.0 / M_PI);
    return out;
  }
  if (out.covered_fraction < 1.0 - 1e-9) {
    out.reason = ValidityReason::FlangeOffRivetArea;
    out.message = who + " hangs off rivet area " + area->name + ": only " +
                  num("%.2f %% of its %.1f mm^2 lies over it", 100.0 * out.covered_fraction, probe.flange_area * 1e6);
    return out;
  }
  out.rivets = rivet_positions(part, rp, i, spec);
  if (out.rivets.empty()) {
    out.reason = ValidityReason::NoRoomForRivet;
    out.message = who + " has no room for a rivet at edge distance " +
                  num("%.3f mm beyond its bend setback %.3f mm", spec.manufacturing.rivet_edge_distance * 1e3,
                      bend_setback(part.tabs[i].params.theta3, spec) * 1e3);
  }
  return out;
}

std::vector<Vec2> rivet_region(const Part& part, const RealisedPart& rp, int i, const SheetSpec& spec) {
  const RealisedTab& t = rp.tabs[i];
  std::vector<Vec2> poly = ccw(t.local);
  if (i > 0) poly = clip_half_plane(poly, Vec2(0, 1), bend_setback(part.tabs[i].params.theta3, spec));
  if (poly.size() < 3) return {};
  return inset_convex(poly, spec.manufacturing.rivet_edge_distance);
}

std::vector<Vec3> rivet_positions(const Part& part, const RealisedPart& rp, int i, const SheetSpec& spec) {
  const std::vector<Vec2> region = rivet_region(part, rp, i, spec);
  if (region.empty()) return {};
  const RealisedTab& t = rp.tabs[i];
  auto world = [&](const Vec2& q) { return Vec3(t.origin + q.x() * t.x_axis + q.y() * t.y_axis); };
  double ymin = std::numeric_limits<double>::infinity(), ymax = -ymin;
  for (const Vec2& q : region) {
    ymin = std::min(ymin, q.y());
    ymax = std::max(ymax, q.y());
  }
  const double ym = 0.5 * (ymin + ymax);
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0;
  const size_t m = region.size();
  for (size_t k = 0; k < m; ++k) {
    const Vec2 &a = region[k], &b = region[(k + 1) % m];
    if ((a.y() - ym) * (b.y() - ym) > 0 || a.y() == b.y()) continue;
    const double x = a.x() + (ym - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
  }
  const double pitch = spec.manufacturing.rivet_pitch;
  if (!(x1 >= x0) || !(pitch > 0)) return {world(polygon_centroid(region))};
  const int count = static_cast<int>(std::floor((x1 - x0) / pitch)) + 1;
  if (count <= 1) return {world(polygon_centroid(region))};
  std::vector<Vec3> out;
  const double start = x0 + 0.5 * ((x1 - x0) - (count - 1) * pitch);
  for (int k = 0; k < count; ++k) out.push_back(world(Vec2(start + k * pitch, ym)));
  return out;
}

}  // namespace sheetgen
