// Problem files: defaults, and every bad input of issue 2 giving one sentence
// that names the file, the field and the problem - through the library and
// through the real `sheetgen check` (exit code 1).
#include "sheetgen/core/problem.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "sheetgen/core/input_error.hpp"
#include "../common/cli_path.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

fs::path temp_dir() {
  fs::path d = fs::temp_directory_path() / ("sheetgen_problem_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

const char* kWallObj =
    "v 0 -0.3 0\nv 0 0.3 0\nv 0 0.3 0.6\nv 0 -0.3 0.6\n"
    "f 1 2 3\nf 1 3 4\n";

json valid_problem() {
  return json::parse(R"({
    "format": "sheetgen-problem/1",
    "environment": {"meshes": [
      {"name": "wall", "file": "wall.obj"},
      {"name": "floor", "vertices": [[0,-0.3,0],[0.6,-0.3,0],[0.6,0.3,0],[0,0.3,0]], "triangles": [[0,1,2],[0,2,3]]}
    ]},
    "rivet_areas": [{"name": "wall_ra", "mesh": "wall", "faces": [0, 1]}, {"name": "floor_ra", "mesh": "floor", "faces": [1]}],
    "loads": [{"name": "box", "center": [0.3, 0, 0.3], "size": [0.1, 0.1, 0.1], "force": [0, 0, -100]}]
  })");
}

struct Files {
  fs::path dir = temp_dir();
  Files() { std::ofstream(dir / "wall.obj") << kWallObj; }
  ~Files() { std::error_code ec; fs::remove_all(dir, ec); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

// Runs the real CLI; returns exit code and the first line of stderr.
testing::CliRun run_check(const std::string& path) {
  return testing::run_cli("check '" + path + "' 2>&1 >/dev/null");
}

TEST(Problem, ValidProblemGetsDocumentedDefaults) {
  Files files;
  const std::string path = files.write("problem.json", valid_problem().dump());
  const Problem p = load_problem(path);
  ASSERT_EQ(p.meshes.size(), 2u);
  EXPECT_EQ(p.triangle_count(), 4);
  EXPECT_NEAR(p.rivet_areas[0].area_m2, 0.36, 1e-12);   // the whole 0.6 x 0.6 wall
  EXPECT_NEAR(p.rivet_areas[1].area_m2, 0.18, 1e-12);   // half the floor
  EXPECT_DOUBLE_EQ(p.material.thickness, 1.6e-3);
  EXPECT_DOUBLE_EQ(p.material.youngs_modulus, 73.1e9);
  EXPECT_DOUBLE_EQ(p.manufacturing.bend_radius, 4 * 1.6e-3);                 // R = 4 t
  EXPECT_DOUBLE_EQ(p.manufacturing.min_flange, 4 * 1.6e-3 + 4 * 1.6e-3);     // 4 t + R
  EXPECT_TRUE(p.manufacturing.press_brake_required);                        // "prefer"
  EXPECT_TRUE(p.manufacturing.press_brake_fallback);
  EXPECT_DOUBLE_EQ(p.requirements.safety_factor, 1.5);
  EXPECT_DOUBLE_EQ(p.requirements.compliance_limit(100.0), 100.0 * 1e-3);    // default 1 mm deflection
  EXPECT_EQ(p.search.chains, 10);
  EXPECT_EQ(p.search.iterations, 1000);
  EXPECT_TRUE(p.loads[0].rotation.isApprox(Eigen::Quaterniond::Identity()));
  EXPECT_EQ(run_check(path).exit_code, 0);
}

TEST(Problem, PressBrakeIsRequiredOnlyWhenAsked) {
  Files files;
  for (const std::string use : {"report", "prefer", "require"}) {
    json j = valid_problem();
    j["manufacturing"]["press_brake"] = use;
    const Problem p = load_problem(files.write("press_" + use + ".json", j.dump()));
    EXPECT_EQ(p.manufacturing.press_brake_required, use != "report") << use;
    EXPECT_EQ(p.manufacturing.press_brake_fallback, use == "prefer") << use;
  }
}

TEST(Problem, PressBrakeToolsReplaceListsAndKeepOmittedSizes) {
  Files files;
  json j = valid_problem();
  j["manufacturing"]["press_brake_tools"] = json::parse(R"({
    "punches": [{"name": "box punch", "kind": "straight", "height": 0.3}, {"kind": "gooseneck", "throat_top": 0.1}],
    "dies": [{"v_opening": 0.01, "angle": 1.5}],
    "open_height": 0.7})");
  const PressBrakeTooling t = load_problem(files.write("tools.json", j.dump())).manufacturing.press_brake_tools;
  ASSERT_EQ(t.punches.size(), 2u);
  EXPECT_EQ(t.punches[0].name, "box punch");
  EXPECT_DOUBLE_EQ(t.punches[0].height, 0.3);
  EXPECT_EQ(t.punches[1].kind, PunchKind::Gooseneck);
  EXPECT_DOUBLE_EQ(t.punches[1].throat_top, 0.1);
  EXPECT_DOUBLE_EQ(t.punches[1].height, PunchSpec{}.height);  // left out: the default
  ASSERT_EQ(t.dies.size(), 1u);
  EXPECT_DOUBLE_EQ(die_opening(t, t.dies[0], 1.6e-3), 0.01);
  EXPECT_DOUBLE_EQ(t.dies[0].angle, 1.5);
  EXPECT_DOUBLE_EQ(t.dies[0].min_flange_ratio, DieSpec{}.min_flange_ratio);
  EXPECT_DOUBLE_EQ(t.open_height, 0.7);
  EXPECT_DOUBLE_EQ(t.ram_width, PressBrakeTooling{}.ram_width);
  // Without the field: the standard set.
  const Problem d = load_problem(files.write("no_tools.json", valid_problem().dump()));
  EXPECT_EQ(d.manufacturing.press_brake_tools.punches.size(), default_press_brake_tooling().punches.size());
  EXPECT_EQ(d.manufacturing.press_brake_tools.dies.size(), default_press_brake_tooling().dies.size());
}

struct BadCase {
  const char* label;
  std::function<void(json&, Files&)> edit;
  const char* field;    // must appear in the message
  const char* problem;  // must appear in the message
};

TEST(Problem, EveryBadInputGivesOneSentenceAndExitCodeOne) {
  const std::vector<BadCase> cases = {
      {"missing field", [](json& j, Files&) { j["loads"][0].erase("force"); }, "loads[0].force", "required field is missing"},
      {"wrong type", [](json& j, Files&) { j["loads"][0]["size"] = "big"; }, "loads[0].size", "expected an array of 3 numbers"},
      {"NaN", [](json& j, Files&) { j["loads"][0]["force"][1] = "NAN_TOKEN"; }, "loads[0].force[1]", "finite number, got NaN"},
      {"infinity", [](json& j, Files&) { j["loads"][0]["center"][0] = "INF_TOKEN"; }, "loads[0].center[0]", "finite number, got Infinity"},
      {"negative thickness", [](json& j, Files&) { j["material"]["thickness"] = -0.0016; }, "material.thickness", "greater than zero"},
      {"face index out of range", [](json& j, Files&) { j["rivet_areas"][1]["faces"][0] = 7; }, "rivet_areas[1].faces[0]", "out of range"},
      {"rivet area with no faces", [](json& j, Files&) { j["rivet_areas"][0]["faces"] = json::array(); }, "rivet_areas[0].faces", "has no faces"},
      {"load box of zero size", [](json& j, Files&) { j["loads"][0]["size"] = {0.1, 0.0, 0.1}; }, "loads[0].size", "must be positive"},
      {"unreadable mesh file", [](json& j, Files& f) { f.write("broken.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"); j["environment"]["meshes"][0]["file"] = "broken.obj"; },
       "environment.meshes[0].file", "line 4"},
      {"missing mesh file", [](json& j, Files&) { j["environment"]["meshes"][0]["file"] = "nowhere.obj"; }, "environment.meshes[0].file", "does not exist"},
      {"empty mesh", [](json& j, Files& f) { f.write("empty.obj", "# nothing\n"); j["environment"]["meshes"][0]["file"] = "empty.obj"; },
       "environment.meshes[0]", "the mesh is empty"},
      {"non-finite vertex", [](json& j, Files& f) { f.write("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"); j["environment"]["meshes"][0]["file"] = "nan.obj"; },
       "line 2", "not finite"},
      {"non-finite inline vertex", [](json& j, Files&) { j["environment"]["meshes"][1]["vertices"][2][0] = "NAN_TOKEN"; }, "environment.meshes[1].vertices[2][0]", "finite number"},
      {"unknown field", [](json& j, Files&) { j["requirments"] = json::object(); }, "(top level)", "unknown field 'requirments'"},
      {"wrong format", [](json& j, Files&) { j["format"] = "sheetgen-problem/9"; }, "format", "unsupported format"},
      {"unknown rivet mesh", [](json& j, Files&) { j["rivet_areas"][0]["mesh"] = "ceiling"; }, "rivet_areas[0].mesh", "no environment mesh is named 'ceiling'"},
      {"press-brake use", [](json& j, Files&) { j["manufacturing"]["press_brake"] = "always"; }, "manufacturing.press_brake",
       "must be \"report\", \"prefer\" or \"require\", got \"always\""},
      {"no punches", [](json& j, Files&) { j["manufacturing"]["press_brake_tools"]["punches"] = json::array(); },
       "manufacturing.press_brake_tools.punches", "must list at least one punch"},
      {"punch kind", [](json& j, Files&) { j["manufacturing"]["press_brake_tools"]["punches"] = {{{"kind", "swan"}}}; },
       "manufacturing.press_brake_tools.punches[0].kind", "must be \"straight\" or \"gooseneck\", got \"swan\""},
      {"gooseneck throat", [](json& j, Files&) { j["manufacturing"]["press_brake_tools"]["punches"] = {{{"kind", "gooseneck"}, {"throat_top", 0.2}}}; },
       "manufacturing.press_brake_tools.punches[0]", "a gooseneck needs throat_bottom < throat_top < height"},
      {"die angle", [](json& j, Files&) { j["manufacturing"]["press_brake_tools"]["dies"] = {{{"angle", 4.0}}}; },
       "manufacturing.press_brake_tools.dies[0].angle", "must lie between 0 and pi (radians), got 4"},
      {"die opening twice", [](json& j, Files&) { j["manufacturing"]["press_brake_tools"]["dies"] = {{{"v_opening", 0.01}, {"v_per_thickness", 6}}}; },
       "manufacturing.press_brake_tools.dies[0]", "give v_opening or v_per_thickness, not both"},
      {"machine too low", [](json& j, Files&) { j["manufacturing"]["press_brake_tools"]["open_height"] = 0.15; },
       "manufacturing.press_brake_tools", "open_height 0.150 m leaves no room under punches[0] (0.120 m high) on the lowest die (0.060 m)"},
      {"unknown tool field", [](json& j, Files&) { j["manufacturing"]["press_brake_tools"]["tonnage"] = 100; },
       "manufacturing.press_brake_tools", "unknown field 'tonnage'"},
      {"gauge not thicker", [](json& j, Files&) { j["material"]["gauges"] = {0.002, 0.0018}; }, "material.gauges[1]",
       "gauges must be listed thinnest first, each once"},
      {"gauge below the sheet", [](json& j, Files&) { j["material"]["gauges"] = {0.0012}; }, "material.gauges[0]",
       "must be thicker than material.thickness (0.0016 m)"},
      {"gauges not a list", [](json& j, Files&) { j["material"]["gauges"] = 0.002; }, "material.gauges", "expected an array"},
      {"free sheet", [](json& j, Files&) { j["cost"]["material_per_kg"] = 0; }, "cost.material_per_kg", "greater than zero"},
      {"negative bend price", [](json& j, Files&) { j["cost"]["per_bend"] = -1; }, "cost.per_bend", "must not be negative, got -1"},
      {"empty batch", [](json& j, Files&) { j["cost"]["batch_size"] = 0; }, "cost.batch_size", "must lie in [1, 1000000] parts, got 0"},
      {"unknown objective", [](json& j, Files&) { j["cost"]["objective"] = "mass"; }, "cost.objective",
       "must be \"area\" or \"cost\", got \"mass\""},
      {"unknown cost field", [](json& j, Files&) { j["cost"]["per_weld"] = 3; }, "cost", "unknown field 'per_weld'"},
      {"inline triangle index", [](json& j, Files&) { j["environment"]["meshes"][1]["triangles"][1][2] = 9; }, "environment.meshes[1].triangles[1][2]", "out of range"},
  };
  Files files;
  for (const auto& c : cases) {
    json j = valid_problem();
    BadCase bc = c;
    bc.edit(j, files);
    std::string text = j.dump();
    // Python's json module writes NaN and Infinity as bare tokens; so do we here.
    for (auto [marker, token] : {std::pair{"\"NAN_TOKEN\"", "NaN"}, std::pair{"\"INF_TOKEN\"", "Infinity"}})
      for (size_t pos; (pos = text.find(marker)) != std::string::npos;) text.replace(pos, std::strlen(marker), token);
    const std::string path = files.write(std::string("bad_") + std::to_string(&c - &cases[0]) + ".json", text);
    try {
      load_problem(path);
      ADD_FAILURE() << c.label << ": accepted";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(path), std::string::npos) << c.label << ": file not named in: " << msg;
      EXPECT_NE(msg.find(c.field), std::string::npos) << c.label << ": field '" << c.field << "' not named in: " << msg;
      EXPECT_NE(msg.find(c.problem), std::string::npos) << c.label << ": problem '" << c.problem << "' not in: " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << c.label << ": more than one line";
    }
    const auto [code, err] = run_check(path);
    EXPECT_EQ(code, 1) << c.label;
    EXPECT_EQ(err.rfind("sheetgen: ", 0), 0u) << c.label << ": " << err;
    EXPECT_NE(err.find(c.field), std::string::npos) << c.label << ": " << err;
  }
}

TEST(Problem, NotJsonAndMissingFileAreOneLine) {
  Files files;
  const std::string path = files.write("truncated.json", valid_problem().dump().substr(0, 120));
  const auto [code, err] = run_check(path);
  EXPECT_EQ(code, 1);
  EXPECT_NE(err.find("is not valid JSON"), std::string::npos) << err;
  const auto [code2, err2] = run_check((files.dir / "absent.json").string());
  EXPECT_EQ(code2, 1);
  EXPECT_NE(err2.find("file does not exist"), std::string::npos) << err2;
}

TEST(Problem, LoadBoxGeometry) {
  Load l;
  l.center = Vec3(1, 2, 3);
  l.size = Vec3(0.2, 0.4, 0.6);
  l.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()));
  // Local +x maps to world +y under a quarter turn about z.
  EXPECT_NEAR(l.signed_distance(Vec3(1, 2 + 0.1 + 0.05, 3)), 0.05, 1e-12);
  EXPECT_NEAR(l.signed_distance(Vec3(1, 2, 3)), -0.1, 1e-12);
  const auto bottom = l.bottom_face();
  for (const auto& c : bottom) EXPECT_NEAR(c.z(), 3 - 0.3, 1e-12);
  const TriangleMesh box = l.box_mesh();
  EXPECT_TRUE(box.is_closed());
  EXPECT_NEAR(box.area(), 2 * (0.2 * 0.4 + 0.4 * 0.6 + 0.2 * 0.6), 1e-12);
  // Outward normals: each face normal points away from the centre.
  for (int f = 0; f < 12; ++f) {
    const auto& t = box.triangles[f];
    const Vec3 c = (box.vertices[t[0]] + box.vertices[t[1]] + box.vertices[t[2]]) / 3.0;
    EXPECT_GT(box.face_normal(f).dot(c - l.center), 0);
  }
}

}  // namespace
}  // namespace sheetgen

