// `sheetgen export-ccx` writes exactly the deck of the in-process model, and
// bad requests are one line with exit code 1.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "sheetgen/fem/ccx_export.hpp"
#include "sheetgen/part/exports.hpp"
#include "sheetgen/structure/part_model.hpp"
#include "../common/cli_path.hpp"
#include "../common/test_files.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;

// Exit code and both output streams.
testing::CliRun run(const std::string& args) { return testing::run_cli(args + " 2>&1"); }

using testing::slurp;

// A 10 cm box 15 cm above a floor that is one rivet area, written to
// dir/problem.json with `force` (N, JSON array), and a part: the base under the
// box, a leg folded down from its edge 1, a foot folded onto the floor.
struct LegAndFoot {
  Problem problem;
  Part part;
  int leg = -1, foot = -1;
};

LegAndFoot leg_and_foot(const fs::path& dir, const std::string& force) {
  const nlohmann::json problem = nlohmann::json::parse(R"({
    "format": "sheetgen-problem/1",
    "environment": {"meshes": [{"name": "floor", "vertices": [[-1,-1,0],[1,-1,0],[1,1,0],[-1,1,0]], "triangles": [[0,1,2],[0,2,3]]}]},
    "rivet_areas": [{"name": "floor", "mesh": "floor", "faces": [0, 1]}],
    "loads": [{"name": "box", "center": [0, 0, 0.2], "size": [0.1, 0.1, 0.1], "force": )" + force + R"(}]
  })");
  std::ofstream(dir / "problem.json") << problem.dump(2);
  LegAndFoot f;
  f.problem = load_problem((dir / "problem.json").string());
  const double t = f.problem.material.thickness;
  f.part = make_base_part(f.problem.loads[0], 0, t);
  const double zb = 0.15 - 0.5 * t;  // base mid-surface height
  f.leg = f.part.add_tab(0, 1, TabParameters{0.0, 0.1, zb - 0.5 * t, 0, 0, -M_PI / 2});
  f.foot = f.part.add_tab(f.leg, kFarEdge, TabParameters{0.0, 0.1, 0.03, 0, 0, M_PI / 2}, 0);
  return f;
}

