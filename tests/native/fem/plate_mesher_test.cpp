// Conformity and quality of the plate mesher, and the rivet layout rule.
#include "sheetgen/fem/plate_mesher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "sheetgen/core/geometry.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/rivet_layout.hpp"

namespace sheetgen {
namespace {

using Poly = std::vector<Vec3>;

// Undirected edge -> number of triangles using it, per polygon.
std::map<std::pair<int, int>, std::vector<int>> edge_use(const PlateMesh& pm) {
  std::map<std::pair<int, int>, std::vector<int>> use;
  for (size_t f = 0; f < pm.mesh.triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      int a = pm.mesh.triangles[f][k], b = pm.mesh.triangles[f][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      use[{a, b}].push_back(pm.element_polygon[f]);
    }
  return use;
}

bool on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  return (closest_point_on_segment(p, a, b) - p).norm() < 1e-9;
}

double min_angle_deg(const PlateMesh& pm) {
  double worst = 180;
  for (const auto& t : pm.mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec3 u = pm.mesh.vertices[t[(k + 1) % 3]] - pm.mesh.vertices[t[k]];
      const Vec3 v = pm.mesh.vertices[t[(k + 2) % 3]] - pm.mesh.vertices[t[k]];
      worst = std::min(worst, std::acos(u.normalized().dot(v.normalized())) * 180 / M_PI);
    }
  return worst;
}

TEST(PlateMesher, SingleRectangleIsAreaExactOrientedAndWellShaped) {
  const Poly rect = {Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.04, 0), Vec3(0, 0.04, 0)};
  PlateMeshOptions opt;
  opt.element_size = 0.005;
  const PlateMesh pm = mesh_plates({rect}, {}, opt);
  EXPECT_NEAR(pm.mesh.area(), 0.06 * 0.04, 1e-12);
  for (size_t f = 0; f < pm.mesh.triangles.size(); ++f) EXPECT_GT(pm.mesh.face_normal(f).z(), 0.99);
  for (const auto& [edge, polys] : edge_use(pm)) {
    const Vec3 a = pm.mesh.vertices[edge.first], b = pm.mesh.vertices[edge.second];
    if (polys.size() == 1) {  // a boundary edge lies on the rectangle's outline and is at most h long
      const Vec3 m = 0.5 * (a + b);
      EXPECT_TRUE(std::abs(m.x()) < 1e-12 || std::abs(m.x() - 0.06) < 1e-12 || std::abs(m.y()) < 1e-12 ||
                  std::abs(m.y() - 0.04) < 1e-12);
      EXPECT_LE((b - a).norm(), 0.005 + 1e-12);
    } else {
      EXPECT_EQ(polys.size(), 2u);
    }
  }
  const double angle = min_angle_deg(pm);
  std::printf("rectangle mesh: %zu triangles, min angle %.1f deg\n", pm.mesh.triangles.size(), angle);
  EXPECT_GT(angle, 25.0);  // near-equilateral: an equilateral lattice with a smoothed boundary band
}

// Parent 60 x 40 mm in z = 0; child root edge = the sub-segment x in [20, 45]
// of the parent's edge y = 40, bent 90 deg up to z = 30; a second child on
// the full parent edge x = 60, bent down.
Poly t_junction_parent() { return {Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.04, 0), Vec3(0, 0.04, 0)}; }
Poly t_junction_child() {
  return {Vec3(0.045, 0.04, 0), Vec3(0.02, 0.04, 0), Vec3(0.02, 0.04, 0.03), Vec3(0.045, 0.04, 0.03)};
}
Poly t_junction_child2() {
  return {Vec3(0.06, 0, 0), Vec3(0.06, 0.04, 0), Vec3(0.06, 0.04, -0.025), Vec3(0.06, 0.0, -0.025)};
}

