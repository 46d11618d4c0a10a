// Fuzz regressions (issue 9): every input that crashed, hung or blew up memory
// in tests/fuzz/ is replayed here with the outcome it must have now, and every
// file in tests/fuzz/regressions/<target>/ is replayed under the fuzzers'
// contract (loads, or one-line InputError naming the file; nothing else).
#include <gtest/gtest.h>

#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/mesh_io.hpp"
#include "sheetgen/core/problem.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(SHEETGEN_SOURCE_DIR) / "tests" / "fuzz";

std::string slurp_existing(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  EXPECT_TRUE(in) << p;
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `f`, which must throw InputError; returns it for further checks.
template <class F>
InputError expect_input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "not one line: " << msg;
    EXPECT_EQ(msg.back(), '.') << msg;
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", "", "");
}

std::string mesh_dir() { return (kFuzzDir / "mesh_dir").string(); }

// ---------------------------------------------------------------- crashes the fuzzers found

// fuzz_problem_json, first minute: nlohmann throws out_of_range (406), not
// parse_error, for a number literal beyond double; it escaped as an internal
// error (CLI exit 3). Now a JSON error like any other.
TEST(FuzzRegression, NumberOverflowIsInvalidJson) {
  const std::string text = slurp_existing(kFuzzDir / "regressions/fuzz_problem_json/number_overflow_1e999.json");
  const InputError e = expect_input_error([&] { parse_problem(text, "p.json", mesh_dir()); });
  EXPECT_EQ(e.field(), "");
  EXPECT_EQ(std::string(e.what()), "p.json: is not valid JSON (number overflow parsing '1e999').");
  // The same literal in a well-formed problem, in a field: still named as overflow.
  const InputError e2 = expect_input_error([&] { parse_problem(R"({"format": "sheetgen-problem/1", "loads": [{"force": [0, 0, -1e999]}]})", "q.json", "."); });
  EXPECT_EQ(std::string(e2.what()), "q.json: is not valid JSON (number overflow parsing '-1e999').");
}

// fuzz_mesh_readers, first minute: a binary PLY whose face list (uint) held
// 2587880000 was cast to int (UBSan: outside the range of representable values).
TEST(FuzzRegression, PlyFaceIndexBeyondIntIsRefused) {
  const std::string bytes = slurp_existing(kFuzzDir / "regressions/fuzz_mesh_readers/ply_index_outside_int.ply");
  const InputError e = expect_input_error([&] { parse_ply(bytes, "m.ply"); });
  EXPECT_EQ(e.field().rfind("face ", 0), 0u) << e.what();
  EXPECT_NE(e.problem().find("is not a valid index"), std::string::npos) << e.what();
}

// Same class, written by hand: float and NaN indices, and the largest uint.
TEST(FuzzRegression, PlyNonIntegerIndicesAreRefused) {
  auto ply = [](const std::string& type, const std::string& face) {
    return "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           "element face 1\nproperty list uchar " + type + " vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n" + face + "\n";
  };
  for (const auto& bad : {std::pair{"float", "3 0 1 1e30"}, {"float", "3 0 1 nan"}, {"float", "3 0 1 1.5"},
                          {"uint", "3 0 1 4294967295"}, {"int", "3 0 1 -1"}}) {
    // Not a structured binding: a lambda may capture one only from C++20 on (clang refuses it).
    const std::string type = bad.first, face = bad.second;
    SCOPED_TRACE(face);
    const InputError e = expect_input_error([&] { parse_ply(ply(type, face), "m.ply"); });
    EXPECT_EQ(e.field(), "face 0");
    EXPECT_NE(e.problem().find("is not a valid index"), std::string::npos) << e.what();
  }
  EXPECT_EQ(std::string(expect_input_error([&] { parse_ply(ply("uint", "3 0 1 4294967295"), "m.ply"); }).what()),
            "m.ply: face 0: vertex index 4294967295 is not a valid index.");
  EXPECT_EQ(std::string(expect_input_error([&] { parse_ply(ply("float", "3 0 1 1.5"), "m.ply"); }).what()),
            "m.ply: face 0: vertex index 1.5 is not a valid index.");
  // The valid version still reads.
  EXPECT_EQ(parse_ply(ply("float", "3 0 1 2"), "m.ply").triangles.size(), 1u);
}

