// Self-riveting (paper Sec. 5.2): the visibility of free-edge pairs and the
// gusset that joins them, on hand-built parts with known geometry.
#include "sheetgen/compose/self_rivet.hpp"

#include <gtest/gtest.h>

#include "sheet_rules.hpp"

#include <filesystem>

#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/fem/rivet_layout.hpp"

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


// A gusset on the flange's side edge stops short of the flange's rivet row:
// its root ends at least 2 e + t from the far edge, so its bend zone and the
// relief notch beyond it keep e from the row, and the flange keeps every rivet
// it has without the gusset (the FEM's layout would drop the nearest one).
TEST(SelfRivet, GussetOnAFlangeLeavesItsRivetRowWhole) {
  const Problem p = wall_problem();
  const Part part = springboard(p);
  const RealisedPart rp = realise(part);
  const PartModel plain = build_part_model(p, 0, plate_geometry(part, rp));
  auto flange_rivets = [](const PartModel& pm) {
    int n = 0;
    for (int k : pm.rivet_polygon) n += k == 1;
    return n;
  };
  const double e = p.manufacturing.rivet_edge_distance, t = p.material.thickness;
  int on_flange = 0;
  for (const auto& pair : visible_edge_pairs(part, rp, t)) {
    if (!((pair.a.tab == 0 && pair.b.tab == 1) || (pair.a.tab == 1 && pair.b.tab == 0))) continue;
    for (const auto& plan : gusset_plans(part, rp, pair, p)) {
      const RealisedPart grp = realise(plan.part);
      for (int g : {plan.tab_a, plan.tab_b}) {
        if (plan.part.tabs[g].parent != 1) continue;
        ++on_flange;
        // Far edge of the flange: corners 2 -> 3. Both root ends of the gusset keep 2 e + t from its line.
        const Vec3 f0 = grp.tabs[1].corners[2], f1 = grp.tabs[1].corners[3];
        const Vec3 u = (f1 - f0).normalized();
        for (int c : {0, 1}) {
          const Vec3 r = grp.tabs[g].corners[c] - f0;
          EXPECT_GE((r - r.dot(u) * u).norm(), 2 * e + t - 1e-9);
        }
      }
      PartModelOptions mo;
      for (size_t r = 0; r < plan.rivets_a.size(); ++r)
        mo.self_rivets.push_back(SelfRivetTie{plan.tab_a, plan.tab_b, plan.rivets_a[r], plan.rivets_b[r]});
      EXPECT_EQ(flange_rivets(build_part_model(p, 0, plate_geometry(plan.part, grp), mo)), flange_rivets(plain));
    }
  }
  std::printf("%d gussets on the flange, each leaving its %d rivets\n", on_flange, flange_rivets(plain));
  EXPECT_GT(on_flange, 0);
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

// A 20 mm rivet flange (about the shortest that holds a rivet row: 7.2 mm bend setback + 2 x 6.35 mm edge distance) has side edges too short for a gusset
// root between the bend zones at their ends. Lengthening the flange gives it
// one: the plans' added area is what the part grew by (flange extension and
// both gussets), and the riveted gusset stiffens the springboard.
TEST(SelfRivet, ShortFlangeIsLengthenedForItsGusset) {
  const Problem p = wall_problem();
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  part.add_tab(0, 3, TabParameters{0.0, 0.1, 0.02, 0, 0, -M_PI / 2}, 0);
  const RealisedPart rp = realise(part);
  const Environment env(p);
  ValidityOptions vo;
  ASSERT_TRUE(check_validity(part, rp, env, vo).valid()) << check_validity(part, rp, env, vo).summary();
  auto area = [](const RealisedPart& r) {
    double a = 0;
    for (const auto& t : r.tabs) a += std::abs(signed_area(t.local));
    return a;
  };
  const double plain_compliance = analyse_part(p, 0, plate_geometry(part, rp)).compliance;
  int short_pairs = 0, valid = 0;
  for (const auto& pr : visible_edge_pairs(part, rp, p.material.thickness)) {
    if (!((pr.a.tab == 0 && pr.b.tab == 1) || (pr.a.tab == 1 && pr.b.tab == 0)) || std::abs(pr.plane_normal.y()) < 1 - 1e-9) continue;
    EXPECT_TRUE(gusset_plans(part, rp, pr, p).empty());  // 20 mm: no room between the bend zones
    ++short_pairs;
    const auto plans = lengthened_gusset_plans(part, rp, pr, p);
    ASSERT_FALSE(plans.empty());
    for (size_t k = 1; k < plans.size(); ++k) EXPECT_LE(plans[k - 1].added_area, plans[k].added_area);  // lightest first
    for (const auto& plan : plans) {
      const RealisedPart grp = realise(plan.part);
      EXPECT_GT(plan.part.tabs[1].params.l, 0.02);
      EXPECT_NEAR(plan.added_area, area(grp) - area(rp), 1e-9);
      if (!check_validity(plan.part, grp, env, vo).valid()) continue;
      ++valid;
      PartModelOptions mo;
      for (size_t r = 0; r < plan.rivets_a.size(); ++r)
        mo.self_rivets.push_back(SelfRivetTie{plan.tab_a, plan.tab_b, plan.rivets_a[r], plan.rivets_b[r]});
      const double riveted = analyse_part(p, 0, plate_geometry(plan.part, grp), mo).compliance;
      const double loose = analyse_part(p, 0, plate_geometry(plan.part, grp)).compliance;
      // The longer flange moves its rivet row (along its far edge) away from the
      // bend, which softens the part; the tie is what must stiffen it.
      std::printf("flange 20.0 -> %.1f mm, +%.1f cm^2: compliance %.4g J; lengthened with loose gussets %.4g J, riveted %.4g J\n",
                  plan.part.tabs[1].params.l * 1e3, plan.added_area * 1e4, plain_compliance, loose, riveted);
      EXPECT_LT(riveted, 0.8 * loose);
      break;
    }
  }
  EXPECT_EQ(short_pairs, 2);  // the side planes y = -0.05 and y = +0.05
  EXPECT_GT(valid, 0);
}

// A self-rivet ties its whole footprint on both sheets (every node within d
// of its centre, as a flange rivet clamps its own), so its stiffness
// converges under refinement and CalculiX, on the same deck, agrees.
TEST(SelfRivet, TieFootprintIsWholeConvergesAndAgreesWithCalculix) {
  const Problem p = wall_problem();
  const Part part = springboard(p);
  const RealisedPart rp = realise(part);
  const Environment env(p);
  ValidityOptions vo;
  const SelfRivetPlan* chosen = nullptr;
  std::vector<SelfRivetPlan> plans;
  for (const auto& pr : visible_edge_pairs(part, rp, p.material.thickness))
    if (((pr.a.tab == 0 && pr.b.tab == 1) || (pr.a.tab == 1 && pr.b.tab == 0)) && std::abs(pr.plane_normal.y()) > 1 - 1e-9) {
      plans = gusset_plans(part, rp, pr, p);
      break;
    }
  for (const auto& plan : plans)
    if (check_validity(plan.part, realise(plan.part), env, vo).valid()) {
      chosen = &plan;
      break;
    }
  ASSERT_NE(chosen, nullptr);
  const RealisedPart grp = realise(chosen->part);
  const PlateGeometry g = plate_geometry(chosen->part, grp);
  auto options = [&](double h) {
    PartModelOptions mo;
    mo.element_size = h;
    for (size_t r = 0; r < chosen->rivets_a.size(); ++r)
      mo.self_rivets.push_back(SelfRivetTie{chosen->tab_a, chosen->tab_b, chosen->rivets_a[r], chosen->rivets_b[r]});
    return mo;
  };
  // Every node of either gusset within d of a rivet centre follows that rivet's link.
  const PartModel fine = build_part_model(p, 0, g, options(1.5e-3));
  RivetLayoutOptions ro;
  ro.thickness = p.material.thickness;
  ro.diameter = p.manufacturing.rivet_diameter;
  const double d = rivet_diameter(ro);  // the footprint radius (docs/fem.md "Rivets")
  std::vector<char> linked(fine.model.nodes.size(), 0);
  for (const RigidLink& l : fine.model.rigid_links) {
    linked[l.master] = 1;
    for (int v : l.slaves) linked[v] = 1;
  }
  int inside = 0;
  for (size_t v = 0; v < fine.model.nodes.size(); ++v)
    for (size_t r = 0; r < chosen->rivets_a.size(); ++r)
      for (const Vec3& c : {chosen->rivets_a[r], chosen->rivets_b[r]})
        if ((fine.model.nodes[v] - c).norm() <= d * (1 + 1e-9)) {
          ++inside;
          EXPECT_TRUE(linked[v]) << "node " << v << " is inside a self-rivet footprint but not tied";
        }
  EXPECT_GT(inside, static_cast<int>(chosen->rivets_a.size()) * 7);  // more than centre + ring on a sheet
  // Converged: within 1 % from h = 3 to 1.5 mm.
  const double c3 = analyse_part(p, 0, g, options(3e-3)).compliance, c15 = analyse_part(p, 0, g, options(1.5e-3)).compliance;
  // CalculiX S4 on the same deck (ties as rigid bodies), at 3 mm.
  const PartModel mid = build_part_model(p, 0, g, options(3e-3));
  const auto dir = std::filesystem::temp_directory_path() / ("sheetgen_self_rivet_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const CcxSolution ccx = solve_with_ccx(mid.model, dir.string(), "gusset");
  std::filesystem::remove_all(dir);
  std::printf("gusseted springboard: compliance %.6g J at h = 3 mm, %.6g J at 1.5 mm; CalculiX S4 %.6g J at 3 mm\n", c3, c15,
              ccx.compliance);
  EXPECT_NEAR(c15 / c3, 1.0, 0.01);
  EXPECT_NEAR(c3 / ccx.compliance, 1.0, 0.03);
}

}  // namespace
}  // namespace sheetgen