TEST(PlateMesher, TJunctionSharesEveryNodeOfTheSharedSegment) {
  // Edge lengths are not multiples of h.
  const Poly parent = t_junction_parent(), child = t_junction_child(), child2 = t_junction_child2();
  PlateMeshOptions opt;
  opt.element_size = 0.0043;
  opt.grade_fold_ends = false;  // uniform pieces, counted below; graded: TJunctionIsGradedAtBothFoldEnds
  const PlateMesh pm = mesh_plates({parent, child, child2}, {}, opt);
  EXPECT_NEAR(pm.mesh.area(), 0.06 * 0.04 + 0.025 * 0.03 + 0.04 * 0.025, 1e-12);
  int shared_edges = 0;
  for (const auto& [edge, polys] : edge_use(pm)) {
    const Vec3 a = pm.mesh.vertices[edge.first], b = pm.mesh.vertices[edge.second];
    const bool on_root = on_segment(a, child[0], child[1]) && on_segment(b, child[0], child[1]);
    const bool on_root2 = on_segment(a, child2[0], child2[1]) && on_segment(b, child2[0], child2[1]);
    if (on_root || on_root2) {
      // Conforming: each piece of a shared segment is an edge of one triangle of each side.
      ASSERT_EQ(polys.size(), 2u);
      EXPECT_NE(polys[0], polys[1]);
      ++shared_edges;
    } else {
      EXPECT_LE(polys.size(), 2u);
      if (polys.size() == 2) {
        EXPECT_EQ(polys[0], polys[1]);
      }
    }
  }
  // 25 mm at h = 4.3 mm -> 6 pieces; 40 mm -> 10 pieces.
  EXPECT_EQ(shared_edges, 6 + 10);
  // No hanging node: every node on the parent's edge y = 40 is a vertex of a parent triangle.
  std::vector<char> in_parent(pm.mesh.vertices.size(), 0);
  for (size_t f = 0; f < pm.mesh.triangles.size(); ++f)
    if (pm.element_polygon[f] == 0)
      for (int v : pm.mesh.triangles[f]) in_parent[v] = 1;
  for (int v : nodes_on_segment(pm.mesh, parent[2], parent[3])) EXPECT_TRUE(in_parent[v]);
  // The split points (child corners) are nodes.
  EXPECT_EQ(nodes_on_segment(pm.mesh, child[0], child[0], 1e-9).size(), 1u);
  EXPECT_EQ(nodes_on_segment(pm.mesh, child[1], child[1], 1e-9).size(), 1u);
}

TEST(PlateMesher, TJunctionIsGradedAtBothFoldEnds) {
  // The same T-junction, graded (the default): both ends of the child's root
  // lie inside the parent's edge y = 40 and are found as fold ends; the full
  // fold over x = 60 has none. Next to each the shared pieces are about the
  // corner size h0 = t/4 = 0.4 mm and grow by about half their distance from
  // it; the mesh stays conforming, and no triangle is a sliver.
  const Poly parent = t_junction_parent(), child = t_junction_child(), child2 = t_junction_child2();
  PlateMeshOptions opt;
  opt.element_size = 0.0043;
  const PlateMesh pm = mesh_plates({parent, child, child2}, {}, opt);
  ASSERT_EQ(pm.fold_ends.size(), 2u);
  for (const Vec3& p : pm.fold_ends)
    EXPECT_TRUE((p - child[0]).norm() < 1e-12 || (p - child[1]).norm() < 1e-12);
  EXPECT_NEAR(pm.mesh.area(), 0.06 * 0.04 + 0.025 * 0.03 + 0.04 * 0.025, 1e-12);
  std::vector<double> root_pieces;
  for (const auto& [edge, polys] : edge_use(pm)) {
    ASSERT_LE(polys.size(), 2u);
    const Vec3 a = pm.mesh.vertices[edge.first], b = pm.mesh.vertices[edge.second];
    if (polys.size() == 2 && polys[0] != polys[1] && on_segment(a, child[0], child[1]) && on_segment(b, child[0], child[1])) {
      root_pieces.push_back((b - a).norm());
      // Size rule: h0 + grading * distance of the piece's nearer end, to within
      // the rounding of whole pieces (at most one piece's worth, a factor ~1.6).
      const double d = std::min({(a - child[0]).norm(), (a - child[1]).norm(), (b - child[0]).norm(), (b - child[1]).norm()});
      EXPECT_LT((b - a).norm(), 1.6 * std::min(0.0043, 0.4e-3 + 0.5 * d));
    }
  }
  ASSERT_FALSE(root_pieces.empty());
  const double smallest = *std::min_element(root_pieces.begin(), root_pieces.end());
  std::printf("graded T-junction: %zu triangles, %zu pieces on the 25 mm root (uniform: 6), smallest %.3f mm, min angle %.1f deg\n",
              pm.mesh.triangles.size(), root_pieces.size(), smallest * 1e3, min_angle_deg(pm));
  EXPECT_GT(smallest, 0.3e-3);
  EXPECT_LT(smallest, 0.6e-3);
  EXPECT_GT(min_angle_deg(pm), 20.0);
}

