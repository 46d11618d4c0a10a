// result.json of a hand-made run: each load's entry says what the pipeline
// found, with the fields a part has only where there is one.
#include <gtest/gtest.h>

#include "hand_made_result.hpp"
#include "sheetgen/pipeline/result_json.hpp"

namespace sheetgen {
namespace {

TEST(ResultJson, OneEntryPerLoadWithTheSettingsOfTheRun) {
  const Problem p = test::two_load_corner();
  const GenerateResult r = test::hand_made_result(p);
  const nlohmann::json doc = result_json(p, r, "../problem.json");
  EXPECT_EQ(doc["format"], "sheetgen-result/1");
  EXPECT_EQ(doc["problem"], "../problem.json");
  EXPECT_EQ(doc["search"]["chains"], p.search.chains);
  EXPECT_EQ(doc["search"]["seed"], p.search.seed);
  EXPECT_DOUBLE_EQ(doc["timing"]["total_s"].get<double>(), 1.5);
  ASSERT_EQ(doc["parts"].size(), 2u);
  EXPECT_EQ(doc["parts"][0]["load"], "avionics_box");
  EXPECT_EQ(doc["parts"][1]["load"], "second box");
}

TEST(ResultJson, APartCarriesItsMassTabsAndFlatPattern) {
  const Problem p = test::two_load_corner();
  const nlohmann::json part = result_json(p, test::hand_made_result(p), "")["parts"][0];
  EXPECT_EQ(part["status"], "ok");
  EXPECT_FALSE(part.contains("reason"));
  // mass = area * t * density: 0.01 m^2 of 1.6 mm Al 2024-T3 (2780 kg/m^3) is 44.48 g.
  EXPECT_DOUBLE_EQ(part["mass_kg"].get<double>(), 0.01 * p.material.thickness * p.material.density);
  EXPECT_NEAR(part["mass_kg"].get<double>(), 0.04448, 1e-9);
  EXPECT_EQ(part["tabs"].size(), 1u);             // the base tab only
  EXPECT_EQ(part["bend_sequence"].size(), 0u);    // nothing to bend
  EXPECT_TRUE(part["flat_pattern"].contains("outline"));
  EXPECT_FALSE(part.contains("compliance"));      // not analysed: no FEM numbers
}

// A part found in a thicker gauge (docs/pipeline.md "Thicker gauges") is
// written in that sheet: its thickness, its mass and the sheet's share of its cost.
TEST(ResultJson, APartInAThickerGaugeIsWrittenInItsSheet) {
  const Problem p = test::two_load_corner();
  GenerateResult r = test::hand_made_result(p);
  const double t = 0.071 * 0.0254;
  r.loads[0].thickness = t;
  r.loads[0].gauges_tried = 1;
  const nlohmann::json doc = result_json(p, r, "");
  const nlohmann::json& part = doc["parts"][0];
  EXPECT_DOUBLE_EQ(part["thickness_m"].get<double>(), t);
  EXPECT_EQ(part["gauges_tried"], 1);
  EXPECT_DOUBLE_EQ(part["mass_kg"].get<double>(), 0.01 * t * p.material.density);
  // 15 USD/kg of sheet (docs/cost.md).
  EXPECT_NEAR(part["cost"]["material"].get<double>(), 15.0 * 0.01 * t * p.material.density, 1e-12);
  // The load without a part, and any part of the problem's own sheet, say that sheet.
  EXPECT_DOUBLE_EQ(doc["parts"][1]["thickness_m"].get<double>(), p.material.thickness);
  EXPECT_EQ(doc["parts"][1]["gauges_tried"], 0);
}

TEST(ResultJson, ALoadWithoutAPartSaysWhyAndKeepsItsHistory) {
  const Problem p = test::two_load_corner();
  const nlohmann::json none = result_json(p, test::hand_made_result(p), "")["parts"][1];
  EXPECT_EQ(none["status"], "no_valid_part");
  EXPECT_EQ(none["reason"], "no segment reached a rivet area");
  EXPECT_FALSE(none.contains("area_m2"));
  EXPECT_FALSE(none.contains("tabs"));
  EXPECT_EQ(none["fem_calls"], 35);
  ASSERT_EQ(none["history"].size(), 2u);
  EXPECT_EQ(none["history"][1]["iteration"], 2);
  EXPECT_EQ(none["history"][1]["evaluated"], 25);
  EXPECT_EQ(none["history"][1]["found"], true);
  EXPECT_DOUBLE_EQ(none["history"][1]["best_cost_m2"].get<double>(), 0.0125);
}

}  // namespace
}  // namespace sheetgen
