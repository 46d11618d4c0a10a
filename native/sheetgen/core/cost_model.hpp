#pragma once
// What a part costs to make (docs/cost.md): the sheet it is cut from, its
// bends, its rivets and its share of the batch's set-up, at prices the problem
// file may give (`cost`). result.json reports it in money beside mass and
// area. The composition ranks candidates by it, in square metres of the part's
// sheet (search_score()); `cost.objective` "area" ranks by area + 2e-3 m^2
// per bend instead, the paper's objective with our weight for a bend.
#include <string>

namespace sheetgen {

class JsonNode;
struct Material;

// The problem-level `cost` (docs/problem-format.md "Cost"). Amounts are in
// `currency`; the defaults and their sources are in docs/cost.md.
struct CostModel {
  std::string currency = "USD";
  double material_per_kg = 15.0; // currency/kg of sheet bought
  double per_bend = 1.00;       // currency per bend: press-brake time (position, bend, remove)
  double per_rivet = 1.00;      // currency per rivet set (drill, deburr, install), flange and self-rivets alike
  double setup = 60.0;          // currency per batch: laser nest and press-brake tooling set-up
  int batch_size = 10;          // parts made per set-up
  // What the composition ranks by: true ("cost", the default)
  // cost_as_sheet_area(); false ("area") area + 2e-3 m^2 per bend (docs/cost.md
  // "How the search uses it").
  bool rank_by_cost = true;
};

// One part's cost, split as a shop would quote it; currency of the model.
struct PartCost {
  double material = 0;  // material_per_kg x flat-pattern area x t x density
  double bends = 0;     // per_bend x bends
  double rivets = 0;    // per_rivet x rivets
  double setup = 0;     // setup / batch_size
  double total() const { return material + bends + rivets + setup; }
};

PartCost part_cost(const CostModel& model, const Material& material, double area_m2, int bends, int rivets);

// The composition's score of a part, m^2: its cost without the set-up share
// (the same for every candidate of a load, so it cannot change the ranking)
// divided by the price of one square metre of its sheet. A part with no bends
// and no rivets scores its flat-pattern area.
double cost_as_sheet_area(const CostModel& model, const Material& material, double area_m2, int bends, int rivets);

// The composition's score of a part, m^2: cost_as_sheet_area() when the model
// ranks by cost, else the area objective area + kAreaObjectiveBendCost * bends.
double search_score(const CostModel& model, const Material& material, double area_m2, int bends, int rivets);
inline constexpr double kAreaObjectiveBendCost = 2.0e-3;  // m^2 per bend (about a 45 mm square)

// The price of a square metre of the sheet, currency/m^2.
double sheet_price_per_m2(const CostModel& model, const Material& material);

// Reads `cost` (an object) into `model`; throws InputError naming the field.
void parse_cost_model(const JsonNode& node, CostModel& model);

}  // namespace sheetgen