// A child whose root corner sits 0.4 um beside the parent's corner (round-off
// of the tab parameters, seen on a bay part): no sliver element. Before, the
// parent's edge was split 0.4 um from its corner and CalculiX refused the
// deck ("gen3dnor: size of estimated shell normal ... smaller than 1.e-10").
TEST(PlateMesher, CornerAHairBesideANeighbourMakesNoSliver) {
  const Poly parent = {Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.04, 0), Vec3(0, 0.04, 0)};
  const double hair = 4e-7;
  const Poly child = {Vec3(0.06, 0.04, 0), Vec3(hair, 0.04, 0), Vec3(hair, 0.04, 0.03), Vec3(0.06, 0.04, 0.03)};
  PlateMeshOptions opt;
  opt.element_size = 0.005;
  const PlateMesh pm = mesh_plates({parent, child}, {}, opt);
  double min_edge = 1e9, min_area = 1e9;
  for (const auto& t : pm.mesh.triangles) {
    const Vec3 a = pm.mesh.vertices[t[0]], b = pm.mesh.vertices[t[1]], c = pm.mesh.vertices[t[2]];
    min_edge = std::min({min_edge, (b - a).norm(), (c - b).norm(), (a - c).norm()});
    min_area = std::min(min_area, 0.5 * (b - a).cross(c - a).norm());
  }
  std::printf("hair corner: %zu triangles, shortest edge %.3g m, smallest area %.3g m^2\n", pm.mesh.triangles.size(),
              min_edge, min_area);
  // A fraction of h: the shortest edge comes from the mesher's own grading, not the hair.
  EXPECT_GT(min_edge, 0.1 * opt.element_size);
  EXPECT_GT(min_area, 1e-3 * opt.element_size * opt.element_size);
  // The child's corner is snapped onto the parent's (0.4 um away), which adds
  // at most hair x 30 mm / 2 = 6e-9 m^2 to the child.
  EXPECT_NEAR(pm.mesh.area(), 0.06 * 0.04 + (0.06 - hair) * 0.03, 0.5 * hair * 0.03 + 1e-12);
}

// Shared root edges count for conformity: pieces of the segment [a, b] that
// are an edge of a triangle of each of two different polygons, and pieces
// used by one polygon only (a crack when the other side has its own).
struct SharedSegment {
  int shared = 0, one_sided = 0;
};
SharedSegment shared_segment(const PlateMesh& pm, const Vec3& a, const Vec3& b, double tolerance) {
  SharedSegment s;
  for (const auto& [edge, polys] : edge_use(pm)) {
    const Vec3 p = pm.mesh.vertices[edge.first], q = pm.mesh.vertices[edge.second];
    if ((closest_point_on_segment(p, a, b) - p).norm() > tolerance ||
        (closest_point_on_segment(q, a, b) - q).norm() > tolerance)
      continue;
    if (polys.size() == 2 && polys[0] != polys[1]) ++s.shared;
    else ++s.one_sided;
  }
  return s;
}

