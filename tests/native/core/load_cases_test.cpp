// Load cases (issue 33, docs/problem-format.md "Load cases"): box masses and
// their inertia, the acceleration envelope and its FAR/CS 25.561 preset,
// explicit cases, the buckling and frequency floors; old single-force files
// unchanged; every bad input one sentence naming the field, in the library and
// through the real `sheetgen check`.
#include "sheetgen/core/load_cases.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/problem.hpp"
#include "../common/cli_path.hpp"

namespace sheetgen {
namespace {

// The corner scene as written before the scenes had load envelopes (one 9 g
// downward force), its meshes the scene's.
fs::path old_corner_file() {
  return fs::path(SHEETGEN_SOURCE_DIR) / "tests/native/core/data/corner_single_force.json";
}

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kG0 = 9.80665;  // m/s^2, written out here rather than taken from the code under test

// A wall and a floor inline (no mesh files), one 0.2 x 0.1 x 0.05 m box.
json base_problem() {
  return json::parse(R"({
    "format": "sheetgen-problem/1",
    "environment": {"meshes": [
      {"name": "wall", "vertices": [[0,-0.3,0],[0,0.3,0],[0,0.3,0.6],[0,-0.3,0.6]], "triangles": [[0,1,2],[0,2,3]]},
      {"name": "floor", "vertices": [[0,-0.3,0],[0.6,-0.3,0],[0.6,0.3,0],[0,0.3,0]], "triangles": [[0,1,2],[0,2,3]]}
    ]},
    "rivet_areas": [{"name": "wall_ra", "mesh": "wall", "faces": [0, 1]}, {"name": "floor_ra", "mesh": "floor", "faces": [1]}],
    "loads": [{"name": "box", "center": [0.3, 0, 0.3], "size": [0.2, 0.1, 0.05], "force": [0, 0, -100]}]
  })");
}

// base_problem() with a 2.5 kg box under the FAR 25.561 preset, aircraft
// forward = scene +y (given unnormalised), up = scene +z.
json enveloped_problem() {
  json j = base_problem();
  j["loads"][0].erase("force");
  j["loads"][0]["mass"] = 2.5;
  j["load_cases"] = {{"forward", {0, 2, 0}}, {"up", {0, 0, 5}}, {"factors", "far25.561"}};
  return j;
}

Problem parse(const json& j) { return parse_problem(j.dump(), "p.json", "."); }

void expect_vec(const Vec3& got, const Vec3& want, double tol, const std::string& what) {
  EXPECT_LE((got - want).norm(), tol) << what << ": got " << got.transpose() << ", want " << want.transpose();
}

struct Scratch {
  fs::path dir = fs::temp_directory_path() / ("sheetgen_load_cases_test_" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() { std::error_code ec; fs::remove_all(dir, ec); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return (dir / name).string();
  }
};

// Runs the real CLI's check; exit code and stdout (or stderr with `errors`).
testing::CliRun run_check(const std::string& path, bool errors) {
  return testing::run_cli("check '" + path + "'" + (errors ? " 2>&1 >/dev/null" : " 2>/dev/null"));
}

// The six cases of FAR/CS 25.561(b)(3) with forward = +y and up = +z, so that
// left = up x forward = -x: each force is m * g0 * factor along its own axis.
TEST(LoadCases, Far25561PresetGivesSixForcesAlongTheAircraftAxes) {
  const Problem p = parse(enveloped_problem());
  const Load& box = p.loads[0];
  const double mg = 2.5 * kG0;  // N per g
  const std::vector<std::pair<std::string, Vec3>> want = {
      {"forward 9 g", Vec3(0, 9 * mg, 0)},  {"rearward 1.5 g", Vec3(0, -1.5 * mg, 0)}, {"left 3 g", Vec3(-3 * mg, 0, 0)},
      {"right 3 g", Vec3(3 * mg, 0, 0)},    {"down 6 g", Vec3(0, 0, -6 * mg)},        {"up 3 g", Vec3(0, 0, 3 * mg)},
  };
  ASSERT_EQ(box.cases.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) {
    EXPECT_EQ(box.cases[k].name, want[k].first);
    expect_vec(box.cases[k].force, want[k].second, 1e-9, want[k].first);
    EXPECT_TRUE(box.cases[k].moment.isZero(0)) << want[k].first;  // the force acts at the centre of mass
  }
  // Single-case code keeps reading the first case.
  expect_vec(box.force, want[0].second, 0, "Load::force");
  ASSERT_TRUE(p.load_cases);
  EXPECT_EQ(p.load_cases->preset, "far25.561");
  expect_vec(p.load_cases->left(), Vec3(-1, 0, 0), 1e-15, "left");
  expect_vec(p.load_cases->forward.cross(p.load_cases->left()), p.load_cases->up, 1e-15, "forward x left = up");
}

// An explicit factor list in oblique axes: forward (1, 1, 0)/sqrt 2, up +z, so
// left = (-1, 1, 0)/sqrt 2; g = (1, 2, 3) gives m g0 ((-1, 3, 0)/sqrt 2 + (0, 0, 3)).
// A load with its own force keeps it as "design", first; a load without a
// mass gets no inertia case.
TEST(LoadCases, FactorListCombinesWithTheDesignCaseOfMassedLoadsOnly) {
  json j = base_problem();
  j["loads"][0]["mass"] = 4.0;
  j["loads"][0]["center_of_mass"] = {0.32, 0.01, 0.29};
  json other = base_problem()["loads"][0];
  other["name"] = "light";
  other["center"] = {0.3, 0, 0.45};
  j["loads"].push_back(other);
  j["load_cases"] = {{"forward", {1, 1, 0}}, {"up", {0, 0, 1}},
                     {"factors", {{{"name", "oblique"}, {"g", {1, 2, 3}}, {"max_deflection", 2e-3}}}}};
  const Problem p = parse(j);
  const Load& box = p.loads[0];
  ASSERT_EQ(box.cases.size(), 2u);
  EXPECT_EQ(box.cases[0].name, "design");
  expect_vec(box.cases[0].force, Vec3(0, 0, -100), 0, "design");
  EXPECT_EQ(box.cases[1].name, "oblique");
  expect_vec(box.cases[1].force, 4.0 * kG0 * Vec3(-1 / std::sqrt(2.0), 3 / std::sqrt(2.0), 3), 1e-12, "oblique");
  EXPECT_EQ(box.cases[1].max_deflection, 2e-3);
  expect_vec(box.center_of_mass, Vec3(0.32, 0.01, 0.29), 0, "center_of_mass");
  expect_vec(box.force, Vec3(0, 0, -100), 0, "Load::force is the first case's");
  ASSERT_EQ(p.loads[1].cases.size(), 1u);
  EXPECT_EQ(p.loads[1].cases[0].name, "design");
  EXPECT_FALSE(p.loads[1].mass);
}

// Inertia about a uniform box's centroid in closed form, I_xx = m/12 (b^2 + c^2)
// etc., for the box as it lies and turned in the scene.
TEST(LoadCases, UniformBoxInertiaMatchesTheClosedFormWhenRotated) {
  const double m = 3.0, a = 0.2, b = 0.1, c = 0.05;
  const Vec3 size(a, b, c);
  const double A = m / 12 * (b * b + c * c), B = m / 12 * (a * a + c * c), C = m / 12 * (a * a + b * b);
  const Eigen::Matrix3d straight = uniform_box_inertia(m, size, Eigen::Quaterniond::Identity());
  EXPECT_TRUE(straight.isApprox(Vec3(A, B, C).asDiagonal().toDenseMatrix(), 1e-14)) << straight;
  // A quarter turn about z carries local x to world y: the world moments swap.
  const Eigen::Matrix3d quarter = uniform_box_inertia(m, size, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())));
  EXPECT_TRUE(quarter.isApprox(Vec3(B, A, C).asDiagonal().toDenseMatrix(), 1e-14)) << quarter;
  // 45 degrees about x mixes y and z: I_yy = I_zz = (B + C)/2, I_yz = (B - C)/2.
  const Eigen::Matrix3d tilted = uniform_box_inertia(m, size, Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 4, Vec3::UnitX())));
  Eigen::Matrix3d want;
  want << A, 0, 0, 0, (B + C) / 2, (B - C) / 2, 0, (B - C) / 2, (B + C) / 2;
  EXPECT_LE((tilted - want).cwiseAbs().maxCoeff(), 1e-14 * A) << tilted;

  // The reader fills the same default for a rotated box given only a mass.
  json j = base_problem();
  j["loads"][0]["mass"] = m;
  const double h = std::sqrt(0.5);
  j["loads"][0]["rotation"] = {h, h, 0, 0};  // 90 degrees about x
  const Load box = parse(j).loads[0];
  Eigen::Matrix3d turned = Vec3(A, C, B).asDiagonal();
  EXPECT_LE((box.inertia - turned).cwiseAbs().maxCoeff(), 1e-14 * A) << box.inertia;
  expect_vec(box.center_of_mass, box.center, 0, "default centre of mass");
}

