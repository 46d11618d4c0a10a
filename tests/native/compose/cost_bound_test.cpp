// The composition's cost bound (ComposeOptions::kept_valid, docs/pipeline.md
// "Cost bound") only leaves out work: against the unbounded search it must
// give the same best part, the same beam (so the same candidates and history)
// and the same cheapest valid parts, and every candidate it did not analyse is
// one the unbounded search analysed.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "sheetgen/compose/composition.hpp"
#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"

namespace sheetgen {
namespace {

ComposeResult compose_with(const Problem& p, const Environment& env, const DiscoveryResult& found, int kept_valid) {
  ComposeOptions o;
  o.kept_valid = kept_valid;
  o.threads = 2;
  return compose_part(p, env, 0, found.base, found.library, o);
}

TEST(CostBound, LeavesOutOnlyCandidatesThatCannotMatter) {
  const Problem p = load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/corner/problem.json");
  const Environment env(p);
  DiscoveryOptions d = DiscoveryOptions::from(p);
  d.chains = 6;
  d.iterations = 300;
  d.threads = 2;
  const DiscoveryResult found = discover_segments(p, env, 0, d);
  ASSERT_GT(found.library.size(), 0);

  const ComposeResult full = compose_with(p, env, found, 0);
  ASSERT_TRUE(full.found) << full.reason;
  ASSERT_EQ(full.skipped_by_cost, 0);
  for (int kept : {1, 3}) {
    SCOPED_TRACE("kept_valid " + std::to_string(kept));
    const ComposeResult bounded = compose_with(p, env, found, kept);
    std::printf("kept_valid %d: %d of %d candidates not analysed, FEM calls %d (unbounded %d), valid %zu (%zu)\n", kept,
                bounded.skipped_by_cost, bounded.candidates, bounded.fem_calls, full.fem_calls, bounded.valid.size(),
                full.valid.size());
    ASSERT_TRUE(bounded.found);
    // Measured: 4 candidates left out at kept_valid 1, 2 at 3 (6 x 300, seed of the scene).
    if (kept == 1) EXPECT_GT(bounded.skipped_by_cost, 0) << "the bound was not exercised";
    EXPECT_EQ(bounded.best.segments, full.best.segments);
    EXPECT_EQ(bounded.best.cost, full.best.cost);
    // The same beam at every level: the same candidates were generated.
    EXPECT_EQ(bounded.candidates, full.candidates);
    ASSERT_EQ(bounded.history.size(), full.history.size());
    for (size_t i = 0; i < full.history.size(); ++i) EXPECT_EQ(bounded.history[i].best_cost, full.history[i].best_cost);
    // Each candidate left out would have been analysed by the unbounded search.
    EXPECT_EQ(bounded.fem_calls + bounded.skipped_by_cost, full.fem_calls);
    // The kept cheapest valid parts are the unbounded search's, in order.
    ASSERT_GE(bounded.valid.size(), std::min<size_t>(kept, full.valid.size()));
    for (size_t i = 0; i < static_cast<size_t>(kept) && i < full.valid.size(); ++i) {
      EXPECT_EQ(bounded.valid[i].segments, full.valid[i].segments);
      EXPECT_EQ(bounded.valid[i].cost, full.valid[i].cost);
    }
    for (const Candidate& v : bounded.valid) EXPECT_FALSE(v.over_cost_bound);
  }
}

}  // namespace
}  // namespace sheetgen
