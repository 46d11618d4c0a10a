// Discovery's press-brake filter (discovery/bendable.hpp): with the press
// brake required, every segment of the library is bendable on the base and
// its ancestors; the filter's premise (a segment that is not bendable alone
// is not bendable in any larger part) holds on a library found without it;
// and without the requirement the filter lets everything through.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sheetgen/discovery/bendable.hpp"
#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/manufacturing_plan.hpp"

namespace sheetgen {
namespace {

// The corner scene: the standard tools cannot bend several of the segments
// an unfiltered discovery finds there (the bed below the die is in the way).
Problem corner(bool press_required) {
  Problem p = load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/corner/problem.json");
  p.manufacturing.press_brake_required = press_required;
  return p;
}

DiscoveryResult discover(const Problem& p, const Environment& env) {
  DiscoveryOptions o = DiscoveryOptions::from(p);
  o.chains = 6;
  o.iterations = 300;
  o.threads = 2;
  return discover_segments(p, env, 0, o);
}

// The part the composition would assemble from segments `ids` (and their ancestors), bent with the tools.
bool tools_bend(const Problem& p, const DiscoveryResult& found, std::vector<int> ids) {
  std::vector<int> closed;
  for (int id : ids)
    for (int a : segment_closure(found.library, id)) closed.push_back(a);
  ManufacturingPlanOptions o;
  o.press_brake = true;
  o.press_brake_tools = p.manufacturing.press_brake_tools;
  const ManufacturingPlan plan = plan_manufacturing(assemble_part(found.base, found.library, closed), SheetSpec::from(p), o);
  return plan.ok() && plan.press.ok;
}

TEST(DiscoveryPressFilter, EverySegmentIsBendableAloneWhenThePressBrakeIsRequired) {
  const Problem p = corner(true);
  const Environment env(p);
  const DiscoveryResult found = discover(p, env);
  ASSERT_GT(found.library.size(), 0);
  // The filter was exercised: some optimised segments were dropped.
  EXPECT_GT(found.stats.press_rejected, 0);
  for (const Segment& s : found.library.segments())
    EXPECT_TRUE(tools_bend(p, found, {s.id})) << "segment " << s.id << " (rivet area " << s.rivet_area << ")";
}

TEST(DiscoveryPressFilter, ASegmentTheToolsCannotBendAloneSpoilsEveryPairItIsIn) {
  const Problem unfiltered = corner(false);
  const Environment env(unfiltered);
  const DiscoveryResult found = discover(unfiltered, env);
  EXPECT_EQ(found.stats.press_rejected, 0);  // no requirement, no filter
  const Problem p = corner(true);  // the same tools, now required
  std::vector<int> bad, good;
  for (const Segment& s : found.library.segments()) (tools_bend(p, found, {s.id}) ? good : bad).push_back(s.id);
  // The premise of the test: both kinds exist in an unfiltered library.
  ASSERT_FALSE(bad.empty());
  ASSERT_FALSE(good.empty());
  for (const Segment& s : found.library.segments()) {
    const BendableResult r = segment_bendable(p, found.base, found.library, s);
    EXPECT_EQ(r.ok, tools_bend(p, found, {s.id})) << "segment " << s.id << ": " << r.message;
    if (!r.ok) EXPECT_FALSE(r.message.empty());
  }
  // Composition's parts of two segments: none holding an unbendable one is bendable.
  int pairs = 0;
  for (int b : bad)
    for (int g : good) {
      ++pairs;
      EXPECT_FALSE(tools_bend(p, found, {b, g})) << "segments " << b << " + " << g;
    }
  EXPECT_GT(pairs, 0);
}

}  // namespace
}  // namespace sheetgen
