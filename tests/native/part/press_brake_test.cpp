// Press-brake feasibility (part/press_brake.hpp) on parts whose outcome
// follows from the tools' drawn dimensions: a return lip a straight punch
// cannot clear and a gooseneck can, a flange shorter than the smallest die
// takes, a downturned flange that meets the bed, a tall flange that does not
// fit under the open punch and one that meets the ram. Sheet 1.6 mm: V-dies
// of 9.6, 12.8, 16 and 19.2 mm (85 deg) and 12.8 mm (30 deg).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sheetgen/part/bend_sequence.hpp"
#include "sheetgen/part/manufacturing_plan.hpp"
#include "sheetgen/part/press_brake.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;
using fixtures::spec;

// A 60 mm wide strip, 40 mm deep; tab 1 stands up on its front edge (90 deg,
// `leg` long) and carries tab 2, a lip bent back over the strip (90 deg,
// `lip` long). Bent lip first, then the leg.
Part channel_with_lip(double leg, double lip) {
  Part p = make_base_part({Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.04, 0), Vec3(0, 0.04, 0)}, Vec3::UnitZ());
  const int a = p.add_tab(0, 0, {0.0, 0.06, leg, 0, 0, 90 * kDeg});
  p.add_tab(a, kFarEdge, {0.0, 0.06, lip, 0, 0, 90 * kDeg});
  return p;
}

ToolSet only_punch(int index) {
  ToolSet tools = standard_tool_set(spec().thickness);
  tools.punches = {tools.punches[index]};
  return tools;
}

TEST(PressBrake, StandardToolsAreTheDocumentedOnes) {
  const ToolSet tools = standard_tool_set(1.6e-3);
  ASSERT_EQ(tools.punches.size(), 3u);
  EXPECT_EQ(tools.punches[0].name, "straight 30 deg");
  EXPECT_EQ(tools.punches[1].name, "gooseneck 30 deg");
  EXPECT_EQ(tools.punches[2].name, "straight 30 deg 180 mm");
  EXPECT_DOUBLE_EQ(tools.machine.open_height, 0.42);
  ASSERT_EQ(tools.dies.size(), 5u);
  EXPECT_EQ(tools.dies[0].name, "V12.8 85 deg");  // 8 t first
  EXPECT_NEAR(tools.dies[1].v_opening, 6 * 1.6e-3, 1e-15);
  EXPECT_EQ(tools.dies[4].name, "V12.8 30 deg");
}

TEST(PressBrake, ReturnLipNeedsTheGooseneck) {
  // At the end of the leg's bend both flanges stand 45 deg up in the tool
  // frame: the leg's far edge at (17.7, 17.7) mm, the lip's edge at
  // (7.1, 28.3) mm. The straight punch is 2 x 28.3 tan 15 deg = 15.2 mm wide
  // there: the lip's edge is inside it. The gooseneck's column has moved to
  // x < -1.2 mm at that height, and the lip lies in its throat.
  const Part part = channel_with_lip(0.025, 0.015);
  const PressBrakeResult straight = check_press_brake(part, {2, 1}, spec(), only_punch(0));
  ASSERT_FALSE(straight.ok);
  EXPECT_EQ(straight.failed_tab, 1);
  EXPECT_NE(straight.message.find("tab 2 hits the punch straight 30 deg"), std::string::npos) << straight.message;
  const PressBrakeResult goose = check_press_brake(part, {2, 1}, spec(), only_punch(1));
  EXPECT_TRUE(goose.ok) << goose.message;
  // The standard set bends the lip with the straight punch and the leg with the gooseneck.
  const PressBrakeResult both = check_press_brake(part, {2, 1}, spec(), standard_tool_set(spec().thickness));
  ASSERT_TRUE(both.ok) << both.message;
  ASSERT_EQ(both.tooling.size(), 2u);
  EXPECT_EQ(both.tooling[0].punch, 0);
  EXPECT_EQ(both.tooling[1].punch, 1);
  // A leg 40 mm long puts the lip outside the straight punch (edge at x = 17.7 mm, 7.7 mm clear of its 10 mm body).
  EXPECT_TRUE(check_press_brake(channel_with_lip(0.040, 0.015), {2, 1}, spec(), only_punch(0)).ok);
}

