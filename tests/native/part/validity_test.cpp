// Validity without an environment: every limit fails for its own reason at the
// number it names, and self-intersection is measured against t + gap.
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/part/validity.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;

using fixtures::spec;

using fixtures::square_base;

ValidityReason reason_for(const TabParameters& p, int rivet_area = -1) {
  Part part = square_base();
  part.add_tab(0, 0, p, rivet_area);
  const ValidityReport r = check_validity(part, realise(part), spec());
  return r.first_reason();
}

TEST(Validity, LimitsEachFailForTheirReason) {
  const TabParameters good{0.01, 0.02, 0.03, 0, 0, 90 * kDeg};
  EXPECT_EQ(reason_for(good), ValidityReason::Ok);
  auto with = [&](auto edit) { TabParameters p = good; edit(p); return reason_for(p); };
  EXPECT_EQ(with([](TabParameters& p) { p.w = 0.0159; }), ValidityReason::TabTooNarrow);    // w_min = 10 t = 16 mm
  EXPECT_EQ(with([](TabParameters& p) { p.l = 0.0159; }), ValidityReason::TabTooShort);     // l_min = 2R + 2t = 16 mm
  EXPECT_EQ(with([](TabParameters& p) { p.l = 0.501; }), ValidityReason::TabTooLong);       // l_max = 0.5 m
  EXPECT_EQ(with([](TabParameters& p) { p.theta3 = 4.9 * kDeg; }), ValidityReason::BendAngleTooSmall);
  EXPECT_EQ(with([](TabParameters& p) { p.theta3 = -135.1 * kDeg; }), ValidityReason::BendAngleTooLarge);
  EXPECT_EQ(with([](TabParameters& p) { p.theta2 = 60.1 * kDeg; }), ValidityReason::SkewTooLarge);
  EXPECT_EQ(with([](TabParameters& p) { p.d = 0.021; }), ValidityReason::RootOutsideParentEdge);  // 21 + 20 > 40 mm
  EXPECT_EQ(with([](TabParameters& p) { p.d = -1e-6; }), ValidityReason::RootOutsideParentEdge);
  // |theta1 + theta2| = 90 deg: the far edge is parallel to the sides.
  EXPECT_EQ(with([](TabParameters& p) { p.theta1 = 45 * kDeg; p.theta2 = 45 * kDeg; }), ValidityReason::DegenerateTab);
  // Rivet flanges use min_flange = 4t + R = 12.8 mm instead of l_min.
  TabParameters flange = good;
  flange.l = 0.0130;
  EXPECT_EQ(reason_for(flange, 0), ValidityReason::Ok);
  flange.l = 0.0127;
  EXPECT_EQ(reason_for(flange, 0), ValidityReason::FlangeTooShort);
}

TEST(Validity, ViolationNamesTheNumber) {
  Part part = square_base();
  part.add_tab(0, 0, {0.01, 0.015, 0.03, 0, 0, 90 * kDeg});
  const ValidityReport r = check_validity(part, realise(part), spec());
  ASSERT_EQ(r.violations.size(), 1u);
  EXPECT_EQ(r.violations[0].tab, 1);
  EXPECT_DOUBLE_EQ(r.violations[0].value, 0.015);
  EXPECT_NE(r.summary().find("15.000 mm"), std::string::npos) << r.summary();
  EXPECT_STREQ(to_string(r.first_reason()), "tab_too_narrow");
}

// Bend zones: a 135 deg child on the far edge of a 135 deg tab needs
// l >= 2 SB(135) = 2 tan(67.5)(R + t/2) = 34.764 mm; l = 30 mm is too short by 4.764 mm.
TEST(Validity, BendZonesNeedRoom) {
  Part part = square_base();
  const int a = part.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, 135 * kDeg});
  part.add_tab(a, kFarEdge, {0.0, 0.02, 0.02, 0, 0, -135 * kDeg});
  const ValidityReport r = check_limits(part, realise(part), spec());
  ASSERT_EQ(r.first_reason(), ValidityReason::BendZonesOverlap) << r.summary();
  EXPECT_NEAR(r.violations[0].value, 0.03 - 2 * std::tan(67.5 * kDeg) * 7.2e-3, 1e-12);
  // At 90 deg the same tab has 30 - 14.4 = 15.6 mm of flat left.
  part.tabs[1].params.theta3 = 90 * kDeg;
  part.tabs[2].params.theta3 = 90 * kDeg;
  EXPECT_TRUE(check_limits(part, realise(part), spec()).valid());
}