// Tab corners computed from bend angles and offsets miss their neighbour's
// corner by round-off: on the right-angle bay's gps_receiver part by 0.2-0.4 um
// across the fold and up to 6 um along it. Both sides of the fold must still
// get the same nodes. Before, each side kept its own end point, the nodes in
// between were 0.1-6 um apart and stayed unmerged (the node tolerance is 0.1
// um): three of the part's folds were cracked, and its compliance jumped
// between 0.081 and 0.092 J with the element size (docs/fem.md).
TEST(PlateMesher, FoldWithCornersMicrometresApartIsConforming) {
  const Poly parent = {Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.04, 0), Vec3(0, 0.04, 0)};
  // (h, offset along the fold): 3 um at h = 5 mm; the part's 2.4 um at h = 2 mm,
  // where h / 1000 alone would keep the pair apart (a 2.4 um sliver, singular).
  for (const auto& [h, along] : {std::pair{0.005, 3e-6}, std::pair{0.002, 2.4e-6}}) {
    const double across = 3e-7;  // more than the 0.1 um node tolerance
    const Poly child = {Vec3(0.06 - along, 0.04 + across, 0), Vec3(along, 0.04 - across, 0),
                        Vec3(along, 0.04 - across, 0.03), Vec3(0.06 - along, 0.04 + across, 0.03)};
    PlateMeshOptions opt;
    opt.element_size = h;
    const PlateMesh pm = mesh_plates({parent, child}, {}, opt);
    const SharedSegment s = shared_segment(pm, parent[2], parent[3], 1e-5);
    std::printf("fold with corners %.3g um / %.3g um apart, h = %.3g mm: %d shared pieces, %d one-sided\n", along * 1e6,
                across * 1e6, h * 1e3, s.shared, s.one_sided);
    // 60 mm at h: 12 or 30 pieces, each an edge of a parent and of a child triangle.
    EXPECT_EQ(s.shared, static_cast<int>(std::lround(0.06 / h)));
    EXPECT_EQ(s.one_sided, 0);
    // No two nodes closer than 10 um (an unmerged pair is a crack or a sliver).
    for (size_t i = 0; i < pm.mesh.vertices.size(); ++i)
      for (size_t j = i + 1; j < pm.mesh.vertices.size(); ++j)
        ASSERT_GT((pm.mesh.vertices[i] - pm.mesh.vertices[j]).norm(), 1e-5) << "nodes " << i << ", " << j;
  }
}

TEST(PlateMesher, SkewedTrapezoidTabsStayConformingAndWellShaped) {
  // Grammar tabs are trapezoids with skew: a parent trapezoid and a skewed
  // child on the middle of its far edge, bent 60 deg; default element size.
  const Poly parent = {Vec3(0, 0, 0), Vec3(0.07, 0, 0), Vec3(0.06, 0.035, 0), Vec3(0.005, 0.035, 0)};
  const double c = std::cos(M_PI / 3), sn = std::sin(M_PI / 3);
  const Vec3 up(0, c, sn);  // child's in-plane direction away from the root
  const Vec3 r0(0.045, 0.035, 0), r1(0.02, 0.035, 0);
  const Poly child = {r0, r1, r1 + 0.03 * up + Vec3(0.008, 0, 0), r0 + 0.03 * up + Vec3(0.012, 0, 0)};
  const PlateMesh pm = mesh_plates({parent, child});
  EXPECT_NEAR(pm.element_size, default_element_size({parent, child}, 1.6e-3), 0);
  EXPECT_NEAR(pm.mesh.area(), polygon_area(parent) + polygon_area(child), 1e-12);
  int shared = 0;
  for (const auto& [edge, polys] : edge_use(pm)) {
    ASSERT_LE(polys.size(), 2u);
    if (polys.size() == 2 && polys[0] != polys[1]) {
      ++shared;
      EXPECT_TRUE(on_segment(pm.mesh.vertices[edge.first], r0, r1) && on_segment(pm.mesh.vertices[edge.second], r0, r1));
    }
  }
  // Graded at both ends of the root (docs/fem.md "Graded fold ends"): more
  // pieces than the uniform ceil(25 mm / h), every one shared.
  EXPECT_GT(shared, static_cast<int>(std::ceil(0.025 / pm.element_size - 1e-6)));
  EXPECT_EQ(pm.fold_ends.size(), 2u);
  const double angle = min_angle_deg(pm);
  std::printf("skewed tabs: %zu triangles, h = %.2f mm, min angle %.1f deg\n", pm.mesh.triangles.size(),
              pm.element_size * 1e3, angle);
  EXPECT_GT(angle, 20.0);
}

