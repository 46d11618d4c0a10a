#include "sheetgen/fem/plate_mesher.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>

#include "sheetgen/fem/delaunay_2d.hpp"
#include "sheetgen/fem/fem_error.hpp"

namespace sheetgen {
namespace {

// A polygon's plane: origin, in-plane axes ex, ey, normal ez = ex x ey
// (the right-hand normal of its vertex order).
struct PlaneFrame {
  Vec3 origin, ex, ey, ez;
  Vec2 to2d(const Vec3& p) const { return Vec2((p - origin).dot(ex), (p - origin).dot(ey)); }
  Vec3 to3d(const Vec2& q) const { return origin + q.x() * ex + q.y() * ey; }
};

std::string polygon_name(size_t k) { return "polygon " + std::to_string(k); }

PlaneFrame polygon_frame(const std::vector<Vec3>& poly, size_t k, double tol) {
  if (poly.size() < 3) throw FemError(polygon_name(k), "has fewer than 3 vertices");
  for (const Vec3& p : poly)
    if (!p.allFinite()) throw FemError(polygon_name(k), "has a non-finite vertex");
  Vec3 normal = Vec3::Zero();  // Newell's vector area
  size_t longest = 0;
  double longest_len = -1;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = poly[i];
    const Vec3& b = poly[(i + 1) % poly.size()];
    normal += a.cross(b);
    const double len = (b - a).norm();
    if (len > longest_len) {
      longest_len = len;
      longest = i;
    }
  }
  const double area = 0.5 * normal.norm();
  if (!(area > tol * longest_len)) throw FemError(polygon_name(k), "is degenerate (zero area)");
  PlaneFrame f;
  f.origin = poly[0];
  f.ez = normal.normalized();
  f.ex = (poly[(longest + 1) % poly.size()] - poly[longest]).normalized();
  f.ex = (f.ex - f.ex.dot(f.ez) * f.ez).normalized();
  f.ey = f.ez.cross(f.ex);
  const double plane_tol = std::max(tol, 1e-9 * longest_len);
  for (size_t i = 0; i < poly.size(); ++i) {
    if (std::abs((poly[i] - f.origin).dot(f.ez)) > 10 * plane_tol)
      throw FemError(polygon_name(k), "is not planar (vertex " + std::to_string(i) + " is off its plane)");
    const Vec2 a = f.to2d(poly[i]), b = f.to2d(poly[(i + 1) % poly.size()]),
               c = f.to2d(poly[(i + 2) % poly.size()]);
    const double cross = (b - a).x() * (c - b).y() - (b - a).y() * (c - b).x();
    if (cross < -plane_tol * longest_len)
      throw FemError(polygon_name(k), "is not convex (at vertex " + std::to_string((i + 1) % poly.size()) + ")");
  }
  return f;
}

// Signed distance of q from the edge line (a, b) of a counter-clockwise 2-D
// polygon: positive inside.
double inside_distance(const Vec2& a, const Vec2& b, const Vec2& q) {
  const Vec2 d = (b - a).normalized();
  return d.x() * (q - a).y() - d.y() * (q - a).x();
}

double min_inside_distance(const std::vector<Vec2>& poly2, const Vec2& q) {
  double m = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly2.size(); ++i) {
    const Vec2& a = poly2[i];
    const Vec2& b = poly2[(i + 1) % poly2.size()];
    if ((b - a).norm() > 0) m = std::min(m, inside_distance(a, b, q));
  }
  return m;
}