// A given inertia is kept (made exactly symmetric), not replaced by the box's.
TEST(LoadCases, GivenInertiaIsKept) {
  json j = base_problem();
  j["loads"][0]["mass"] = 1.0;
  j["loads"][0]["inertia"] = {{0.02, 0.001, 0}, {0.001, 0.03, 0}, {0, 0, 0.04}};
  const Load box = parse(j).loads[0];
  EXPECT_DOUBLE_EQ(box.inertia(0, 1), 0.001);
  EXPECT_DOUBLE_EQ(box.inertia(2, 2), 0.04);
  EXPECT_EQ(box.inertia, box.inertia.transpose());
}

// Explicit cases replace `force`; a case's own max_deflection sets its
// compliance limit, C_max = |F| * delta.
TEST(LoadCases, ExplicitCasesAndTheirStiffnessLimits) {
  json j = base_problem();
  j["loads"][0].erase("force");
  j["loads"][0]["cases"] = {{{"name", "hang"}, {"force", {0, 0, -300}}},
                            {{"name", "twist"}, {"moment", {0, 5, 0}}},
                            {{"name", "push"}, {"force", {40, 0, 30}}, {"max_deflection", 0.5e-3}}};
  j["requirements"] = {{"max_deflection", 2e-3}};
  const Problem p = parse(j);
  const Load& box = p.loads[0];
  ASSERT_EQ(box.cases.size(), 3u);
  expect_vec(box.force, Vec3(0, 0, -300), 0, "Load::force");
  expect_vec(box.cases[1].moment, Vec3(0, 5, 0), 0, "twist moment");
  EXPECT_TRUE(box.cases[1].force.isZero(0));
  EXPECT_DOUBLE_EQ(p.requirements.compliance_limit(box.cases[0]), 300 * 2e-3);  // the problem's 2 mm
  EXPECT_DOUBLE_EQ(p.requirements.compliance_limit(box.cases[2]), 50 * 0.5e-3); // its own 0.5 mm, |F| = 50 N
}