TEST(ExportCcxCli, DeckEqualsTheLibraryModel) {
  const fs::path dir = fs::temp_directory_path() / ("sheetgen export ccx " + std::to_string(::getpid()));  // a space on purpose
  fs::create_directories(dir);
  const LegAndFoot f = leg_and_foot(dir, "[0, 0, -350]");
  const Problem& p = f.problem;
  const Part& part = f.part;
  const RealisedPart rp = realise(part);
  nlohmann::json result = {{"format", "sheetgen-result/1"}, {"problem", "problem.json"},
                           {"parts", {{{"load", "box"}, {"status", "ok"}, {"tabs", part_json(part, rp)}}}}};
  std::ofstream(dir / "result.json") << result.dump(2);

  const auto [code, out] = run("export-ccx '" + (dir / "result.json").string() + "' --load box --out '" + (dir / "deck.inp").string() + "'");
  ASSERT_EQ(code, 0) << out;
  CcxExportOptions cli;  // export-ccx's defaults: *BUCKLE of the first case, 3 modes
  cli.buckle_case = 0;
  cli.frequency_modes = 3;
  std::ostringstream expected;
  write_ccx_deck(build_part_model(p, 0, plate_geometry(part, rp)).model, expected, cli);
  EXPECT_EQ(slurp(dir / "deck.inp"), expected.str());
  EXPECT_FALSE(fs::exists(dir / "deck.inp.tmp"));

  // --element-size (mm) meshes at that size, --solve prints our compliance of
  // the same model (refinement studies against CalculiX, docs/fem.md).
  const auto [code3, out3] = run("export-ccx '" + (dir / "result.json").string() + "' --load box --element-size 7 --solve --out '" +
                                 (dir / "deck7.inp").string() + "' --displacements '" + (dir / "u.csv").string() + "'");
  ASSERT_EQ(code3, 0) << out3;
  PartModelOptions seven;
  seven.element_size = 7e-3;
  std::ostringstream expected7;
  write_ccx_deck(build_part_model(p, 0, plate_geometry(part, rp), seven).model, expected7, cli);
  EXPECT_EQ(slurp(dir / "deck7.inp"), expected7.str());
  const StructuralResult ours = analyse_part(p, 0, plate_geometry(part, rp), seven);
  const auto at = out3.find("compliance ");
  ASSERT_NE(at, std::string::npos) << out3;
  EXPECT_NEAR(std::stod(out3.substr(at + 11)), ours.compliance, 1e-7 * ours.compliance) << out3;  // printed to 8 digits
  EXPECT_NE(out3.find("h = 7 mm"), std::string::npos) << out3;
  // ... and where the stress rule's maximum is, with its value.
  const auto at_vm = out3.find("max von Mises ");
  ASSERT_NE(at_vm, std::string::npos) << out3;
  EXPECT_NEAR(std::stod(out3.substr(at_vm + 14)) * 1e6, ours.max_von_mises, 1e-5 * ours.max_von_mises) << out3;
  // --displacements: our u by deck node id; the deck's *CLOAD lines dotted
  // with it give back the compliance f^T u.
  std::map<int, std::array<double, 3>> u;
  {
    std::istringstream csv(slurp(dir / "u.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "deck_node,x_m,y_m,z_m,ux_m,uy_m,uz_m");
    while (std::getline(csv, line)) {
      std::array<double, 7> v{};
      int id = 0;
      ASSERT_EQ(std::sscanf(line.c_str(), "%d,%lf,%lf,%lf,%lf,%lf,%lf", &id, &v[0], &v[1], &v[2], &v[3], &v[4], &v[5]), 7) << line;
      u[id] = {v[3], v[4], v[5]};
    }
  }
  const std::string deck7 = slurp(dir / "deck7.inp");
  std::istringstream cloads(deck7.substr(deck7.find("*CLOAD\n") + 7));
  double f_dot_u = 0;
  std::string line;
  int n_loads = 0;
  while (std::getline(cloads, line) && !line.empty() && line[0] != '*') {
    int node = 0, dof = 0;
    double value = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d, %d, %lf", &node, &dof, &value), 3) << line;
    ASSERT_TRUE(dof >= 1 && dof <= 3) << line;  // this load has no moment
    ASSERT_TRUE(u.count(node)) << "load node " << node << " missing from the CSV";
    f_dot_u += value * u[node][dof - 1];
    ++n_loads;
  }
  EXPECT_GT(n_loads, 0);
  EXPECT_NEAR(f_dot_u, ours.compliance, 1e-6 * ours.compliance);

  const auto [code2, out2] = run("export-ccx '" + (dir / "result.json").string() + "' --load crate --out '" + (dir / "x.inp").string() + "'");
  EXPECT_EQ(code2, 1);
  EXPECT_NE(out2.find("no load named 'crate'"), std::string::npos) << out2;
  EXPECT_FALSE(fs::exists(dir / "x.inp"));
  fs::remove_all(dir);
}

// A self-riveted part's ties (result.json self_rivets[]) reach the deck: a
// re-analysis that dropped them would check a softer part than the one solved.
TEST(ExportCcxCli, SelfRivetTiesReachTheDeck) {
  const fs::path dir = fs::temp_directory_path() / ("sheetgen export ties " + std::to_string(::getpid()));
  fs::create_directories(dir);
  const LegAndFoot f = leg_and_foot(dir, "[-200, 0, -350]");
  const Problem& p = f.problem;
  const Part& part = f.part;
  const int leg = f.leg, foot = f.foot;
  const RealisedPart rp = realise(part);
  // A tie from the middle of the leg to the foot near its fold (clear of the
  // foot's rivets along its far edge; the base is all under the box link): a brace across the fold.
  auto along = [&](int i, double f) {  // on the centre line of tab i, a fraction f from its root to its far edge
    const auto& c = rp.tabs[i].corners;
    return Vec3(0.5 * (c[0] + c[1]) + f * (0.5 * (c[2] + c[3]) - 0.5 * (c[0] + c[1])));
  };
  const SelfRivetTie tie{leg, foot, along(leg, 0.5), along(foot, 0.25)};
  auto v3 = [](const Vec3& q) { return nlohmann::json::array({q.x(), q.y(), q.z()}); };
  nlohmann::json part_doc = {{"load", "box"}, {"status", "ok"}, {"tabs", part_json(part, rp)},
                             {"self_rivets", {{{"tabs", {leg, foot}}, {"points", {v3(tie.point_a), v3(tie.point_b)}}}}}};
  nlohmann::json result = {{"format", "sheetgen-result/1"}, {"problem", "problem.json"}, {"parts", {part_doc}}};
  std::ofstream(dir / "result.json") << result.dump(2);

  const auto [code, out] = run("export-ccx '" + (dir / "result.json").string() + "' --load box --solve --out '" + (dir / "deck.inp").string() + "'");
  ASSERT_EQ(code, 0) << out;
  PartModelOptions tied;
  tied.self_rivets = {tie};
  CcxExportOptions cli;  // export-ccx's defaults: *BUCKLE of the first case, 3 modes
  cli.buckle_case = 0;
  cli.frequency_modes = 3;
  std::ostringstream expected, untied;
  write_ccx_deck(build_part_model(p, 0, plate_geometry(part, rp), tied).model, expected, cli);
  write_ccx_deck(build_part_model(p, 0, plate_geometry(part, rp)).model, untied);
  EXPECT_EQ(slurp(dir / "deck.inp"), expected.str());
  EXPECT_NE(expected.str(), untied.str());
  // The printed compliance is the tied part's, and the tie stiffens it (it can only lower f^T u).
  const double c_tied = analyse_part(p, 0, plate_geometry(part, rp), tied).compliance;
  const double c_free = analyse_part(p, 0, plate_geometry(part, rp)).compliance;
  const auto at = out.find("compliance ");
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_NEAR(std::stod(out.substr(at + 11)), c_tied, 1e-7 * c_tied) << out;
  EXPECT_LT(c_tied, c_free);

  // A tie naming a tab the part does not have: one line naming the field, exit 1, no deck.
  part_doc["self_rivets"][0]["tabs"] = {0, 7};
  result["parts"] = {part_doc};
  std::ofstream(dir / "bad.json") << result.dump(2);
  const auto [code2, out2] = run("export-ccx '" + (dir / "bad.json").string() + "' --load box --out '" + (dir / "bad.inp").string() + "'");
  EXPECT_EQ(code2, 1);
  EXPECT_NE(out2.find("self_rivets[0].tabs[1]"), std::string::npos) << out2;
  EXPECT_NE(out2.find("is not a tab index of this part (it has 3 tabs)"), std::string::npos) << out2;
  EXPECT_FALSE(fs::exists(dir / "bad.inp"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sheetgen
