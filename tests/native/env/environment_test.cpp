#include "sheetgen/env/environment.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>

#include "sheetgen/core/geometry.hpp"
#include "sheetgen/env/distance_field.hpp"
#include "test_meshes.hpp"

namespace sheetgen {
namespace {

// A floor z = 0 (0.6 m square, 12 x 12 cells) whose central 4 x 4 cells are a rivet area,
// and one load box above it.
Problem floor_problem() {
  Problem p;
  p.source = "<test>";
  EnvironmentMesh floor{"floor", testing::plane(Vec3::Zero(), Vec3::UnitZ(), 0.6, 12), "<inline>"};
  p.meshes.push_back(floor);
  RivetAreaSpec ra;
  ra.name = "centre";
  ra.mesh = 0;
  ra.faces = testing::plane_cell_block(12, 4, 8);
  p.rivet_areas.push_back(ra);
  Load l;
  l.name = "box";
  l.center = Vec3(0.2, 0.2, 0.2);
  l.size = Vec3(0.1, 0.1, 0.1);
  l.force = Vec3(0, 0, -100);
  p.loads.push_back(l);
  p.manufacturing.bend_radius = 4 * p.material.thickness;
  return p;
}

std::vector<Vec3> square(const Vec3& c, double half, double z) {
  return {c + Vec3(-half, -half, z), c + Vec3(half, -half, z), c + Vec3(half, half, z), c + Vec3(-half, half, z)};
}

// Obstacles added to a built environment (the parts of earlier loads,
// docs/environment.md "Obstacles added later"): the environment built from the scene
// plus one small field over the added meshes answers like one built from
// scratch over all of them, and both keep the field's accuracy contract
// against brute force.
TEST(Environment, AddedObstaclesAnswerLikeAnEnvironmentBuiltWithThem) {
  const Problem p = floor_problem();
  std::vector<EnvironmentMesh> added = {
      {"part:a", testing::plane(Vec3(-0.1, -0.15, 0.06), Vec3(0.3, 0.1, 1.0).normalized(), 0.12, 3), "<generated>"},
      {"part:b", testing::icosphere(0.04, 2, Vec3(0.05, 0.2, 0.08)), "<generated>"}};
  Problem all = p;
  for (const auto& m : added) all.meshes.push_back(m);
  const Environment scratch(all);
  const Environment base(p);
  const Environment grown(base, added);
  ASSERT_EQ(grown.problem().meshes.size(), all.meshes.size());
  EXPECT_EQ(grown.rivet_area_of_face(1, 0), -1);
  EXPECT_EQ(grown.rivet_area_of_face(0, p.rivet_areas[0].faces[0]), 0);
  const double h = grown.voxel_size();
  EXPECT_EQ(h, scratch.voxel_size());
  // The added field's grids come on top of the shared ones.
  EXPECT_GT(base.field_memory_bytes(), 0u);
  EXPECT_GT(grown.field_memory_bytes(), base.field_memory_bytes());

  // Exact distance to every obstacle but the rivet area, and to the box.
  std::vector<std::array<Vec3, 3>> tris;
  std::vector<char> is_ra(all.meshes[0].mesh.triangles.size(), 0);
  for (int f : p.rivet_areas[0].faces) is_ra[f] = 1;
  for (size_t m = 0; m < all.meshes.size(); ++m)
    for (size_t f = 0; f < all.meshes[m].mesh.triangles.size(); ++f) {
      if (m == 0 && is_ra[f]) continue;
      const auto& t = all.meshes[m].mesh.triangles[f];
      const auto& v = all.meshes[m].mesh.vertices;
      tris.push_back({v[t[0]], v[t[1]], v[t[2]]});
    }
  AllowedContacts allow_ra;
  allow_ra.rivet_areas = {0};
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ux(-0.2, 0.2), uz(0.0, 0.14);
  int compared = 0;
  double worst_vs_exact = 0, worst_vs_scratch = 0;
  for (int k = 0; k < 20000; ++k) {
    const Vec3 q(ux(rng), ux(rng), uz(rng));
    double exact = p.loads[0].signed_distance(q);
    for (const auto& t : tris) exact = std::min(exact, (q - closest_point_on_triangle(q, t[0], t[1], t[2])).norm());
    const double band = 4 * h;  // inside every field's band (5 voxels by default)
    if (exact > band) continue;
    ++compared;
    const double g = grown.clearance(q, allow_ra), s = scratch.clearance(q, allow_ra);
    worst_vs_exact = std::max(worst_vs_exact, std::abs(g - exact));
    worst_vs_scratch = std::max(worst_vs_scratch, std::abs(g - s));
  }
  std::printf("added obstacles: %d points in the band, max error %.4f voxel (scratch build: %.4f voxel apart)\n", compared,
              worst_vs_exact / h, worst_vs_scratch / h);
  EXPECT_GT(compared, 800);
  EXPECT_LT(worst_vs_exact, 0.5 * h);    // the field's contract (docs/environment.md "Accuracy")
  EXPECT_LT(worst_vs_scratch, 0.25 * h);

  // The exact tab test and the rays see the added meshes as the scratch build does.
  const std::vector<Vec3> tab = square(Vec3(0.05, 0.2, 0.0), 0.05, 0.125);  // 5 mm over the sphere's top
  for (double required : {0.003, 0.006}) {
    const ContactResult a = grown.polygon_contact(tab, required, {}), b = scratch.polygon_contact(tab, required, {});
    EXPECT_EQ(a.clear, b.clear) << required;
    EXPECT_NEAR(a.min_clearance, b.min_clearance, 1e-12);
  }
  const auto hit = grown.cast_ray(Vec3(0.05, 0.2, 0.3), Vec3(0, 0, -1), 1.0);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->mesh, 2);
  EXPECT_NEAR(hit->distance, 0.3 - 0.12, 2e-3);  // the icosphere's top, a level-2 facet below 0.12
  // The gradient near an added mesh points away from it.
  EXPECT_GT(grown.clearance_gradient(Vec3(0.05, 0.2, 0.125)).z(), 0.9);
}

TEST(Environment, ClearanceCombinesFieldsAndBoxes) {
  const Problem p = floor_problem();
  Environment env(p);
  // 5 cm above the plain floor, far from the box: 5 cm.
  EXPECT_NEAR(env.clearance(Vec3(-0.25, -0.25, 0.05)), 0.05, 1e-9);
  // Just below the box bottom (z = 0.15): the box is nearer than the floor.
  EXPECT_NEAR(env.clearance(Vec3(0.2, 0.2, 0.14)), 0.01, 1e-9);
  // Inside the box: negative.
  EXPECT_NEAR(env.clearance(Vec3(0.2, 0.2, 0.2)), -0.05, 1e-9);
  // Gradient above the floor points up.
  EXPECT_NEAR(env.clearance_gradient(Vec3(-0.25, -0.25, 0.003)).z(), 1.0, 1e-9);
}

// Many rotated load boxes (an avionics bay): the clearance near them equals
// the exact box distance (Load::signed_distance) of the nearest box not
// allowed, and the sphere culling in the query never skips the nearest one.
TEST(Environment, ManyRotatedBoxesGiveTheExactNearestBoxDistance) {
  Problem p = floor_problem();
  p.loads.clear();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 12; ++k) {
    Load l;
    l.name = "box" + std::to_string(k);
    l.center = Vec3(0.25 * u(rng), 0.25 * u(rng), 0.3 + 0.1 * u(rng));
    l.size = Vec3(0.03 + 0.02 * (u(rng) + 1), 0.04, 0.02 + 0.03 * (u(rng) + 1));
    l.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI * u(rng), Vec3(u(rng), u(rng), u(rng)).normalized()));
    l.force = Vec3(0, 0, -10);
    p.loads.push_back(l);
  }
  Environment env(p);
  const AllowedContacts allowed{{}, {3, 8}};
  int checked = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 q(0.3 * u(rng), 0.3 * u(rng), 0.3 + 0.2 * u(rng));
    double all = env.obstacle_field().distance(q), some = all;  // the floor outside its rivet area
    for (int k = 0; k < static_cast<int>(p.loads.size()); ++k) {
      const double d = p.loads[k].signed_distance(q);
      all = std::min(all, d);
      if (k != 3 && k != 8) some = std::min(some, d);
    }
    // Where the rivet area is nearer than every box the query answers with it: not what this test is about.
    if (env.rivet_area_distance(0, q) < all) continue;
    ASSERT_NEAR(env.clearance(q), all, 1e-12) << i;
    ++checked;
    if (env.rivet_area_distance(0, q) >= some) {
      ASSERT_NEAR(env.clearance(q, allowed), some, 1e-12) << i;
    }
  }
  std::printf("rotated boxes: %d of 4000 points checked\n", checked);
  EXPECT_GT(checked, 2000);
}

