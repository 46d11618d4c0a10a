// Web roots (docs/discovery.md "Web roots"): webs hung from the base edges
// stop the clearance above what is below them, are valid with each other and
// unfold, and the chains grow connecting segments from them.
#include "sheetgen/discovery/web_roots.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/realisation.hpp"
#include "sheetgen/part/validity.hpp"
#include "../common/scene_fixture.hpp"

namespace sheetgen {
namespace {

using testing_scenes::quad;

// A 100 x 80 x 60 mm box whose base tab lies at z = 0.3 m; optionally a floor
// (an obstacle, not a rivet area) at z = floor_z; a rivet wall at x = 0.2 m.
Problem scene(double floor_z) {
  Problem p = testing_scenes::base_problem();
  Load& l = p.loads[0];
  l.size = Vec3(0.10, 0.08, 0.06);
  l.center = Vec3(0, 0, 0.3 + 0.5 * p.material.thickness + 0.03);
  testing_scenes::add_rivet_mesh(p, "wall", quad(Vec3(0.2, 0.2, 0.0), Vec3(0, -0.4, 0), Vec3(0, 0, 0.6)));  // normal -x
  if (floor_z > 0) p.meshes.push_back({"floor", quad(Vec3(-0.5, -0.5, floor_z), Vec3(1, 0, 0), Vec3(0, 1, 0)), "<inline>"});
  return p;
}

// The scene, its environment and sheet rules, the base part alone, and its webs.
struct Webs {
  Problem p;
  Environment env;
  SheetSpec spec;
  Part base;
  explicit Webs(double floor_z)
      : p(scene(floor_z)), env(p), spec(SheetSpec::from(p)), base(make_base_part(p.loads[0], 0, p.material.thickness)) {}
  std::vector<Segment> make(const WebRootOptions& o = {}) const { return make_web_roots(base, env, spec, resolve_prior({}, spec), o); }
};

Part with_webs(const Part& base, const std::vector<Segment>& webs) {
  Part part = base;
  for (const Segment& s : webs) part.add_tab(0, s.parent_edge, s.tabs[0].params, -1);
  return part;
}

TEST(WebRoots, HangFromEveryEdgeAndStopTheClearanceAboveTheFloor) {
  const Webs w(0.25);
  const Problem& p = w.p;
  const Environment& env = w.env;
  const SheetSpec& spec = w.spec;
  const std::vector<Segment> webs = w.make();
  ASSERT_EQ(webs.size(), 4u);
  const double gap = 0.3 - 0.25;                                          // m, base to floor
  const double need = 0.5 * p.material.thickness + p.requirements.clearance;  // t/2 + clearance
  for (size_t k = 0; k < webs.size(); ++k) {
    const Segment& s = webs[k];
    EXPECT_EQ(s.parent_edge, static_cast<int>(k));
    EXPECT_EQ(s.parent, -1);
    EXPECT_EQ(s.rivet_area, -1);
    ASSERT_EQ(s.tabs.size(), 1u);
    EXPECT_DOUBLE_EQ(s.tabs[0].params.theta3, -0.5 * M_PI);  // down, away from the load
    const double l = s.tabs[0].params.l;
    // The cast stops t/2 + clearance (+ half a voxel of margin) before the floor.
    EXPECT_LE(l, gap - need);
    EXPECT_GE(l, gap - need - env.voxel_size());
    EXPECT_NEAR(s.area, s.tabs[0].params.w * l, 1e-15);
  }
  const Part part = with_webs(w.base, webs);
  const RealisedPart rp = realise(part);
  for (int i = 1; i < part.size(); ++i)
    for (const Vec3& c : rp.tabs[i].corners) EXPECT_GE(c.z(), 0.25 + need - 1e-9) << "web " << i;
  const ValidityReport v = check_validity(part, rp, env);
  EXPECT_TRUE(v.valid()) << v.summary();
  const FlatPattern flat = unfold(part, spec);
  ASSERT_TRUE(flat.ok()) << flat.message;
  EXPECT_TRUE(check_flat_pattern(flat, spec).valid());
}

TEST(WebRoots, WithNothingBelowAreAsDeepAsTheLongestEdge) {
  const Webs w(0);
  const std::vector<Segment> webs = w.make();
  ASSERT_EQ(webs.size(), 4u);
  for (const Segment& s : webs) EXPECT_DOUBLE_EQ(s.tabs[0].params.l, 0.10);
  WebRootOptions o;
  o.max_depth = 0.03;
  for (const Segment& s : w.make(o)) EXPECT_DOUBLE_EQ(s.tabs[0].params.l, 0.03);
}

TEST(WebRoots, NoneWhereTheFloorLeavesLessThanAMinimumTab) {
  const Webs w(0.29);  // 10 mm below the base: less than min_tab_length (16 mm) + clearance
  EXPECT_TRUE(w.make().empty());
}

// A plate 15 mm under the base's (+x, +y) corner (less than a minimum tab plus
// clearance). Edge 1 (+x side, from (+x, -y) to (+x, +y)) ends at that corner:
// the insets 4.8 and 9.6 mm leave its web over the plate, 19.2 mm clears it
// (its end at y = 20.8 mm, the plate from y = 30 mm). Edge 2 starts at the
// corner, where no inset helps: no web there.
TEST(WebRoots, ANarrowerWebPassesAnObstacleUnderACorner) {
  Problem p = scene(0);
  p.meshes.push_back({"plate", quad(Vec3(0.045, 0.03, 0.285), Vec3(0.03, 0, 0), Vec3(0, 0.03, 0)), "<inline>"});
  const Environment env(p);
  const SheetSpec spec = SheetSpec::from(p);
  const Part base = make_base_part(p.loads[0], 0, p.material.thickness);
  const std::vector<Segment> webs = make_web_roots(base, env, spec, resolve_prior({}, spec));
  const Segment* on1 = nullptr;
  for (const Segment& s : webs) {
    EXPECT_NE(s.parent_edge, 2);
    if (s.parent_edge == 1) on1 = &s;
  }
  ASSERT_NE(on1, nullptr);
  EXPECT_NEAR(on1->tabs[0].params.w, 0.08 - 19.2e-3, 1e-12);
  EXPECT_DOUBLE_EQ(on1->tabs[0].params.l, 0.10);  // nothing below it: the longest base edge
}

TEST(WebRoots, DiscoveryGrowsConnectingSegmentsFromThem) {
  const Problem p = scene(0.25);
  const Environment env(p);
  const SheetSpec spec = SheetSpec::from(p);
  DiscoveryOptions o = DiscoveryOptions::from(p);
  o.chains = 4;
  o.iterations = 150;
  o.threads = 2;
  o.web_roots = true;
  const DiscoveryResult r = discover_segments(p, env, 0, o);
  int webs = 0, from_webs = 0;
  for (const Segment& s : r.library.segments()) {
    if (s.rivet_area < 0) {
      ++webs;
      EXPECT_EQ(s.parent, -1);
      continue;
    }
    const Segment* parent = s.parent >= 0 ? r.library.find(s.parent) : nullptr;
    if (parent && parent->rivet_area < 0) {
      ++from_webs;
      EXPECT_GE(s.parent_edge, 1);  // a free edge of the web (start side, far, end side)
      EXPECT_LE(s.parent_edge, 3);
    }
    // Every connecting segment with its ancestors is a valid part that unfolds.
    std::vector<int> ids;
    for (const Segment* g = &s; g; g = g->parent >= 0 ? r.library.find(g->parent) : nullptr) ids.push_back(g->id);
    const Part part = assemble_part(r.base, r.library, ids);
    EXPECT_TRUE(check_validity(part, realise(part), env).valid()) << "segment " << s.id;
    EXPECT_TRUE(unfold(part, spec).ok()) << "segment " << s.id;
  }
  EXPECT_EQ(webs, 4);
  EXPECT_GE(from_webs, 1);
  EXPECT_GE(r.stats.per_rivet_area.at(0), 1);
}

}  // namespace
}  // namespace sheetgen
