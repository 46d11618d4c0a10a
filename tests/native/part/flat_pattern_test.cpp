// Flat pattern: closed-form numbers for an L bracket, the area identity and
// fold-back consistency on the hand-built parts, and failures for the right
// reason (overlap, relief room, skewed root leaving its edge).
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/core/polygon_geometry.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;

using fixtures::spec;

using fixtures::square_base;

Part l_bracket() {
  Part p = square_base();
  p.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  return p;
}
Part z_bracket() {
  Part p = square_base();
  const int a = p.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, -90 * kDeg});
  p.add_tab(a, kFarEdge, {0.0, 0.02, 0.025, 0, 0, 90 * kDeg});
  return p;
}
Part skewed() {
  Part p = square_base();
  p.add_tab(0, 0, {0.005, 0.02, 0.03, 10 * kDeg, 20 * kDeg, 90 * kDeg});
  return p;
}
Part three_level() {
  Part p = square_base();
  const int t1 = p.add_tab(0, 1, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  const int t2 = p.add_tab(t1, kEndSideEdge, {0.002, 0.02, 0.025, 0, 0, -90 * kDeg});
  p.add_tab(t2, kFarEdge, {0.002, 0.016, 0.02, 0, 0, 45 * kDeg});
  return p;
}

// 90 deg, R = 6.4 mm, K = 0.45, t = 1.6 mm:
// BA = pi/2 (6.4 + 0.72) = 11.184070 mm, SB = tan45 (6.4 + 0.8) = 7.2 mm,
// dL = BA - 2 SB = -3.215930 mm.
TEST(FlatPattern, BendNumbersClosedForm) {
  const SheetSpec s = spec();
  EXPECT_NEAR(bend_allowance(90 * kDeg, s), M_PI / 2 * (6.4e-3 + 0.45 * 1.6e-3), 1e-15);
  EXPECT_NEAR(bend_setback(90 * kDeg, s), 7.2e-3, 1e-15);
  EXPECT_NEAR(bend_length_change(90 * kDeg, s), -3.2159301532203362e-3, 1e-15);
  // K <= 1/2 always shortens: dL = theta (R + K t) - 2 tan(theta/2)(R + t/2) < 0.
  for (double a = 5; a <= 135; a += 5) EXPECT_LT(bend_length_change(a * kDeg, s), 0) << a;
  EXPECT_NEAR(bend_zone_depth(90 * kDeg, s), 8e-3, 1e-15);                       // max(R + t, SB + t/2) = 8 mm
  EXPECT_NEAR(bend_zone_depth(135 * kDeg, s), std::tan(67.5 * kDeg) * 7.2e-3 + 0.8e-3, 1e-15);
}

// L bracket: base 40 x 40 mm plus a 20 x 30 mm tab at d = 10 mm bent 90 deg.
// Flat: the tab lies in y < 0, its far corners at y = -(30 + dL) = -26.784070 mm;
// two reliefs t x 8 mm (depth max(R + t, SB + t/2) = 8 mm) beside the bend;
// area = 1600 + 600 + 20 dL - 2 (1.6 x 8) mm^2 = 2110.081397 mm^2.
TEST(FlatPattern, LBracketNumbers) {
  const SheetSpec s = spec();
  const Part part = l_bracket();
  const FlatPattern flat = unfold(part, s);
  ASSERT_TRUE(flat.ok()) << flat.message;
  const double dL = -3.2159301532203362e-3;
  const FlatPiece& pc = flat.pieces[1];
  EXPECT_LT((pc.polygon[2] - Vec2(0.01, -(0.03 + dL))).norm(), 1e-12);
  EXPECT_LT((pc.polygon[3] - Vec2(0.03, -(0.03 + dL))).norm(), 1e-12);
  EXPECT_LT((pc.polygon[1] - Vec2(0.01, 0)).norm(), 1e-12);  // J0 = P0 (no skew)
  ASSERT_EQ(flat.reliefs.size(), 2u);
  for (const auto& r : flat.reliefs) {
    EXPECT_NEAR(r.width, 1.6e-3, 1e-15);
    EXPECT_NEAR(r.depth, 8e-3, 1e-15);
  }
  const double expected = 1600e-6 + 600e-6 + 0.02 * dL - 2 * 1.6e-3 * 8e-3;
  EXPECT_NEAR(flat.area(), expected, 1e-9 * expected);
  EXPECT_NEAR(flat.area(), 2110.0813969355935e-6, 1e-15);
  // 4 base corners + 3 per relief + J0, F0', F1', J1.
  EXPECT_EQ(flat.outline.size(), 14u);
  // Bend centre line: BA/2 - SB = -1.607965 mm from the edge line along the
  // outward -y, i.e. at y = +1.607965 mm inside the base, 20 mm long, UP.
  ASSERT_EQ(flat.bends.size(), 1u);
  const FlatBend& b = flat.bends[0];
  EXPECT_NEAR(b.a.y(), -(0.5 * 11.184069846779663e-3 - 7.2e-3), 1e-15);
  EXPECT_NEAR((b.b - b.a).norm(), 0.02, 1e-15);
  EXPECT_EQ(b.direction, BendDirection::Up);
  EXPECT_TRUE(check_flat_pattern(flat, s).valid());
}

void expect_consistent(const Part& part, const char* name) {
  const SheetSpec s = spec();
  const RealisedPart rp = realise(part);
  const FlatPattern flat = unfold(part, s);
  ASSERT_TRUE(flat.ok()) << name << ": " << flat.message;
  const ValidityReport overlap = check_flat_pattern(flat, s);
  EXPECT_TRUE(overlap.valid()) << name << ": " << overlap.summary();
  // Area: sum of 3-D tab areas + sum w dL - reliefs (docs/manufacturing.md).
  const double predicted = predicted_flat_area(part, rp, flat, s);
  EXPECT_NEAR(flat.area(), predicted, 1e-9 * predicted) << name;
  // Same prediction recomputed here from first principles.
  double hand = 0;
  for (const auto& t : rp.tabs) hand += std::abs(signed_area(t.local));
  for (int i = 1; i < part.size(); ++i) hand += part.tabs[i].params.w * bend_length_change(part.tabs[i].params.theta3, s);
  for (const auto& r : flat.reliefs) hand -= r.width * r.depth;
  EXPECT_NEAR(flat.area(), hand, 1e-9 * hand) << name;
  // Folding the flat pattern back reproduces the 3-D corners.
  const auto folded = fold_flat_pattern(flat);
  double worst = 0;
  for (int i = 0; i < part.size(); ++i)
    for (size_t k = 0; k < rp.tabs[i].corners.size(); ++k)
      worst = std::max(worst, (folded[i][k] - rp.tabs[i].corners[k]).norm());
  EXPECT_LT(worst, 1e-9) << name;
  std::printf("[ %s ] flat area %.9f mm^2 (predicted %.9f), fold-back error %.3g m, %zu reliefs\n", name,
              flat.area() * 1e6, predicted * 1e6, worst, flat.reliefs.size());
}

TEST(FlatPattern, AreaIdentityAndFoldBack) {
  expect_consistent(l_bracket(), "L bracket");
  expect_consistent(z_bracket(), "Z bracket");
  expect_consistent(skewed(), "skewed trapezoid");
  expect_consistent(three_level(), "three-level tree");
}

// Skewed tab: the flat root slides along the edge by -dL tan(theta2)
// = 3.215930 tan20 = 1.170496 mm, so J0 is at d + 1.170496 mm.
TEST(FlatPattern, SkewedRootSlidesAlongTheEdge) {
  const FlatPattern flat = unfold(skewed(), spec());
  ASSERT_TRUE(flat.ok()) << flat.message;
  EXPECT_NEAR(flat.bends[0].root_a.x(), 0.005 + 3.2159301532203362e-3 * std::tan(20 * kDeg), 1e-15);
  EXPECT_NEAR(flat.bends[0].root_a.y(), 0.0, 1e-15);
}

// A tab whose skew pushes the flat root past the edge start: d = 0, theta2 = -20 deg
// gives a0 = -1.170496 mm.
TEST(FlatPattern, SkewedRootOffTheEdgeIsRejected) {
  Part part = square_base();
  part.add_tab(0, 0, {0.0, 0.02, 0.03, 0, -20 * kDeg, 90 * kDeg});
  const FlatPattern flat = unfold(part, spec());
  EXPECT_EQ(flat.status, ValidityReason::FlatJunctionOutsideEdge) << flat.message;
  EXPECT_EQ(flat.tab, 1);
}

// A bend ending 0.5 mm from the corner leaves no room for a t = 1.6 mm relief.
TEST(FlatPattern, ReliefNeedsRoom) {
  Part part = square_base();
  part.add_tab(0, 0, {0.0005, 0.02, 0.03, 0, 0, 90 * kDeg});
  const FlatPattern flat = unfold(part, spec());
  EXPECT_EQ(flat.status, ValidityReason::ReliefDoesNotFit) << flat.message;
  // At the corner exactly no relief is needed.
  Part corner = square_base();
  corner.add_tab(0, 0, {0.0, 0.02, 0.03, 0, 0, 90 * kDeg});
  const FlatPattern ok = unfold(corner, spec());
  EXPECT_TRUE(ok.ok()) << ok.message;
  EXPECT_EQ(ok.reliefs.size(), 1u);
}

// Overlap: A (up) and B (down) on edge 0; S hangs off A's end side and is bent
// -90 deg, away from everything in 3-D (>= 12 mm from B and the base), but in
// the flat S (x 18..39.8 mm, y -24.8..-8.8 mm) lies on B's flat (x 24..40 mm).
Part overlapping() {
  Part p = square_base();
  const int a = p.add_tab(0, 0, {0.002, 0.016, 0.03, 0, 0, 90 * kDeg});
  p.add_tab(0, 0, {0.024, 0.016, 0.03, 0, 0, -90 * kDeg});
  p.add_tab(a, kEndSideEdge, {0.002, 0.016, 0.025, 0, 0, -90 * kDeg});
  return p;
}

TEST(FlatPattern, OverlapIsFound) {
  const SheetSpec s = spec();
  const Part part = overlapping();
  const RealisedPart rp = realise(part);
  const ValidityReport in3d = check_validity(part, rp, s);
  EXPECT_TRUE(in3d.valid()) << "the 3-D part itself is fine: " << in3d.summary();
  const FlatPattern flat = unfold(part, s);
  ASSERT_TRUE(flat.ok()) << flat.message;
  ValidityOptions all;
  all.stop_at_first = false;
  const ValidityReport r = check_flat_pattern(flat, s, all);
  ASSERT_FALSE(r.valid());
  EXPECT_EQ(r.first_reason(), ValidityReason::FlatPatternOverlap);
  bool s_and_b = false;
  for (const auto& v : r.violations) s_and_b |= (v.tab == 3 && v.other == 2);
  EXPECT_TRUE(s_and_b) << r.summary();
  // Sanity of the claim in the comment: the crossing pieces really share area.
  const auto inter = clip_convex(flat.pieces[3].polygon, flat.pieces[2].polygon);
  EXPECT_GT(signed_area(inter), 100e-6);  // > 100 mm^2 of S lies on B
}

}  // namespace
}  // namespace sheetgen
