// Contraction of a zig-zag feeler and widening against a wall.
#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/discovery/segment_optimiser.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/validity.hpp"
#include "../common/scene_fixture.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using namespace testing_scenes;
using fixtures::kDeg;

// A rivet wall in the plane x = -0.2 m facing +x (towards the base at x 0..0.04).
Problem wall_problem() {
  Problem p = base_problem();
  add_rivet_mesh(p, "wall", quad(Vec3(-0.2, -0.2, -0.2), Vec3(0, 0.4, 0), Vec3(0, 0, 0.4)));
  return p;
}

RivetPlane wall_plane() { return {0, Vec3(-0.2, 0, 0), Vec3(1, 0, 0)}; }

// A segment to the wall that holds only the base tab so far; each test adds its own feeler tabs.
SegmentWork wall_segment(const Problem& problem, const SheetSpec& spec) {
  SegmentWork w;
  w.plane = wall_plane();
  w.part = make_base_part(problem.loads[0], 0, spec.thickness);
  w.first = 1;
  return w;
}

TEST(SegmentOptimiser, ContractionShortensZigZagAndStaysValid) {
  const Problem problem = wall_problem();
  const Environment env(problem);
  const SheetSpec spec = SheetSpec::from(problem);
  SegmentWork w = wall_segment(problem, spec);
  // Zig-zag from base edge 3 (the -x side): up 30 deg for 60 mm, then down 60 deg to the wall.
  const int a = w.part.add_tab(0, 3, {0.012, 0.016, 0.06, 0, 0, 30 * kDeg});
  const int b = w.part.add_tab(a, kFarEdge, {0.0, 0.016, 0.05, 0, 0, -60 * kDeg});
  w.flange = attach_flange(w.part, b, w.plane, spec);
  ASSERT_EQ(w.flange, 3);
  ASSERT_TRUE(check_validity(w.part, realise(w.part), env).valid()) << check_validity(w.part, realise(w.part), env).summary();
  ContractOptions o;
  o.record_states = true;
  const ContractResult r = contract_segment(w, env, spec, o);
  // Before: 60 + the second leg down from z = 30 mm at x = -52 mm to the wall: about 170 mm.
  std::printf("contraction: %.1f mm -> %.1f mm in %d steps\n", r.length_before * 1e3, r.length_after * 1e3, r.steps);
  ASSERT_GT(r.steps, 0);
  // Strictly decreasing, every intermediate state valid and attached.
  double prev = r.length_before;
  for (size_t k = 0; k < r.states.size(); ++k) {
    EXPECT_LT(r.lengths[k], prev);
    prev = r.lengths[k];
    const ValidityReport v = check_validity(r.states[k], realise(r.states[k]), env);
    EXPECT_TRUE(v.valid()) << "state " << k << ": " << v.summary();
    EXPECT_EQ(r.states[k].tabs.back().rivet_area, 0);
  }
  // Lower bound: the far edge lies on x = -0.2 + t/2, so the summed perpendicular
  // lengths of unskewed tabs cannot be below 0.2 - t/2 m. The zig-zag gains at least 10 %.
  EXPECT_GE(r.length_after, 0.2 - spec.thickness / 2 - 1e-9);
  EXPECT_LT(r.length_after, 0.9 * r.length_before);
}

