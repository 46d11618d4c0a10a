// Validity against an Environment built from a Problem assembled in code:
// a tab through an obstacle, and rivet flanges on / off / above their rivet area.
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/rivet_flange.hpp"
#include "sheetgen/part/validity.hpp"
#include "../common/scene_fixture.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;
constexpr double kT = 1.6e-3;

// Load: 40 x 40 x 20 mm box whose bottom is at z = t/2, so the base tab is
// the square (0,0)-(40,40) mm at z = 0; the sheet is kT thick.
using testing_scenes::base_problem;
using testing_scenes::rectangle;

// A tab on edge 0 bent down 90 deg: plane y = 0, x 10..30 mm, z 0..-l.
Part down_tab(const Problem& problem, double l) {
  Part part = make_base_part(problem.loads[0], 0, kT);
  part.add_tab(0, 0, {0.01, 0.02, l, 0, 0, -90 * kDeg});
  return part;
}

// Obstacle: a plate at z = -25 mm (x -50..100, y -50..50 mm, 25 mm below the base).
TEST(EnvironmentValidity, TabThroughAnObstacle) {
  Problem problem = base_problem();
  problem.meshes.push_back({"plate", rectangle(-0.05, 0.1, -0.05, 0.05, -0.025), "<inline>"});
  const Environment env(problem);
  // l = 18 mm ends 7 mm above the plate (needs t/2 + clearance = 1.8 mm); its
  // root touches the load's bottom edge, which the bend-zone rule allows.
  const Part ok = down_tab(problem, 0.018);
  const ValidityReport good = check_validity(ok, realise(ok), env);
  EXPECT_TRUE(good.valid()) << good.summary();
  // l = 30 mm goes 5 mm through the plate.
  const Part through = down_tab(problem, 0.03);
  const ValidityReport bad = check_validity(through, realise(through), env);
  ASSERT_EQ(bad.first_reason(), ValidityReason::ObstacleCollision) << bad.summary();
  EXPECT_EQ(bad.violations[0].tab, 1);
  EXPECT_LT(bad.violations[0].value, 1.8e-3);
  // Bent up instead, the tab goes into the load box, which only the base may touch.
  Part up = make_base_part(problem.loads[0], 0, kT);
  up.add_tab(0, 0, {0.01, 0.02, 0.018, 0, 0, 100 * kDeg});
  const ValidityReport into_box = check_environment(up, realise(up), env);
  EXPECT_EQ(into_box.first_reason(), ValidityReason::ObstacleCollision) << into_box.summary();
}

// A search in another grammar than the environment's problem (the flat-extension
// and right-angle passes) is judged by its own limits: a flat extension is
// valid where its grammar allows it, a 45 deg bend is not in the right-angle
// grammar, and the environment's scene still applies to both.
TEST(EnvironmentValidity, TheSearchsGrammarDecidesTheLimits) {
  Problem problem = base_problem();
  problem.meshes.push_back({"plate", rectangle(-0.05, 0.1, -0.05, 0.05, -0.025), "<inline>"});
  ASSERT_FALSE(problem.manufacturing.flat_extensions);
  const Environment env(problem);
  Part flat = make_base_part(problem.loads[0], 0, kT);
  const int e = flat.add_tab(0, 0, {0.0, 0.04, 0.03, 0, 0, 0.0});  // the base continued 30 mm, flat
  flat.add_tab(e, kFarEdge, {0.01, 0.02, 0.018, 0, 0, -90 * kDeg});
  EXPECT_EQ(check_validity(flat, realise(flat), env).first_reason(), ValidityReason::BendAngleTooSmall);
  Problem with_flat = problem;
  with_flat.manufacturing.flat_extensions = true;
  const ValidityReport allowed = check_validity(flat, realise(flat), SheetSpec::from(with_flat), env);
  EXPECT_TRUE(allowed.valid()) << allowed.summary();

  Problem square = problem;
  square.manufacturing.restrict_to_right_angles();
  Part slanted = make_base_part(problem.loads[0], 0, kT);
  slanted.add_tab(0, 0, {0.01, 0.02, 0.018, 0, 0, -45 * kDeg});
  EXPECT_TRUE(check_validity(slanted, realise(slanted), env).valid());
  EXPECT_EQ(check_validity(slanted, realise(slanted), SheetSpec::from(square), env).first_reason(),
            ValidityReason::BendAngleTooSmall);
  EXPECT_TRUE(check_validity(down_tab(problem, 0.018), realise(down_tab(problem, 0.018)), SheetSpec::from(square), env).valid());
  // The scene is the environment's in every grammar: through the plate is a collision.
  const Part through = down_tab(problem, 0.03);
  EXPECT_EQ(check_validity(through, realise(through), SheetSpec::from(square), env).first_reason(),
            ValidityReason::ObstacleCollision);
}

// Rivet flange: A goes down 30 mm from edge 0 (plane y = 0); the flange F on
// A's far edge is bent +90 deg, horizontal at z = -30 mm, reaching y = -25 mm,
// x 10..30 mm, top normal +z. The floor (rivet area) lies t/2 below it at
// z = -30.8 mm, facing up.
struct FlangeScene {
  Problem problem;
  Part part;
};