TEST(LoadCases, BucklingFloorDefaultsToTheSafetyFactor) {
  json j = base_problem();
  j["requirements"] = {{"safety_factor", 2.0}};
  Problem p = parse(j);
  EXPECT_DOUBLE_EQ(p.requirements.min_buckling_factor, 2.0);
  EXPECT_FALSE(p.requirements.min_frequency_hz);
  j["requirements"] = {{"safety_factor", 2.0}, {"min_buckling_factor", 3.0}, {"min_frequency_hz", 25.0}};
  p = parse(j);
  EXPECT_DOUBLE_EQ(p.requirements.min_buckling_factor, 3.0);
  EXPECT_EQ(p.requirements.min_frequency_hz, 25.0);
}

// The buckling and frequency checks apply to a file that uses the envelope
// format or names a floor; a one-force file keeps the checks it had.
TEST(LoadCases, EigenChecksOnlyWhereTheFileAsksForThem) {
  json j = base_problem();
  EXPECT_FALSE(parse(j).requirements.eigen_checks);
  json with_floor = j;
  with_floor["requirements"] = {{"min_buckling_factor", 1.5}};
  EXPECT_TRUE(parse(with_floor).requirements.eigen_checks);
  json with_frequency = j;
  with_frequency["requirements"] = {{"min_frequency_hz", 30}};
  EXPECT_TRUE(parse(with_frequency).requirements.eigen_checks);
  json with_mass = j;
  with_mass["loads"][0]["mass"] = 2.0;
  EXPECT_TRUE(parse(with_mass).requirements.eigen_checks);
}

