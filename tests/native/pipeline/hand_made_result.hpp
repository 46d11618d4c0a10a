#pragma once
// A run's result made by hand for the output tests (no search): the corner
// scene with two loads, the first answered by its bare base tab (a 1-tab part
// that is a valid sheet), the second without a part and with a history.
#include <string>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/part/manufacturing_plan.hpp"
#include "sheetgen/part/realisation.hpp"
#include "sheetgen/pipeline/generate.hpp"

namespace sheetgen::test {

inline Problem two_load_corner() {
  Problem p = load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/corner/problem.json");
  Load second = p.loads.front();
  second.name = "second box";  // a space on purpose: it names a folder
  p.loads.push_back(second);
  return p;
}

inline GenerateResult hand_made_result(const Problem& p) {
  GenerateResult r;
  r.search = p.search;
  r.seconds = 1.5;

  LoadOutcome ok;
  ok.load = p.loads[0].name;
  ok.ok = true;
  ok.part.segments = {0};
  ok.part.part = make_base_part(p.loads[0], 0, p.material.thickness);
  ok.part.area = 0.01;  // m^2
  ok.part.cost = 0.01;
  ok.realised = realise(ok.part.part);
  ok.plan = plan_manufacturing(ok.part.part, SheetSpec::from(p));
  r.loads.push_back(ok);

  LoadOutcome none;
  none.load = p.loads[1].name;
  none.reason = "no segment reached a rivet area";
  ComposeHistoryRow first;
  first.level = 1;
  first.evaluated = 10;
  ComposeHistoryRow second;
  second.level = 2;
  second.evaluated = 25;
  second.found = true;
  second.best_cost = 0.0125;
  second.best_area = 0.0105;
  second.compliance = 0.25;
  second.margin_of_safety = 0.5;
  none.history = {first, second};
  none.fem_calls = 35;
  r.loads.push_back(none);
  return r;
}

}  // namespace sheetgen::test
