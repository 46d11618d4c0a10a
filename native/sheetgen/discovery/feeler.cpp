#include "sheetgen/discovery/feeler.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sheetgen/env/environment.hpp"

namespace sheetgen {

std::uint64_t ChainRng::seed_for(std::uint64_t seed, int chain) {
  std::uint64_t z = seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(chain + 1) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

FeelerPrior resolve_prior(const FeelerPrior& p, const SheetSpec& spec) {
  FeelerPrior r = p;
  const Manufacturing& m = spec.manufacturing;
  if (r.min_bend_angle < 0) r.min_bend_angle = m.min_bend_angle;
  if (r.max_bend_angle < 0) r.max_bend_angle = m.max_bend_angle;
  if (r.max_skew < 0) r.max_skew = m.max_skew;
  if (r.max_length < 0) r.max_length = m.max_tab_length;
  r.min_bend_angle = std::max(r.min_bend_angle, m.min_bend_angle);
  r.max_bend_angle = std::min(r.max_bend_angle, m.max_bend_angle);
  r.max_skew = std::min(r.max_skew, m.max_skew);
  r.max_length = std::min(r.max_length, m.max_tab_length);
  return r;
}

std::optional<TabParameters> sample_feeler_parameters(const FeelerPrior& prior, const SheetSpec& spec,
                                                      double edge_length, ChainRng& rng) {
  const double w = spec.manufacturing.min_tab_width;
  if (edge_length < w) return std::nullopt;
  TabParameters p;
  p.w = w;
  p.d = rng.uniform(0.0, edge_length - w);
  p.theta1 = rng.uniform(-prior.max_skew, prior.max_skew);
  p.theta2 = rng.uniform(-prior.max_skew, prior.max_skew);
  if (spec.manufacturing.flat_extensions && rng.uniform() < prior.flat_probability) {
    p.theta3 = 0.0;  // a flat extension: the feeler widens or lengthens its parent's plate
  } else {
    const double mag = rng.uniform(prior.min_bend_angle, prior.max_bend_angle);
    p.theta3 = rng.uniform() < 0.5 ? -mag : mag;
  }
  p.l = 0;
  return p;
}

namespace {

// Distance along the unit ray o + s d (s > 0) to the exit of the box.
double exit_distance(const BoundingBox& box, const Vec3& o, const Vec3& d) {
  double s = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (d[k] > 1e-12) s = std::min(s, (box.max[k] - o[k]) / d[k]);
    else if (d[k] < -1e-12) s = std::min(s, (box.min[k] - o[k]) / d[k]);
  }
  return std::max(0.0, s);
}

}  // namespace

CastResult cast_tab_length(const Part& part, const RealisedPart& realised, int tab, const Environment& env,
                           const SheetSpec& spec, const FeelerPrior& prior, int rays) {
  CastResult out;
  const TabParameters& p = part.tabs[tab].params;
  const RealisedTab& rt = realised.tabs[tab];
  const double t2 = std::tan(p.theta2), c2 = std::cos(p.theta2);
  const Vec3 dir = (t2 * rt.x_axis + rt.y_axis).normalized();
  const double c12 = std::cos(p.theta1 + p.theta2);
  const double h = c12 > 1e-9 ? p.w * c2 / (2 * c12) : 0.0;
  const double hs = h * std::sin(p.theta1);  // F1 is hs further from the root than M1, F0 hs closer
  BoundingBox bounds = env.problem().bounds();
  bounds.min -= Vec3::Constant(prior.bounds_margin);
  bounds.max += Vec3::Constant(prior.bounds_margin);
  // t/2 + clearance as validity demands, plus half a voxel for the field's error.
  const double required = spec.thickness / 2 + spec.clearance + 0.5 * env.voxel_size();
  const double s_max = prior.max_length / std::max(c2, 1e-6) + 1.0;
  double l = prior.max_length;
  rays = std::max(2, rays);
  std::optional<RivetPlane> middle_rivet, side_rivet;
  for (int r = 0; r < rays; ++r) {
    const double u = static_cast<double>(r) / (rays - 1);
    // inset the outer rays by 1 % of w so they do not graze the parent's corners
    const double x = p.w * (0.01 + 0.98 * u);
    const Vec3 o = rt.origin + x * rt.x_axis;
    double s = std::min(s_max, exit_distance(bounds, o, dir));
    bool hit_obstacle = false;
    if (auto hit = env.cast_ray(o, dir, s)) {
      const double cosi = std::abs(hit->normal.dot(dir));
      s = hit->distance - required / std::max(cosi, 0.3);
      hit_obstacle = true;
      if (hit->rivet_area >= 0) {
        RivetPlane plane;
        plane.rivet_area = hit->rivet_area;
        plane.point = hit->point;
        plane.normal = hit->normal.dot(dir) < 0 ? Vec3(hit->normal) : Vec3(-hit->normal);
        if (2 * r == rays - 1 || (rays % 2 == 0 && r == rays / 2)) middle_rivet = plane;
        else if (!side_rivet) side_rivet = plane;
      }
    }
    // Where along the far edge this ray's side line ends: y of the far-edge point above x.
    const double far_offset = (u - 0.5) * 2 * hs;
    const double limit = s * c2 - far_offset;
    if (limit < l) {
      l = limit;
      out.hit = hit_obstacle;
    }
  }
  out.length = std::max(0.0, l);
  out.rivet = middle_rivet ? middle_rivet : side_rivet;
  return out;
}

double flange_length(double theta3, const SheetSpec& spec) {
  const Manufacturing& m = spec.manufacturing;
  return std::max(m.min_flange, bend_setback(theta3, spec) + 2 * m.rivet_edge_distance + 1e-3);
}

int attach_flange(Part& part, int tab, const RivetPlane& plane, const SheetSpec& spec, int flange,
                  double preferred_theta3, bool other_solution) {
  const Manufacturing& m = spec.manufacturing;
  TabParameters& p = part.tabs[tab].params;
  // The tab's frame does not depend on its own (l, theta1): realise once,
  // and only the tabs it hangs from (the discovery's parts have many others).
  // The storage is the thread's, refilled by every call.
  p.l = std::max(p.l, 1e-3);
  thread_local RealisedPart rp;
  realise_path_into(part, tab, rp);
  const RealisedTab& rt = rp.tabs[tab];
  const Vec3& N = plane.normal;
  const double xn = rt.x_axis.dot(N), yn = rt.y_axis.dot(N);
  // Far edge direction cos(t1) x + sin(t1) y must be perpendicular to N.
  double t1 = std::atan2(-xn, yn);
  if (t1 > M_PI / 2) t1 -= M_PI;
  if (t1 < -M_PI / 2) t1 += M_PI;
  if (std::abs(t1) > m.max_skew || std::cos(t1 + p.theta2) < 0.2) return -1;
  // Far-edge midpoint M1 = P0 + (w/2 + l tan t2) x + l y at signed distance t/2 from the plane.
  const double t2 = std::tan(p.theta2);
  const double rate = N.dot(t2 * rt.x_axis + rt.y_axis);  // d(signed distance)/dl
  if (rate > -1e-6) return -1;
  const double base = N.dot(rt.origin + 0.5 * p.w * rt.x_axis - plane.point);
  const double l = (spec.thickness / 2 - base) / rate;
  if (!(l >= m.min_tab_length) || l > m.max_tab_length) return -1;
  p.theta1 = t1;
  p.l = l;
  realise_path_into(part, tab, rp);
  const RealisedTab& rk = rp.tabs[tab];
  const Vec3 f0 = rk.corners[2], f1 = rk.corners[3];
  const double far_len = (f1 - f0).norm();
  const Vec3 o = (f1 - f0).cross(rk.normal).normalized();
  // Flange direction v = cos(t3) o + sin(t3) n must lie in the plane: v . N = 0.
  const double a = std::atan2(-o.dot(N), rk.normal.dot(N));
  double sols[2] = {a, a > 0 ? a - M_PI : a + M_PI};
  bool ok[2];
  for (int k = 0; k < 2; ++k)
    ok[k] = std::abs(sols[k]) >= m.min_bend_angle - 1e-12 && std::abs(sols[k]) <= m.max_bend_angle + 1e-12;
  int first = 0;
  if (std::isnan(preferred_theta3)) first = std::abs(sols[0]) <= std::abs(sols[1]) ? 0 : 1;
  else first = std::abs(sols[0] - preferred_theta3) <= std::abs(sols[1] - preferred_theta3) ? 0 : 1;
  const int pick = other_solution ? 1 - first : first;
  if (!ok[pick]) return -1;
  const double t3 = sols[pick];
  TabParameters fp;
  fp.d = 0;
  fp.w = far_len;
  fp.l = flange_length(t3, spec);
  fp.theta3 = t3;
  if (flange >= 0) {
    Tab& f = part.tabs[flange];
    // keep a widened flange's extent where the far edge still holds it
    fp.l = std::max(fp.l, f.params.l);
    f.params = fp;
    f.rivet_area = plane.rivet_area;
    return flange;
  }
  return part.add_tab(tab, kFarEdge, fp, plane.rivet_area);
}

}  // namespace sheetgen
