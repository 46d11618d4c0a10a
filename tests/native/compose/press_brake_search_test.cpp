// The composition with the press-brake check (`"manufacturing":
// {"press_brake": "prefer"}`, the default, or "require"; docs/manufacturing.md
// "Press brake"): every valid part it keeps is one the standard press-brake
// tools bend, by the same plan the answer gets; without it ("report") the
// search ignores the tools, and on the corner scene its cheapest part is one
// the tools cannot bend, so the check changes the answer.
#include <gtest/gtest.h>

#include <string>

#include "sheetgen/compose/composition.hpp"
#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/manufacturing_plan.hpp"

namespace sheetgen {
namespace {

ManufacturingPlan answer_plan(const Problem& problem, const Part& part) {
  ManufacturingPlanOptions o;
  o.press_brake = true;
  return plan_manufacturing(part, SheetSpec::from(problem), o);
}

TEST(PressBrakeSearch, RequiredKeepsOnlyPartsTheToolsBend) {
  Problem problem = load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/corner/problem.json");
  // A library found without the press-brake filter of discovery
  // (discovery/bendable.hpp), so the composition sees segments the tools
  // cannot bend and its own check has something to refuse.
  problem.manufacturing.press_brake_required = false;
  const Environment env(problem);
  DiscoveryOptions d = DiscoveryOptions::from(problem);
  d.chains = 6;
  d.iterations = 300;
  d.threads = 2;
  const DiscoveryResult found = discover_segments(problem, env, 0, d);
  ASSERT_GT(found.library.size(), 0);
  ComposeOptions co;
  co.beam_width = 4;
  co.threads = 2;

  problem.manufacturing.press_brake_required = false;  // "report"
  const ComposeResult reported = compose_part(problem, env, 0, found.base, found.library, co);
  ASSERT_TRUE(reported.found) << reported.reason;
  const ManufacturingPlan reported_plan = answer_plan(problem, reported.best.part);
  ASSERT_TRUE(reported_plan.press_checked);
  // The premise: without the requirement the cheapest part cannot be bent.
  ASSERT_FALSE(reported_plan.press.ok);

  problem.manufacturing.press_brake_required = true;
  const ComposeResult required = compose_part(problem, env, 0, found.base, found.library, co);
  ASSERT_TRUE(required.found) << required.reason;
  ASSERT_FALSE(required.valid.empty());
  for (const Candidate& c : required.valid) {
    const ManufacturingPlan plan = answer_plan(problem, c.part);
    EXPECT_TRUE(plan.press.ok) << "a kept part the tools cannot bend: " << plan.press.message;
  }
}

}  // namespace
}  // namespace sheetgen