TEST(PressBrake, TheBendTableNamesEachBendsTools) {
  // The answer's plan checks its bend sequence on the standard tools; bends.csv names them.
  const Part part = channel_with_lip(0.025, 0.015);
  ManufacturingPlanOptions o;
  o.press_brake = true;
  const ManufacturingPlan plan = plan_manufacturing(part, spec(), o);
  ASSERT_TRUE(plan.ok()) << plan.message;
  ASSERT_TRUE(plan.press_checked);
  ASSERT_TRUE(plan.press.ok) << plan.press.message;
  // The part-only planner would bend the leg first (shallow first); then the
  // strip stands in the way of the lip's bend (it hits the gooseneck at 76 deg,
  // the straight punch earlier), so the press-aware planner bends the lip first.
  ASSERT_EQ(plan.sequence.order, (std::vector<int>{2, 1}));
  const std::string csv = bend_table_csv(plan.flat, plan.sequence.order, bend_tool_rows(plan));
  EXPECT_NE(csv.find("\n1,90.000000,UP,6.400000,60.000000,2,straight 30 deg,V12.8 85 deg,no\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n2,90.000000,UP,6.400000,60.000000,1,gooseneck 30 deg,V12.8 85 deg,no\n"), std::string::npos)
      << csv;
  EXPECT_EQ(plan_bend_sequence(part, spec()).order, (std::vector<int>{1, 2}));
  EXPECT_FALSE(check_press_brake(part, {1, 2}, spec(), plan.tools).ok);
  // Without the option nothing is checked and the columns stay empty.
  const ManufacturingPlan plain = plan_manufacturing(part, spec());
  EXPECT_FALSE(plain.press_checked);
  EXPECT_TRUE(bend_tool_rows(plain).empty());
}

TEST(PressBrake, FlangeShorterThanTheSmallestDieTakes) {
  // The smallest die: V = 6 t = 9.6 mm; its shortest flange 0.7 V = 6.72 mm.
  Part part = fixtures::square_base();
  part.add_tab(0, 0, {0.005, 0.03, 0.005, 0, 0, 90 * kDeg});
  const PressBrakeResult r = check_press_brake(part, {1}, spec(), standard_tool_set(spec().thickness));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.failed_tab, 1);
  EXPECT_NE(r.message.find("the flange of tab 1 reaches 0.7 x V = 6.7 mm on the die V9.6 85 deg along 0 % of the "
                           "bend line, not half (it is 5.0 mm deep at most)"),
            std::string::npos) << r.message;
  // 7 mm: too short for the 8 t die (8.96 mm), long enough for the 6 t one.
  Part longer = fixtures::square_base();
  longer.add_tab(0, 0, {0.005, 0.03, 0.007, 0, 0, 90 * kDeg});
  const PressBrakeResult ok = check_press_brake(longer, {1}, spec(), standard_tool_set(spec().thickness));
  ASSERT_TRUE(ok.ok) << ok.message;
  EXPECT_EQ(ok.tooling[0].die, 1);
}

TEST(PressBrake, ASlantedFlangeNeedsTheMinimumAlongHalfItsBendLine) {
  // A 30 mm root whose far edge is turned by theta1 = 20 deg about its
  // midpoint (l = 8 mm there): the depth runs linearly along the root from
  // 8 - 15 tan 20 = 2.54 mm to 13.46 mm. It reaches the 8 t die's 8.96 mm on
  // 41 % of the line (42.5 % of the 40 points): refused; the 6 t die's
  // 6.72 mm on 62 %: taken. Measured at both ends only, neither die would do.
  Part part = fixtures::square_base();
  part.add_tab(0, 0, {0.005, 0.03, 0.008, 20 * kDeg, 0, 90 * kDeg});
  const PressBrakeResult r = check_press_brake(part, {1}, spec(), standard_tool_set(spec().thickness));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.tooling[0].die, 1);
}

TEST(PressBrake, DownturnedFlangeMeetsTheBed) {
  // A 40 mm strip with a flange turned 90 deg down at its back edge: bending
  // the front edge, that flange hangs from x = -40 mm. The bed (100 mm wide)
  // starts 60 mm below the die's shoulders: 70 mm of flange reaches it at
  // once, 50 mm does not.
  for (double drop : {0.070, 0.050}) {
    Part part = fixtures::square_base(0.04);
    part.add_tab(0, 2, {0.005, 0.03, drop, 0, 0, -90 * kDeg});
    part.add_tab(0, 0, {0.005, 0.03, 0.02, 0, 0, 90 * kDeg});
    const PressBrakeResult r = check_press_brake(part, {1, 2}, spec(), standard_tool_set(spec().thickness));
    if (drop > 0.06) {
      ASSERT_FALSE(r.ok);
      EXPECT_EQ(r.failed_tab, 2);
      EXPECT_NE(r.message.find("tab 1 hits the bed below the die at 0 deg"), std::string::npos) << r.message;
    } else {
      EXPECT_TRUE(r.ok) << r.message;
    }
  }
}