// Global node table with merging of points closer than tol.
class NodeTable {
 public:
  NodeTable(std::vector<Vec3>& nodes, double tol) : nodes_(nodes), tol_(tol) {}
  int insert(const Vec3& p) {
    const std::array<std::int64_t, 3> c = cell(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = map_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == map_.end()) continue;
          for (int i : it->second)
            if ((nodes_[i] - p).norm() <= tol_) return i;
        }
    nodes_.push_back(p);
    const int id = static_cast<int>(nodes_.size()) - 1;
    map_[key(c)].push_back(id);
    return id;
  }

 private:
  std::array<std::int64_t, 3> cell(const Vec3& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / tol_)), static_cast<std::int64_t>(std::floor(p.y() / tol_)),
            static_cast<std::int64_t>(std::floor(p.z() / tol_))};
  }
  static std::int64_t key(const std::array<std::int64_t, 3>& c) {
    return (c[0] * 73856093) ^ (c[1] * 19349663) ^ (c[2] * 83492791);
  }
  std::vector<Vec3>& nodes_;
  double tol_;
  std::unordered_map<std::int64_t, std::vector<int>> map_;
};

double polygon_min_width(const std::vector<Vec3>& poly) {
  // Width of a convex polygon = min over edges of the farthest vertex from that edge's line.
  double width = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = poly[i];
    const Vec3 d = poly[(i + 1) % poly.size()] - a;
    if (d.norm() <= 0) continue;
    double far = 0;
    for (const Vec3& p : poly) far = std::max(far, (p - a).cross(d).norm() / d.norm());
    width = std::min(width, far);
  }
  return width;
}

constexpr double kPi = 3.14159265358979323846;

// Target element size: h, except near fold ends, where it shrinks to h0 at
// the corner and grows by `grading` per unit distance from it. Distances are
// in 3-D, so the two polygons sharing an edge see the same field and sample
// the edge at the same points.
class SizeField {
 public:
  SizeField(double h, double h0, double grading, std::vector<Vec3> corners)
      : h_(h), h0_(h0), grading_(grading), corners_(std::move(corners)) {
    if (corners_.empty()) return;
    // Rings of points around a corner: each ring one local size (times the
    // height of an equilateral triangle) beyond the last, up to the first
    // ring where the size is h.
    for (double r = h0_; ; r += 0.87 * size_at_distance(r)) {
      ring_radii_.push_back(r);
      if (size_at_distance(r) >= h_) break;
    }
  }
  bool graded() const { return !corners_.empty(); }
  const std::vector<Vec3>& corners() const { return corners_; }
  const std::vector<double>& ring_radii() const { return ring_radii_; }
  // Beyond this distance from every corner the equilateral lattice of h fills the inside.
  double lattice_distance() const { return ring_radii_.empty() ? 0.0 : ring_radii_.back() + 0.6 * h_; }
  double size_at_distance(double d) const { return std::min(h_, h0_ + grading_ * d); }
  int nearest(const Vec3& x, double* distance = nullptr) const {
    int best = -1;
    double d2 = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < corners_.size(); ++i)
      if ((corners_[i] - x).squaredNorm() < d2) d2 = (corners_[i] - x).squaredNorm(), best = static_cast<int>(i);
    if (distance) *distance = std::sqrt(d2);
    return best;
  }
  double at(const Vec3& x) const {
    double d = std::numeric_limits<double>::infinity();
    nearest(x, &d);
    return size_at_distance(d);
  }

  // Points dividing the piece [P, Q] into elements: P first, Q left out.
  // Uniform (ceil(len / h) equal parts) where the field is h all along;
  // otherwise spaced so each part is one local size. Both the choice and the
  // spacing are computed from the lexicographically smaller end, so that the
  // two sides of a shared piece get the same points even at round-off.
  std::vector<Vec3> divide(const Vec3& P, const Vec3& Q) const {
    const double len = (Q - P).norm();
    const bool flip = std::lexicographical_compare(Q.data(), Q.data() + 3, P.data(), P.data() + 3);
    const Vec3& A = flip ? Q : P;
    const Vec3& B = flip ? P : Q;
    std::vector<Vec3> out;
    if (!graded() || segment_distance(A, B) >= (h_ - h0_) / grading_) {
      const int pieces = std::max(1, static_cast<int>(std::ceil(len / h_ - 1e-6)));
      for (int j = 0; j < pieces; ++j) out.push_back(P + (Q - P) * (static_cast<double>(j) / pieces));
      return out;
    }
    // Element count along [A, B] as a function of the parameter: the integral of 1 / size.
    std::vector<double> tau = {0.0}, count = {0.0};
    while (tau.back() < 1.0) {
      const double t0 = tau.back();
      const double step = std::min(1.0 - t0, at(A + t0 * (B - A)) / (8.0 * len));
      const double mid = at(A + (t0 + 0.5 * step) * (B - A));
      tau.push_back(t0 + step >= 1.0 - 1e-12 ? 1.0 : t0 + step);
      count.push_back(count.back() + step * len / mid);
    }
    const int pieces = std::max(1, static_cast<int>(std::ceil(count.back() - 1e-6)));
    std::vector<Vec3> inner;
    size_t i = 1;
    for (int j = 1; j < pieces; ++j) {
      const double target = count.back() * j / pieces;
      while (count[i] < target) ++i;
      const double w = (target - count[i - 1]) / (count[i] - count[i - 1]);
      inner.push_back(A + (tau[i - 1] + w * (tau[i] - tau[i - 1])) * (B - A));
    }
    if (flip) std::reverse(inner.begin(), inner.end());
    out.push_back(P);
    out.insert(out.end(), inner.begin(), inner.end());
    return out;
  }

 private:
  double segment_distance(const Vec3& P, const Vec3& Q) const {
    double d = std::numeric_limits<double>::infinity();
    const Vec3 e = Q - P;
    for (const Vec3& c : corners_) {
      const double t = e.squaredNorm() > 0 ? std::clamp((c - P).dot(e) / e.squaredNorm(), 0.0, 1.0) : 0.0;
      d = std::min(d, (P + t * e - c).norm());
    }
    return d;
  }
  double h_, h0_, grading_;
  std::vector<Vec3> corners_;
  std::vector<double> ring_radii_;
};

