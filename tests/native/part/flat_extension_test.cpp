// Flat extensions (theta3 = 0, docs/grammar.md "Flat extensions"): a tab that
// continues its parent's plane is cut in one piece with it. Closed-form flat
// areas, no bend line, bend number, relief or bend-sequence step of its own,
// and the same part whether a plate is one tab or two flat ones.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "sheetgen/part/bend_sequence.hpp"
#include "sheetgen/part/exports.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/core/polygon_geometry.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;

SheetSpec spec(bool flat_extensions) {
  SheetSpec s = fixtures::aluminium_sheet_1_6mm();
  s.manufacturing.flat_extensions = flat_extensions;
  return s;
}

using fixtures::square_base;

// 40 x 40 mm base; on its -y edge a full-width 40 x 20 mm flat extension; on
// the extension's far edge a 20 x 30 mm tab bent 90 deg at d = 10 mm.
Part extended_l_bracket() {
  Part p = square_base();
  const int e = p.add_tab(0, 0, {0.0, 0.04, 0.02, 0, 0, 0.0});
  p.add_tab(e, kFarEdge, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  return p;
}

TEST(FlatExtension, ValidOnlyWhereTheManufacturingSettingsAllowIt) {
  const Part part = extended_l_bracket();
  const RealisedPart rp = realise(part);
  // In the parent's plane, 20 mm beyond the edge.
  for (const Vec3& c : rp.tabs[1].corners) EXPECT_NEAR(c.z(), 0.0, 1e-15);
  EXPECT_NEAR(rp.tabs[1].corners[2].y(), -0.02, 1e-15);
  const ValidityReport off = check_validity(part, rp, spec(false));
  ASSERT_FALSE(off.valid());
  EXPECT_EQ(off.violations[0].reason, ValidityReason::BendAngleTooSmall);
  EXPECT_EQ(off.violations[0].tab, 1);
  const ValidityReport on = check_validity(part, rp, spec(true));
  EXPECT_TRUE(on.valid()) << on.summary();
  EXPECT_EQ(part.bend_count(), 1);
  // A bend of 1 deg is still a bend below the minimum, flat extensions or not.
  Part slight = part;
  slight.tabs[1].params.theta3 = 1 * kDeg;
  EXPECT_EQ(check_validity(slight, realise(slight), spec(true)).violations.at(0).reason, ValidityReason::BendAngleTooSmall);
}

// dL of the 90 deg bend = -3.215930 mm (flat_pattern_test.cpp). The extension
// adds its 800 mm^2 exactly, with no relief: area = 1600 + 800 + 600 + 20 dL
// - 2 (1.6 x 8) mm^2 (the bent tab's two reliefs, cut into the extension).
TEST(FlatExtension, FlatPatternAddsTheExtensionWithoutBendOrRelief) {
  const SheetSpec s = spec(true);
  const Part part = extended_l_bracket();
  const FlatPattern flat = unfold(part, s);
  ASSERT_TRUE(flat.ok()) << flat.message;
  EXPECT_TRUE(check_flat_pattern(flat, s).valid());
  const double dL = -3.2159301532203362e-3;
  EXPECT_NEAR(flat.area(), 1600e-6 + 800e-6 + 600e-6 + 0.02 * dL - 2 * 1.6e-3 * 8e-3, 1e-15);
  ASSERT_EQ(flat.bends.size(), 1u);
  EXPECT_EQ(flat.bends[0].tab, 2);
  ASSERT_EQ(flat.reliefs.size(), 2u);
  for (const FlatRelief& r : flat.reliefs) EXPECT_EQ(r.parent, 1);
  // The extension's flat piece is the tab itself, not shifted.
  const FlatPiece& pc = flat.pieces[1];
  EXPECT_EQ(pc.shift, 0.0);
  EXPECT_LT((pc.polygon[2] - Vec2(0.0, -0.02)).norm(), 1e-15);
  EXPECT_LT((pc.polygon[3] - Vec2(0.04, -0.02)).norm(), 1e-15);
  // The cut contour has no relief notch at the extension's root: on the line
  // y = 0 lie only the base corners (0,0) and (0.04,0), where its sides start.
  int at_root = 0;
  for (const Vec2& q : flat.outline) at_root += std::abs(q.y()) < 1e-12 ? 1 : 0;
  EXPECT_EQ(at_root, 2);
  // Folding the plan back gives the realised part.
  const RealisedPart rp = realise(part);
  const auto folded = fold_flat_pattern(flat);
  for (int i = 0; i < part.size(); ++i)
    for (size_t k = 0; k < rp.tabs[i].corners.size(); ++k)
      EXPECT_LT((folded[i][k] - rp.tabs[i].corners[k]).norm(), 1e-12) << "tab " << i << " corner " << k;
}

TEST(FlatExtension, BendTableNumbersAndSequenceCountOnlyRealBends) {
  const SheetSpec s = spec(true);
  const Part part = extended_l_bracket();
  const FlatPattern flat = unfold(part, s);
  const std::vector<int> number = bend_numbers(flat, {});
  EXPECT_EQ(number, (std::vector<int>{0, 0, 1}));
  const std::string csv = bend_table_csv(flat);
  EXPECT_EQ(csv, "order,angle_deg,direction,inside_radius_mm,length_mm,tab,punch,die,turned_over\n1,90.000000,UP,6.400000,20.000000,2,,,\n");
  const BendSequenceResult seq = plan_bend_sequence(part, s);
  ASSERT_TRUE(seq.ok()) << seq.message;
  EXPECT_EQ(seq.order, (std::vector<int>{2}));
  EXPECT_TRUE(check_bend_order(part, {2}, s).ok());
  EXPECT_THROW(check_bend_order(part, {1, 2}, s), std::invalid_argument);
  const auto dxf = flat_pattern_dxf(flat);
  size_t lines = 0;  // entities on a bend layer (the layer table before ENTITIES names them too)
  for (size_t at = dxf.find("BEND_", dxf.find("ENTITIES")); at != std::string::npos; at = dxf.find("BEND_", at + 1)) ++lines;
  EXPECT_EQ(lines, 1u);  // one bend line, on BEND_UP
}

// A 40 mm plate as one flat extension or as two 20 mm ones in a row: the same
// bent part and the same flat area (the joint between them is no cut and no bend).
TEST(FlatExtension, TwoFlatTabsInARowAreOnePlate) {
  const SheetSpec s = spec(true);
  Part one = square_base();
  const int e = one.add_tab(0, 0, {0.0, 0.04, 0.04, 0, 0, 0.0});
  one.add_tab(e, kFarEdge, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  Part two = square_base();
  const int a = two.add_tab(0, 0, {0.0, 0.04, 0.02, 0, 0, 0.0});
  const int b = two.add_tab(a, kFarEdge, {0.0, 0.04, 0.02, 0, 0, 0.0});
  two.add_tab(b, kFarEdge, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  EXPECT_TRUE(check_validity(one, realise(one), s).valid());
  EXPECT_TRUE(check_validity(two, realise(two), s).valid()) << check_validity(two, realise(two), s).summary();
  const RealisedPart r1 = realise(one), r2 = realise(two);
  for (int k = 0; k < 4; ++k) EXPECT_LT((r1.tabs[2].corners[k] - r2.tabs[3].corners[k]).norm(), 1e-15);
  const FlatPattern f1 = unfold(one, s), f2 = unfold(two, s);
  ASSERT_TRUE(f2.ok()) << f2.message;
  EXPECT_NEAR(f2.area(), f1.area(), 1e-15);
  EXPECT_EQ(two.bend_count(), 1);
}

}  // namespace
}  // namespace sheetgen