// What a valid conforming mesh of one polygon must satisfy: every triangle
// of positive area and oriented like the polygon; the polygon's edges
// covered exactly once by mesh edges, in `pieces[i]` pieces on edge i; the
// triangles a tiling of a disk (Euler: outline nodes - 2 + 2 x inner nodes).
void expect_valid_polygon_mesh(const PlateMesh& pm, int k, const Poly& poly, const std::vector<int>& pieces) {
  Vec3 normal = Vec3::Zero();
  for (size_t i = 0; i < poly.size(); ++i) normal += poly[i].cross(poly[(i + 1) % poly.size()]);
  normal.normalize();
  std::map<std::pair<int, int>, int> uses;  // undirected edge -> triangles of polygon k using it
  std::map<int, int> nodes;                 // node -> 1 on the outline, 0 inside
  int triangles = 0, bad = 0;
  double min_area = 1e30;
  for (size_t f = 0; f < pm.mesh.triangles.size(); ++f) {
    if (pm.element_polygon[f] != k) continue;
    ++triangles;
    const auto& t = pm.mesh.triangles[f];
    const Vec3 a = pm.mesh.vertices[t[0]], b = pm.mesh.vertices[t[1]], c = pm.mesh.vertices[t[2]];
    const double area = 0.5 * (b - a).cross(c - a).dot(normal);
    if (!(area > 0)) ++bad;
    min_area = std::min(min_area, area);
    for (int q = 0; q < 3; ++q) {
      ++uses[{std::min(t[q], t[(q + 1) % 3]), std::max(t[q], t[(q + 1) % 3])}];
      nodes[t[q]] = 0;
    }
  }
  EXPECT_EQ(bad, 0) << "polygon " << k << ": triangles of zero or negative area";
  std::vector<int> found(poly.size(), 0);
  std::vector<double> covered(poly.size(), 0.0);
  for (const auto& [edge, n] : uses) {
    if (n == 2) continue;
    ASSERT_EQ(n, 1) << "polygon " << k << ": an edge in more than two triangles";
    const Vec3 a = pm.mesh.vertices[edge.first], b = pm.mesh.vertices[edge.second];
    int on = -1;
    for (size_t i = 0; i < poly.size(); ++i)
      if (on_segment(a, poly[i], poly[(i + 1) % poly.size()]) && on_segment(b, poly[i], poly[(i + 1) % poly.size()]))
        on = static_cast<int>(i);
    ASSERT_GE(on, 0) << "polygon " << k << ": a boundary edge off the outline (a hole or a missing triangle)";
    ++found[on];
    covered[on] += (b - a).norm();
    nodes[edge.first] = nodes[edge.second] = 1;
  }
  for (size_t i = 0; i < poly.size(); ++i) {
    const double len = (poly[(i + 1) % poly.size()] - poly[i]).norm();
    EXPECT_EQ(found[i], pieces[i]) << "polygon " << k << " edge " << i;
    EXPECT_NEAR(covered[i], len, 1e-12 * len) << "polygon " << k << " edge " << i;
  }
  int outline = 0, inner = 0;
  for (const auto& [node, on] : nodes) (on ? outline : inner) += 1;
  EXPECT_EQ(triangles, outline - 2 + 2 * inner) << "polygon " << k;
  std::printf("  polygon %d: %d triangles, %d outline + %d inner nodes, smallest area %.3g m^2\n", k, triangles, outline,
              inner, min_area);
}