// Fold ends: a vertex of one polygon lying inside (not at an end of) an edge
// of another, within `merge`. Each is listed once.
std::vector<Vec3> find_fold_ends(const std::vector<std::vector<Vec3>>& snapped, double merge) {
  std::vector<Vec3> out;
  for (size_t k = 0; k < snapped.size(); ++k)
    for (size_t i = 0; i < snapped[k].size(); ++i) {
      const Vec3& a = snapped[k][i];
      const Vec3& b = snapped[k][(i + 1) % snapped[k].size()];
      const double len = (b - a).norm();
      if (len <= merge) continue;
      for (size_t j = 0; j < snapped.size(); ++j) {
        if (j == k) continue;
        for (const Vec3& q : snapped[j]) {
          const double t = (q - a).dot(b - a) / (len * len);
          if (t * len <= merge || (1 - t) * len <= merge || (a + t * (b - a) - q).norm() > merge) continue;
          bool known = false;
          for (const Vec3& o : out) known = known || (o - q).norm() <= merge;
          if (!known) out.push_back(q);
        }
      }
    }
  return out;
}


// Polygon vertices closer than `merge` are one point: each is replaced by the
// cluster's representative, the first such vertex in polygon order. Tab
// corners computed from bend angles and offsets miss their neighbour's corner
// by round-off (0.3, 0.4 and 2.4 um on the right-angle bay's gps_receiver
// part, up to 1.9 um on the other parts of out/: more than the node
// tolerance). Every edge therefore starts, ends and splits at a
// representative, never at its own copy, so both sides of a shared segment
// are split at bit-identical end points and get the same nodes. Dropping the
// near-duplicate on one side only (no sliver) but keeping each side's own end
// point left the fold between them cracked: its nodes 0.1-2.4 um apart,
// unmerged, and the part 5-15 % softer or stiffer at random element sizes
// (docs/fem.md "A large right-angle part").
std::vector<std::vector<Vec3>> snap_corners(const std::vector<std::vector<Vec3>>& polygons, double merge) {
  std::vector<Vec3> representatives;
  std::vector<std::vector<Vec3>> snapped(polygons.size());
  for (size_t k = 0; k < polygons.size(); ++k)
    for (const Vec3& v : polygons[k]) {
      const Vec3* rep = nullptr;
      for (const Vec3& r : representatives)
        if ((r - v).norm() <= merge) {
          rep = &r;
          break;
        }
      if (!rep) representatives.push_back(v);
      snapped[k].push_back(rep ? *rep : v);
    }
  return snapped;
}

