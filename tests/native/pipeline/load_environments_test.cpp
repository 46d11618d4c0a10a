#include "sheetgen/pipeline/load_environments.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "../common/scene_fixture.hpp"

namespace sheetgen {
namespace {

using testing_scenes::rectangle;

// base_problem()'s box over a floor rivet area, and two parts made for
// earlier loads: plates over the floor beside the box.
Problem floor_scene() {
  Problem p = testing_scenes::base_problem();
  testing_scenes::add_rivet_mesh(p, "floor", rectangle(-0.1, 0.15, -0.1, 0.15, -0.01));
  return p;
}

EnvironmentMesh part(const std::string& name, double x0) {
  return {"part:" + name, rectangle(x0, x0 + 0.03, -0.05, 0.05, 0.03), "<generated>"};
}

// The clearance of a grid of points around the box, the floor and the parts.
std::vector<double> clearances(const Environment& env) {
  std::vector<double> out;
  for (double x = -0.06; x <= 0.12; x += 0.0037)
    for (double y = -0.06; y <= 0.06; y += 0.0041)
      for (double z = -0.008; z <= 0.04; z += 0.0029) out.push_back(env.clearance(Vec3(x, y, z), {}));
  return out;
}

// A released environment, built again, answers every query as the one it
// replaced, to the last bit (docs/pipeline.md "Environments"): the solve's
// parts do not depend on whether a load searched a thicker gauge.
TEST(LoadEnvironments, AReleasedEnvironmentIsBuiltAgainToTheSameAnswers) {
  const Problem p = floor_scene();
  LoadEnvironments kept(p, nullptr), released(p, nullptr);
  ASSERT_NE(kept.next(), nullptr);
  ASSERT_NE(released.next(), nullptr);
  kept.add_part(part("a", 0.05));
  released.add_part(part("a", 0.05));
  const Environment* second = kept.next();
  ASSERT_NE(second, nullptr);
  ASSERT_NE(released.next(), nullptr);
  const std::vector<double> want = clearances(*second);

  released.release();
  const Environment* rebuilt = released.current();
  ASSERT_NE(rebuilt, nullptr);
  EXPECT_EQ(rebuilt->problem().meshes.size(), second->problem().meshes.size());
  EXPECT_EQ(rebuilt->voxel_size(), second->voxel_size());
  EXPECT_EQ(clearances(*rebuilt), want);
  EXPECT_EQ(released.current(), rebuilt);  // kept until the next release

  // The next load after a release: the scene, every earlier batch, the new part.
  kept.add_part(part("b", -0.05));
  released.add_part(part("b", -0.05));
  released.release();
  const Environment* third_kept = kept.next();
  const Environment* third_released = released.next();
  ASSERT_NE(third_kept, nullptr);
  ASSERT_NE(third_released, nullptr);
  EXPECT_EQ(third_released->problem().meshes.size(), p.meshes.size() + 2);
  EXPECT_EQ(clearances(*third_released), clearances(*third_kept));
}

// A thicker gauge's environment holds the parts made so far, at its own voxel.
TEST(LoadEnvironments, AThickerSheetsEnvironmentHoldsTheEarlierParts) {
  const Problem p = floor_scene();
  LoadEnvironments envs(p, nullptr);
  ASSERT_NE(envs.next(), nullptr);
  envs.add_part(part("a", 0.05));
  const Environment* current = envs.next();
  ASSERT_NE(current, nullptr);
  Problem thick = p;
  thick.material.thickness = 2.0e-3;
  envs.release();
  const auto gauge = envs.at_sheet(thick);
  ASSERT_NE(gauge, nullptr);
  EXPECT_EQ(gauge->problem().meshes.size(), p.meshes.size() + 1);
  EXPECT_EQ(gauge->problem().material.thickness, 2.0e-3);
  // 1 mm clear of the part's top face (z = 0.03) at the thicker sheet's voxel.
  EXPECT_NEAR(gauge->clearance(Vec3(0.065, 0.0, 0.031), {}), 1e-3, 0.5 * gauge->voxel_size());
}

}  // namespace
}  // namespace sheetgen
