// Exports: DXF R12 structure and numbers, SVG, bend table, OBJ, JSON. The
// sample part's files are also written for tests/python/test_part_dxf.py
// (to $SHEETGEN_PART_DXF_OUT, else <build>/part_test_output/flat.dxf).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sheetgen/part/bend_sequence.hpp"
#include "sheetgen/part/exports.hpp"
#include "../common/dxf_pairs.hpp"
#include "../common/sample_part.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::kDeg;

using fixtures::spec;

Part sample() { return fixtures::four_bend_sample(); }

std::vector<std::pair<int, std::string>> pairs(const std::string& dxf) { return fixtures::dxf_pairs(dxf); }

int count(const std::vector<std::pair<int, std::string>>& p, int code, const std::string& value) {
  int n = 0;
  for (const auto& kv : p) n += (kv.first == code && kv.second == value);
  return n;
}

TEST(Exports, SamplePartIsValidAndPlanned) {
  const Part part = sample();
  const RealisedPart rp = realise(part);
  EXPECT_TRUE(check_validity(part, rp, spec()).valid()) << check_validity(part, rp, spec()).summary();
  const FlatPattern flat = unfold(part, spec());
  ASSERT_TRUE(flat.ok()) << flat.message;
  EXPECT_TRUE(check_flat_pattern(flat, spec()).valid()) << check_flat_pattern(flat, spec()).summary();
  EXPECT_TRUE(plan_bend_sequence(part, spec()).ok());
}

TEST(Exports, DxfStructure) {
  const Part part = sample();
  const FlatPattern flat = unfold(part, spec());
  const std::string dxf = flat_pattern_dxf(flat);
  const auto p = pairs(dxf);
  ASSERT_GT(p.size(), 10u);
  EXPECT_EQ(p.back(), std::make_pair(0, std::string("EOF")));
  EXPECT_EQ(count(p, 1, "AC1009"), 1);
  // $INSUNITS followed by 70 / 4 (millimetres).
  EXPECT_EQ(count(p, 9, "$INSUNITS"), 1);
  for (size_t i = 0; i + 1 < p.size(); ++i) {
    if (p[i].second == "$INSUNITS") {
      EXPECT_EQ(p[i + 1], std::make_pair(70, std::string("4")));
    }
  }
  EXPECT_EQ(count(p, 0, "SECTION"), count(p, 0, "ENDSEC"));
  EXPECT_EQ(count(p, 2, "DASHED"), 1);  // defined once in LTYPE
  EXPECT_EQ(count(p, 6, "DASHED"), 2 + 4);  // two bend layers + four lines
  EXPECT_EQ(count(p, 0, "POLYLINE"), 1);
  EXPECT_EQ(count(p, 0, "VERTEX"), static_cast<int>(flat.outline.size()));
  EXPECT_EQ(count(p, 0, "LINE"), 4);
  EXPECT_EQ(count(p, 0, "TEXT"), 4);
  EXPECT_EQ(count(p, 8, "BEND_UP"), 2);    // two LINEs
  EXPECT_EQ(count(p, 8, "BEND_DOWN"), 2);
  EXPECT_EQ(count(p, 1, "B1 UP 90.000%%d"), 1);
  EXPECT_EQ(count(p, 1, "B4 UP 120.000%%d"), 1);
  EXPECT_EQ(count(p, 1, "B3 DOWN 45.000%%d"), 1);
}