// An old file (one force, no mass) reads as before: the file's force and
// moment, one case "design", no mass, centre of mass at the centroid, and the
// defaults of the new requirements.
TEST(LoadCases, OldSingleForceFileReadsAsBefore) {
  json j = base_problem();
  j["loads"][0]["moment"] = {1, 2, 3};
  const Problem p = parse(j);
  const Load& box = p.loads[0];
  expect_vec(box.force, Vec3(0, 0, -100), 0, "force");
  expect_vec(box.moment, Vec3(1, 2, 3), 0, "moment");
  ASSERT_EQ(box.cases.size(), 1u);
  EXPECT_EQ(box.cases[0].name, "design");
  expect_vec(box.cases[0].force, box.force, 0, "design force");
  expect_vec(box.cases[0].moment, box.moment, 0, "design moment");
  EXPECT_FALSE(box.cases[0].max_deflection);
  EXPECT_FALSE(box.mass);
  expect_vec(box.center_of_mass, box.center, 0, "centre of mass");
  EXPECT_TRUE(box.inertia.isZero(0));
  EXPECT_FALSE(p.load_cases);
  EXPECT_DOUBLE_EQ(p.requirements.min_buckling_factor, p.requirements.safety_factor);
  EXPECT_FALSE(p.requirements.min_frequency_hz);
  EXPECT_DOUBLE_EQ(p.requirements.compliance_limit(box.cases[0]), p.requirements.compliance_limit(box.force.norm()));

  // A saved old file (the corner scene as it was written before the scenes
  // had envelopes): each load's force is the file's, one case, centre of mass
  // at the box's centre.
  const fs::path file = old_corner_file();
  const json raw = json::parse(std::ifstream(file));
  const Problem scene = load_problem(file.string());
  ASSERT_EQ(scene.loads.size(), 1u);
  const Load& l = scene.loads[0];
  const json& rl = raw["loads"][0];
  expect_vec(l.force, Vec3(rl["force"][0].get<double>(), rl["force"][1].get<double>(), rl["force"][2].get<double>()), 0,
             "old corner force");
  ASSERT_EQ(l.cases.size(), 1u);
  expect_vec(l.cases[0].force, l.force, 0, "old corner case");
  expect_vec(l.center_of_mass, l.center, 0, "old corner centre of mass");
  EXPECT_FALSE(scene.requirements.eigen_checks);
}

// `sheetgen check` lists every case with its force (%.4g of m g0 * 9 = 220.6 N).
TEST(LoadCases, CheckPrintsTheCases) {
  Scratch scratch;
  const auto [code, out] = run_check(scratch.write("env.json", enveloped_problem().dump()), false);
  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find("case forward 9 g      force [0, 220.6, 0] N"), std::string::npos) << out;
  EXPECT_NE(out.find("load cases: far25.561, 6 factors"), std::string::npos) << out;
  EXPECT_NE(out.find("mass 2.5 kg"), std::string::npos) << out;
  EXPECT_NE(out.find("min buckling factor 1.5, min frequency none"), std::string::npos) << out;
}

// An old one-force file names no floor: `check` says buckling and frequency
// are not checked rather than print a floor the search does not apply.
TEST(LoadCases, CheckSaysAnOldFileHasNoEigenChecks) {
  const auto [code, out] = run_check(old_corner_file().string(), false);
  EXPECT_EQ(code, 0) << out;
  EXPECT_NE(out.find("buckling and frequency not checked"), std::string::npos) << out;
  EXPECT_EQ(out.find("min buckling factor"), std::string::npos) << out;
}

struct BadInput {
  const char* label;
  std::function<void(json&)> edit;  // applied to enveloped_problem()
  const char* field;                // must appear in the message
  const char* problem;              // must appear in the message
};

