#include "sheetgen/env/distance_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sheetgen/core/geometry.hpp"
#include "test_meshes.hpp"

namespace sheetgen {
namespace {

// Exact reference: distance to every triangle, keeping the closest point.
ClosestPoint brute_force(const TriangleMesh& m, const Vec3& p) {
  ClosestPoint best;
  best.distance = 1e300;
  for (int f = 0; f < static_cast<int>(m.triangles.size()); ++f) {
    const auto& t = m.triangles[f];
    Vec3 q = closest_point_on_triangle(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]);
    if ((q - p).norm() < best.distance) {
      best.distance = (q - p).norm();
      best.point = q;
      best.face = f;
    }
  }
  return best;
}

struct Errors {
  double max_distance_error = 0;  // m
  double max_angle_deg = 0;
  int samples = 0;
};

// Random points within the narrow band, the field against brute force.
Errors measure(const TriangleMesh& mesh, const DistanceFieldOptions& o, int samples, unsigned seed) {
  DistanceField field(mesh, o);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  Errors e;
  for (int i = 0; i < samples; ++i) {
    const Vec3 p = testing::random_surface_point(mesh, rng) + u01(rng) * field.band_width() * 0.95 * testing::random_unit(rng);
    const ClosestPoint ref = brute_force(mesh, p);
    if (ref.distance >= field.band_width()) continue;  // outside the band
    e.max_distance_error = std::max(e.max_distance_error, std::abs(field.distance(p) - ref.distance));
    if (ref.distance > 0.05 * o.voxel_size) {
      const Vec3 g = field.gradient(p), g_ref = (p - ref.point).normalized();
      const double c = std::clamp(g.dot(g_ref), -1.0, 1.0);
      e.max_angle_deg = std::max(e.max_angle_deg, std::acos(c) * 180.0 / M_PI);
    }
    ++e.samples;
  }
  return e;
}

TEST(DistanceField, ClosedMeshWithinHalfVoxelInBand) {
  DistanceFieldOptions o;
  o.voxel_size = 2e-3;
  o.band_voxels = 5;
  const TriangleMesh sphere = testing::icosphere(0.1, 3, Vec3(0.013, -0.021, 0.007));  // 1280 triangles
  const Errors e = measure(sphere, o, 4000, 1);
  EXPECT_GT(e.samples, 3000);
  EXPECT_LE(e.max_distance_error, 0.5 * o.voxel_size);
  EXPECT_LE(e.max_angle_deg, 5.0);
  RecordProperty("max_error_voxels", std::to_string(e.max_distance_error / o.voxel_size));
  std::printf("closed: %d samples, max error %.4f voxels, max gradient angle %.3f deg\n", e.samples,
              e.max_distance_error / o.voxel_size, e.max_angle_deg);
}

TEST(DistanceField, OpenTiltedPlaneWithinHalfVoxelInBand) {
  DistanceFieldOptions o;
  o.voxel_size = 1.6e-3;
  o.band_voxels = 4;
  // A plane at an awkward angle and offset, so voxel centres do not line up with it.
  const TriangleMesh p = testing::plane(Vec3(0.0123, 0.0456, -0.0078), Vec3(0.3, -0.5, 0.81), 0.2, 8);
  const Errors e = measure(p, o, 4000, 2);
  EXPECT_GT(e.samples, 3000);
  EXPECT_LE(e.max_distance_error, 0.5 * o.voxel_size);
  EXPECT_LE(e.max_angle_deg, 5.0);
  std::printf("open: %d samples, max error %.4f voxels, max gradient angle %.3f deg\n", e.samples,
              e.max_distance_error / o.voxel_size, e.max_angle_deg);
}

TEST(DistanceField, OutsideTheBandIsALowerBound) {
  DistanceFieldOptions o;
  o.voxel_size = 2e-3;
  o.band_voxels = 3;
  o.exact_fallback_triangles = 0;  // force the bound path
  const TriangleMesh sphere = testing::icosphere(0.05, 2);
  DistanceField field(sphere, o);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> r(-0.3, 0.3);
  int far = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p(r(rng), r(rng), r(rng));
    const double exact = brute_force(sphere, p).distance;
    if (exact < field.band_width()) continue;
    ++far;
    EXPECT_LE(field.distance(p), exact + 1e-12) << "not a lower bound at " << p.transpose();
    EXPECT_GE(field.distance(p), field.band_width() - 1e-12);
  }
  EXPECT_GT(far, 1000);
}

TEST(DistanceField, SmallMeshIsExactEverywhere) {
  DistanceFieldOptions o;
  o.voxel_size = 2e-3;
  o.band_voxels = 3;
  const TriangleMesh p = testing::plane(Vec3::Zero(), Vec3::UnitZ(), 0.1, 2);  // 8 triangles
  DistanceField field(p, o);
  // 1 m above the plane's centre and diagonally away from a corner: exact values.
  EXPECT_NEAR(field.distance(Vec3(0, 0, 1)), 1.0, 1e-12);
  EXPECT_NEAR(field.distance(Vec3(0.05 + 0.3, 0.05 + 0.4, 0)), 0.5, 1e-12);
}

TEST(DistanceField, EmptyMeshIsInfinitelyFar) {
  DistanceField field(TriangleMesh{}, DistanceFieldOptions{});
  EXPECT_TRUE(std::isinf(field.distance(Vec3::Zero())));
}

}  // namespace
}  // namespace sheetgen
