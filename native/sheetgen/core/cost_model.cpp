#include "sheetgen/core/cost_model.hpp"

#include "sheetgen/core/json_reader.hpp"
#include "sheetgen/core/problem.hpp"

namespace sheetgen {

double sheet_price_per_m2(const CostModel& model, const Material& material) {
  return model.material_per_kg * material.density * material.thickness;
}

PartCost part_cost(const CostModel& model, const Material& material, double area_m2, int bends, int rivets) {
  PartCost c;
  c.material = sheet_price_per_m2(model, material) * area_m2;
  c.bends = model.per_bend * bends;
  c.rivets = model.per_rivet * rivets;
  c.setup = model.setup / model.batch_size;
  return c;
}

double cost_as_sheet_area(const CostModel& model, const Material& material, double area_m2, int bends, int rivets) {
  const PartCost c = part_cost(model, material, area_m2, bends, rivets);
  return area_m2 + (c.bends + c.rivets) / sheet_price_per_m2(model, material);
}

double search_score(const CostModel& model, const Material& material, double area_m2, int bends, int rivets) {
  if (model.rank_by_cost) return cost_as_sheet_area(model, material, area_m2, bends, rivets);
  return area_m2 + kAreaObjectiveBendCost * bends;
}

void parse_cost_model(const JsonNode& node, CostModel& model) {
  node.expect_object();
  reject_unknown(node, {"currency", "material_per_kg", "per_bend", "per_rivet", "setup", "batch_size", "objective"});
  if (auto o = node.find("objective")) {
    const std::string use = o->as_string();
    if (use != "area" && use != "cost") o->fail("must be \"area\" or \"cost\", got \"" + use + "\"");
    model.rank_by_cost = use == "cost";
  }
  if (auto c = node.find("currency")) {
    model.currency = c->as_string();
    if (model.currency.empty()) c->fail("must name a currency (e.g. \"USD\")");
  }
  // The search ranks parts by their cost in square metres of sheet, so the
  // sheet must have a price; bends, rivets and set-up may be free.
  model.material_per_kg = node.positive_or("material_per_kg", model.material_per_kg);
  model.per_bend = node.non_negative_or("per_bend", model.per_bend);
  model.per_rivet = node.non_negative_or("per_rivet", model.per_rivet);
  model.setup = node.non_negative_or("setup", model.setup);
  if (auto b = node.find("batch_size")) {
    const long long n = b->as_integer();
    if (n < 1 || n > 1000000) b->fail("must lie in [1, 1000000] parts, got " + std::to_string(n));
    model.batch_size = static_cast<int>(n);
  }
}

}  // namespace sheetgen
