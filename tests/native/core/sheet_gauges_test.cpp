// Sheet gauges (core/sheet_gauges.hpp): the default ladder, and a problem
// moved to another gauge derives what scales with the thickness exactly as a
// file written at that thickness would, and keeps what the file gave.
#include "sheetgen/core/sheet_gauges.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace sheetgen {
namespace {

using nlohmann::json;

constexpr double kInch = 0.0254;

Problem parse(const json& j) { return parse_problem(j.dump(), "gauges.json", "."); }

json problem_json() {
  return json::parse(R"({
    "format": "sheetgen-problem/1",
    "environment": {"meshes": [
      {"name": "floor", "vertices": [[0,-0.3,0],[0.6,-0.3,0],[0.6,0.3,0],[0,0.3,0]], "triangles": [[0,1,2],[0,2,3]]}]},
    "rivet_areas": [{"name": "floor_ra", "mesh": "floor", "faces": [0, 1]}],
    "loads": [{"name": "box", "center": [0.3, 0, 0.3], "size": [0.1, 0.1, 0.1], "force": [0, 0, -100]}]
  })");
}

// A load in the envelope format (a mass and the FAR 25.561 factors).
json envelope_json() {
  json j = problem_json();
  j["loads"][0].erase("force");
  j["loads"][0]["mass"] = 2.0;
  j["load_cases"] = {{"forward", {1, 0, 0}}, {"up", {0, 0, 1}}, {"factors", "far25.561"}};
  return j;
}

TEST(SheetGauges, TheDefaultLadderIsTheStandardGaugesAboveTheSheet) {
  const Problem p = parse(envelope_json());
  // 0.063 in (1.6 mm) sheet: 0.071, 0.080, 0.090, 0.100, 0.125 and 0.160 in.
  const std::vector<double> inches = {0.071, 0.080, 0.090, 0.100, 0.125, 0.160};
  ASSERT_EQ(p.material.gauges.size(), inches.size());
  for (size_t k = 0; k < inches.size(); ++k) EXPECT_DOUBLE_EQ(p.material.gauges[k], inches[k] * kInch) << k;
  // A sheet of the last gauge has none above it; one between gauges starts at the next.
  EXPECT_TRUE(default_gauges(0.160 * kInch).empty());
  ASSERT_FALSE(default_gauges(2.2e-3).empty());
  EXPECT_DOUBLE_EQ(default_gauges(2.2e-3).front(), 0.090 * kInch);
  // A file with one force per load solves as it was written for: in its own sheet.
  EXPECT_TRUE(parse(problem_json()).material.gauges.empty());
  // Listed gauges replace the ladder, in either format; an empty list turns it off.
  json j = problem_json();
  j["material"]["gauges"] = {0.002, 0.003};
  EXPECT_EQ(parse(j).material.gauges, (std::vector<double>{0.002, 0.003}));
  j["material"]["gauges"] = json::array();
  EXPECT_TRUE(parse(j).material.gauges.empty());
}

// at_gauge(problem at t1, t2) has the manufacturing lengths of the same file
// written at t2: R = 4 t, min flange 4 t + R, w_min = 10 t, l_min = 2 R + 2 t,
// the rivet 2 t rounded up to 1/32 in (at least 1/8 in), its edge distance and pitch.
TEST(SheetGauges, AnotherGaugeDerivesWhatAFileAtThatThicknessWould) {
  for (double t2 : {0.071 * kInch, 0.125 * kInch, 0.160 * kInch}) {
    json at_t2 = problem_json();
    at_t2["material"]["thickness"] = t2;
    const Manufacturing want = parse(at_t2).manufacturing;
    const Problem moved = at_gauge(parse(problem_json()), t2);
    const Manufacturing& got = moved.manufacturing;
    EXPECT_DOUBLE_EQ(moved.material.thickness, t2);
    EXPECT_DOUBLE_EQ(got.bend_radius, 4 * t2);
    EXPECT_DOUBLE_EQ(got.bend_radius, want.bend_radius);
    EXPECT_DOUBLE_EQ(got.min_flange, want.min_flange);
    EXPECT_DOUBLE_EQ(got.min_tab_width, 10 * t2);
    EXPECT_DOUBLE_EQ(got.min_tab_length, want.min_tab_length);
    EXPECT_DOUBLE_EQ(got.rivet_diameter, want.rivet_diameter);
    EXPECT_DOUBLE_EQ(got.rivet_edge_distance, want.rivet_edge_distance);
    EXPECT_DOUBLE_EQ(got.rivet_pitch, want.rivet_pitch);
  }
  // 0.125 in: D = 2 t = 6.35 mm, exactly 8/32 in.
  EXPECT_NEAR(at_gauge(parse(problem_json()), 0.125 * kInch).manufacturing.rivet_diameter, 6.35e-3, 1e-12);
  // 0.071 in: 2 t = 3.607 mm rounds up to 5/32 in (3.969 mm).
  EXPECT_NEAR(at_gauge(parse(problem_json()), 0.071 * kInch).manufacturing.rivet_diameter, 5 * 0.79375e-3, 1e-12);
}

TEST(SheetGauges, LengthsTheFileGaveStayAtEveryGauge) {
  json j = problem_json();
  j["manufacturing"] = {{"bend_radius", 0.004}, {"rivet_diameter", 0.0048}};
  const Problem moved = at_gauge(parse(j), 3.175e-3);
  EXPECT_DOUBLE_EQ(moved.manufacturing.bend_radius, 0.004);
  EXPECT_DOUBLE_EQ(moved.manufacturing.min_flange, 4 * 3.175e-3 + 0.004);  // 4 t + the given R
  EXPECT_DOUBLE_EQ(moved.manufacturing.rivet_diameter, 0.0048);
  EXPECT_DOUBLE_EQ(moved.manufacturing.rivet_pitch, 6 * 0.0048);
  // problem_at_sheet: the problem's own sheet (or none given) leaves it untouched.
  Problem by_hand = parse(problem_json());
  by_hand.manufacturing.bend_radius = 1e-3;  // set in code, not in `given`
  std::optional<Problem> storage;
  EXPECT_EQ(&problem_at_sheet(by_hand, 1.6e-3, storage), &by_hand);  // itself, not a copy
  EXPECT_EQ(&problem_at_sheet(by_hand, 0.0, storage), &by_hand);
  EXPECT_FALSE(storage.has_value());
  EXPECT_DOUBLE_EQ(problem_at_sheet(by_hand, 2.0e-3, storage).manufacturing.bend_radius, 8e-3);
  EXPECT_TRUE(storage.has_value());
}

}  // namespace
}  // namespace sheetgen