TEST(LoadCases, EveryBadInputIsOneSentenceNamingTheField) {
  auto case_list = [](json& j, json cases) { j["loads"][0]["cases"] = std::move(cases); };
  const std::vector<BadInput> bad = {
      {"zero mass", [](json& j) { j["loads"][0]["mass"] = 0; }, "loads[0].mass", "must be greater than zero, got 0"},
      {"negative mass", [](json& j) { j["loads"][0]["mass"] = -2; }, "loads[0].mass", "must be greater than zero"},
      {"NaN mass", [](json& j) { j["loads"][0]["mass"] = "NAN_TOKEN"; }, "loads[0].mass", "finite number, got NaN"},
      {"overflowing mass", [](json& j) { j["loads"][0]["mass"] = 1e307; j["loads"][0]["inertia"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; },
       "loads[0].mass", "not finite"},
      {"skew axes", [](json& j) { j["load_cases"]["up"] = {0, 0.01, 1}; }, "load_cases.up", "not orthogonal"},
      {"zero forward", [](json& j) { j["load_cases"]["forward"] = {0, 0, 0}; }, "load_cases.forward", "zero length"},
      {"missing up", [](json& j) { j["load_cases"].erase("up"); }, "load_cases.up", "required field is missing"},
      {"unknown preset", [](json& j) { j["load_cases"]["factors"] = "far25.562"; }, "load_cases.factors", "unknown preset 'far25.562'"},
      {"no factors", [](json& j) { j["load_cases"]["factors"] = json::array(); }, "load_cases.factors", "no factors"},
      {"zero factor", [](json& j) { j["load_cases"]["factors"] = {{{"name", "still"}, {"g", {0, 0, 0}}}}; },
       "load_cases.factors[0].g", "no force and no moment"},
      {"duplicate factor", [](json& j) { j["load_cases"]["factors"] = {{{"name", "x"}, {"g", {1, 0, 0}}}, {{"name", "x"}, {"g", {2, 0, 0}}}}; },
       "load_cases.factors[1].name", "duplicate factor name 'x'"},
      {"envelope on no mass", [](json& j) { j["loads"][0].erase("mass"); j["loads"][0]["force"] = {0, 0, -10}; }, "load_cases",
       "no load has one"},
      {"case without force or moment", [&](json& j) { case_list(j, {{{"name", "idle"}}}); }, "loads[0].cases[0]",
       "case 'idle' has no force and no moment"},
      {"case of zero force and moment", [&](json& j) { case_list(j, {{{"name", "nil"}, {"force", {0, 0, 0}}, {"moment", {0, 0, 0}}}}); },
       "loads[0].cases[0]", "has no force and no moment"},
      {"duplicate case", [&](json& j) { case_list(j, {{{"name", "a"}, {"force", {1, 0, 0}}}, {{"name", "a"}, {"force", {2, 0, 0}}}}); },
       "loads[0].cases[1].name", "duplicate case name 'a'"},
      {"case named like a factor", [&](json& j) { case_list(j, {{{"name", "up 3 g"}, {"force", {1, 0, 0}}}}); },
       "loads[0].cases[0].name", "also a factor of load_cases"},
      {"cases and force", [&](json& j) { case_list(j, {{{"name", "a"}, {"force", {1, 0, 0}}}}); j["loads"][0]["force"] = {0, 0, -1}; },
       "loads[0].force", "not both"},
      {"empty cases", [&](json& j) { case_list(j, json::array()); }, "loads[0].cases", "no cases"},
      {"unknown case field", [&](json& j) { case_list(j, {{{"name", "a"}, {"forse", {1, 0, 0}}}}); }, "loads[0].cases[0]",
       "unknown field 'forse'"},
      {"inertia 2 rows", [](json& j) { j["loads"][0]["inertia"] = {{1, 0, 0}, {0, 1, 0}}; }, "loads[0].inertia", "expected a 3x3 array"},
      {"inertia short row", [](json& j) { j["loads"][0]["inertia"] = {{1, 0, 0}, {0, 1}, {0, 0, 1}}; }, "loads[0].inertia[1]",
       "expected an array of 3 numbers"},
      {"inertia asymmetric", [](json& j) { j["loads"][0]["inertia"] = {{1, 0.2, 0}, {0, 1, 0}, {0, 0, 1}}; }, "loads[0].inertia",
       "not symmetric"},
      {"inertia indefinite", [](json& j) { j["loads"][0]["inertia"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}}; }, "loads[0].inertia",
       "not positive definite"},
      {"inertia of no body", [](json& j) { j["loads"][0]["inertia"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 3}}; }, "loads[0].inertia",
       "not that of a rigid body"},
      {"inertia without mass", [](json& j) { j["loads"][0].erase("mass"); j["loads"][0]["force"] = {0, 0, -1}; j.erase("load_cases");
         j["loads"][0]["inertia"] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}; }, "loads[0].inertia", "without 'mass'"},
      {"centre of mass outside", [](json& j) { j["loads"][0]["center_of_mass"] = {0.3, 0, 0.4}; }, "loads[0].center_of_mass",
       "outside the load box"},
      {"mass but no case", [](json& j) { j.erase("load_cases"); }, "loads[0].force", "required field is missing"},
      {"buckling floor zero", [](json& j) { j["requirements"] = {{"min_buckling_factor", 0}}; }, "requirements.min_buckling_factor",
       "greater than zero"},
      {"frequency floor negative", [](json& j) { j["requirements"] = {{"min_frequency_hz", -5}}; }, "requirements.min_frequency_hz",
       "greater than zero"},
  };
  Scratch scratch;
  for (const auto& c : bad) {
    json j = enveloped_problem();
    c.edit(j);
    std::string text = j.dump();
    for (size_t pos; (pos = text.find("\"NAN_TOKEN\"")) != std::string::npos;) text.replace(pos, 11, "NaN");
    const std::string path = scratch.write(std::string("bad_") + std::to_string(&c - &bad[0]) + ".json", text);
    try {
      load_problem(path);
      ADD_FAILURE() << c.label << ": accepted";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(path + ": " + c.field + ": ", 0), 0u) << c.label << ": file and field not named in: " << msg;
      EXPECT_NE(msg.find(c.problem), std::string::npos) << c.label << ": problem '" << c.problem << "' not in: " << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << c.label << ": more than one line";
    }
    const auto [code, err] = run_check(path, true);
    EXPECT_EQ(code, 1) << c.label;
    EXPECT_NE(err.find(std::string(c.field) + ": "), std::string::npos) << c.label << ": " << err;
  }
}

}  // namespace
}  // namespace sheetgen
