// convex_polygon_closest against dense sampling: the distance it reports is
// attained at the point it reports, and no sample of the first polygon comes
// nearer to the second.
#include "sheetgen/core/polygon_geometry.hpp"

#include <gtest/gtest.h>

#include <random>

#include "sheetgen/core/geometry.hpp"

namespace sheetgen {
namespace {

Vec3 unit_normal(const std::vector<Vec3>& p) {
  return (p[1] - p[0]).cross(p[2] - p[0]).normalized();
}

// Distance from q to a triangle; for a degenerate one, to its three edges.
double to_triangle(const Vec3& q, const std::vector<Vec3>& t) { return point_triangle_distance(q, t[0], t[1], t[2]); }

TEST(PolygonGeometry, ClosestPairAgreesWithDenseSampling) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  const int n = 40;
  int touching = 0;
  for (int k = 0; k < 300; ++k) {
    const Vec3 c(u(rng), u(rng), u(rng)), a = 0.6 * Vec3(u(rng), u(rng), u(rng));
    const Vec3 b = a.cross(Vec3(u(rng), u(rng), u(rng))).normalized() * 0.5 * std::abs(u(rng));
    const std::vector<Vec3> quad = {c - a - b, c + a - b, c + a + b, c - a + b};
    std::vector<Vec3> tri = {Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng)), Vec3(u(rng), u(rng), u(rng))};
    Vec3 tn = unit_normal(tri);
    if (k % 5 == 0) {  // a degenerate triangle: its third corner on its first edge
      tri[2] = tri[0] + 0.3 * (tri[1] - tri[0]);
      tn = Vec3::Zero();
    }
    const PolygonPair pair = convex_polygon_closest(quad, unit_normal(quad), tri, tn);
    // The point lies on the quad, and the triangle is that far from it.
    EXPECT_NEAR(point_convex_polygon_distance(pair.on_a, quad, unit_normal(quad)), 0.0, 1e-12) << k;
    EXPECT_NEAR(to_triangle(pair.on_a, tri), pair.distance, 1e-12) << k;
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double s = static_cast<double>(i) / n, t = static_cast<double>(j) / n;
        sampled = std::min(sampled, to_triangle((1 - t) * ((1 - s) * quad[0] + s * quad[1]) + t * ((1 - s) * quad[3] + s * quad[2]), tri));
      }
    const double gap = 0.5 * std::sqrt((2 * a / n).squaredNorm() + (2 * b / n).squaredNorm());
    EXPECT_GE(sampled, pair.distance - 1e-12) << k;
    EXPECT_LE(sampled, pair.distance + gap + 1e-12) << k;
    touching += pair.distance == 0.0;
    EXPECT_DOUBLE_EQ(convex_polygon_distance(quad, unit_normal(quad), tri, tn), pair.distance);
  }
  std::printf("closest pairs: %d of 300 touching or crossing\n", touching);
  EXPECT_GT(touching, 10);
  EXPECT_LT(touching, 200);
}

}  // namespace
}  // namespace sheetgen
