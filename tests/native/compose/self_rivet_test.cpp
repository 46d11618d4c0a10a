// Self-riveting (paper Sec. 5.2): the visibility of free-edge pairs and the
// gusset that joins them, on hand-built parts with known geometry.
#include "sheetgen/compose/self_rivet.hpp"

#include <gtest/gtest.h>

#include "sheet_rules.hpp"

#include "sheetgen/env/environment.hpp"
#include "sheetgen/core/polygon_geometry.hpp"
#include "sheetgen/part/validity.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {
namespace {

// The paper's Fig. 9: a light box against a wall (x = 0), far above the floor.
// A springboard: the base under the box, cantilevered from one flange bent
// down 90 deg onto the wall.
Problem wall_problem() {
  Problem p;
  p.source = "<test>";
  EnvironmentMesh wall;
  wall.name = "wall";
  wall.mesh.vertices = {Vec3(0, -0.3, 0), Vec3(0, 0.3, 0), Vec3(0, 0.3, 0.8), Vec3(0, -0.3, 0.8)};
  wall.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};  // normal +x
  p.meshes.push_back(wall);
  p.rivet_areas.push_back(RivetAreaSpec{"wall", 0, {0, 1}, 0.48});
  Load l;
  l.name = "box";
  l.center = Vec3(0.05 + 0.8e-3, 0, 0.6);  // base's -x edge at x = t/2: its flange lies on the wall
  l.size = Vec3(0.1, 0.1, 0.06);
  l.force = Vec3(0, 0, -30);
  p.loads.push_back(l);
  testing::set_sheet_rules(p);
  return p;
}

Part springboard(const Problem& p) {
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  // Base edge 3 is the -x side (docs/grammar.md); theta3 < 0 folds away from the
  // base's top normal (+z), i.e. down, into the plane x = t/2 of the wall.
  part.add_tab(0, 3, TabParameters{0.0, 0.1, 0.06, 0, 0, -M_PI / 2}, 0);
  return part;
}

TEST(SelfRivet, FullWidthTabsMakeVisibleSideEdges) {
  const Problem p = wall_problem();
  const Part part = springboard(p);
  const RealisedPart rp = realise(part);
  // Flange flush on the wall (mid-surface at x = t/2).
  for (const Vec3& c : rp.tabs[1].corners) EXPECT_NEAR(c.x(), 0.5 * p.material.thickness, 1e-9);
  const auto pairs = visible_edge_pairs(part, rp, p.material.thickness);
  ASSERT_FALSE(pairs.empty());
  // The invariant of visibility: all four endpoints in the common plane (to the
  // stacking tolerance 1.5 t), and the two tabs not in one plane.
  bool side_plane = false;
  for (const auto& pr : pairs) {
    for (const Vec3& q : {pr.a.b, pr.b.a, pr.b.b}) EXPECT_LE(std::abs((q - pr.a.a).dot(pr.plane_normal)), 1.5 * p.material.thickness + 1e-12);
    side_plane = side_plane || (std::abs(pr.plane_normal.y()) > 1 - 1e-9 && std::abs(pr.a.a.y() - pr.b.a.y()) < 1e-9);
  }
  EXPECT_TRUE(side_plane);  // the base's and the flange's side edges in y = +-0.05
}

