// Hostile inputs (issue 9): each test poses one input a careless or malicious
// user could give, and asserts the specific outcome - the exact message, or the
// documented behaviour (docs/reliability.md). Problems go through load_problem
// and, where the outcome is user-facing, through the real `sheetgen check`.
#include <sys/resource.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/problem.hpp"
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include "../common/cli_path.hpp"
#include "../common/test_files.hpp"

extern char** environ;

namespace sheetgen {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, removed afterwards.
struct ScratchDir {
  fs::path dir;
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = fs::temp_directory_path() /
          ("sheetgen_reliability_" + std::to_string(::getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  fs::path write(const fs::path& rel, const std::string& bytes) const {
    const fs::path p = dir / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }
};

using testing::slurp;

struct CliRun {
  int exit_code = -1;
  std::string out, err;
  long peak_rss_kb = 0;  // of the sheetgen process itself (wait4)
  double seconds = 0;    // wall clock
};

// Runs the sheetgen CLI (common/cli_path.hpp) with `args` (no shell).
inline CliRun run_sheetgen(const std::vector<std::string>& args, const fs::path& scratch) {
  const std::string exe = sheetgen::testing::sheetgen_cli();
  std::vector<std::string> all{exe};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  const fs::path out = scratch / "cli.out", err = scratch / "cli.err";
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  CliRun r;
  pid_t pid = 0;
  const auto start = std::chrono::steady_clock::now();
  const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) {
    r.err = "posix_spawn failed";
    return r;
  }
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.peak_rss_kb = usage.ru_maxrss;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}


using nlohmann::json;

const char* kWallObjWithComment =
    "# wall 0.6 m, metres\nv 0 -0.3 0\nv 0 0.3 0\nv 0 0.3 0.6\nv 0 -0.3 0.6\nf 1 2 3\nf 1 3 4\n";

// The corner of problem_test.cpp, every mesh inline: a 0.6 m wall and floor, one box.
json corner(double scale = 1.0) {
  const double h = 0.3 * scale, L = 0.6 * scale;
  return json{{"format", "sheetgen-problem/1"},
              {"environment", {{"meshes", json::array({
                  {{"name", "wall"}, {"vertices", {{0, -h, 0}, {0, h, 0}, {0, h, L}, {0, -h, L}}}, {"triangles", {{0, 1, 2}, {0, 2, 3}}}},
                  {{"name", "floor"}, {"vertices", {{0, -h, 0}, {L, -h, 0}, {L, h, 0}, {0, h, 0}}}, {"triangles", {{0, 1, 2}, {0, 2, 3}}}}})}}},
              {"rivet_areas", json::array({{{"name", "wall_ra"}, {"mesh", "wall"}, {"faces", {0, 1}}}})},
              {"loads", json::array({{{"name", "box"}, {"center", {0.26 * scale, 0, 0.34 * scale}},
                                      {"size", {0.16 * scale, 0.12 * scale, 0.08 * scale}}, {"force", {0, 0, -353.16}}}})}};
}

template <class F>
InputError expect_one_line_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

// ---------------------------------------------------------------- degenerate and duplicate triangles

// An environment mesh with a duplicated triangle, a triangle with a repeated
// vertex and a collinear (zero-area) one loads as given: no repair, no error.
// Degenerate faces add no rivet area; a rivet area made only of them is refused;
// a duplicated face named twice in a rivet area is merged, but a second copy of
// the same geometry under another index counts again (the area is a sum over faces).
TEST(HostileInput, DegenerateAndDuplicateTrianglesLoadAsGiven) {
  ScratchDir scratch;
  json j = corner();
  auto& floor = j["environment"]["meshes"][1];
  floor["vertices"].push_back({0.3, -0.3, 0});                 // 4: midpoint of edge 0-1
  floor["triangles"] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 0, 1}, {0, 4, 1}};  // dup, repeated vertex, collinear
  j["rivet_areas"].push_back({{"name", "dup"}, {"mesh", "floor"}, {"faces", {0, 2, 2, 0}}});
  j["rivet_areas"].push_back({{"name", "mixed"}, {"mesh", "floor"}, {"faces", {1, 3, 4}}});
  const Problem p = parse_problem(j.dump(), "p.json", scratch.dir.string());
  ASSERT_EQ(p.meshes[1].mesh.triangles.size(), 5u);
  EXPECT_EQ(p.triangle_count(), 7);
  EXPECT_FALSE(p.meshes[1].mesh.is_closed());
  EXPECT_EQ(p.rivet_areas[1].faces, (std::vector<int>{0, 2}));
  EXPECT_NEAR(p.rivet_areas[1].area_m2, 2 * 0.18, 1e-12);      // two copies of a 0.18 m^2 triangle
  EXPECT_NEAR(p.rivet_areas[2].area_m2, 0.18, 1e-12);          // the degenerate faces add 0
  EXPECT_EQ(p.meshes[1].mesh.face_normal(3), Vec3::Zero());    // documented: zero normal when degenerate