TEST(Environment, RivetFlangeOnItsAreaIsAllowedButNotOffIt) {
  const Problem p = floor_problem();
  Environment env(p);
  const double t = p.material.thickness, required = 0.5 * t + p.requirements.clearance;
  // A 6 cm flange lying flush (mid-surface t/2 above) in the middle of the 20 cm rivet area.
  const auto flange = square(Vec3::Zero(), 0.03, 0.5 * t);
  EXPECT_FALSE(env.polygon_contact(flange, required, AllowedContacts{}).clear);
  EXPECT_TRUE(env.polygon_contact(flange, required, AllowedContacts{{0}, {}}).clear);
  // The same flange shifted so it hangs 1 cm past the rivet area's edge (x = 0.1): a collision with the plain floor.
  const auto hanging = square(Vec3(0.08, 0, 0), 0.03, 0.5 * t);
  const ContactResult r = env.polygon_contact(hanging, required, AllowedContacts{{0}, {}});
  EXPECT_FALSE(r.clear);
  EXPECT_GT(r.worst_point.x(), 0.1 - 0.01);  // found past the edge, where the plain floor is
}

TEST(Environment, BaseTabUnderItsLoadIsAllowed) {
  const Problem p = floor_problem();
  Environment env(p);
  const double t = p.material.thickness, required = 0.5 * t + p.requirements.clearance;
  const auto base = square(Vec3(0.2, 0.2, 0), 0.05, 0.15 - 0.5 * t);
  EXPECT_FALSE(env.polygon_contact(base, required, AllowedContacts{}).clear);
  EXPECT_TRUE(env.polygon_contact(base, required, AllowedContacts{{}, {0}}).clear);
}

