#include "sheetgen/env/ray_caster.hpp"

#include <gtest/gtest.h>

#include <random>

#include <tbb/global_control.h>

#include "sheetgen/core/geometry.hpp"
#include "test_meshes.hpp"

namespace sheetgen {
namespace {

TEST(RayCaster, FirstHitMatchesBruteForceOnRandomRays) {
  const TriangleMesh sphere = testing::icosphere(0.1, 3, Vec3(0.02, 0, 0));
  const TriangleMesh wall = testing::plane(Vec3(0.3, 0.05, 0), Vec3(1, 0.2, 0.1), 0.5, 6);
  RayCaster rays({&sphere, &wall});
  const TriangleMesh* meshes[2] = {&sphere, &wall};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> r(-0.4, 0.4);
  int hits = 0, misses = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 o(r(rng), r(rng), r(rng));
    const Vec3 d = testing::random_unit(rng);
    double best = 1e300;
    int best_geom = -1, best_face = -1;
    for (int g = 0; g < 2; ++g)
      for (int f = 0; f < static_cast<int>(meshes[g]->triangles.size()); ++f) {
        const auto& t = meshes[g]->triangles[f];
        auto s = ray_triangle_intersect(o, d, meshes[g]->vertices[t[0]], meshes[g]->vertices[t[1]], meshes[g]->vertices[t[2]]);
        if (s && *s <= 10.0 && *s < best) { best = *s; best_geom = g; best_face = f; }
      }
    auto hit = rays.first_hit(o, d, 10.0);
    if (best_geom < 0) {
      EXPECT_FALSE(hit.has_value());
      ++misses;
      continue;
    }
    ASSERT_TRUE(hit.has_value()) << "missed a hit at " << best;
    ++hits;
    // Single-precision traversal: a ray grazing a shared edge may report the
    // neighbour face; the distance must agree regardless.
    EXPECT_NEAR(hit->distance, best, 1e-6);
    EXPECT_EQ(hit->geometry, best_geom);
    if (hit->face != best_face) {
      const auto& t = meshes[best_geom]->triangles[hit->face];
      auto s = ray_triangle_intersect(o, d, meshes[best_geom]->vertices[t[0]], meshes[best_geom]->vertices[t[1]],
                                      meshes[best_geom]->vertices[t[2]], -1e-6);
      EXPECT_TRUE(s.has_value() && std::abs(*s - best) < 1e-6) << "reported a face the ray does not meet";
    }
  }
  EXPECT_GT(hits, 300);
  EXPECT_GT(misses, 200);
}

// Embree built on TBB turns a device's "threads=N" into a process-wide
// tbb::global_control: with N = 1 every parallel loop of sheetgen (the chains,
// the composition) ran on one thread while an Environment lived.
TEST(RayCaster, LeavesTheProcessThreadLimitAlone) {
  const auto limit = [] { return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism); };
  const size_t before = limit();
  const TriangleMesh sphere = testing::icosphere(0.1, 2);
  RayCaster rays({&sphere});
  EXPECT_EQ(limit(), before);
  ASSERT_TRUE(rays.first_hit(Vec3(0, 0, -1), Vec3(0, 0, 1), 10.0).has_value());
}

TEST(RayCaster, ClosestPointMatchesBruteForce) {
  const TriangleMesh sphere = testing::icosphere(0.1, 2);
  RayCaster rays({&sphere});
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> r(-0.3, 0.3);
  for (int i = 0; i < 500; ++i) {
    const Vec3 p(r(rng), r(rng), r(rng));
    double best = 1e300;
    for (const auto& t : sphere.triangles)
      best = std::min(best, point_triangle_distance(p, sphere.vertices[t[0]], sphere.vertices[t[1]], sphere.vertices[t[2]]));
    EXPECT_NEAR(rays.closest_point(p).distance, best, 1e-9);
  }
}

TEST(RayCaster, RespectsMaximumDistance) {
  const TriangleMesh wall = testing::plane(Vec3(1, 0, 0), Vec3(1, 0, 0), 1.0, 1);
  RayCaster rays({&wall});
  EXPECT_FALSE(rays.first_hit(Vec3::Zero(), Vec3::UnitX(), 0.99).has_value());
  auto hit = rays.first_hit(Vec3::Zero(), Vec3(2, 0, 0), 1.01);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(hit->distance, 1.0, 1e-12);
}

}  // namespace
}  // namespace sheetgen