// Polygons given in a local frame (x, y in the plane, z out of it; m) placed
// in a skewed plane, so that every coordinate carries round-off and points
// computed on one edge are only nearly collinear.
Poly skewed(const Poly& local) {
  const Eigen::AngleAxisd turn(0.7, Vec3(1, 2, 3).normalized());
  Poly out;
  for (const Vec3& p : local) out.push_back(Vec3(0.1, -0.2, 0.3) + turn * p);
  return out;
}

// Outlines that are degenerate for floating-point predicates: many nearly
// collinear points on a long skewed edge with a T-junction on it, a sliver
// tab 0.1 mm wide, and a 120-gon whose vertices are nearly on one circle.
// The floating-point triangulation before CGAL's exact predicates covered
// the convex hull of each polygon's points and relied on a jitter of the
// points and on dropping slivers by height (docs/fem.md "Mesher"); the
// constrained triangulation must give each a valid conforming mesh as is.
TEST(PlateMesher, NearlyDegenerateOutlinesGiveValidConformingMeshes) {
  PlateMeshOptions opt;
  opt.grade_fold_ends = false;  // uniform pieces, counted below
  {
    // A 500 x 20 mm strip at h = 1 mm (500 nearly collinear outline points on
    // each long edge) with a 25 x 30 mm tab bent down from x in [150, 175] mm
    // of its edge y = 0, whose corners are computed apart from the strip's.
    const Poly strip = skewed({Vec3(0, 0, 0), Vec3(0.5, 0, 0), Vec3(0.5, 0.02, 0), Vec3(0, 0.02, 0)});
    const Poly tab = skewed({Vec3(0.175, 0, 0), Vec3(0.15, 0, 0), Vec3(0.15, 0, -0.03), Vec3(0.175, 0, -0.03)});
    opt.element_size = 1e-3;
    const PlateMesh pm = mesh_plates({strip, tab}, {}, opt);
    std::printf("strip with a T-junction, h = 1 mm:\n");
    expect_valid_polygon_mesh(pm, 0, strip, {500, 20, 500, 20});  // 150 + 25 + 325 pieces on edge 0
    expect_valid_polygon_mesh(pm, 1, tab, {25, 30, 25, 30});
    const SharedSegment s = shared_segment(pm, tab[0], tab[1], 1e-9);
    EXPECT_EQ(s.shared, 25);
    EXPECT_EQ(s.one_sided, 0);
    EXPECT_NEAR(pm.mesh.area(), 0.5 * 0.02 + 0.025 * 0.03, 1e-12 * (0.5 * 0.02 + 0.025 * 0.03));
  }
  {
    // A parallelogram 200 mm long and 0.1 mm wide (aspect 2000), at h = 5 mm:
    // 40 pieces on each long edge, 1 on each short one, no inner point, so
    // 82 - 2 = 80 triangles, each 0.1 mm high.
    const Poly sliver = skewed({Vec3(0, 0, 0), Vec3(0.2, 0, 0), Vec3(0.2003, 1e-4, 0), Vec3(3e-4, 1e-4, 0)});
    opt.element_size = 5e-3;
    const PlateMesh pm = mesh_plates({sliver}, {}, opt);
    std::printf("sliver 200 x 0.1 mm, h = 5 mm:\n");
    expect_valid_polygon_mesh(pm, 0, sliver, {40, 1, 40, 1});
    EXPECT_EQ(pm.mesh.triangles.size(), 80u);
    EXPECT_NEAR(pm.mesh.area(), 0.2 * 1e-4, 1e-12 * 0.2 * 1e-4);
  }
  {
    // A regular 120-gon of radius 40 mm at h = 4 mm: its edges (2.09 mm) are
    // one piece each; area (n/2) R^2 sin(2 pi / n).
    Poly local;
    for (int i = 0; i < 120; ++i) local.emplace_back(0.04 * std::cos(2 * M_PI * i / 120), 0.04 * std::sin(2 * M_PI * i / 120), 0);
    const Poly disc = skewed(local);
    opt.element_size = 4e-3;
    const PlateMesh pm = mesh_plates({disc}, {}, opt);
    std::printf("120-gon, R = 40 mm, h = 4 mm:\n");
    expect_valid_polygon_mesh(pm, 0, disc, std::vector<int>(120, 1));
    const double area = 60 * 0.04 * 0.04 * std::sin(2 * M_PI / 120);
    EXPECT_NEAR(pm.mesh.area(), area, 1e-12 * area);
  }
}