namespace sheetgen {
namespace {

// Rivet areas a flange cannot use are refused with the reason (issue 9).
TEST(Problem, NonPlanarAndTooSmallRivetAreasAreRefused) {
  // Two faces of a 90-degree corner in one rivet area.
  json bent = json::parse(R"({
    "format": "sheetgen-problem/1",
    "environment": {"meshes": [{"name": "corner", "vertices": [[0,0,0],[0.2,0,0],[0.2,0.2,0],[0,0.2,0],[0,0,0.2],[0,0.2,0.2]],
                                "triangles": [[0,1,2],[0,3,4],[3,5,4]]}]},
    "rivet_areas": [{"name": "bent", "mesh": "corner", "faces": [0, 1]}],
    "loads": [{"name": "box", "center": [0.1, 0.1, 0.2], "size": [0.1, 0.1, 0.1], "force": [0, 0, -100]}]
  })");
  try {
    parse_problem(bent.dump(), "p.json", ".");
    FAIL() << "accepted a bent rivet area";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rivet area 'bent' is not planar (its faces differ by up to 45 degrees"), std::string::npos) << e.what();
  }
  // Each face alone is planar and large enough (0.02 m^2): accepted.
  bent["rivet_areas"][0]["faces"] = {0};
  EXPECT_NO_THROW(parse_problem(bent.dump(), "p.json", "."));
  // A 10 x 10 mm area: smaller than one flange (12.8 x 16 mm = 2.05 cm^2 by default).
  json tiny = bent;
  tiny["environment"]["meshes"][0]["vertices"] = {{0, 0, 0}, {0.01, 0, 0}, {0.01, 0.01, 0}, {0, 0.01, 0}, {0, 0, 0.2}, {0, 0.2, 0.2}};
  try {
    parse_problem(tiny.dump(), "p.json", ".");
    FAIL() << "accepted a rivet area smaller than a flange";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is 0.50 cm^2, smaller than the smallest rivet flange (12.8 x 16.0 mm = 2.05 cm^2)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sheetgen

namespace sheetgen {
namespace {

// The right-angle grammar (the right-angle pass, docs/pipeline.md): a subset of
// the default limits, not of limits that exclude 90 deg, and not run twice.
TEST(Manufacturing, RightAngleGrammarIsASubsetOfTheLimitsThatAdmitIt) {
  Manufacturing m;
  EXPECT_FALSE(m.right_angles_only());
  EXPECT_TRUE(m.admits_right_angle_pass());
  Manufacturing square = m;
  square.restrict_to_right_angles();
  EXPECT_TRUE(square.right_angles_only());
  EXPECT_FALSE(square.admits_right_angle_pass());
  EXPECT_TRUE(square.flat_extensions);
  EXPECT_NEAR(square.min_bend_angle, 89.5 * M_PI / 180, 1e-12);
  EXPECT_NEAR(square.max_bend_angle, 90.5 * M_PI / 180, 1e-12);
  Manufacturing shallow = m;
  shallow.max_bend_angle = 80 * M_PI / 180;  // a shop whose tools stop short of 90 deg
  EXPECT_FALSE(shallow.admits_right_angle_pass());
  Manufacturing steep = m;
  steep.min_bend_angle = 91 * M_PI / 180;
  EXPECT_FALSE(steep.admits_right_angle_pass());
  Manufacturing straight = m;
  straight.max_skew = 0;  // no skew at all is stricter than the pass's 1 mrad
  EXPECT_FALSE(straight.admits_right_angle_pass());
}

}  // namespace
}  // namespace sheetgen