TEST(Exports, BendTableObjJson) {
  const Part part = sample();
  const RealisedPart rp = realise(part);
  const FlatPattern flat = unfold(part, spec());
  const std::string csv = bend_table_csv(flat, {3, 1, 2, 4});
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "order,angle_deg,direction,inside_radius_mm,length_mm,tab,punch,die,turned_over");
  std::getline(in, line);
  EXPECT_EQ(line, "1,45.000000,DOWN,6.400000,20.000000,3,,,");
  std::getline(in, line);
  EXPECT_EQ(line, "2,90.000000,UP,6.400000,20.000000,1,,,");
  std::getline(in, line);
  EXPECT_EQ(line, "3,90.000000,DOWN,6.400000,16.000000,2,,,");

  const std::string obj = part_obj(rp);
  int v = 0, f = 0;
  std::istringstream o(obj);
  while (std::getline(o, line)) {
    v += line.rfind("v ", 0) == 0;
    f += line.rfind("f ", 0) == 0;
  }
  EXPECT_EQ(v, 4 + 4 * 4);
  EXPECT_EQ(f, 5);

  const nlohmann::json tabs = part_json(part, rp);
  ASSERT_EQ(tabs.size(), 5u);
  EXPECT_EQ(tabs[0]["parent"], -1);
  EXPECT_EQ(tabs[2]["parent"], 1);
  EXPECT_DOUBLE_EQ(tabs[4]["parameters"]["theta3"].get<double>(), 120 * kDeg);
  EXPECT_DOUBLE_EQ(tabs[1]["corners"][2][2].get<double>(), rp.tabs[1].corners[2].z());
  const nlohmann::json fj = flat_pattern_json(flat);
  EXPECT_NEAR(fj["area_m2"].get<double>(), flat.area(), 1e-18);
  EXPECT_EQ(fj["bends"].size(), 4u);

  const std::string svg = flat_pattern_svg(flat);
  EXPECT_NE(svg.find("<g id=\"CUT\""), std::string::npos);
  EXPECT_NE(svg.find("stroke-dasharray"), std::string::npos);
  EXPECT_NE(svg.find("B4 UP 120.000"), std::string::npos);
}

// Writes the sample's exports for the Python DXF check.
TEST(Exports, WritesSampleDxfForPython) {
  const char* env = std::getenv("SHEETGEN_PART_DXF_OUT");
  const std::filesystem::path dxf_path =
      env ? std::filesystem::path(env) : std::filesystem::path(SHEETGEN_BINARY_DIR) / "part_test_output" / "flat.dxf";
  std::filesystem::create_directories(dxf_path.parent_path());
  const Part part = sample();
  const RealisedPart rp = realise(part);
  const FlatPattern flat = unfold(part, spec());
  const BendSequenceResult seq = plan_bend_sequence(part, spec());
  ASSERT_TRUE(seq.ok()) << seq.message;
  DrawingOptions d;
  d.bend_order = seq.order;
  // Holes: a rivet at the middle of B (tab 3) and a self-rivet joining A (1) and C (4).
  auto middle = [&](int tab) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& p : rp.tabs[tab].corners) c += p / static_cast<double>(rp.tabs[tab].corners.size());
    return c;
  };
  const auto holes = rivet_holes(flat, rp, {{3, middle(3)}}, {{{1, middle(1)}, {4, middle(4)}}}, seq.order);
  write_text_file(dxf_path.string(), flat_pattern_dxf(flat, d, holes));
  const auto dir = dxf_path.parent_path();
  write_text_file((dir / "flat.svg").string(), flat_pattern_svg(flat, d, holes));
  write_text_file((dir / "bends.csv").string(), bend_table_csv(flat, seq.order));
  write_text_file((dir / "part.obj").string(), part_obj(rp));
  // What the Python test checks the DXF against.
  nlohmann::json expected;
  expected["area_mm2"] = flat.area() * 1e6;
  expected["outline_vertices"] = flat.outline.size();
  const std::vector<int> number = bend_numbers(flat, seq.order);
  for (const FlatBend& b : flat.bends)
    expected["bends"].push_back({{"number", number[b.tab]},
                                 {"angle_deg", std::abs(b.angle) * 180.0 / M_PI},
                                 {"direction", b.direction == BendDirection::Up ? "UP" : "DOWN"},
                                 {"length_mm", b.length * 1e3}});
  Vec2 org = Vec2::Constant(1e9);
  for (const Vec2& q : flat.outline) org = org.cwiseMin(q);
  for (const RivetHole& h : holes) {
    const Vec2 q = 1e3 * (h.flat - org);
    const bool self = h.kind == RivetKind::Self;
    expected["holes"].push_back({{"layer", self ? "SELF_RIVET_HOLES" : "RIVET_HOLES"},
                                 {"x_mm", q.x()},
                                 {"y_mm", q.y()},
                                 {"diameter_mm", 1e3 * h.diameter}});
    if (self) expected["notes"].push_back(hole_label(h) + " AFTER B" + std::to_string(h.after_bend));
  }
  write_text_file((dir / "expected.json").string(), expected.dump(2));
  write_text_file((dir / "part.json").string(), part_json(part, rp).dump(2));
  EXPECT_TRUE(std::filesystem::exists(dxf_path));
}

}  // namespace
}  // namespace sheetgen
