// The exact tab clearance (docs/environment.md "Exact tab clearance"): the box
// tree finds what brute force finds, and a tab's measured clearance agrees
// with dense point sampling of the tab against every triangle, which shares no
// code with it but core's point-triangle distance.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "sheetgen/core/geometry.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/env/triangle_bvh.hpp"
#include "test_meshes.hpp"

namespace sheetgen {
namespace {

bool boxes_meet(const BoundingBox& a, const BoundingBox& b) {
  return (a.min.array() <= b.max.array()).all() && (b.min.array() <= a.max.array()).all();
}

TEST(TriangleBvh, BoxQueryFindsWhatBruteForceFinds) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::array<Vec3, 3>> tris;
  const TriangleMesh sphere = testing::icosphere(0.5, 3);
  for (const auto& t : sphere.triangles) tris.push_back({sphere.vertices[t[0]], sphere.vertices[t[1]], sphere.vertices[t[2]]});
  for (int k = 0; k < 500; ++k) {
    const Vec3 c(u(rng), u(rng), u(rng));
    tris.push_back({c, c + 0.1 * Vec3(u(rng), u(rng), u(rng)), c + 0.1 * Vec3(u(rng), u(rng), u(rng))});
  }
  const TriangleBvh bvh(tris);
  ASSERT_EQ(bvh.size(), 1280 + 500);
  long long found = 0;
  for (int q = 0; q < 300; ++q) {
    BoundingBox box;
    box.extend(Vec3(u(rng), u(rng), u(rng)));
    box.extend(box.min + 0.3 * Vec3(u(rng), u(rng), u(rng)).cwiseAbs());
    std::vector<int> want;
    for (int i = 0; i < bvh.size(); ++i) {
      BoundingBox tb;
      for (const Vec3& p : tris[i]) tb.extend(p);
      if (boxes_meet(tb, box)) want.push_back(i);
    }
    std::vector<int> got;
    ASSERT_TRUE(bvh.overlapping(box, got, bvh.size()));
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, want) << q;
    found += static_cast<long long>(got.size());
    if (want.size() >= 2) {
      std::vector<int> capped;
      EXPECT_FALSE(bvh.overlapping(box, capped, static_cast<int>(want.size()) - 1));
    }
  }
  EXPECT_GT(found, 300);  // the queries were not all empty (643 with this seed)
}

// Floor (rivet area in the middle), a closed sphere standing on it, a rotated box load.
Problem scene() {
  Problem p;
  p.source = "<test>";
  p.meshes.push_back({"floor", testing::plane(Vec3::Zero(), Vec3::UnitZ(), 0.6, 12), "<inline>"});
  p.meshes.push_back({"sphere", testing::icosphere(0.08, 2, Vec3(-0.15, 0.1, 0.1)), "<inline>"});
  p.rivet_areas.push_back({"centre", 0, testing::plane_cell_block(12, 4, 8)});
  Load l;
  l.name = "box";
  l.center = Vec3(0.15, 0.1, 0.15);
  l.size = Vec3(0.12, 0.08, 0.1);
  l.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
  l.force = Vec3(0, 0, -100);
  p.loads.push_back(l);
  return p;
}

// A random rectangle (a tab) near the scene's geometry.
std::vector<Vec3> random_tab(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1), size(0.005, 0.08);
  const Vec3 c(0.25 * u(rng), 0.25 * u(rng), 0.12 + 0.12 * u(rng));
  const Eigen::Matrix3d r = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  const Vec3 a = size(rng) * r.col(0), b = size(rng) * r.col(1);
  return {c - a - b, c + a - b, c + a + b, c - a + b};
}

// Smallest distance from points on the tab (an n x n grid) to every obstacle
// not allowed: triangle by triangle, and the load box by its signed distance.
double sampled_clearance(const Problem& p, const std::vector<Vec3>& tab, const AllowedContacts& allowed, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double s = static_cast<double>(i) / n, t = static_cast<double>(j) / n;
      const Vec3 q = (1 - t) * ((1 - s) * tab[0] + s * tab[1]) + t * ((1 - s) * tab[3] + s * tab[2]);
      for (size_t m = 0; m < p.meshes.size(); ++m) {
        const TriangleMesh& mesh = p.meshes[m].mesh;
        for (int f = 0; f < static_cast<int>(mesh.triangles.size()); ++f) {
          const bool in_ra = m == 0 && std::find(p.rivet_areas[0].faces.begin(), p.rivet_areas[0].faces.end(), f) !=
                                           p.rivet_areas[0].faces.end();
          if (in_ra && !allowed.rivet_areas.empty()) continue;
          const auto& tr = mesh.triangles[f];
          best = std::min(best, point_triangle_distance(q, mesh.vertices[tr[0]], mesh.vertices[tr[1]], mesh.vertices[tr[2]]));
        }
      }
      if (allowed.loads.empty()) best = std::min(best, p.loads[0].signed_distance(q));
    }
  return best;
}