// A 60 x `depth` mm strip: tab 1 stands 250 mm high on its back edge, tab 2
// (20 mm, 90 deg) is bent on its front edge after it.
Part strip_with_tall_flange(double depth) {
  Part p = make_base_part({Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, depth, 0), Vec3(0, depth, 0)}, Vec3::UnitZ());
  p.add_tab(0, 2, {0.015, 0.03, 0.25, 0, 0, 90 * kDeg});
  p.add_tab(0, 0, {0.015, 0.03, 0.02, 0, 0, 90 * kDeg});
  return p;
}

TEST(PressBrake, TallFlangeUnderTheRamDoesNotFitUnderTheOpenPunch) {
  // Open height 420 mm - die 60 mm - punch 120 mm: 240 mm under the punch
  // (under the 180 mm punch, 180 mm). On a 20 mm strip the 250 mm flange
  // stands at x = -20 mm, under the 60 mm wide ram: the part does not go in.
  const PressBrakeResult r =
      check_press_brake(strip_with_tall_flange(0.02), {1, 2}, spec(), standard_tool_set(spec().thickness));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.failed_tab, 2);
  EXPECT_NE(r.message.find("the part stands 251 mm above the die, more than the 240 mm under the open punch"),
            std::string::npos) << r.message;
}

TEST(PressBrake, TallFlangeBesideTheRamMeetsItAsTheStripRises) {
  // On a 40 mm strip it stands at x = -40 mm, in front of the ram (half-width
  // 30 mm), and goes in; but the strip rises with the bend and tips the
  // flange's top towards the ram: at 4 deg of the bend (2 deg of tilt) it is
  // at x = -40 cos 2 deg + 250 sin 2 deg = -31.26 mm, 1.26 mm from the ram's
  // face, inside the clearance t/2 + 0.5 mm = 1.3 mm (at 2 deg: 5.6 mm).
  const PressBrakeResult r =
      check_press_brake(strip_with_tall_flange(0.04), {1, 2}, spec(), standard_tool_set(spec().thickness));
  ASSERT_FALSE(r.ok);
  EXPECT_EQ(r.failed_tab, 2);
  EXPECT_NE(r.message.find("tab 1 hits the ram above the punch at 4 deg of its 90 deg"), std::string::npos) << r.message;
}

// A 100 mm square base with a 140 mm side standing on its front edge, then a
// 30 mm flange on its right edge (80 mm long, 10 mm short of each corner):
// the corner of an open box 140 mm deep.
Part open_box_corner() {
  Part part = fixtures::square_base(0.10);
  part.add_tab(0, 0, {0.0, 0.10, 0.14, 0, 0, 90 * kDeg});
  part.add_tab(0, 1, {0.01, 0.08, 0.03, 0, 0, 90 * kDeg});
  return part;
}

TEST(PressBrake, ABoxDeeperThanTheStandardPunchesTakesTheTallOne) {
  // Bending the flange, the side stands 10 mm beyond the end of its bend
  // line, clear of the segmented punch, but the ram spans the machine. With
  // the two 120 mm punches alone it comes down to 120.8 mm above the sheet's
  // mid-surface, over a 140 mm side.
  const Part part = open_box_corner();
  PressBrakeTooling tooling = default_press_brake_tooling();
  tooling.punches.resize(2);
  const PressBrakeResult low = check_press_brake(part, {1, 2}, spec(), make_tool_set(tooling, spec().thickness));
  ASSERT_FALSE(low.ok);
  EXPECT_EQ(low.failed_tab, 2);
  EXPECT_NE(low.message.find("tab 1 hits the ram above the punch at 0 deg"), std::string::npos) << low.message;
  // The standard set's 180 mm punch: the side's far corner, 100 mm from the
  // bend line, rises to at most sqrt(100^2 + 140^2) = 172 mm as the base tips
  // (at 35.5 deg of tilt), under the ram at 180.8 mm by more than the 1.3 mm
  // clearance; the open press keeps 420 - 60 - 180 = 180 mm over the 140.8 mm side.
  const PressBrakeResult standard = check_press_brake(part, {1, 2}, spec(), standard_tool_set(spec().thickness));
  ASSERT_TRUE(standard.ok) << standard.message;
  EXPECT_EQ(standard.tooling[0].punch, 0);  // the side itself: the first punch
  EXPECT_EQ(standard.tooling[1].punch, 2);
  // On a machine with 20 mm less open height the side no longer goes in under it.
  tooling = default_press_brake_tooling();
  tooling.punches = {tooling.punches[2]};
  tooling.open_height = 0.38;  // 140 mm under the punch
  const PressBrakeResult shallow = check_press_brake(part, {1, 2}, spec(), make_tool_set(tooling, spec().thickness));
  ASSERT_FALSE(shallow.ok);
  EXPECT_NE(shallow.message.find("the part stands 141 mm above the die, more than the 140 mm under the open punch"),
            std::string::npos) << shallow.message;
}

