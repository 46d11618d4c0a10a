#include "sheetgen/part/rivet_flange.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

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

}  // namespace

FlangeAttachment check_rivet_flange(const Part& part, const RealisedPart& rp, int i, const Problem& problem,
                                    const ValidityOptions& o) {
  FlangeAttachment out;
  const std::string who = "tab " + std::to_string(i);
  const int ra = part.tabs[i].rivet_area;
  if (ra < 0 || ra >= static_cast<int>(problem.rivet_areas.size())) {
    out.reason = ValidityReason::BadRivetArea;
    out.message = who + " names rivet area " + std::to_string(ra) + ", which does not exist";
    return out;
  }
  const RivetAreaSpec& area = problem.rivet_areas[ra];
  if (area.mesh < 0 || area.mesh >= static_cast<int>(problem.meshes.size())) {
    out.reason = ValidityReason::BadRivetArea;
    out.message = "rivet area " + area.name + " names a mesh that does not exist";
    return out;
  }
  const TriangleMesh& mesh = problem.meshes[area.mesh].mesh;
  const RealisedTab& t = rp.tabs[i];
  const SheetSpec spec = SheetSpec::from(problem);
  const double half = 0.5 * spec.thickness;
  const std::vector<Vec2> flange = ccw(t.local);
  const double flange_area = signed_area(flange);
  const double cos_tol = std::cos(o.flush_angle_tolerance);
  const double near = half + 2.0 * spec.thickness + o.flush_distance_tolerance;  // faces farther than this are not "under" the flange
  BoundingBox box = t.box;
  box.min -= Vec3::Constant(near);
  box.max += Vec3::Constant(near);

  double covered = 0;
  int bad_face = -1;
  double bad_angle = 0, bad_dist = 0;
  for (int f : area.faces) {
    const auto& tri = mesh.triangles[f];
    const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
    BoundingBox fb;
    fb.extend(a);
    fb.extend(b);
    fb.extend(c);
    if ((fb.min.array() > box.max.array()).any() || (fb.max.array() < box.min.array()).any()) continue;
    const Vec3 nf = mesh.face_normal(f);
    if (nf.squaredNorm() == 0) continue;
    std::vector<Vec2> tri2;
    for (const Vec3* q : {&a, &b, &c}) tri2.emplace_back((*q - t.origin).dot(t.x_axis), (*q - t.origin).dot(t.y_axis));
    tri2 = ccw(tri2);
    const std::vector<Vec2> common = clip_convex(flange, tri2);
    if (common.size() < 3) continue;
    const double ca = signed_area(common);
    if (!(ca > 1e-12 * flange_area)) continue;
    double smin = std::numeric_limits<double>::infinity(), smax = -smin;
    for (const Vec2& q : common) {
      const Vec3 Q = t.origin + q.x() * t.x_axis + q.y() * t.y_axis;
      const double s = (Q - a).dot(nf);
      smin = std::min(smin, s);
      smax = std::max(smax, s);
    }
    // A face's winding says nothing about which side is free: a bulkhead or
    // a shelf drawn as one sheet may face either way (Blender does not care),
    // and a rivet area is used from the side the part comes from. Measure
    // from the flange's side; a flange inside a solid fails the clearance of
    // the path that would have to reach it.
    if (smin + smax < 0) {
      const double lo = -smax;
      smax = -smin;
      smin = lo;
    }
    if (std::abs(smin) > near && std::abs(smax) > near && smin * smax > 0) continue;  // a face far behind or in front
    const double ang = std::acos(std::clamp(std::abs(nf.dot(t.normal)), 0.0, 1.0));
    out.max_angle = std::max(out.max_angle, ang);
    const double derr = std::max(std::abs(smin - half), std::abs(smax - half));
    if (std::abs(nf.dot(t.normal)) < cos_tol || derr > o.flush_distance_tolerance) {
      if (bad_face < 0) {
        bad_face = f;
        bad_angle = ang;
        bad_dist = std::abs(smin - half) > std::abs(smax - half) ? smin : smax;
      }
      continue;
    }
    out.max_distance_error = std::max(out.max_distance_error, derr);
    covered += ca;
  }
  out.covered_fraction = flange_area > 0 ? covered / flange_area : 0;
  if (bad_face >= 0) {
    out.reason = ValidityReason::FlangeNotFlush;
    out.message = who + " is not flush on rivet area " + area.name + ": face " + std::to_string(bad_face) + " is at " +
                  num("%.3f mm (needs t/2 = %.3f mm)", bad_dist * 1e3, half * 1e3) + " and " +
                  num("%.3f deg from parallel", bad_angle * 180.0 / M_PI);
    return out;
  }
  if (out.covered_fraction < 1.0 - 1e-9) {
    out.reason = ValidityReason::FlangeOffRivetArea;
    out.message = who + " hangs off rivet area " + area.name + ": only " +
                  num("%.2f %% of its %.1f mm^2 lies over it", 100.0 * out.covered_fraction, flange_area * 1e6);
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