// Bends on the two sides of a 20 mm wide tab each take SB of it: at 90 deg
// 2 x 7.2 = 14.4 mm leaves 5.6 mm flat; at 120 deg SB = tan(60) (R + t/2) =
// 12.471 mm each, so the strips overlap 2 SB - 20 = 4.941 mm deep over the
// 20 mm both roots span. Bends on edges meeting at a corner are not this case.
TEST(Validity, BendsOnBothSidesOfANarrowTabNeedFlatSheetBetweenThem) {
  Part part = square_base();
  const int a = part.add_tab(0, 0, {0.01, 0.02, 0.04, 0, 0, 90 * kDeg});
  part.add_tab(a, kStartSideEdge, {0.01, 0.02, 0.02, 0, 0, 90 * kDeg});
  part.add_tab(a, kEndSideEdge, {0.01, 0.02, 0.02, 0, 0, 90 * kDeg});
  EXPECT_TRUE(check_limits(part, realise(part), spec()).valid()) << check_limits(part, realise(part), spec()).summary();
  part.tabs[2].params.theta3 = 120 * kDeg;
  part.tabs[3].params.theta3 = 120 * kDeg;
  const ValidityReport r = check_limits(part, realise(part), spec());
  ASSERT_EQ(r.first_reason(), ValidityReason::BendZonesOverlap) << r.summary();
  EXPECT_EQ(r.violations[0].tab, 3);
  EXPECT_EQ(r.violations[0].other, 2);
  const double sb = std::tan(60 * kDeg) * 7.2e-3;
  EXPECT_NEAR(r.violations[0].value, (2 * sb - 0.02) * 0.02, 1e-3 * (2 * sb - 0.02) * 0.02);
  EXPECT_NE(r.summary().find("across tab 1"), std::string::npos) << r.summary();

  Part corner = square_base();
  corner.add_tab(0, 0, {0.02, 0.02, 0.03, 0, 0, 120 * kDeg});  // ends at the corner (40, 0)
  corner.add_tab(0, 1, {0.0, 0.02, 0.03, 0, 0, 120 * kDeg});   // starts there
  EXPECT_FALSE(check_limits(corner, realise(corner), spec()).has(ValidityReason::BendZonesOverlap));
}

// Two flanges bent up on adjacent edges, both reaching the shared corner,
// touch there (distance 0); moved 5 mm apart along both edges they are
// sqrt(5^2 + 5^2) = 7.07 mm apart at their nearest corners.
TEST(Validity, SelfIntersectionBetweenSiblings) {
  Part part = square_base();
  part.add_tab(0, 0, {0.02, 0.02, 0.03, 0, 0, 90 * kDeg});  // ends at the corner (40, 0)
  part.add_tab(0, 1, {0.0, 0.02, 0.03, 0, 0, 90 * kDeg});   // starts there
  ValidityOptions o;
  o.stop_at_first = false;
  const ValidityReport r = check_self_intersection(part, realise(part), spec(), o);
  ASSERT_EQ(r.violations.size(), 1u);
  EXPECT_EQ(r.violations[0].reason, ValidityReason::SelfIntersection);
  EXPECT_NEAR(r.violations[0].value, 0.0, 1e-15);
  part.tabs[1].params.d = 0.015;
  part.tabs[2].params.d = 0.005;
  const RealisedPart rp = realise(part);
  EXPECT_TRUE(check_self_intersection(part, rp, spec(), o).valid());
}

// A tab folding back over its own grandparent: B at 135 deg on A's far edge
// comes back towards the base; with A 20 mm tall and B 40 mm long its far edge
// would pass below z = 0.
TEST(Validity, FoldBackThroughTheBase) {
  Part part = square_base();
  const int a = part.add_tab(0, 0, {0.01, 0.02, 0.02, 0, 0, 90 * kDeg});
  part.add_tab(a, kFarEdge, {0.0, 0.02, 0.04, 0, 0, 135 * kDeg});
  const ValidityReport r = check_self_intersection(part, realise(part), spec());
  ASSERT_EQ(r.first_reason(), ValidityReason::SelfIntersection);
  EXPECT_EQ(r.violations[0].tab, 2);
  EXPECT_EQ(r.violations[0].other, 0);
}

TEST(Validity, OnlyTabRestrictsTheChecks) {
  Part part = square_base();
  part.add_tab(0, 0, {0.01, 0.015, 0.03, 0, 0, 90 * kDeg});  // too narrow
  part.add_tab(0, 2, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});   // fine
  ValidityOptions o;
  o.only_tab = 2;
  EXPECT_TRUE(check_validity(part, realise(part), spec(), o).valid());
  o.only_tab = 1;
  EXPECT_EQ(check_validity(part, realise(part), spec(), o).first_reason(), ValidityReason::TabTooNarrow);
}

}  // namespace
}  // namespace sheetgen