TEST(PlateMesher, DefaultElementSizeRule) {
  // Narrowest width 24 mm -> 6 mm; a 4 mm wide strip clamps to 2 t = 3.2 mm; a 1 m plate to 20 mm.
  const Poly a = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.024, 0), Vec3(0, 0.024, 0)};
  EXPECT_NEAR(default_element_size({a}, 1.6e-3), 0.006, 1e-15);
  const Poly b = {Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.004, 0), Vec3(0, 0.004, 0)};
  EXPECT_NEAR(default_element_size({a, b}, 1.6e-3), 0.0032, 1e-15);
  const Poly c = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  EXPECT_NEAR(default_element_size({c}, 1.6e-3), 0.020, 1e-15);
}

TEST(PlateMesher, RejectsNonConvexAndNonPlanar) {
  const Poly dart = {Vec3(0, 0, 0), Vec3(0.04, 0, 0), Vec3(0.01, 0.01, 0), Vec3(0, 0.04, 0)};
  EXPECT_THROW(mesh_plates({dart}), FemError);
  const Poly warped = {Vec3(0, 0, 0), Vec3(0.04, 0, 0), Vec3(0.04, 0.04, 0.005), Vec3(0, 0.04, 0)};
  EXPECT_THROW(mesh_plates({warped}), FemError);
}

TEST(RivetLayout, DefaultsForSixteenHundredthsSheet) {
  // t = 1.6 mm: d = 2 t = 3.2 mm rounded up to 1/32 in = 5/32 in = 3.96875 mm;
  // edge distance 2 d = 7.9375 mm; pitch 6 d = 23.8125 mm. A 60 mm far edge
  // leaves 60 - 2 e = 44.125 mm -> 2 rivets, 23.8125 mm apart, centred.
  const Poly flange = {Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.02, 0), Vec3(0, 0.02, 0)};
  const RivetLayout r = layout_rivets(flange, 2);  // far edge: (0.06, 0.02) -> (0, 0.02)
  EXPECT_NEAR(r.diameter, 5.0 / 32.0 * 0.0254, 1e-12);
  EXPECT_NEAR(r.edge_distance, 2 * r.diameter, 1e-12);
  EXPECT_NEAR(r.pitch, 6 * r.diameter, 1e-12);
  ASSERT_EQ(r.points.size(), 2u);
  for (const Vec3& p : r.points) EXPECT_NEAR(p.y(), 0.02 - r.edge_distance, 1e-12);
  EXPECT_NEAR(std::abs(r.points[0].x() - r.points[1].x()), r.pitch, 1e-12);
  EXPECT_NEAR(0.5 * (r.points[0].x() + r.points[1].x()), 0.03, 1e-12);
  // Footprints: the centre and a ring of 6 points at radius d.
  ASSERT_EQ(r.footprints.size(), 2u);
  EXPECT_EQ(r.footprints[0].size(), 7u);
  for (size_t k = 1; k < 7; ++k) EXPECT_NEAR((r.footprints[1][k] - r.points[1]).norm(), r.diameter, 1e-12);
  EXPECT_EQ(r.all_points().size(), 14u);
  // As fixed points they become mesh nodes.
  const PlateMesh pm = mesh_plates({flange}, {r.points});
  ASSERT_EQ(pm.fixed_point_nodes[0].size(), 2u);
  for (int i = 0; i < 2; ++i) EXPECT_LT((pm.mesh.vertices[pm.fixed_point_nodes[0][i]] - r.points[i]).norm(), 1e-12);
  // A flange narrower than two edge distances holds no rivet.
  const Poly thin = {Vec3(0, 0, 0), Vec3(0.01, 0, 0), Vec3(0.01, 0.02, 0), Vec3(0, 0.02, 0)};
  EXPECT_THROW(layout_rivets(thin, 2), FemError);
}