// One polygon's points to triangulate, in the 2-D frame of its plane (m): the
// outline first, in order around the polygon, then the fixed points, the
// fold-end rings and the interior lattice.
struct PolygonPoints {
  std::vector<Vec2> points;     // #P, m
  std::vector<Vec3> outline3d;  // m, the outline points exactly as the neighbours compute them
  size_t n_fixed = 0;           // fixed (rivet) points, right after the outline
  size_t n_pinned = 0;          // points [0, n_pinned) are not smoothed: outline, fixed points, rings
  size_t n_outline() const { return outline3d.size(); }
};

// The outline of snapped polygon k: each edge split at every representative
// lying on it (within `merge`), each piece divided by the size field. A split
// at a neighbour's vertex uses that vertex exactly, which the neighbour's own
// edge starts or ends at, rather than its projection onto this edge; it may
// therefore lie up to `merge` off the edge's line, which the constrained
// triangulation takes as it is (an outline with a kink of that height).
// Boundary points closer than `merge` are one (snap_corners): a corner of a
// neighbouring tab a fraction of a micrometre from this tab's corner would
// otherwise make a sliver element that CalculiX cannot give a normal
// ("gen3dnor"), and that carries no mechanics at the scale of a sheet.
void add_outline(PolygonPoints& pp, const std::vector<std::vector<Vec3>>& snapped, size_t k, const PlaneFrame& f,
                 const SizeField& field, double merge) {
  const size_t nv = snapped[k].size();
  for (size_t i = 0; i < nv; ++i) {
    const Vec3& a = snapped[k][i];
    const Vec3& b = snapped[k][(i + 1) % nv];
    const double len = (b - a).norm();
    if (len <= merge) continue;  // repeated vertex (its neighbour edge starts at b)
    std::vector<std::pair<double, Vec3>> ts = {{0.0, a}, {1.0, b}};  // (parameter along a->b, split point)
    for (const auto& other : snapped)
      for (const Vec3& q : other) {
        const double t = (q - a).dot(b - a) / (len * len);
        if (t * len <= merge || (1 - t) * len <= merge) continue;
        if ((a + t * (b - a) - q).norm() <= merge) ts.emplace_back(t, q);
      }
    std::sort(ts.begin(), ts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<std::pair<double, Vec3>> uniq;
    for (const auto& t : ts)
      if (uniq.empty() || (t.first - uniq.back().first) * len > merge) uniq.push_back(t);
    // The end point b stays the last split (a neighbour's vertex within
    // `merge` of b was skipped above, so it cannot displace it).
    for (size_t s = 0; s + 1 < uniq.size(); ++s)
      for (const Vec3& p : field.divide(uniq[s].second, uniq[s + 1].second)) {
        pp.outline3d.push_back(p);
        pp.points.push_back(f.to2d(p));
      }
  }
}

// Fixed interior points (rivets) of polygon k, checked against its outline.
void add_fixed_points(PolygonPoints& pp, const std::vector<Vec3>& fixed, size_t k, const PlaneFrame& f,
                      const std::vector<Vec2>& poly2, double tol) {
  for (const Vec3& q : fixed) {
    if (!q.allFinite()) throw FemError(polygon_name(k), "fixed point is not finite");
    const Vec2 q2 = f.to2d(q);
    if (std::abs((q - f.origin).dot(f.ez)) > 1e3 * tol || min_inside_distance(poly2, q2) < -tol)
      throw FemError(polygon_name(k), "a fixed (rivet) point lies outside the polygon");
    pp.points.push_back(q2);
    ++pp.n_fixed;
  }
}

// Around each fold end near the polygon's plane: rings of points spaced by the
// local size, each kept at least half its size from the boundary, the fixed
// points and the ring points before it. A ring of 3-D radius r around a
// corner at distance delta from the plane is a circle of radius
// sqrt(r^2 - delta^2) about the corner's foot.
void add_fold_end_rings(PolygonPoints& pp, const PlaneFrame& f, const std::vector<Vec2>& poly2,
                        const SizeField& field) {
  const size_t first = pp.points.size();
  const size_t n_fixed_end = pp.n_outline() + pp.n_fixed;
  for (size_t c = 0; c < field.corners().size(); ++c) {
    const Vec3& corner = field.corners()[c];
    const double delta = std::abs((corner - f.origin).dot(f.ez));
    const Vec2 foot = f.to2d(corner);
    for (size_t ring = 0; ring < field.ring_radii().size(); ++ring) {
      const double r = field.ring_radii()[ring];
      if (r <= delta) continue;
      const double rho = std::sqrt(r * r - delta * delta);
      const int n = std::max(3, static_cast<int>(std::ceil(2 * kPi * rho / field.size_at_distance(r))));
      for (int j = 0; j < n; ++j) {
        const double angle = 2 * kPi * (j + 0.5 * (ring % 2)) / n;
        const Vec2 q = foot + rho * Vec2(std::cos(angle), std::sin(angle));
        double d = 0;
        if (field.nearest(f.to3d(q), &d) != static_cast<int>(c)) continue;  // another corner's rings cover it
        const double size = field.size_at_distance(d);
        if (min_inside_distance(poly2, q) < 0.5 * size) continue;
        bool crowded = false;
        for (size_t i = pp.n_outline(); i < n_fixed_end; ++i) crowded = crowded || (pp.points[i] - q).norm() < 0.5 * size;
        for (size_t i = first; i < pp.points.size(); ++i) crowded = crowded || (pp.points[i] - q).norm() < 0.5 * size;
        if (!crowded) pp.points.push_back(q);
      }
    }
  }
}

// Interior: an equilateral lattice of spacing h aligned with the longest edge
// (the frame's x axis), kept at least h/2 from the boundary and from the fixed
// points, and clear of the fold ends' rings.
void add_lattice(PolygonPoints& pp, const PlaneFrame& f, const std::vector<Vec2>& poly2, const SizeField& field,
                 double h) {
  Vec2 lo = poly2[0], hi = poly2[0];
  for (const Vec2& q : poly2) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const size_t n_fixed_end = pp.n_outline() + pp.n_fixed;
  const double dy = h * std::sqrt(3.0) / 2.0;
  const int rows = static_cast<int>(std::ceil((hi.y() - lo.y()) / dy)) + 1;
  const int cols = static_cast<int>(std::ceil((hi.x() - lo.x()) / h)) + 2;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const Vec2 q(lo.x() + (c + (r % 2 ? 0.5 : 0.0)) * h, lo.y() + r * dy);
      if (min_inside_distance(poly2, q) < 0.5 * h) continue;
      bool near_fixed = false;
      for (size_t i = pp.n_outline(); i < n_fixed_end; ++i) near_fixed = near_fixed || (pp.points[i] - q).norm() < 0.5 * h;
      if (near_fixed) continue;
      if (field.graded()) {
        double d = 0;
        field.nearest(f.to3d(q), &d);
        if (d < field.lattice_distance()) continue;
      }
      pp.points.push_back(q);
    }
}