TEST(SelfRivet, GussetTiesTheBaseToItsFlangeAndStiffensTheSpringboard) {
  const Problem p = wall_problem();
  const Part part = springboard(p);
  const RealisedPart rp = realise(part);
  const Environment env(p);
  ValidityOptions vo;
  ASSERT_TRUE(check_validity(part, rp, env, vo).valid()) << check_validity(part, rp, env, vo).summary();
  const StructuralResult plain = analyse_part(p, 0, plate_geometry(part, rp));
  // The base (tab 0) and the flange (tab 1): their side edges share the plane y = -0.05 (and +0.05).
  const auto pairs = visible_edge_pairs(part, rp, p.material.thickness);
  const VisiblePair* base_foot = nullptr;
  for (const auto& pr : pairs)
    if (((pr.a.tab == 0 && pr.b.tab == 1) || (pr.a.tab == 1 && pr.b.tab == 0)) && std::abs(pr.plane_normal.y()) > 1 - 1e-9) base_foot = &pr;
  ASSERT_NE(base_foot, nullptr);
  const auto plans = gusset_plans(part, rp, *base_foot, p);
  ASSERT_FALSE(plans.empty());
  int tried = 0;
  for (const auto& plan : plans) {
    const RealisedPart grp = realise(plan.part);
    const ValidityReport rep = check_validity(plan.part, grp, env, vo);
    if (!rep.valid()) {
      std::printf("gusset +%.1f cm^2 rejected: %s\n", plan.added_area * 1e4, rep.summary().c_str());
      continue;
    }
    ++tried;
    PartModelOptions mo;
    for (size_t r = 0; r < plan.rivets_a.size(); ++r)
      mo.self_rivets.push_back(SelfRivetTie{plan.tab_a, plan.tab_b, plan.rivets_a[r], plan.rivets_b[r]});
    const StructuralResult riveted = analyse_part(p, 0, plate_geometry(plan.part, grp), mo);
    const StructuralResult loose = analyse_part(p, 0, plate_geometry(plan.part, grp));  // gussets, not riveted
    std::printf("gusset +%.1f cm^2, %zu rivets: compliance %.4g J, with loose gussets %.4g J, riveted %.4g J\n",
                plan.added_area * 1e4, plan.rivets_a.size(), plain.compliance, loose.compliance, riveted.compliance);
    // Linear elasticity: adding material or ties can only lower the compliance f^T u;
    // the rivets are what makes the gusset a brace.
    EXPECT_LE(loose.compliance, plain.compliance * (1 + 1e-9));
    EXPECT_LT(riveted.compliance, 0.7 * loose.compliance);
    // Both gusset tabs lie in y = -0.05 (within the stacking tolerance) and overlap where the rivets are.
    for (int g : {plan.tab_a, plan.tab_b})
      for (const Vec3& c : grp.tabs[g].corners) EXPECT_NEAR(std::abs(c.y()), 0.05, 1.5 * p.material.thickness + 1e-9);
    break;
  }
  EXPECT_GT(tried, 0);
}


// A tab folded under the base (interior angle 60 deg): a gusset square to its
// edge would cross the other tab's edge, and a gusset on the tab's side edge
// would start inside the tab's own root bend zone. Both are fitted: every
// plan keeps the sheets' clearance and at least one passes the whole check.
TEST(SelfRivet, GussetsFitIntoAnAcuteCorner) {
  Problem p = wall_problem();
  p.loads[0].center.x() += 0.03;  // room for the folded tab between the base and the wall
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  part.add_tab(0, 3, TabParameters{0.0, 0.1, 0.07, 0, 0, -2.0 * M_PI / 3}, -1);
  const RealisedPart rp = realise(part);
  const Environment env(p);
  ValidityOptions vo;
  ASSERT_TRUE(check_validity(part, rp, env, vo).valid()) << check_validity(part, rp, env, vo).summary();
  int plans_seen = 0, valid = 0;
  for (const auto& pr : visible_edge_pairs(part, rp, p.material.thickness)) {
    if (!((pr.a.tab == 0 && pr.b.tab == 1) || (pr.a.tab == 1 && pr.b.tab == 0))) continue;
    for (const auto& plan : gusset_plans(part, rp, pr, p)) {
      ++plans_seen;
      const RealisedPart grp = realise(plan.part);
      const ValidityReport rep = check_validity(plan.part, grp, env, vo);
      if (rep.valid()) ++valid;
      else std::printf("gusset +%.1f cm^2 rejected: %s\n", plan.added_area * 1e4, rep.summary().c_str());
      // No gusset comes closer to the other tab than t + gap.
      for (const auto& [g, other] : {std::pair{plan.tab_a, plan.part.tabs[plan.tab_b].parent},
                                     std::pair{plan.tab_b, plan.part.tabs[plan.tab_a].parent}}) {
        const double d = convex_polygon_distance(grp.tabs[g].corners, grp.tabs[g].normal, grp.tabs[other].corners,
                                                 grp.tabs[other].normal, 1.0);
        EXPECT_GE(d, p.material.thickness + vo.self_gap) << "gusset " << g << " and tab " << other;
      }
    }
  }
  std::printf("acute corner: %d gusset plans, %d valid\n", plans_seen, valid);
  EXPECT_GT(plans_seen, 0);
  EXPECT_GT(valid, 0);
}

}  // namespace
}  // namespace sheetgen