TEST(PressBrake, AcuteBendTakesTheAcuteDie) {
  // 120 deg of bend closes the sheet to 60 - 3 (springback) = 57 deg: inside
  // the 85 deg dies, outside the 30 deg tools.
  Part part = fixtures::square_base();
  part.add_tab(0, 0, {0.005, 0.03, 0.02, 0, 0, 120 * kDeg});
  const PressBrakeResult r = check_press_brake(part, {1}, spec(), standard_tool_set(spec().thickness));
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.tooling[0].die, 4);
}

TEST(PressBrake, ThePlanKeepsThePartOnlyOrderWhenTheToolsMakeIt) {
  // A 40 mm strip with a 50 mm flange turned down at its back edge and a 20 mm
  // one up at its front (DownturnedFlangeMeetsTheBed): the part-only order
  // suits the press, and the plan keeps it with the tools the check chose.
  Part part = fixtures::square_base(0.04);
  part.add_tab(0, 2, {0.005, 0.03, 0.050, 0, 0, -90 * kDeg});
  part.add_tab(0, 0, {0.005, 0.03, 0.02, 0, 0, 90 * kDeg});
  ManufacturingPlanOptions o;
  o.press_brake = true;
  const ManufacturingPlan plan = plan_manufacturing(part, spec(), o);
  ASSERT_TRUE(plan.press.ok) << plan.press.message;
  const std::vector<int> part_only = plan_bend_sequence(part, spec()).order;
  EXPECT_EQ(plan.sequence.order, part_only);
  const PressBrakeResult check = check_press_brake(part, part_only, spec(), plan.tools);
  ASSERT_EQ(plan.press.tooling.size(), check.tooling.size());
  for (size_t i = 0; i < check.tooling.size(); ++i) {
    EXPECT_EQ(plan.press.tooling[i].tab, check.tooling[i].tab);
    EXPECT_EQ(plan.press.tooling[i].punch, check.tooling[i].punch);
    EXPECT_EQ(plan.press.tooling[i].die, check.tooling[i].die);
    EXPECT_EQ(plan.press.tooling[i].flipped, check.tooling[i].flipped);
  }
}

TEST(PressBrake, ThePressAwareSearchReturnsTheToolsOfItsOrder) {
  // The channel with a return lip: the search's order {2, 1} and, per bend,
  // the same punch and die as check_press_brake chooses for that order.
  const Part part = channel_with_lip(0.025, 0.015);
  const ToolSet tools = standard_tool_set(spec().thickness);
  BendSequenceOptions o;
  o.tools = &tools;
  const BendSequenceResult r = plan_bend_sequence(part, spec(), o);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.order, (std::vector<int>{2, 1}));
  const PressBrakeResult check = check_press_brake(part, r.order, spec(), tools);
  ASSERT_TRUE(check.ok);
  ASSERT_EQ(r.tooling.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(r.tooling[i].tab, r.order[i]);
    EXPECT_EQ(r.tooling[i].punch, check.tooling[i].punch);
    EXPECT_EQ(r.tooling[i].die, check.tooling[i].die);
  }
  // The part-only search returns no tools.
  EXPECT_TRUE(plan_bend_sequence(part, spec()).tooling.empty());
}

TEST(PressBrake, APartNoOrderSuitsKeepsItsPlanAndNamesTheFailure) {
  // A 20 mm strip with a 250 mm flange up on each long edge: whichever is
  // bent first stands 20 mm from the other's bend line, under the ram, and
  // 251 mm high where 220 mm is free. The plan itself stays ok (the part
  // folds); plan.press says which bend fails and why.
  Part part = make_base_part({Vec3(0, 0, 0), Vec3(0.06, 0, 0), Vec3(0.06, 0.02, 0), Vec3(0, 0.02, 0)}, Vec3::UnitZ());
  part.add_tab(0, 2, {0.015, 0.03, 0.25, 0, 0, 90 * kDeg});
  part.add_tab(0, 0, {0.015, 0.03, 0.25, 0, 0, 90 * kDeg});
  ManufacturingPlanOptions o;
  o.press_brake = true;
  const ManufacturingPlan plan = plan_manufacturing(part, spec(), o);
  ASSERT_TRUE(plan.ok()) << plan.message;
  ASSERT_TRUE(plan.press_checked);
  EXPECT_FALSE(plan.press.ok);
  EXPECT_EQ(plan.sequence.order, plan_bend_sequence(part, spec()).order);
  EXPECT_EQ(plan.press.failed_tab, plan.sequence.order[1]);
  EXPECT_NE(plan.press.message.find("the part stands 251 mm above the die, more than the 240 mm under the open punch"),
            std::string::npos) << plan.press.message;
}

}  // namespace
}  // namespace sheetgen
