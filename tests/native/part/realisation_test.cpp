// Realisation of hand-built parts against coordinates computed by hand
// (docs/grammar.md gives the formulas; every expected number below is derived
// in the comment above it).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "sheetgen/core/geometry.hpp"
#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

constexpr double kTol = 1e-12;  // m; the formulas are a few flops deep
using fixtures::kDeg;

// Base: 40 mm x 40 mm square in z = 0, top normal +z, corners
// (0,0) (40,0) (40,40) (0,40) mm. Edge 0 runs +x along y = 0 (outward -y),
// edge 1 runs +y along x = 40 (outward +x).
using fixtures::square_base;

void expect_near(const Vec3& got, const Vec3& want, const char* what) {
  EXPECT_LT((got - want).norm(), kTol) << what << ": got " << got.transpose() << " want " << want.transpose();
}

TEST(Realisation, BaseFromLoadTouchesTheBoxBottom) {
  Load load;
  load.center = Vec3(0.02, 0.02, 0.0108);
  load.size = Vec3(0.04, 0.04, 0.02);  // bottom face at z = 0.0008 = t/2
  const Part part = make_base_part(load, 0, 1.6e-3);
  const RealisedPart rp = realise(part);
  ASSERT_EQ(rp.tabs[0].corners.size(), 4u);
  // Corners (-x,-y), (+x,-y), (+x,+y), (-x,+y) of the box, t/2 below its bottom.
  expect_near(rp.tabs[0].corners[0], Vec3(0, 0, 0), "c0");
  expect_near(rp.tabs[0].corners[1], Vec3(0.04, 0, 0), "c1");
  expect_near(rp.tabs[0].corners[2], Vec3(0.04, 0.04, 0), "c2");
  expect_near(rp.tabs[0].corners[3], Vec3(0, 0.04, 0), "c3");
  expect_near(rp.tabs[0].normal, Vec3::UnitZ(), "normal");
  EXPECT_EQ(rp.free_edges().size(), 4u);
}

// L bracket: one tab on edge 0, d = 10, w = 20, l = 30 mm, theta3 = +90 deg.
// e = +x, o = e x n = -y, v = cos90 o + sin90 n = +z, normal = cos90 n - sin90 o = +y.
// P0 = (10,0,0), P1 = (30,0,0), F0 = (10,0,30), F1 = (30,0,30) mm.
TEST(Realisation, LBracket) {
  Part part = square_base();
  part.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  const RealisedPart rp = realise(part);
  const auto& c = rp.tabs[1].corners;
  expect_near(c[0], Vec3(0.03, 0, 0), "P1");
  expect_near(c[1], Vec3(0.01, 0, 0), "P0");
  expect_near(c[2], Vec3(0.01, 0, 0.03), "F0");
  expect_near(c[3], Vec3(0.03, 0, 0.03), "F1");
  expect_near(rp.tabs[1].normal, Vec3::UnitY(), "normal");
  EXPECT_EQ(rp.tabs[1].direction, BendDirection::Up);
  // Three new free edges: 4 (base) + 3.
  EXPECT_EQ(rp.free_edges().size(), 7u);
}

// Z bracket: A on edge 0 bent -90 deg (down): v = -z, normal = +o = -y;
// A: P0 (10,0,0) P1 (30,0,0) F0 (10,0,-30) F1 (30,0,-30) mm.
// B on A's far edge (F0 -> F1, e = +x), d = 0, w = 20, l = 25, +90 deg:
// o = x X (-y) = -z, v = n_A = -y, normal = -o = +z (parallel to the base, like a Z).
// B: P0 (10,0,-30) P1 (30,0,-30) F0 (10,-25,-30) F1 (30,-25,-30) mm.
TEST(Realisation, ZBracket) {
  Part part = square_base();
  const int a = part.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, -90 * kDeg});
  part.add_tab(a, kFarEdge, {0.0, 0.02, 0.025, 0, 0, 90 * kDeg});
  const RealisedPart rp = realise(part);
  expect_near(rp.tabs[1].corners[2], Vec3(0.01, 0, -0.03), "A.F0");
  expect_near(rp.tabs[1].normal, -Vec3::UnitY(), "A.normal");
  EXPECT_EQ(rp.tabs[1].direction, BendDirection::Down);
  const auto& c = rp.tabs[2].corners;
  expect_near(c[0], Vec3(0.03, 0, -0.03), "B.P1");
  expect_near(c[1], Vec3(0.01, 0, -0.03), "B.P0");
  expect_near(c[2], Vec3(0.01, -0.025, -0.03), "B.F0");
  expect_near(c[3], Vec3(0.03, -0.025, -0.03), "B.F1");
  expect_near(rp.tabs[2].normal, Vec3::UnitZ(), "B.normal");
}