// The constrained Delaunay triangulation of the points inside their outline
// (delaunay_2d.hpp: exact predicates, so no jitter of cocircular points and
// no sliver outside the outline to drop), then `passes` rounds of Laplacian
// smoothing of the lattice points, each re-triangulated; they even out the
// band next to the boundary.
std::vector<std::array<int, 3>> triangulate_smoothed(PolygonPoints& pp, int passes, size_t k) {
  std::vector<int> outline(pp.n_outline());
  std::iota(outline.begin(), outline.end(), 0);
  auto triangulate = [&]() {
    PolygonTriangulation t;
    try {
      t = triangulate_polygon(pp.points, outline);
    } catch (const FemError& e) {
      throw FemError(polygon_name(k), "triangulation: " + std::string(e.what()));
    }
    if (!t.unused_points.empty()) {
      const size_t i = t.unused_points.front();
      const bool fixed = i >= pp.n_outline() && i < pp.n_outline() + pp.n_fixed;
      throw FemError(polygon_name(k), fixed ? "a fixed (rivet) point lies outside the polygon"
                                            : "mesh point " + std::to_string(i) + " lies outside the outline");
    }
    return t.triangles;
  };
  std::vector<std::array<int, 3>> tris = triangulate();
  for (int pass = 0; pass < passes; ++pass) {
    std::vector<Vec2> sum(pp.points.size(), Vec2::Zero());
    std::vector<int> count(pp.points.size(), 0);
    for (const auto& t : tris)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          if (a != b) {
            sum[t[a]] += pp.points[t[b]];
            ++count[t[a]];
          }
    for (size_t i = pp.n_pinned; i < pp.points.size(); ++i)
      if (count[i] > 0) pp.points[i] = sum[i] / count[i];
    tris = triangulate();
  }
  return tris;
}

