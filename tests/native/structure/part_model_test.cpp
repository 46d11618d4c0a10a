// A realised part's structural model: checked against CalculiX on the deck of
// the same model, and the bad inputs of issue 4 (no rivet flange, a
// disconnected tab, zero thickness) give a sentence naming the cause.
#include "sheetgen/structure/part_model.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/part/exports.hpp"

namespace sheetgen {
namespace {

// A 10 cm cube load whose bottom is 15 cm above a floor; the floor is one rivet area.
Problem bracket_problem() {
  Problem p;
  p.source = "<test>";
  EnvironmentMesh floor;
  floor.name = "floor";
  floor.mesh.vertices = {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)};
  floor.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  p.meshes.push_back(floor);
  p.rivet_areas.push_back(RivetAreaSpec{"floor", 0, {0, 1}, 4.0});
  Load l;
  l.name = "box";
  l.center = Vec3(0, 0, 0.2);
  l.size = Vec3(0.1, 0.1, 0.1);
  l.force = Vec3(30, 0, -350);
  l.moment = Vec3(0, 2, 0);
  p.loads.push_back(l);
  const double t = p.material.thickness;
  p.manufacturing.bend_radius = 4 * t;
  p.manufacturing.rivet_diameter = 3.175e-3;
  p.manufacturing.rivet_edge_distance = 2 * 3.175e-3;
  p.manufacturing.rivet_pitch = 6 * 3.175e-3;
  return p;
}

// Base under the box; from its -x and +x edges a leg folds down to the floor
// and a flange folds flat onto it (a "hat" bracket: two legs, two flanges).
Part hat_part(const Problem& p) {
  Part part = make_base_part(p.loads[0], 0, p.material.thickness);
  const double zb = 0.15 - 0.5 * p.material.thickness;  // base mid-surface height
  for (int edge : {1, 3}) {
    TabParameters leg{0.0, 0.1, zb - 0.5 * p.material.thickness, 0, 0, -M_PI / 2};
    const int l = part.add_tab(0, edge, leg);
    TabParameters flange{0.0, 0.1, 0.03, 0, 0, M_PI / 2};
    part.add_tab(l, kFarEdge, flange, 0);
  }
  return part;
}

TEST(PartModel, HatBracketFlangesLieOnTheFloorAndAgreeWithCalculix) {
  const Problem p = bracket_problem();
  const Part part = hat_part(p);
  const RealisedPart rp = realise(part);
  // The flanges are flush with the floor (mid-surface t/2 above) and point outward.
  for (int i : {2, 4}) {
    for (const Vec3& c : rp.tabs[i].corners) EXPECT_NEAR(c.z(), 0.5 * p.material.thickness, 1e-12);
    double cx = 0;
    for (const Vec3& c : rp.tabs[i].corners) cx += c.x() / 4;
    EXPECT_GT(std::abs(cx), 0.05);
  }
  const PlateGeometry g = plate_geometry(part, rp);
  // 3 mm elements for both solvers. Ours barely moves with h (deflection 1.7064,
  // 1.7059, 1.7060, 1.7061 mm at h = 7.5, 5, 3, 2 mm); CalculiX's S4 on the
  // split mesh still stiffens-then-softens (1.637, 1.695, 1.726, 1.734 mm), and
  // its compliance drifts more (0.1035 .. 0.1136 J vs ours 0.1069 .. 0.1084 J):
  // at 3 mm the gaps are 1.1 % and 3.5 %. docs/fem.md lists this as open.
  PartModelOptions mo;
  mo.element_size = 3e-3;
  PartModel pm = build_part_model(p, 0, g, mo);
  EXPECT_EQ(pm.rivets.size(), 2u * 5u);  // 10 cm flange: (0.1 - 2 * 2d) / 6d + 1 = 5 rivets per flange (pitch 19 mm)
  const StructuralResult ours = analyse_part(p, 0, g, mo);
  std::printf("h = %.4g m, %d elements\n", pm.mesh.element_size, ours.elements);
  const auto dir = std::filesystem::temp_directory_path() / ("sheetgen_part_model_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const CcxSolution ccx = solve_with_ccx(pm.model, dir.string(), "hat");  // the folder stays on failure, for a look
  std::filesystem::remove_all(dir);
  std::printf("hat bracket: compliance ours %.6g J, ccx %.6g J; deflection ours %.6g m, ccx %.6g m\n", ours.compliance,
              ccx.compliance, ours.deflection, ccx.load_deflection);
  EXPECT_NEAR(ours.deflection / ccx.load_deflection, 1.0, 0.03);
  EXPECT_NEAR(ours.compliance / ccx.compliance, 1.0, 0.05);
  EXPECT_GT(ours.margin_of_safety, -1.0);
  EXPECT_EQ(ours.compliance_limit, 1e-3 * p.loads[0].force.norm());
}

TEST(PartModel, JsonTabsGiveTheSameModel) {
  const Problem p = bracket_problem();
  const Part part = hat_part(p);
  const RealisedPart rp = realise(part);
  const nlohmann::json tabs = part_json(part, rp);
  const PlateGeometry g = plate_geometry_from_json(nlohmann::json{{"tabs", tabs}}.dump(), "result.json");
  const StructuralResult a = analyse_part(p, 0, plate_geometry(part, rp));
  const StructuralResult b = analyse_part(p, 0, g);
  EXPECT_NEAR(a.compliance, b.compliance, 1e-9 * a.compliance);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const FemError& e) {
    return e.what();
  }
  return "";
}

TEST(PartModel, BadInputsNameTheirCause) {
  Problem p = bracket_problem();
  // No rivet flange: a mechanism.
  Part bare = hat_part(p);
  for (auto& t : bare.tabs) t.rivet_area = -1;
  const std::string none = error_of([&] { build_part_model(p, 0, plate_geometry(bare, realise(bare))); });
  EXPECT_NE(none.find("no rivet flange"), std::string::npos) << none;
  // A disconnected tab: its root lies past the end of the parent edge.
  Part loose = hat_part(p);
  loose.add_tab(0, 0, TabParameters{0.3, 0.05, 0.05, 0, 0, M_PI / 2});
  const std::string loose_msg = error_of([&] { analyse_part(p, 0, plate_geometry(loose, realise(loose))); });
  EXPECT_NE(loose_msg.find("connected to no support"), std::string::npos) << loose_msg;
  // Zero thickness.
  Problem thin = p;
  thin.material.thickness = 0;
  const Part part = hat_part(p);
  const std::string thin_msg = error_of([&] { build_part_model(thin, 0, plate_geometry(part, realise(part))); });
  EXPECT_NE(thin_msg.find("thickness"), std::string::npos) << thin_msg;
}

}  // namespace
}  // namespace sheetgen