// Skewed trapezoid: edge 0, d = 5, w = 20, l = 30 mm, theta1 = 10, theta2 = 20,
// theta3 = 90 deg. Local: M1 = (w/2 + l tan20, l) = (20.9191070, 30);
// h = w cos20 / (2 cos30) = 10.8509...; F0,1 = M1 -/+ h (cos10, sin10)
// = (10.2333168, 28.1158069), (31.6048972, 31.8841931) mm (local x, y).
// In 3-D x -> +x from (5,0,0), y -> +z.
TEST(Realisation, SkewedTrapezoid) {
  Part part = square_base();
  part.add_tab(0, 0, {0.005, 0.02, 0.03, 10 * kDeg, 20 * kDeg, 90 * kDeg});
  const RealisedPart rp = realise(part);
  const auto& c = rp.tabs[1].corners;
  expect_near(c[0], Vec3(0.025, 0, 0), "P1");
  expect_near(c[1], Vec3(0.005, 0, 0), "P0");
  expect_near(c[2], Vec3(0.015233316814969783, 0, 0.02811580687525477), "F0");
  expect_near(c[3], Vec3(0.036604897241002354, 0, 0.031884193124745226), "F1");
  // Sides parallel to the skewed centre line (tan20 run per unit rise), far
  // edge at 10 deg, area w * l (rotating the far edge about its midpoint adds
  // and removes two equal triangles).
  const Vec3 s0 = c[2] - c[1], s1 = c[3] - c[0];
  EXPECT_NEAR(s0.x() / s0.z(), std::tan(20 * kDeg), 1e-12);
  EXPECT_NEAR(s1.x() / s1.z(), std::tan(20 * kDeg), 1e-12);
  const Vec3 far = c[3] - c[2];
  EXPECT_NEAR(std::atan2(far.z(), far.x()), 10 * kDeg, 1e-12);
  EXPECT_NEAR(polygon_area(c), 0.02 * 0.03, 1e-15);
  EXPECT_FALSE(rp.tabs[1].degenerate);
}

// Three-level tree:
// T1 on base edge 1 (e = +y, o = +x), d 10 w 20 l 30, +90: v = +z, normal = -x;
//   P0 (40,10,0) P1 (40,30,0) F0 (40,10,30) F1 (40,30,30).
// T2 on T1's end side (edge 3, F1 -> P1, e = -z, o = e x n1 = +y), d 2 w 20 l 25, -90:
//   v = -n1 = +x, normal = +o = +y;
//   P0 (40,30,28) P1 (40,30,8) F0 (65,30,28) F1 (65,30,8).
// T3 on T2's far edge (F0 -> F1, e = -z, o = e x n2 = +x), d 2 w 16 l 20, +45:
//   v = (x + y)/sqrt2, normal = (n2 - o)/sqrt2 = (-x + y)/sqrt2;
//   P0 (65,30,26) P1 (65,30,10) F0 = P0 + 20 v, F1 = P1 + 20 v.
TEST(Realisation, ThreeLevelTree) {
  Part part = square_base();
  const int t1 = part.add_tab(0, 1, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  const int t2 = part.add_tab(t1, kEndSideEdge, {0.002, 0.02, 0.025, 0, 0, -90 * kDeg});
  const int t3 = part.add_tab(t2, kFarEdge, {0.002, 0.016, 0.02, 0, 0, 45 * kDeg});
  const RealisedPart rp = realise(part);
  expect_near(rp.tabs[t1].corners[1], Vec3(0.04, 0.01, 0), "T1.P0");
  expect_near(rp.tabs[t1].corners[3], Vec3(0.04, 0.03, 0.03), "T1.F1");
  expect_near(rp.tabs[t1].normal, -Vec3::UnitX(), "T1.normal");
  expect_near(rp.tabs[t2].corners[0], Vec3(0.04, 0.03, 0.008), "T2.P1");
  expect_near(rp.tabs[t2].corners[1], Vec3(0.04, 0.03, 0.028), "T2.P0");
  expect_near(rp.tabs[t2].corners[2], Vec3(0.065, 0.03, 0.028), "T2.F0");
  expect_near(rp.tabs[t2].corners[3], Vec3(0.065, 0.03, 0.008), "T2.F1");
  expect_near(rp.tabs[t2].normal, Vec3::UnitY(), "T2.normal");
  const double r = 0.02 / std::sqrt(2.0);
  expect_near(rp.tabs[t3].corners[0], Vec3(0.065, 0.03, 0.010), "T3.P1");
  expect_near(rp.tabs[t3].corners[1], Vec3(0.065, 0.03, 0.026), "T3.P0");
  expect_near(rp.tabs[t3].corners[2], Vec3(0.065 + r, 0.03 + r, 0.026), "T3.F0");
  expect_near(rp.tabs[t3].corners[3], Vec3(0.065 + r, 0.03 + r, 0.010), "T3.F1");
  expect_near(rp.tabs[t3].normal, Vec3(-1, 1, 0).normalized(), "T3.normal");
  EXPECT_EQ(part.depth(t3), 3);
}

TEST(Realisation, CopiesAreIndependentAndRealiseIsPure) {
  Part a = square_base();
  a.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, 90 * kDeg});
  Part b = a;
  b.tabs[1].params.theta3 = -90 * kDeg;
  const RealisedPart ra = realise(a), rb = realise(b), ra2 = realise(a);
  EXPECT_NEAR(ra.tabs[1].corners[2].z(), 0.03, kTol);
  EXPECT_NEAR(rb.tabs[1].corners[2].z(), -0.03, kTol);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(ra.tabs[1].corners[k], ra2.tabs[1].corners[k]);
}