// Found by reading the PLY reader and confirmed with the fuzzer binary (libFuzzer
// timeout after 6 s): an element with no properties and a count of 2^62 passed the
// size guard (it takes no bytes) and the reader looped over every entry.
TEST(FuzzRegression, PlyElementWithoutPropertiesDoesNotHang) {
  const std::string bytes = slurp_existing(kFuzzDir / "regressions/fuzz_mesh_readers/ply_element_without_properties_huge_count.ply");
  const auto start = std::chrono::steady_clock::now();
  const TriangleMesh m = parse_ply(bytes, "m.ply");
  EXPECT_EQ(m.vertices.size(), 3u);
  ASSERT_EQ(m.triangles.size(), 1u);
  EXPECT_EQ(m.triangles[0], (std::array<int, 3>{0, 1, 2}));
  // Not a timing test: the old code took longer than the age of the universe.
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 60.0);
}

// fuzz_mesh_readers, run 4 (10 214 execs): an ASCII PLY whose header ends
// with "end_header" and no newline put the data offset one past the end, and
// bytes.substr() threw std::out_of_range (CLI: internal error).
TEST(FuzzRegression, PlyHeaderEndingWithoutNewline) {
  const std::string bytes = slurp_existing(kFuzzDir / "regressions/fuzz_mesh_readers/ply_ascii_end_header_without_newline.ply");
  expect_input_error([&] { validate_mesh(parse_ply(bytes, "m.ply"), "m.ply", "mesh"); });
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header";
  EXPECT_EQ(std::string(expect_input_error([&] { parse_ply(header, "m.ply"); }).what()),
            "m.ply: vertex 0: file ends early (truncated PLY).");
  // A header with no elements and no data is an empty mesh, refused by validate_mesh.
  EXPECT_TRUE(parse_ply("ply\nformat ascii 1.0\nend_header", "m.ply").vertices.empty());
}

// Found by the fuzzer's one-line check (run by hand on a crafted key): a JSON key
// or name with "\n" put a raw newline into the message the CLI prints as one line.
TEST(FuzzRegression, ControlCharactersInMessagesAreEscaped) {
  const std::string text = slurp_existing(kFuzzDir / "regressions/fuzz_problem_json/newline_in_key.json");
  const InputError e = expect_input_error([&] { parse_problem(text, "p.json", mesh_dir()); });
  EXPECT_EQ(e.field(), "(top level)");
  EXPECT_EQ(std::string(e.what()).substr(0, 45), "p.json: (top level): unknown field 'a\\nb' (ex");
  // The raw parts stay available to callers that want them.
  EXPECT_EQ(e.problem().substr(0, 18), "unknown field 'a\nb");
  // Other control characters show as \xNN.
  EXPECT_EQ(std::string(InputError("f\x01", "", "x\ty\r").what()), "f\\x01: x\\ty\\r.");
}

// Found by reading: integers of 2^63 and above are stored unsigned by nlohmann and
// wrapped to negative numbers ("face index -1 is out of range").
TEST(FuzzRegression, HugeUnsignedIntegersAreNamedTooLarge) {
  const std::string text = R"({"format": "sheetgen-problem/1",
    "environment": {"meshes": [{"name": "w", "file": "wall.obj"}]},
    "rivet_areas": [{"name": "r", "mesh": "w", "faces": [18446744073709551615]}],
    "loads": [{"name": "b", "center": [0.3, 0, 0.3], "size": [0.1, 0.1, 0.1], "force": [0, 0, -1]}]})";
  const InputError e = expect_input_error([&] { parse_problem(text, "p.json", mesh_dir()); });
  EXPECT_EQ(std::string(e.what()), "p.json: rivet_areas[0].faces[0]: integer 18446744073709551615 is too large.");
}

// Found by reading: a quaternion with components of 1e200 squared to inf and
// normalised to a zero quaternion (a load box collapsed to a point); one of
// 1e-200 underflowed to "zero length". Both are valid directions.
TEST(FuzzRegression, QuaternionOfExtremeMagnitudeNormalises) {
  auto num = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  for (double s : {1e200, 1e-200, 1.0}) {
    SCOPED_TRACE(s);
    const std::string text = R"({"format": "sheetgen-problem/1",
      "environment": {"meshes": [{"name": "w", "file": "wall.obj"}]},
      "rivet_areas": [{"name": "r", "mesh": "w", "faces": [0]}],
      "loads": [{"name": "b", "center": [0.3, 0, 0.3], "size": [0.1, 0.2, 0.3], "force": [0, 0, -1],
                 "rotation": [)" + num(s) + ", 0, 0, " + num(s) + "]}]}";
    const Problem p = parse_problem(text, "p.json", mesh_dir());
    // 90 degrees about z: w = z = 1/sqrt(2).
    EXPECT_NEAR(p.loads[0].rotation.w(), std::sqrt(0.5), 1e-15);
    EXPECT_NEAR(p.loads[0].rotation.z(), std::sqrt(0.5), 1e-15);
    const auto c = p.loads[0].corners();
    EXPECT_NEAR((c[7] - c[0]).norm(), std::sqrt(0.01 + 0.04 + 0.09), 1e-12);  // the box keeps its size
  }
}

