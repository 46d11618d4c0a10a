// Rivet holes in the flat pattern: each hole, folded back by the flat
// pattern's own fold (fold_flat_pattern, which does not use the frames the
// holes are mapped with), lands on its rivet; a self-rivet is set after the
// last bend on the way to either sheet; the drawings and rivets.csv carry them.
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "sheetgen/part/exports.hpp"
#include "sheetgen/part/rivet_holes.hpp"
#include "../common/dxf_pairs.hpp"
#include "../common/sample_part.hpp"
#include "../common/sheet_fixture.hpp"

namespace sheetgen {
namespace {

using fixtures::spec;

// The world point that flat point q of piece `tab` folds to: the affine map
// taking the piece's flat mid-surface corners onto their folded corners.
Vec3 fold_point(const FlatPattern& flat, const std::vector<std::vector<Vec3>>& folded, int tab, const Vec2& q) {
  const auto& s = flat.pieces[tab].sharp;
  const auto& c = folded[tab];
  // Corner 0, 1 and the corner farthest from their line span the plane.
  size_t k = 2;
  double best = 0;
  for (size_t i = 2; i < s.size(); ++i) {
    const Vec2 e = s[1] - s[0], f = s[i] - s[0];
    const double a = std::abs(e.x() * f.y() - e.y() * f.x());
    if (a > best) best = a, k = i;
  }
  Eigen::Matrix2d A;
  A.col(0) = s[1] - s[0];
  A.col(1) = s[k] - s[0];
  const Vec2 uv = A.colPivHouseholderQr().solve(q - s[0]);
  return c[0] + uv.x() * (c[1] - c[0]) + uv.y() * (c[k] - c[0]);
}

TEST(RivetHoles, FoldBackOntoTheirRivets) {
  const Part part = fixtures::four_bend_sample();
  const RealisedPart rp = realise(part);
  const FlatPattern flat = unfold(part, spec());
  ASSERT_TRUE(flat.ok()) << flat.message;
  const auto folded = fold_flat_pattern(flat);
  const double t = spec().thickness;
  double worst = 0;
  int points = 0;
  for (int tab = 0; tab < part.size(); ++tab) {
    const auto& c = rp.tabs[tab].corners;
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& p : c) centroid += p / static_cast<double>(c.size());
    std::vector<Vec3> on_tab{centroid};
    for (const Vec3& p : c) on_tab.push_back(0.5 * (centroid + p));
    for (const Vec3& p : on_tab) {
      // A self-rivet point may sit up to 1.5 t off the sheet it goes through: the hole is its projection.
      const Vec3 off = p + 0.7 * t * rp.tabs[tab].normal;
      const Vec2 q = flat_position(flat, rp, tab, off);
      worst = std::max(worst, (fold_point(flat, folded, tab, q) - p).norm());
      ++points;
    }
  }
  std::printf("%d points on 5 tabs: folded-back hole to rivet at most %.3g m\n", points, worst);
  EXPECT_LT(worst, 1e-12);
}

TEST(RivetHoles, SelfRivetIsSetAfterTheLastBendToEitherSheet) {
  const Part part = fixtures::four_bend_sample();  // tabs 1 (A), 2 (D, on A), 3 (B), 4 (C)
  const RealisedPart rp = realise(part);
  const FlatPattern flat = unfold(part, spec());
  auto centre = [&](int tab) { return rp.tabs[tab].corners[2]; };
  const std::vector<PlacedSelfRivet> self{{{2, centre(2)}, {0, centre(0)}},
                                          {{3, centre(3)}, {4, centre(4)}},
                                          {{1, centre(1)}, {3, centre(3)}}};
  auto after = [&](const std::vector<int>& order) {
    std::vector<int> out;
    const auto holes = rivet_holes(flat, rp, {}, self, order);
    for (size_t i = 0; i < holes.size(); i += 2) {
      EXPECT_EQ(holes[i].after_bend, holes[i + 1].after_bend);
      EXPECT_EQ(holes[i].number, holes[i + 1].number);
      EXPECT_EQ(holes[i].other_tab, holes[i + 1].tab);
      out.push_back(holes[i].after_bend);
    }
    return out;
  };
  // Tab order: bends 1..4 on tabs 1..4. D needs A (1) and itself (2).
  EXPECT_EQ(after({}), (std::vector<int>{2, 4, 3}));
  // Order B, A, D, C: A is bend 2, D bend 3, B bend 1, C bend 4.
  EXPECT_EQ(after({3, 1, 2, 4}), (std::vector<int>{3, 4, 2}));
}

TEST(RivetHoles, AHoleOnATabThePartHasNotIsRefused) {
  const Part part = fixtures::four_bend_sample();
  const RealisedPart rp = realise(part);
  const FlatPattern flat = unfold(part, spec());
  try {
    rivet_holes(flat, rp, {{1, Vec3::Zero()}, {7, Vec3::Zero()}}, {}, {});
    FAIL() << "tab 7 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "rivet 2 names tab 7 of a part with 5 tabs");
  }
}

std::vector<std::pair<int, std::string>> pairs(const std::string& dxf) { return fixtures::dxf_pairs(dxf); }

TEST(RivetHoles, DrawingsAndRivetTableShowEveryHole) {
  const Part part = fixtures::four_bend_sample();
  const RealisedPart rp = realise(part);
  const FlatPattern flat = unfold(part, spec());
  const Vec3 on_b = rp.tabs[3].corners[2], on_a = rp.tabs[1].corners[3], on_c = rp.tabs[4].corners[2];
  RivetHoleOptions ho;
  ho.rivet_diameter = 3.175e-3;
  ho.clearance = 0.1e-3;
  const auto holes = rivet_holes(flat, rp, {{3, on_b}}, {{{1, on_a}, {4, on_c}}}, {}, ho);
  ASSERT_EQ(holes.size(), 3u);

  // DXF: one CIRCLE per hole on its layer, radius (d + clearance) / 2 = 1.6375 mm,
  // centred where the flat pattern puts the rivet (drawing origin = outline's lower-left corner).
  Vec2 org = Vec2::Constant(1e9);
  for (const Vec2& q : flat.outline) org = org.cwiseMin(q);
  const auto p = pairs(flat_pattern_dxf(flat, {}, holes));
  std::vector<std::string> layers;
  for (size_t i = 0; i < p.size(); ++i) {
    if (p[i] != std::make_pair(0, std::string("CIRCLE"))) continue;
    ASSERT_EQ(p[i + 1].first, 8);
    layers.push_back(p[i + 1].second);
    const size_t k = layers.size() - 1;
    const Vec2 want = 1e3 * (holes[k].flat - org);
    EXPECT_NEAR(std::stod(p[i + 2].second), want.x(), 1e-6);
    EXPECT_NEAR(std::stod(p[i + 3].second), want.y(), 1e-6);
    EXPECT_EQ(p[i + 5], std::make_pair(40, std::string("1.637500")));
  }
  EXPECT_EQ(layers, (std::vector<std::string>{"RIVET_HOLES", "SELF_RIVET_HOLES", "SELF_RIVET_HOLES"}));
  int notes = 0;
  for (const auto& kv : p) notes += kv == std::make_pair(1, std::string("S1 AFTER B4"));
  EXPECT_EQ(notes, 2);  // one beside each sheet's hole; C (tab 4) is bend 4

  const std::string svg = flat_pattern_svg(flat, {}, holes);
  EXPECT_NE(svg.find("<g id=\"SELF_RIVET_HOLES\""), std::string::npos);
  const size_t r = svg.find(" r=\"");
  ASSERT_NE(r, std::string::npos);
  EXPECT_NEAR(std::stod(svg.substr(r + 4)), 1.6375, 0.5e-3);  // mm, written to 3 decimals

  std::istringstream csv(rivet_table_csv(flat, holes));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "label,kind,tab,other_tab,x_mm,y_mm,diameter_mm,after_bend,world_x_m,world_y_m,world_z_m");
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("R1,flange,3,,", 0), 0u) << line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("S1,self,1,4,", 0), 0u) << line;
  EXPECT_NE(line.find(",3.275000,4,"), std::string::npos) << line;

  const nlohmann::json fj = flat_pattern_json(flat, {}, holes);
  ASSERT_EQ(fj["holes"].size(), 3u);
  EXPECT_EQ(fj["holes"][2]["label"], "S1");
  EXPECT_EQ(fj["holes"][2]["tab"], 4);
  EXPECT_EQ(fj["holes"][2]["other_tab"], 1);
  EXPECT_DOUBLE_EQ(fj["holes"][0]["centre"][0].get<double>(), holes[0].flat.x());
}

}  // namespace
}  // namespace sheetgen