// realise_path_into sets the base and the tabs from it to one tab as
// realise_into does, bit for bit, and leaves the part's other tabs alone.
TEST(Realisation, APathIsRealisedAsTheWholePartRealisesIt) {
  Part part = square_base();
  const int t1 = part.add_tab(0, 1, {0.01, 0.02, 0.03, 0.1, 0.05, 70 * kDeg});
  const int side = part.add_tab(0, 3, {0.005, 0.02, 0.02, 0, 0, -40 * kDeg});
  const int t2 = part.add_tab(t1, kEndSideEdge, {0.002, 0.02, 0.025, 0, -0.1, -95 * kDeg});
  const int t3 = part.add_tab(t2, kFarEdge, {0.002, 0.016, 0.02, 0, 0, 45 * kDeg});
  RealiseOptions o;
  o.angles = {0, 30 * kDeg, 10 * kDeg, -60 * kDeg, 45 * kDeg};
  for (const RealiseOptions& options : {RealiseOptions{}, o}) {
    const RealisedPart whole = realise(part, options);
    RealisedPart path;
    path.tabs.resize(part.size());
    path.tabs[side].corners = {Vec3(7, 7, 7)};  // a marker the call must not touch
    realise_path_into(part, t3, path, options);
    for (int i : {0, t1, t2, t3}) {
      ASSERT_EQ(path.tabs[i].corners.size(), whole.tabs[i].corners.size());
      for (size_t k = 0; k < whole.tabs[i].corners.size(); ++k)
        EXPECT_EQ(path.tabs[i].corners[k], whole.tabs[i].corners[k]) << "tab " << i << " corner " << k;
      EXPECT_EQ(path.tabs[i].normal, whole.tabs[i].normal);
      EXPECT_EQ(path.tabs[i].origin, whole.tabs[i].origin);
    }
    ASSERT_EQ(path.tabs[side].corners.size(), 1u);
    EXPECT_EQ(path.tabs[side].corners[0], Vec3(7, 7, 7));
  }
  EXPECT_THROW(realise_path_into(part, part.size(), *std::make_unique<RealisedPart>()), std::invalid_argument);
}

TEST(Realisation, MalformedTreeThrows) {
  Part part = square_base();
  EXPECT_THROW(part.add_tab(0, 7, {}), std::invalid_argument);
  EXPECT_THROW(part.add_tab(3, 0, {}), std::invalid_argument);
  part.add_tab(0, 0, {0.01, 0.02, 0.03, 0, 0, 1.0});
  EXPECT_THROW(part.add_tab(1, kRootEdge, {}), std::invalid_argument);
  part.tabs[1].parent = 1;  // a tab cannot be its own parent
  EXPECT_THROW(realise(part), std::invalid_argument);
}

}  // namespace
}  // namespace sheetgen
