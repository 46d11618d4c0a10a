// Bend sequence: an order that collides while a bend sweeps but whose final
// state is valid, and the planner finding an order that works.
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/part/bend_sequence.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;

using fixtures::spec;

// Cross-section in the y-z plane (all tabs 30 mm wide in x):
//   base y 0..40 at z 0; W (tab 4) stands on y = 40 up to z = 30;
//   C1 (tab 1) stands on y = 0 up to z = 40; C2 (tab 2) is a roof from y 0 to 45
//   at z = 40; C3 (tab 3) hangs from (45, 40) down to (45, 20), 5 mm outside W.
// Final clearances: C3-W 5 mm, C2-W 10 mm (t + gap = 1.8 mm).
// If W, C3 and C2 are bent before C1, C1's sweep turns the hook about the x
// axis: C3's lower edge (radius sqrt(45^2 + 20^2) = 49.24 mm < 50 mm = W's top
// corner radius) crosses the plane y = 40 at z = sqrt(49.24^2 - 40^2) = 28.7 mm,
// inside W, before arriving outside it.
Part hook() {
  Part p = make_base_part({Vec3(0, 0, 0), Vec3(0.03, 0, 0), Vec3(0.03, 0.04, 0), Vec3(0, 0.04, 0)}, Vec3::UnitZ());
  const int c1 = p.add_tab(0, 0, {0.0, 0.03, 0.04, 0, 0, 90 * kDeg});
  const int c2 = p.add_tab(c1, kFarEdge, {0.0, 0.03, 0.045, 0, 0, 90 * kDeg});
  p.add_tab(c2, kFarEdge, {0.0, 0.03, 0.02, 0, 0, 90 * kDeg});
  p.add_tab(0, 2, {0.0, 0.03, 0.03, 0, 0, 90 * kDeg});
  return p;
}

TEST(BendSequence, FinalStateOfTheHookIsValid) {
  const Part part = hook();
  const RealisedPart rp = realise(part);
  const ValidityReport r = check_validity(part, rp, spec());
  EXPECT_TRUE(r.valid()) << r.summary();
  EXPECT_NEAR(rp.tabs[3].corners[2].y(), 0.045, 1e-12);
  EXPECT_NEAR(rp.tabs[3].corners[2].z(), 0.02, 1e-12);
}

TEST(BendSequence, CollidesMidSweepNotAtTheEnd) {
  const Part part = hook();
  const BendSequenceResult r = check_bend_order(part, {4, 3, 2, 1}, spec());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status, ValidityReason::NoBendSequence);
  EXPECT_EQ(r.collision.bend_tab, 1);
  EXPECT_GT(r.collision.fraction, 0.0);
  EXPECT_LT(r.collision.fraction, 1.0);  // strictly before the end of C1's bend
  EXPECT_EQ(std::min(r.collision.tab_a, r.collision.tab_b), 3);
  EXPECT_EQ(std::max(r.collision.tab_a, r.collision.tab_b), 4);
  EXPECT_EQ(r.order, (std::vector<int>{4, 3, 2}));  // the bends done before the failing one
  std::printf("hook, order 4 3 2 1: %s\n", r.message.c_str());
}

TEST(BendSequence, CoarseSamplingOnlyAtTheEndMissesIt) {
  // One sample per bend (the final state only) sees nothing: the sweep matters.
  BendSequenceOptions o;
  o.max_step = M_PI;
  EXPECT_TRUE(check_bend_order(hook(), {4, 3, 2, 1}, spec(), o).ok());
}

TEST(BendSequence, PlannerFindsAWorkingOrder) {
  const Part part = hook();
  const BendSequenceResult r = plan_bend_sequence(part, spec());
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.order.size(), 4u);
  EXPECT_TRUE(check_bend_order(part, r.order, spec()).ok());
  // Shallow first: C1 and W (depth 1) before C2, then C3.
  EXPECT_EQ(r.order, (std::vector<int>{1, 4, 2, 3}));
  std::printf("hook plan: %d %d %d %d after %d sweeps\n", r.order[0], r.order[1], r.order[2], r.order[3], r.sweeps);
}

TEST(BendSequence, ImpossiblePartReportsWhy) {
  // Two siblings that end up crossing: no order can avoid it.
  Part part = make_base_part({Vec3(0, 0, 0), Vec3(0.04, 0, 0), Vec3(0.04, 0.04, 0), Vec3(0, 0.04, 0)}, Vec3::UnitZ());
  part.add_tab(0, 0, {0.012, 0.016, 0.06, 0, 0, 135 * kDeg});
  part.add_tab(0, 2, {0.012, 0.016, 0.06, 0, 0, 135 * kDeg});
  const BendSequenceResult r = plan_bend_sequence(part, spec());
  EXPECT_FALSE(r.ok());
  EXPECT_FALSE(r.exhausted);
  EXPECT_NE(r.message.find("no bend sequence"), std::string::npos) << r.message;
}

TEST(BendSequence, BadOrderThrows) {
  EXPECT_THROW(check_bend_order(hook(), {1, 2, 3}, spec()), std::invalid_argument);
  EXPECT_THROW(check_bend_order(hook(), {1, 2, 3, 3}, spec()), std::invalid_argument);
}

}  // namespace
}  // namespace sheetgen