TEST(Environment, TabThroughTheFloorCollides) {
  const Problem p = floor_problem();
  Environment env(p);
  // A vertical tab crossing z = 0 in the plain part of the floor.
  const std::vector<Vec3> tab = {Vec3(-0.25, -0.2, -0.05), Vec3(-0.25, -0.1, -0.05), Vec3(-0.25, -0.1, 0.05), Vec3(-0.25, -0.2, 0.05)};
  const ContactResult r = env.polygon_contact(tab, 0.5 * p.material.thickness, AllowedContacts{});
  EXPECT_FALSE(r.clear);
  EXPECT_LT(r.min_clearance, 0.5 * p.material.thickness);
  // Lifted 10 cm, it is clear and the bound it reports is honest (>= required).
  const std::vector<Vec3> lifted = {Vec3(-0.25, -0.2, 0.1), Vec3(-0.25, -0.1, 0.1), Vec3(-0.25, -0.1, 0.2), Vec3(-0.25, -0.2, 0.2)};
  const ContactResult ok = env.polygon_contact(lifted, 0.5 * p.material.thickness, AllowedContacts{});
  EXPECT_TRUE(ok.clear);
  EXPECT_LE(ok.min_clearance, 0.1 + 1e-9);
}

TEST(Environment, RaysReportRivetAreasAndLoads) {
  const Problem p = floor_problem();
  Environment env(p);
  auto down = env.cast_ray(Vec3(0.01, 0.01, 0.5), Vec3(0, 0, -1), 10);
  ASSERT_TRUE(down.has_value());
  EXPECT_NEAR(down->distance, 0.5, 1e-9);
  EXPECT_EQ(down->rivet_area, 0);
  auto plain = env.cast_ray(Vec3(-0.25, -0.25, 0.5), Vec3(0, 0, -1), 10);
  ASSERT_TRUE(plain.has_value());
  EXPECT_EQ(plain->rivet_area, -1);
  auto box = env.cast_ray(Vec3(0.2, 0.2, 0.5), Vec3(0, 0, -1), 10);
  ASSERT_TRUE(box.has_value());
  EXPECT_EQ(box->load, 0);
  EXPECT_NEAR(box->distance, 0.25, 1e-9);
}

TEST(Environment, RivetAreaDistanceIsExact) {
  const Problem p = floor_problem();
  Environment env(p);
  // The rivet area is the square |x|,|y| <= 0.1 of z = 0.
  EXPECT_NEAR(env.rivet_area_distance(0, Vec3(0, 0, 0.3)), 0.3, 1e-9);
  EXPECT_NEAR(env.rivet_area_distance(0, Vec3(0.4, 0, 0)), 0.3, 1e-9);
  EXPECT_NEAR(env.rivet_area_distance(0, Vec3(0.13, 0.14, 0.0)), 0.05, 1e-9);
}

}  // namespace
}  // namespace sheetgen