// Adds polygon k's nodes and triangles to `out`: outline points at their
// exact 3-D positions and the fixed points are merged with the other
// polygons' nodes by position; the rest are new.
void add_triangles(PlateMesh& out, NodeTable& table, const PolygonPoints& pp,
                   const std::vector<std::array<int, 3>>& tris, const PlaneFrame& f, size_t k, double h) {
  std::vector<int> node(pp.points.size());
  for (size_t i = 0; i < pp.points.size(); ++i)
    node[i] = table.insert(i < pp.n_outline() ? pp.outline3d[i] : f.to3d(pp.points[i]));
  for (size_t j = 0; j < pp.n_fixed; ++j) out.fixed_point_nodes[k].push_back(node[pp.n_outline() + j]);
  for (const auto& t : tris) {
    const Vec2 u = pp.points[t[1]] - pp.points[t[0]], v = pp.points[t[2]] - pp.points[t[0]];
    const double area2 = u.x() * v.y() - u.y() * v.x();
    // Exact predicates make every triangle counter-clockwise; one this flat
    // comes only from a polygon far too thin for h, and would make the
    // stiffness singular.
    if (area2 <= 1e-10 * h * h) {
      std::ostringstream s;
      s << "the triangulation produced a sliver (area " << 0.5 * area2 << " m^2); polygon too thin for h = " << h
        << " m?";
      throw FemError(polygon_name(k), s.str());
    }
    out.mesh.triangles.push_back({node[t[0]], node[t[1]], node[t[2]]});
    out.element_polygon.push_back(static_cast<int>(k));
  }
}

}  // namespace

double default_element_size(const std::vector<std::vector<Vec3>>& polygons, double thickness) {
  double width = std::numeric_limits<double>::infinity();
  for (const auto& poly : polygons) width = std::min(width, polygon_min_width(poly));
  const double h = width / 4.0;
  return std::clamp(h, 2.0 * thickness, 0.020);
}