double max_gap(const std::vector<Vec3>& tab, int n) {  // half the diagonal of a grid cell: no point is farther from a sample
  return 0.5 * std::max((tab[1] - tab[0]).norm(), (tab[3] - tab[0]).norm()) / n * std::sqrt(2.0);
}

TEST(ExactContact, AgreesWithDenseSamplingOfTheTab) {
  const Problem p = scene();
  Environment env(p);
  std::mt19937 rng(11);
  const double required = 0.01;
  const int n = 24;
  int clear = 0, blocked = 0;
  for (int k = 0; k < 400; ++k) {
    const std::vector<Vec3> tab = random_tab(rng);
    AllowedContacts allowed;
    if (k % 3 == 1) allowed.rivet_areas = {0};
    if (k % 3 == 2) allowed.loads = {0};
    const ContactResult r = env.polygon_contact(tab, required, allowed);
    ASSERT_TRUE(r.exact) << k;
    const double reference = sampled_clearance(p, tab, allowed, n);
    if (r.clear) {
      ++clear;
      // Every sample is a point of the tab: none may come nearer than the exact clearance.
      EXPECT_GE(reference, required - 1e-12) << k;
      EXPECT_LE(r.min_clearance, reference + 1e-12) << k;
    } else {
      ++blocked;
      // The reported distance is attained at worst_point; the samples come within a grid cell of it.
      EXPECT_LT(r.min_clearance, required) << k;
      EXPECT_LE(reference, std::max(r.min_clearance, 0.0) + max_gap(tab, n) + 1e-12) << k;
    }
  }
  std::printf("exact contact: %d clear, %d blocked of 400 random tabs\n", clear, blocked);
  EXPECT_GT(clear, 60);
  EXPECT_GT(blocked, 60);
}

TEST(ExactContact, FindsATabInsideTheLoadBoxAndTheWorstPointOnTheTab) {
  const Problem p = scene();
  Environment env(p);
  const Load& l = p.loads[0];
  const Eigen::Matrix3d r = l.rotation.toRotationMatrix();
  const Vec3 a = 0.02 * r.col(0), b = 0.02 * r.col(1);
  const std::vector<Vec3> inside = {l.center - a - b, l.center + a - b, l.center + a + b, l.center - a + b};
  const ContactResult in = env.polygon_contact(inside, 0.001, AllowedContacts{});
  EXPECT_TRUE(in.exact);
  EXPECT_FALSE(in.clear);
  EXPECT_LT(in.min_clearance, 0.0);
  EXPECT_TRUE(env.polygon_contact(inside, 0.001, AllowedContacts{{}, {0}}).clear);
  // A tab hanging 1 cm past the rivet area's edge (x = 0.1) with its own area allowed: the worst point is past the edge.
  const double z = 0.001;
  const std::vector<Vec3> hanging = {Vec3(0.05, -0.03, z), Vec3(0.11, -0.03, z), Vec3(0.11, 0.03, z), Vec3(0.05, 0.03, z)};
  const ContactResult h = env.polygon_contact(hanging, 0.002, AllowedContacts{{0}, {}});
  EXPECT_TRUE(h.exact);
  EXPECT_FALSE(h.clear);
  EXPECT_GE(h.worst_point.x(), 0.1 - 0.002 - 1e-12);
  EXPECT_NEAR(h.worst_point.z(), z, 1e-12);
}

// The sampled fallback (too many triangles near a tab) answers the same where
// the clearance is not within a voxel of the requirement.
TEST(ExactContact, SampledFallbackAgreesAwayFromTheThreshold) {
  const Problem p = scene();
  EnvironmentOptions sampled_only;
  sampled_only.exact_contact_max_triangles = 0;
  Environment exact(p), sampled(p, sampled_only);
  std::mt19937 rng(5);
  // The requirement the part checks use: the fields' narrow band is sized for it.
  const double required = 0.5 * p.material.thickness + p.requirements.clearance, voxel = sampled.voxel_size();
  int compared = 0;
  for (int k = 0; k < 300; ++k) {
    const std::vector<Vec3> tab = random_tab(rng);
    const AllowedContacts allowed = k % 2 ? AllowedContacts{{0}, {}} : AllowedContacts{};
    const ContactResult s = sampled.polygon_contact(tab, required, allowed);
    EXPECT_FALSE(s.exact);
    const double reference = sampled_clearance(p, tab, allowed, 24);
    if (std::abs(reference - required) < 2 * voxel + max_gap(tab, 24)) continue;
    ++compared;
    EXPECT_EQ(s.clear, reference > required) << k;
    EXPECT_EQ(exact.polygon_contact(tab, required, allowed).clear, reference > required) << k;
  }
  std::printf("sampled fallback: %d of 300 tabs compared (voxel %.2f mm)\n", compared, voxel * 1e3);
  EXPECT_GT(compared, 150);
}

}  // namespace
}  // namespace sheetgen