FlangeScene flange_scene(double floor_x0, double floor_z) {
  FlangeScene s;
  s.problem = base_problem();
  s.problem.meshes.push_back({"floor", rectangle(floor_x0, 0.05, -0.05, 0.01, floor_z), "<inline>"});
  RivetAreaSpec ra;
  ra.name = "floor_area";
  ra.mesh = 0;
  ra.faces = {0, 1};
  s.problem.rivet_areas.push_back(ra);
  s.part = make_base_part(s.problem.loads[0], 0, kT);
  const int a = s.part.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, -90 * kDeg});
  s.part.add_tab(a, kFarEdge, {0.0, 0.02, 0.025, 0, 0, 90 * kDeg}, /*rivet_area=*/0);
  return s;
}

TEST(EnvironmentValidity, FlushFlangeIsValid) {
  const FlangeScene s = flange_scene(-0.01, -0.0308);
  const Environment env(s.problem);
  const RealisedPart rp = realise(s.part);
  const FlangeAttachment fa = check_rivet_flange(s.part, rp, 2, s.problem);
  ASSERT_TRUE(fa.ok()) << fa.message;
  EXPECT_NEAR(fa.covered_fraction, 1.0, 1e-12);
  EXPECT_LT(fa.max_distance_error, 1e-12);
  // Rivet region: x 0..20 mm, y from SB = 7.2 to 25 mm, inset by 2D = 7.9375 mm:
  // x 7.9375..12.0625, y 15.1375..17.0625 mm: one rivet (pitch 23.8 mm) at its
  // centre, local (10, 16.1), world (20, -16.1, -30) mm.
  ASSERT_EQ(fa.rivets.size(), 1u);
  EXPECT_LT((fa.rivets[0] - Vec3(0.02, -(7.2e-3 + 25e-3) / 2, -0.03)).norm(), 1e-12);
  const ValidityReport r = check_validity(s.part, rp, env);
  EXPECT_TRUE(r.valid()) << r.summary();
}

// The floor starts at x = 15 mm: a quarter of the flange (x 10..15 of 10..30 mm) hangs off.
TEST(EnvironmentValidity, FlangeHangingOffItsRivetArea) {
  const FlangeScene s = flange_scene(0.015, -0.0308);
  const Environment env(s.problem);
  const RealisedPart rp = realise(s.part);
  const FlangeAttachment fa = check_rivet_flange(s.part, rp, 2, s.problem);
  EXPECT_EQ(fa.reason, ValidityReason::FlangeOffRivetArea) << fa.message;
  EXPECT_NEAR(fa.covered_fraction, 0.75, 1e-12);
  const ValidityReport r = check_validity(s.part, rp, env);
  EXPECT_EQ(r.first_reason(), ValidityReason::FlangeOffRivetArea) << r.summary();
  EXPECT_EQ(r.violations[0].tab, 2);
}

// Floor 1 mm lower: the flange floats 1.8 mm above it instead of t/2 = 0.8 mm.
TEST(EnvironmentValidity, FlangeNotFlush) {
  const FlangeScene s = flange_scene(-0.01, -0.0318);
  const FlangeAttachment fa = check_rivet_flange(s.part, realise(s.part), 2, s.problem);
  EXPECT_EQ(fa.reason, ValidityReason::FlangeNotFlush) << fa.message;
}

// The same floor wound the other way (normal -z, as a sheet drawn in Blender
// may be): the flange is on it from above all the same, and 1 mm lower it
// still floats (1.8 mm, not t/2). Before the fix the flush flange was rejected
// at "-0.800 mm (needs t/2 = 0.800 mm)", which kept every part off the
// bulkheads of the avionics bay.
TEST(EnvironmentValidity, FlangeIsFlushOnAFaceWoundEitherWay) {
  for (const double z : {-0.0308, -0.0318}) {
    FlangeScene s = flange_scene(-0.01, z);
    for (auto& tri : s.problem.meshes[0].mesh.triangles) std::swap(tri[1], tri[2]);
    ASSERT_LT(s.problem.meshes[0].mesh.face_normal(0).z(), -0.99);
    const FlangeAttachment fa = check_rivet_flange(s.part, realise(s.part), 2, s.problem);
    if (z == -0.0308) {
      EXPECT_TRUE(fa.ok()) << fa.message;
      EXPECT_NEAR(fa.covered_fraction, 1.0, 1e-12);
      EXPECT_LT(fa.max_distance_error, 1e-12);
    } else {
      EXPECT_EQ(fa.reason, ValidityReason::FlangeNotFlush) << fa.message;
    }
  }
}

// A short flange leaves no room: l = 13 mm, flat from SB = 7.2 mm, needs
// 2 x 7.9375 mm across -> empty rivet region.
TEST(EnvironmentValidity, NoRoomForRivet) {
  FlangeScene s = flange_scene(-0.01, -0.0308);
  s.part.tabs[2].params.l = 0.013;
  const FlangeAttachment fa = check_rivet_flange(s.part, realise(s.part), 2, s.problem);
  EXPECT_EQ(fa.reason, ValidityReason::NoRoomForRivet) << fa.message;
}

}  // namespace
}  // namespace sheetgen