PlateMesh mesh_plates(const std::vector<std::vector<Vec3>>& polygons, const std::vector<std::vector<Vec3>>& fixed_points,
                      const PlateMeshOptions& options) {
  if (polygons.empty()) throw FemError("polygons", "no polygon to mesh");
  if (!fixed_points.empty() && fixed_points.size() != polygons.size())
    throw FemError("fixed_points", "must be empty or hold one list per polygon");
  const double tol = options.tolerance;
  if (!(tol > 0)) throw FemError("options.tolerance", "must be > 0 m");
  PlateMesh out;
  out.element_size = options.element_size > 0 ? options.element_size
                                              : default_element_size(polygons, options.thickness);
  const double h = out.element_size;
  if (!std::isfinite(h) || !(h > 10 * tol)) throw FemError("options.element_size", "must be finite and > 10 tolerance");
  NodeTable table(out.mesh.vertices, tol);
  out.fixed_point_nodes.resize(polygons.size());

  // `merge` (snap_corners) is at least t/100 (16 um for 1.6 mm sheet), far
  // below any feature of a sheet part, so that it does not shrink under mesh
  // refinement below the round-off: at h/1000 alone, h = 2 mm left a 2.4 um
  // pair apart and made a sliver (a singular stiffness). A vertex closer than
  // `merge` to another polygon's edge splits it, for the same reason.
  const double merge = std::max({tol, 1e-3 * h, 1e-2 * options.thickness});
  const std::vector<std::vector<Vec3>> snapped = snap_corners(polygons, merge);

  double h0 = options.fold_end_element_size > 0 ? options.fold_end_element_size : 0.25 * options.thickness;
  h0 = std::max(h0, 20 * merge);
  const bool grade = options.grade_fold_ends && h0 < h && options.fold_end_grading > 0;
  if (grade) out.fold_ends = find_fold_ends(snapped, merge);
  const SizeField field(h, h0, options.fold_end_grading, out.fold_ends);

  for (size_t k = 0; k < polygons.size(); ++k) {
    const PlaneFrame f = polygon_frame(polygons[k], k, tol);
    std::vector<Vec2> poly2;
    for (const Vec3& p : polygons[k]) poly2.push_back(f.to2d(p));
    PolygonPoints pp;
    add_outline(pp, snapped, k, f, field, merge);
    if (!fixed_points.empty()) add_fixed_points(pp, fixed_points[k], k, f, poly2, tol);
    add_fold_end_rings(pp, f, poly2, field);
    pp.n_pinned = pp.points.size();
    add_lattice(pp, f, poly2, field, h);
    const std::vector<std::array<int, 3>> tris = triangulate_smoothed(pp, options.smoothing_passes, k);
    add_triangles(out, table, pp, tris, f, k, h);
  }
  return out;
}

std::vector<int> nodes_on_polygon(const TriangleMesh& mesh, const std::vector<Vec3>& polygon, double tolerance) {
  const PlaneFrame f = polygon_frame(polygon, 0, tolerance);
  std::vector<Vec2> poly2;
  for (const Vec3& p : polygon) poly2.push_back(f.to2d(p));
  std::vector<int> out;
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& p = mesh.vertices[i];
    if (std::abs((p - f.origin).dot(f.ez)) > tolerance) continue;
    if (min_inside_distance(poly2, f.to2d(p)) >= -tolerance) out.push_back(static_cast<int>(i));
  }
  return out;
}

std::vector<int> nodes_on_segment(const TriangleMesh& mesh, const Vec3& a, const Vec3& b, double tolerance) {
  std::vector<std::pair<double, int>> hits;
  const Vec3 d = b - a;
  const double len2 = d.squaredNorm();
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& p = mesh.vertices[i];
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    if ((a + t * d - p).norm() <= tolerance) hits.emplace_back(t, static_cast<int>(i));
  }
  std::sort(hits.begin(), hits.end());
  std::vector<int> out;
  for (const auto& hit : hits) out.push_back(hit.second);
  return out;
}

}  // namespace sheetgen