  j["rivet_areas"].push_back({{"name", "only_degenerate"}, {"mesh", "floor"}, {"faces", {3, 4}}});
  EXPECT_EQ(std::string(expect_one_line_error([&] { parse_problem(j.dump(), "p.json", "."); }).what()),
            "p.json: rivet_areas[3].faces: rivet area 'only_degenerate' has zero area (degenerate faces).");
}

// The same mesh through `sheetgen check --env`: the clearance field and the ray
// caster accept degenerate and duplicate triangles (exit 0, queries printed).
TEST(HostileInput, DegenerateTrianglesThroughCheckEnv) {
  ScratchDir scratch;
  json j = corner();
  auto& floor = j["environment"]["meshes"][1];
  floor["vertices"].push_back({0.3, -0.3, 0});
  floor["triangles"] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 2}, {0, 0, 1}, {0, 4, 1}};
  const fs::path path = scratch.write("problem.json", j.dump());
  const CliRun r = run_sheetgen({"check", "--env", path.string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("floor                       5 triangles"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ray -z: hits mesh floor"), std::string::npos) << r.out;
}

// ---------------------------------------------------------------- scale

// A 2 km scene (the corner scaled by 3333) with a normal 0.16 m box loads, is
// not mistaken for millimetres, and `check` summarises it. Environment building
// at this scale is measured in docs/reliability.md (an env issue, not tested here).
TEST(HostileInput, KilometreScaleSceneLoads) {
  ScratchDir scratch;
  json j = corner(2000.0 / 0.6);
  j["loads"][0]["center"] = {0.3, 0, 0.3};
  j["loads"][0]["size"] = {0.16, 0.12, 0.08};
  const Problem p = parse_problem(j.dump(), "p.json", ".");
  EXPECT_NEAR(p.bounds().diagonal(), std::sqrt(3.0) * 2000.0, 1e-6);
  EXPECT_NEAR(p.rivet_areas[0].area_m2, 2000.0 * 2000.0, 1e-3);
  const CliRun r = run_sheetgen({"check", scratch.write("km.json", j.dump()).string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(diagonal 3464 m)"), std::string::npos) << r.out;
}

// A 200 um scene with a 20 um box loads with its areas exact (no rounding to 0).
// A scene 200 micrometres across: its rivet areas cannot hold a 1.6 mm sheet's
// flange (12.8 x 16 mm), so the problem is refused with that reason, through
// the library and the CLI (which also never reaches the environment build,
// where OpenVDB would refuse a sub-micrometre voxel).
TEST(HostileInput, MicrometreScaleSceneIsRefusedForItsRivetAreas) {
  ScratchDir scratch;
  const double s = 200e-6 / 0.6;
  const std::string msg = expect_one_line_error([&] { parse_problem(corner(s).dump(), "p.json", "."); }).what();
  EXPECT_NE(msg.find("smaller than the smallest rivet flange (12.8 x 16.0 mm"), std::string::npos) << msg;
  const CliRun r = run_sheetgen({"check", "--env", scratch.write("um.json", corner(s).dump()).string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
}

// The corner exported in millimetres by mistake: a box 160 units wide in a scene
// 849 units across. Refused with the likely cause, at the load's size.
TEST(HostileInput, MillimetreSceneIsRefusedAsAUnitSlip) {
  ScratchDir scratch;
  const json j = corner(1000.0);
  const std::string expected =
      "p.json: loads[0].size: load box is 160 m across in a scene 1039 m across: the file looks like it is in "
      "millimetres (problem files are in metres; scale the scene by 0.001).";
  EXPECT_EQ(std::string(expect_one_line_error([&] { parse_problem(j.dump(), "p.json", "."); }).what()), expected);
  const fs::path path = scratch.write("mm.json", j.dump());
  const CliRun r = run_sheetgen({"check", path.string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("the file looks like it is in millimetres"), std::string::npos) << r.err;
  // Either condition alone is legitimate: a 12.8 m load in a 48 m hangar
  // (diagonal 83 m), a 0.16 m load in a 2 km scene (KilometreScaleSceneLoads).
  json hangar = corner(80.0);
  EXPECT_NO_THROW(parse_problem(hangar.dump(), "p.json", "."));
}

// ---------------------------------------------------------------- bad numbers, truncation, size

TEST(HostileInput, NanInAForceIsNamed) {
  std::string text = corner().dump();
  const std::string force = "\"force\":[0,0,-353.16]";
  ASSERT_NE(text.find(force), std::string::npos);
  text.replace(text.find(force), force.size(), "\"force\": [0, NaN, -353.16]");
  EXPECT_EQ(std::string(expect_one_line_error([&] { parse_problem(text, "p.json", "."); }).what()),
            "p.json: loads[0].force[1]: expected a finite number, got NaN.");
}

// Every prefix of a valid file (cut anywhere) is an InputError, never a crash.
TEST(HostileInput, TruncatedProblemFileIsInvalidJson) {
  ScratchDir scratch;
  const std::string text = corner().dump(1);
  // Cut where a download or a full disk would: here just before "loads".
  const fs::path path = scratch.write("cut.json", text.substr(0, text.find("\"loads\"")));
  const InputError e = expect_one_line_error([&] { load_problem(path.string()); });
  EXPECT_EQ(e.field(), "");
  EXPECT_EQ(e.problem().rfind("is not valid JSON (parse error at line ", 0), 0u) << e.what();
  EXPECT_NE(e.problem().find("unexpected end of input"), std::string::npos) << e.what();
  const CliRun r = run_sheetgen({"check", path.string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("is not valid JSON"), std::string::npos) << r.err;
  for (size_t n = 0; n < text.size(); n += 7)
    EXPECT_THROW(parse_problem(text.substr(0, n), "p.json", "."), InputError) << n;
}

// A 1 GiB problem file (sparse: costs no disk) is refused before it is read:
// the CLI stays small.
TEST(HostileInput, OneGigabyteProblemFileIsRefusedUnread) {
  ScratchDir scratch;
  const fs::path path = scratch.dir / "huge.json";
  std::ofstream(path).put('{');
  fs::resize_file(path, 1ull << 30);
  EXPECT_EQ(std::string(expect_one_line_error([&] { load_problem(path.string()); }).what()),
            path.string() + ": is 1024 MiB; problem files are limited to 256 MiB (put large meshes in OBJ/PLY files).");
  const CliRun r = run_sheetgen({"check", path.string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_LT(r.peak_rss_kb, 256 * 1024) << "the file was read";  // well under the file's 1 GiB
}

// Same for a mesh file it names: a sparse 3 GiB OBJ is refused unread (mesh
// files are limited to 2 GiB; before, it was read whole, twice over).
TEST(HostileInput, HugeMeshFileIsRefusedUnread) {
  ScratchDir scratch;
  const fs::path mesh = scratch.dir / "huge.obj";
  std::ofstream(mesh).put('v');
  fs::resize_file(mesh, 3ull << 30);
  json j = corner();
  j["environment"]["meshes"][0] = {{"name", "wall"}, {"file", "huge.obj"}};
  const fs::path path = scratch.write("p.json", j.dump());
  EXPECT_EQ(std::string(expect_one_line_error([&] { load_problem(path.string()); }).what()),
            path.string() + ": environment.meshes[0].file: cannot read mesh file '" + mesh.string() +
                "': is 3072 MiB; mesh files are limited to 2048 MiB.");
  const CliRun r = run_sheetgen({"check", path.string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_LT(r.peak_rss_kb, 256 * 1024);
}

// A 256 MiB OBJ of zero bytes (under the cap) is read once and scanned in
// place: the CLI's peak memory stays under twice the file (it was ~5x: a
// stream copy, a getline copy and a line stream copy of the one huge line).
TEST(HostileInput, LargeOneLineObjIsScannedInPlace) {
  ScratchDir scratch;
  const fs::path mesh = scratch.dir / "zeros.obj";
  std::ofstream(mesh).put('#');
  fs::resize_file(mesh, 256ull << 20);
  json j = corner();
  j["environment"]["meshes"][0] = {{"name", "wall"}, {"file", "zeros.obj"}};
  const fs::path path = scratch.write("p.json", j.dump());
  const CliRun r = run_sheetgen({"check", path.string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "sheetgen: " + path.string() + ": environment.meshes[0] (" + mesh.string() +
                       "): the mesh is empty (0 vertices, 0 triangles).\n");
  EXPECT_LT(r.peak_rss_kb, 2 * 256 * 1024) << "KB";
}

// ---------------------------------------------------------------- names

// Problem and mesh files in "dir with spaces/ñandú", with spaces and non-ASCII
// in their own names: loads, and errors quote the names byte for byte.
TEST(HostileInput, PathsWithSpacesAndNonAsciiNames) {
  ScratchDir scratch;
  const fs::path dir = scratch.dir / "dir with spaces" / u8"ñandú";
  scratch.write(dir / u8"pared ñ.obj", kWallObjWithComment);
  scratch.write(dir / u8"suelo ü.ply",
                "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 -0.3 0\n0.6 -0.3 0\n0.6 0.3 0\n0 0.3 0\n4 0 1 2 3\n");
  json j = corner();
  j["environment"]["meshes"][0] = {{"name", u8"pared ñ"}, {"file", u8"pared ñ.obj"}};
  j["environment"]["meshes"][1] = {{"name", "suelo"}, {"file", u8"suelo ü.ply"}};
  j["rivet_areas"][0]["mesh"] = u8"pared ñ";
  const fs::path path = scratch.write(dir / u8"problème 1.json", j.dump());
  const Problem p = load_problem(path.u8string());
  EXPECT_EQ(p.meshes[0].source, (dir / u8"pared ñ.obj").u8string());
  EXPECT_EQ(p.meshes[1].mesh.triangles.size(), 2u);
  EXPECT_NEAR(p.rivet_areas[0].area_m2, 0.36, 1e-12);
  const CliRun r = run_sheetgen({"check", "--env", path.u8string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(u8"ñandú/pared ñ.obj"), std::string::npos) << r.out;

  j["environment"]["meshes"][1]["file"] = u8"falta é.obj";
  const fs::path bad = scratch.write(dir / u8"problème 2.json", j.dump());
  const CliRun r2 = run_sheetgen({"check", bad.u8string()}, scratch.dir);
  EXPECT_EQ(r2.exit_code, 1);
  EXPECT_EQ(r2.err, "sheetgen: " + bad.u8string() + ": environment.meshes[1].file: mesh file '" +
                        (dir / u8"falta é.obj").u8string() + "' does not exist or is not a regular file.\n");
}

// ---------------------------------------------------------------- many loads

// 10 000 loads load (the time `sheetgen check` takes is measured in
// docs/reliability.md, not asserted); a duplicate name is found at the end.
TEST(HostileInput, TenThousandLoads) {
  ScratchDir scratch;
  json j = corner();
  json loads = json::array();
  for (int i = 0; i < 10000; ++i)
    loads.push_back({{"name", "box" + std::to_string(i)}, {"center", {0.1 + 0.00004 * i, 0, 0.34}},
                     {"size", {0.02, 0.02, 0.02}}, {"force", {0, 0, -1.0 - i}}});
  j["loads"] = loads;
  const fs::path path = scratch.write("many.json", j.dump());
  const Problem p = load_problem(path.string());
  ASSERT_EQ(p.loads.size(), 10000u);
  EXPECT_EQ(p.loads[9999].name, "box9999");
  EXPECT_DOUBLE_EQ(p.loads[9999].force.z(), -10000.0);
  const CliRun r = run_sheetgen({"check", path.string()}, scratch.dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("loads: 10000"), std::string::npos);

  j["loads"][9999]["name"] = "box17";
  EXPECT_EQ(std::string(expect_one_line_error([&] { parse_problem(j.dump(), "p.json", "."); }).what()),
            "p.json: loads[9999].name: duplicate load name 'box17'.");
}

}  // namespace
}  // namespace sheetgen