TEST(RivetLayout, BendZonesKeepTheRowOnFlatSheet) {
  // The flange of DefaultsForSixteenHundredthsSheet (60 x 20 mm, row at
  // y = 20 - e = 12.0625 mm, x in [e, 60 - e] = [7.9375, 52.0625] mm).
  const Poly flange = {Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.02, 0), Vec3(0, 0.02, 0)};
  auto rect = [](double x0, double x1, double y0, double y1) {
    return Poly{Vec3(x0, y0, 0), Vec3(x1, y0, 0), Vec3(x1, y1, 0), Vec3(x0, y1, 0)};
  };
  // A gusset's zone on side edge 1 along its whole length, 8 mm deep: the row
  // keeps e from it, x in [7.9375, 44.0625] mm (36.125: 2 rivets), centred at 26 mm.
  const RivetLayout whole = layout_rivets(flange, 2, {}, {rect(0.052, 0.06, -0.001, 0.021)});
  ASSERT_EQ(whole.points.size(), 2u);
  EXPECT_NEAR(0.5 * (whole.points[0].x() + whole.points[1].x()), 26e-3, 1e-9);
  // The same zone ending 4 mm above the root, y in [-1, 4] mm: 8.0625 mm from
  // the row, more than e. Nothing moves.
  const RivetLayout low = layout_rivets(flange, 2, {}, {rect(0.052, 0.06, -0.001, 0.004)});
  ASSERT_EQ(low.points.size(), 2u);
  EXPECT_NEAR(0.5 * (low.points[0].x() + low.points[1].x()), 30e-3, 1e-9);
  // A zone across the middle, x in [26, 34] mm: the row breaks into
  // [7.9375, 18.0625] and [41.9375, 52.0625], one rivet centred in each, at 13 and 47 mm.
  const RivetLayout split = layout_rivets(flange, 2, {}, {rect(0.026, 0.034, 0.0, 0.02)});
  ASSERT_EQ(split.points.size(), 2u);
  // (in the row's direction, along the far edge from (60, 20) to (0, 20))
  EXPECT_NEAR(split.points[0].x(), 47e-3, 1e-9);
  EXPECT_NEAR(split.points[1].x(), 13e-3, 1e-9);
  // The root's bend zone as deep as the row is close: SB = 7.2 mm (90 deg at
  // R = 6.4 mm) leaves 12.0625 - 7.2 = 4.86 mm < e: no flat sheet for a rivet.
  EXPECT_THROW(layout_rivets(flange, 2, {}, {rect(-0.01, 0.07, 0.0, 7.2e-3)}), FemError);
  EXPECT_EQ(layout_rivets(flange, 2, {}, {rect(-0.01, 0.07, 0.0, 4e-3)}).points.size(), 2u);
}

}  // namespace
}  // namespace sheetgen
