// The cost model (core/cost_model.hpp, docs/cost.md): a part's cost from its
// sheet, bends, rivets and set-up share, the composition's score in square
// metres of sheet, and the problem file's `cost`.
#include "sheetgen/core/cost_model.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "sheetgen/core/input_error.hpp"
#include "sheetgen/core/json_reader.hpp"
#include "sheetgen/core/problem.hpp"

namespace sheetgen {
namespace {

TEST(CostModel, PartCostAddsSheetBendsRivetsAndSetupShare) {
  const CostModel model;  // the defaults: 15 USD/kg, 1 USD per bend and per rivet, 60 USD per batch of 10
  const Material al;      // 2024-T3, 1.6 mm, 2780 kg/m^3: 4.448 kg/m^2
  const PartCost c = part_cost(model, al, 0.1, 4, 6);
  EXPECT_NEAR(c.material, 15.0 * 2780.0 * 1.6e-3 * 0.1, 1e-12);  // 6.672 USD
  EXPECT_DOUBLE_EQ(c.bends, 4.0);
  EXPECT_DOUBLE_EQ(c.rivets, 6.0);
  EXPECT_DOUBLE_EQ(c.setup, 6.0);
  EXPECT_NEAR(c.total(), 6.672 + 4.0 + 6.0 + 6.0, 1e-12);
  EXPECT_EQ(model.currency, "USD");
}

TEST(CostModel, SearchScoreIsTheCostInSheetArea) {
  const CostModel model;
  const Material al;
  const double per_m2 = sheet_price_per_m2(model, al);  // 66.72 USD/m^2
  EXPECT_NEAR(per_m2, 66.72, 1e-12);
  // Without bends and rivets the score is the flat-pattern area itself.
  EXPECT_DOUBLE_EQ(cost_as_sheet_area(model, al, 0.1, 0, 0), 0.1);
  // A bend and a rivet are each worth 1 / 66.72 m^2 (150 cm^2) of sheet.
  EXPECT_NEAR(cost_as_sheet_area(model, al, 0.1, 4, 6), 0.1 + 10.0 / 66.72, 1e-12);
  // The set-up share is left out: it is the same for every candidate.
  CostModel dear_setup = model;
  dear_setup.setup = 6000;
  EXPECT_DOUBLE_EQ(cost_as_sheet_area(dear_setup, al, 0.1, 4, 6), cost_as_sheet_area(model, al, 0.1, 4, 6));
  // The ranking does not depend on the currency: every price times 0.9 gives the same score.
  CostModel in_eur = model;
  in_eur.material_per_kg *= 0.9;
  in_eur.per_bend *= 0.9;
  in_eur.per_rivet *= 0.9;
  EXPECT_NEAR(cost_as_sheet_area(in_eur, al, 0.1, 4, 6), cost_as_sheet_area(model, al, 0.1, 4, 6), 1e-15);
  // Thicker sheet costs more per square metre, so a bend is worth less area.
  Material thick = al;
  thick.thickness = 3.2e-3;
  EXPECT_NEAR(cost_as_sheet_area(model, thick, 0.1, 1, 0), 0.1 + 1.0 / 133.44, 1e-12);
}

TEST(CostModel, TheSearchRanksByCostUnlessAskedForArea) {
  CostModel model;
  const Material al;
  EXPECT_TRUE(model.rank_by_cost);  // the default
  EXPECT_DOUBLE_EQ(search_score(model, al, 0.1, 4, 6), cost_as_sheet_area(model, al, 0.1, 4, 6));
  model.rank_by_cost = false;       // "objective": "area"
  EXPECT_DOUBLE_EQ(search_score(model, al, 0.1, 4, 6), 0.1 + 4 * 2e-3);
}

TEST(CostModel, ProblemFileSetsEveryWeight) {
  const nlohmann::json j = nlohmann::json::parse(
      R"({"currency": "EUR", "material_per_kg": 20, "per_bend": 0.5, "per_rivet": 0, "setup": 45, "batch_size": 3,
          "objective": "area"})");
  CostModel m;
  parse_cost_model(JsonNode(j, "p.json", "cost"), m);
  EXPECT_EQ(m.currency, "EUR");
  EXPECT_DOUBLE_EQ(m.material_per_kg, 20.0);
  EXPECT_DOUBLE_EQ(m.per_bend, 0.5);
  EXPECT_DOUBLE_EQ(m.per_rivet, 0.0);  // free rivets are allowed
  EXPECT_DOUBLE_EQ(m.setup, 45.0);
  EXPECT_EQ(m.batch_size, 3);
  EXPECT_FALSE(m.rank_by_cost);
  EXPECT_DOUBLE_EQ(part_cost(m, Material{}, 0, 0, 0).setup, 15.0);
  // Absent fields keep their defaults.
  const nlohmann::json partial = nlohmann::json::parse(R"({"per_bend": 2})");
  CostModel d;
  parse_cost_model(JsonNode(partial, "p.json", "cost"), d);
  EXPECT_DOUBLE_EQ(d.per_bend, 2.0);
  EXPECT_DOUBLE_EQ(d.material_per_kg, CostModel{}.material_per_kg);
}

TEST(CostModel, BadCurrencyNamesTheField) {
  const nlohmann::json j = nlohmann::json::parse(R"({"currency": ""})");
  CostModel m;
  try {
    parse_cost_model(JsonNode(j, "p.json", "cost"), m);
    ADD_FAILURE() << "an empty currency was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cost.currency"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sheetgen
