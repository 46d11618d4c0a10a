// plan_manufacturing: the sample part gets a plan and its files; a part with a
// flat-pattern overlap stops there for that reason.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sheetgen/part/manufacturing_plan.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;

using fixtures::spec;

Part square(double size) {
  return make_base_part({Vec3(0, 0, 0), Vec3(size, 0, 0), Vec3(size, size, 0), Vec3(0, size, 0)}, Vec3::UnitZ());
}

TEST(ManufacturingPlan, LBracketPlanAndFiles) {
  Part part = square(0.04);
  part.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  const ManufacturingPlan plan = plan_manufacturing(part, spec());
  ASSERT_TRUE(plan.ok()) << plan.message;
  EXPECT_EQ(plan.sequence.order, std::vector<int>{1});
  const auto dir = std::filesystem::path(SHEETGEN_BINARY_DIR) / "part_test_output" / "plan_l_bracket";
  write_manufacturing_files(dir.string(), realise(part), plan);
  for (const char* f : {"flat.dxf", "flat.svg", "bends.csv", "part.obj"}) EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;
  std::ifstream csv(dir / "bends.csv");
  std::string header, row;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_EQ(row, "1,90.000000,UP,6.400000,20.000000,1,,,");  // no press-brake check asked: no tools
}

TEST(ManufacturingPlan, StopsAtTheFlatOverlap) {
  Part part = square(0.04);
  const int a = part.add_tab(0, 0, {0.002, 0.016, 0.03, 0, 0, 90 * kDeg});
  part.add_tab(0, 0, {0.024, 0.016, 0.03, 0, 0, -90 * kDeg});
  part.add_tab(a, kEndSideEdge, {0.002, 0.016, 0.025, 0, 0, -90 * kDeg});
  const ManufacturingPlan plan = plan_manufacturing(part, spec());
  EXPECT_EQ(plan.status, ValidityReason::FlatPatternOverlap) << plan.message;
  EXPECT_EQ(plan.sequence.sweeps, 0);  // the bend search was skipped
}

}  // namespace
}  // namespace sheetgen
