// The analysis memo's key (compose/analysis_memo.hpp): equal inputs give one
// key, and a change in any input analyse_part() reads gives another, down to
// the last bit of one corner.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "sheetgen/compose/analysis_memo.hpp"

namespace sheetgen {
namespace {

// A base plate and one flange bent off its far edge.
PlateGeometry two_plates() {
  PlateGeometry g;
  g.polygons = {{Vec3(0, 0, 0), Vec3(0.1, 0, 0), Vec3(0.1, 0.05, 0), Vec3(0, 0.05, 0)},
                {Vec3(0.1, 0, 0), Vec3(0.1, 0.05, 0), Vec3(0.1, 0.05, 0.04), Vec3(0.1, 0, 0.04)}};
  g.rivet_area = {-1, 3};
  g.rivet_edge = {0, 2};
  g.parent = {-1, 0};
  g.bend_angle = {0.0, M_PI / 2};
  return g;
}

PartModelOptions search_mesh() {
  PartModelOptions o;
  o.element_size = 0.006;
  return o;
}

TEST(AnalysisMemoKey, EqualInputsShareAKey) {
  EXPECT_EQ(AnalysisMemo::key_of(two_plates(), search_mesh()), AnalysisMemo::key_of(two_plates(), search_mesh()));
}

TEST(AnalysisMemoKey, EveryInputTheAnalysisReadsChangesIt) {
  const std::string key = AnalysisMemo::key_of(two_plates(), search_mesh());
  PlateGeometry g = two_plates();
  g.polygons[1][2].z() = std::nextafter(0.04, 1.0);  // one ulp on one corner
  EXPECT_NE(AnalysisMemo::key_of(g, search_mesh()), key);
  g = two_plates();
  g.rivet_area[1] = 4;
  EXPECT_NE(AnalysisMemo::key_of(g, search_mesh()), key);
  g = two_plates();
  g.rivet_edge[1] = 1;
  EXPECT_NE(AnalysisMemo::key_of(g, search_mesh()), key);
  g = two_plates();
  g.bend_angle[1] = M_PI / 3;
  EXPECT_NE(AnalysisMemo::key_of(g, search_mesh()), key);
  g = two_plates();
  g.parent.clear();
  g.bend_angle.clear();
  EXPECT_NE(AnalysisMemo::key_of(g, search_mesh()), key);

  PartModelOptions o = search_mesh();
  o.element_size = 0.0;  // the default mesh of the final check
  EXPECT_NE(AnalysisMemo::key_of(two_plates(), o), key);
  o = search_mesh();
  o.eigen_checks = true;
  EXPECT_NE(AnalysisMemo::key_of(two_plates(), o), key);
  o = search_mesh();
  o.element.transverse_shear = false;
  EXPECT_NE(AnalysisMemo::key_of(two_plates(), o), key);
  o = search_mesh();
  o.self_rivets.push_back({0, 1, Vec3(0.09, 0.02, 0), Vec3(0.1, 0.02, 0.01)});
  EXPECT_NE(AnalysisMemo::key_of(two_plates(), o), key);
}

TEST(AnalysisMemo, ReturnsWhatWasKeptAndCounts) {
  AnalysisMemo memo;
  const std::string key = AnalysisMemo::key_of(two_plates(), search_mesh());
  EXPECT_FALSE(memo.find(key).has_value());
  MemoEntry e;
  e.fem.compliance = 0.125;
  memo.insert(key, e);
  memo.insert(AnalysisMemo::key_of(two_plates(), PartModelOptions{}), MemoEntry{{}, "no rivet flange"});
  const auto kept = memo.find(key);
  ASSERT_TRUE(kept.has_value());
  EXPECT_EQ(kept->fem.compliance, 0.125);
  EXPECT_TRUE(kept->fem_error.empty());
  EXPECT_EQ(memo.find(AnalysisMemo::key_of(two_plates(), PartModelOptions{}))->fem_error, "no rivet flange");
  EXPECT_EQ(memo.stats().hits, 2u);
  EXPECT_EQ(memo.stats().misses, 1u);
}

}  // namespace
}  // namespace sheetgen
