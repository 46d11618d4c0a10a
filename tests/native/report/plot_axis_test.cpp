// Axis ranges and ticks: the 1-2-5 steps of Heckbert's rule worked by hand, and
// the axes of the corner sample's convergence plot (compliance 0.176 J against
// a 0.353 J limit, MS 0.866 against 0) as the plot showed them before cairo.
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/report/plot_axis.hpp"

namespace sheetgen {
namespace {

TEST(PlotAxis, NiceStepIsOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(nice_step(7, 5), 1);       // 1.4 -> 1
  EXPECT_DOUBLE_EQ(nice_step(1.2, 5), 0.2);   // 0.24 -> 0.2
  EXPECT_DOUBLE_EQ(nice_step(3.3, 5), 0.5);   // 0.66 -> 0.5
  EXPECT_DOUBLE_EQ(nice_step(0.4, 5), 0.1);   // 0.08 -> 0.1
  EXPECT_DOUBLE_EQ(nice_step(4000, 4), 1000);
  EXPECT_DOUBLE_EQ(nice_step(0, 5), 1);  // degenerate spans get a step of 1
  EXPECT_DOUBLE_EQ(nice_step(std::nan(""), 5), 1);
}

TEST(PlotAxis, ComplianceAxisStartsAtZeroAndHoldsTheLimit) {
  const PlotAxis a = value_axis({0.1756, 0.1756, 0.3532, 0.0}, true, 5);
  EXPECT_DOUBLE_EQ(a.min, 0);
  EXPECT_NEAR(a.max, 0.4, 1e-12);  // 0.3532 + 6 % of the span, rounded up to a tick
  EXPECT_DOUBLE_EQ(a.step, 0.1);
  ASSERT_EQ(a.ticks.size(), 5u);
  EXPECT_EQ(a.label(a.ticks[0]), "0.0");
  EXPECT_EQ(a.label(a.ticks[3]), "0.3");
}

TEST(PlotAxis, MarginAxisGoesBelowZeroAndNeverPrintsMinusZero) {
  const PlotAxis a = value_axis({0.866, 0.866, 0.0}, false, 5);
  EXPECT_NEAR(a.min, -0.2, 1e-12);  // 0 - 6 % of 0.866 = -0.052, rounded down to a 0.2 tick
  EXPECT_NEAR(a.max, 1.0, 1e-12);   // 0.866 + 0.052 = 0.918, rounded up
  EXPECT_DOUBLE_EQ(a.step, 0.2);
  ASSERT_EQ(a.ticks.size(), 7u);
  EXPECT_EQ(a.label(a.ticks[1]), "0.0");  // -0.2 + 0.2 in floating point
  EXPECT_EQ(a.label(a.ticks[0]), "-0.2");
}

TEST(PlotAxis, SingleOrNoValueStillGivesAnAxis) {
  const PlotAxis one = value_axis({5.0}, false, 5);  // 4.5..5.5, padded to 4.44..5.56
  EXPECT_NEAR(one.min, 4.4, 1e-12);
  EXPECT_NEAR(one.max, 5.6, 1e-12);
  const PlotAxis none = value_axis({std::nan("")}, true, 5);
  EXPECT_DOUBLE_EQ(none.min, 0);
  EXPECT_GE(none.max, 1.0);
}

TEST(PlotAxis, LevelAxisHasHalfALevelOfRoomAndWholeTicks) {
  const PlotAxis a = level_axis(1, 4, 5);
  EXPECT_DOUBLE_EQ(a.min, 0.5);
  EXPECT_DOUBLE_EQ(a.max, 4.5);
  EXPECT_EQ(a.ticks, (std::vector<double>{1, 2, 3, 4}));
  EXPECT_EQ(a.label(3), "3");
  const PlotAxis many = level_axis(1, 40, 5);  // 40 levels: a tick every 10
  EXPECT_EQ(many.ticks, (std::vector<double>{10, 20, 30, 40}));
}

TEST(PlotAxis, CountAxisStartsAtZero) {
  const PlotAxis a = count_axis(579, 5);  // 579 * 1.04 = 602: steps of 100 up to 700
  EXPECT_DOUBLE_EQ(a.min, 0);
  EXPECT_DOUBLE_EQ(a.step, 100);
  EXPECT_DOUBLE_EQ(a.max, 700);
  EXPECT_EQ(a.ticks.size(), 8u);
}

}  // namespace
}  // namespace sheetgen
