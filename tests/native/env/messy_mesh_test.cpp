// Messy environment meshes from CAD (issue 9): flipped normals, non-manifold
// edges, self-intersections and duplicate faces. The clearance field is
// unsigned and per-triangle, so none of them needs a repair: the answers equal
// brute-force point-triangle distances.
#include <gtest/gtest.h>

#include <random>

#include "sheetgen/core/geometry.hpp"
#include "sheetgen/env/distance_field.hpp"
#include "sheetgen/env/environment.hpp"
#include "test_meshes.hpp"

namespace sheetgen {
namespace {

double brute(const TriangleMesh& m, const Vec3& p) {
  double d = 1e300;
  for (const auto& t : m.triangles) d = std::min(d, point_triangle_distance(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]));
  return d;
}

// Two planes crossing at 60 degrees, a fin sharing an edge with both (three
// faces on one edge: non-manifold), one face duplicated and every other face flipped.
TriangleMesh messy() {
  TriangleMesh m = testing::plane(Vec3::Zero(), Vec3::UnitZ(), 0.3, 6);
  const TriangleMesh tilted = testing::plane(Vec3(0.01, 0, 0), Vec3(std::sin(M_PI / 3), 0, std::cos(M_PI / 3)), 0.3, 6);
  const int base = static_cast<int>(m.vertices.size());
  m.vertices.insert(m.vertices.end(), tilted.vertices.begin(), tilted.vertices.end());
  for (const auto& t : tilted.triangles) m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  // The fin on the edge of triangle 0.
  const auto t0 = m.triangles[0];
  m.vertices.push_back(0.5 * (m.vertices[t0[0]] + m.vertices[t0[1]]) + Vec3(0, 0, 0.05));
  m.triangles.push_back({t0[0], t0[1], static_cast<int>(m.vertices.size()) - 1});
  m.triangles.push_back(m.triangles[5]);  // duplicate
  for (size_t f = 0; f < m.triangles.size(); f += 2) std::swap(m.triangles[f][1], m.triangles[f][2]);  // flipped
  return m;
}

TEST(MessyMesh, FieldMatchesBruteForceOnANonManifoldSelfIntersectingFlippedMesh) {
  const TriangleMesh m = messy();
  ASSERT_FALSE(m.is_closed());
  DistanceFieldOptions o;
  o.voxel_size = 1.6e-3;
  o.band_voxels = 5;
  DistanceField field(m, o);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  double worst = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p = testing::random_surface_point(m, rng) + u01(rng) * 0.95 * field.band_width() * testing::random_unit(rng);
    const double ref = brute(m, p);
    if (ref >= field.band_width()) continue;
    worst = std::max(worst, std::abs(field.distance(p) - ref));
  }
  EXPECT_LE(worst, 0.5 * o.voxel_size);
}

TEST(MessyMesh, FlippingEveryNormalChangesNothing) {
  Problem p;
  p.source = "<test>";
  TriangleMesh floor = testing::plane(Vec3::Zero(), Vec3::UnitZ(), 0.6, 12);
  TriangleMesh flipped = floor;
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  p.meshes.push_back({"floor", floor, "<inline>"});
  p.rivet_areas.push_back(RivetAreaSpec{"ra", 0, {0, 1}, 0.0025});
  Load l;
  l.name = "box";
  l.center = Vec3(0, 0, 0.2);
  l.size = Vec3(0.1, 0.1, 0.1);
  l.force = Vec3(0, 0, -10);
  p.loads.push_back(l);
  Problem q = p;
  q.meshes[0].mesh = flipped;
  const Environment a(p), b(q);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> r(-0.3, 0.3);
  for (int i = 0; i < 500; ++i) {
    const Vec3 x(r(rng), r(rng), 0.02 * r(rng));
    EXPECT_EQ(a.clearance(x), b.clearance(x));
  }
  const auto ha = a.cast_ray(Vec3(0.1, 0.1, 0.5), Vec3(0, 0, -1), 10), hb = b.cast_ray(Vec3(0.1, 0.1, 0.5), Vec3(0, 0, -1), 10);
  ASSERT_TRUE(ha && hb);
  EXPECT_DOUBLE_EQ(ha->distance, hb->distance);
}

}  // namespace
}  // namespace sheetgen