// ---------------------------------------------------------------- memory blow-up

// A PLY header declaring 2^31 vertices in a 200-byte file must not reserve 48 GiB.
TEST(FuzzRegression, PlyHeaderWithHugeCountIsRefusedBeforeAllocating) {
  const std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2147483648\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" + std::string(12, '\0');
  const InputError e = expect_input_error([&] { parse_ply(ply, "m.ply"); });
  EXPECT_EQ(std::string(e.what()), "m.ply: element vertex: declares 2147483648 entries but the file is too short (truncated PLY).");
  // Also as ASCII, and for faces.
  const std::string ascii =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4294967296\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  const InputError e2 = expect_input_error([&] { parse_ply(ascii, "m.ply"); });
  EXPECT_EQ(e2.field(), "element face");
}

// OBJ face indices beyond long long, beyond int and beyond the vertices read so far.
TEST(FuzzRegression, ObjHugeFaceIndexIsRefused) {
  const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(std::string(expect_input_error([&] { parse_obj(v + "f 1 2 99999999999999999999\n", "m.obj"); }).what()),
            "m.obj: line 4: face index '99999999999999999999' is not a valid OBJ index.");
  EXPECT_EQ(std::string(expect_input_error([&] { parse_obj(v + "f 1 2 2147483648\n", "m.obj"); }).what()),
            "m.obj: line 4: face index 2147483648 is out of range (3 vertices so far).");
  EXPECT_EQ(std::string(expect_input_error([&] { parse_obj(v + "f 1 2 -9223372036854775808\n", "m.obj"); }).what()),
            "m.obj: line 4: face index -9223372036854775808 is out of range (3 vertices so far).");
}

// 100 000 nested arrays: the parser and the destructor are iterative in
// nlohmann 3.11 (no stack overflow); the reader then names the wrong type.
TEST(FuzzRegression, DeeplyNestedJsonDoesNotOverflowTheStack) {
  const int depth = 100000;
  const std::string nested = std::string(depth, '[') + std::string(depth, ']');
  EXPECT_EQ(std::string(expect_input_error([&] { parse_problem(nested, "p.json", "."); }).what()),
            "p.json: (top level): expected an object, got an array.");
  const std::string in_field = R"({"format": "sheetgen-problem/1", "loads": )" + nested + "}";
  EXPECT_EQ(std::string(expect_input_error([&] { parse_problem(in_field, "p.json", "."); }).what()),
            "p.json: environment: required field is missing.");
}

// ---------------------------------------------------------------- every saved input

// Replays tests/fuzz/regressions/ under the fuzzers' contract, so an input
// saved there later is covered without a new test.
TEST(FuzzRegression, EverySavedInputKeepsTheContract) {
  int replayed = 0;
  for (const char* target : {"fuzz_problem_json", "fuzz_mesh_readers"}) {
    const fs::path dir = kFuzzDir / "regressions" / target;
    if (!fs::exists(dir)) continue;
    for (const auto& entry : fs::directory_iterator(dir)) {
      SCOPED_TRACE(entry.path().string());
      const std::string bytes = slurp_existing(entry.path());
      ++replayed;
      auto check = [&](auto&& f, const char* file) {
        try {
          f();
        } catch (const InputError& e) {
          const std::string msg = e.what();
          EXPECT_EQ(msg.rfind(file, 0), 0u) << msg;
          EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
      };
      if (std::string(target) == "fuzz_problem_json") {
        check([&] { parse_problem(bytes, "fuzz.json", mesh_dir()); }, "fuzz.json");
      } else {
        check([&] { validate_mesh(parse_obj(bytes, "fuzz.obj"), "fuzz.obj", "mesh"); }, "fuzz.obj");
        check([&] { validate_mesh(parse_ply(bytes, "fuzz.ply"), "fuzz.ply", "mesh"); }, "fuzz.ply");
      }
    }
  }
  EXPECT_GE(replayed, 4);
}

}  // namespace
}  // namespace sheetgen