// The whole Sec. 4.2 pipeline as discovery runs it on a three-tab zig-zag feeler
// route to the wall: re-aiming (shortcut), contraction, merging, widening.
TEST(SegmentOptimiser, ZigZagBecomesShortAndWide) {
  const Problem problem = wall_problem();
  const Environment env(problem);
  const SheetSpec spec = SheetSpec::from(problem);
  SegmentWork w = wall_segment(problem, spec);
  // From base edge 3 (x = 0, y 0..40 mm): up 40 deg for 80 mm, down 80 deg for 60 mm, up 50 deg to the wall.
  const int a = w.part.add_tab(0, 3, {0.012, 0.016, 0.08, 0, 0, 40 * kDeg});
  const int b = w.part.add_tab(a, kFarEdge, {0.0, 0.016, 0.06, 0, 0, -80 * kDeg});
  const int c = w.part.add_tab(b, kFarEdge, {0.0, 0.016, 0.05, 0, 0, 50 * kDeg});
  w.flange = attach_flange(w.part, c, w.plane, spec);
  ASSERT_EQ(w.flange, 4);
  ASSERT_TRUE(segment_valid(w, env, spec)) << check_validity(w.part, realise(w.part), env).summary();
  const double raw = w.length();
  const ShortcutResult sr = shortcut_segment(w, env, spec);
  const ContractResult cr = contract_segment(w, env, spec);
  if (merge_coplanar(w, env, spec) > 0) contract_segment(w, env, spec);
  const WidenResult wr = widen_segment(w, env, spec);
  double w_min = 1;
  for (int i = w.first; i < w.flange; ++i) w_min = std::min(w_min, w.part.tabs[i].params.w);
  // Straight-line distance from the root edge (x = 0) to the far edge's plane x = -0.2 + t/2.
  const double straight = 0.2 - spec.thickness / 2;
  std::printf("zig-zag: %d tabs %.1f mm -> shortcut %d tabs %.1f mm -> contraction %.1f mm (%d steps); "
              "straight %.1f mm; narrowest tab %.1f mm, area %.0f -> %.0f mm^2\n",
              3, raw * 1e3, w.feeler_count(), sr.length_after * 1e3, cr.length_after * 1e3, cr.steps, straight * 1e3,
              w_min * 1e3, wr.area_before * 1e6, wr.area_after * 1e6);
  EXPECT_TRUE(segment_valid(w, env, spec));
  EXPECT_EQ(w.part.tabs[w.flange].rivet_area, 0);
  // Short: one tab bent by theta3 >= min_bend_angle (5 deg) must be at least straight / cos(5 deg)
  // = 1.004 x straight long; 1.05 leaves room for the contraction's 0.1 mm stopping step and the
  // bend geometry, and is well below the raw zig-zag (233 mm = 1.17 x straight).
  EXPECT_GT(raw, 1.15 * straight);
  EXPECT_LT(w.feeler_count(), 3);
  EXPECT_LE(w.length(), 1.05 * straight);
  EXPECT_GE(w.length(), straight - 1e-9);
  // Wide: nothing is in the way, so every tab widens over most of its 40 mm parent edge; at least
  // twice w_min (32 mm) allows for the 2 mm minimum widening step and the bend relief rules.
  EXPECT_GE(w_min, 2 * spec.manufacturing.min_tab_width);
  EXPECT_GT(wr.area_after, 2 * wr.area_before);
}

TEST(SegmentOptimiser, WideningStopsAtAWall) {
  Problem problem = wall_problem();
  // A plain plate (not a rivet area) in the plane y = 32 mm beside the tab's path.
  problem.meshes.push_back({"plate", quad(Vec3(-0.15, 0.032, -0.2), Vec3(0.145, 0, 0), Vec3(0, 0, 0.25)), "<inline>"});
  const Environment env(problem);
  const SheetSpec spec = SheetSpec::from(problem);
  SegmentWork w = wall_segment(problem, spec);
  // Base edge 3 runs from (0, 40) to (0, 0) mm: d = 12 mm puts the tab at y 12..28 mm.
  const int a = w.part.add_tab(0, 3, {0.012, 0.016, 0.05, 0, 0, -30 * kDeg});
  w.flange = attach_flange(w.part, a, w.plane, spec);
  ASSERT_GE(w.flange, 0);
  ASSERT_TRUE(check_validity(w.part, realise(w.part), env).valid()) << check_validity(w.part, realise(w.part), env).summary();
  ASSERT_TRUE(segment_valid(w, env, spec));
  const WidenResult r = widen_segment(w, env, spec);
  const TabParameters& p = w.part.tabs[1].params;
  std::printf("widening: d %.2f mm, w %.2f mm (y %.2f..%.2f), area %.0f -> %.0f mm^2\n", p.d * 1e3, p.w * 1e3,
              (0.04 - p.d - p.w) * 1e3, (0.04 - p.d) * 1e3, r.area_before * 1e6, r.area_after * 1e6);
  EXPECT_GT(r.steps, 0);
  EXPECT_GT(p.w, 0.016);
  // The -y side is free: it reaches the end of the base edge (y = 0) to within the 2 mm minimum step.
  EXPECT_GE(p.d + p.w, 0.04 - 2e-3 - 1e-9);
  // The +y side stops before the plate: y = 40 - d keeps t/2 + clearance = 1.8 mm from y = 32 mm.
  EXPECT_LE(0.04 - p.d, 0.032 - 1.8e-3 + 1e-6);
  EXPECT_LT(p.d, 0.012);  // it did grow towards the plate
  // One more millimetre towards the plate collides.
  Part more = w.part;
  more.tabs[1].params.d -= 2e-3;
  more.tabs[1].params.w += 2e-3;
  EXPECT_FALSE(check_validity(more, realise(more), env).valid());
  EXPECT_TRUE(segment_valid(w, env, spec));
}

}  // namespace
}  // namespace sheetgen
