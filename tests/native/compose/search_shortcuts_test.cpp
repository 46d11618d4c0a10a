// The composition's shortcuts (docs/pipeline.md "Cost bound", "Screening",
// "Analyses shared between passes") against the plain beam search on the
// corner scene's library.
// * The cost bound (ComposeOptions::kept_valid) only leaves out work: the same
//   best part, the same beam (so the same candidates and history) and the same
//   cheapest valid parts, and every candidate it did not analyse is one the
//   unbounded search analysed.
// * Screening re-analyses on the search mesh what could matter: with every
//   candidate kept it is the plain search; with the default it leaves some out,
//   and every valid part it reports carries its search-mesh analysis.
// * The analyses cache gives the search it would make without it, bit for bit,
//   and a second search of the same library analyses nothing anew; its key
//   changes with every input of an analysis (part, mesh, sheet, material,
//   requirements, load).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "sheetgen/compose/composition.hpp"
#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/fem/plate_mesher.hpp"
#include "sheetgen/part/realisation.hpp"
#include "../common/single_force.hpp"

namespace sheetgen {
namespace {

// The corner scene and its segment library at 6 x 300, found once for every test.
struct CornerLibrary {
  Problem problem;
  Environment env;
  DiscoveryResult found;
  CornerLibrary()
      : problem(test::single_force(load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/corner/problem.json"))),
        env(problem) {
    // One static case: the bound's premise is a library with dear candidates
    // the cheap ones make unneeded, measured on the corner's 9 g case.
    // The shortcuts are measured on the search without the press-brake check
    // ("report"): with it, this library's few bendable candidates leave the
    // cost bound and the screening nothing to skip.
    problem.manufacturing.press_brake_required = false;
    DiscoveryOptions d = DiscoveryOptions::from(problem);
    d.chains = 6;
    d.iterations = 300;
    d.threads = 2;
    found = discover_segments(problem, env, 0, d);
  }
  static const CornerLibrary& get() {
    static const CornerLibrary library;
    return library;
  }
  ComposeResult compose(ComposeOptions o) const {
    o.threads = 2;
    return compose_part(problem, env, 0, found.base, found.library, o);
  }
};

ComposeOptions plain(int kept_valid) {
  ComposeOptions o;
  o.kept_valid = kept_valid;
  o.screen_element_factor = 0;
  return o;
}

TEST(CostBound, LeavesOutOnlyCandidatesThatCannotMatter) {
  const CornerLibrary& lib = CornerLibrary::get();
  ASSERT_GT(lib.found.library.size(), 0);
  const ComposeResult full = lib.compose(plain(0));
  ASSERT_TRUE(full.found) << full.reason;
  ASSERT_EQ(full.skipped_by_cost, 0);
  for (int kept : {1, 3}) {
    SCOPED_TRACE("kept_valid " + std::to_string(kept));
    const ComposeResult bounded = lib.compose(plain(kept));
    std::printf("kept_valid %d: %d of %d candidates not analysed, FEM calls %d (unbounded %d), valid %zu (%zu)\n", kept,
                bounded.skipped_by_cost, bounded.candidates, bounded.fem_calls, full.fem_calls, bounded.valid.size(),
                full.valid.size());
    ASSERT_TRUE(bounded.found);
    // Measured: 4 candidates left out at kept_valid 1, 2 at 3.
    if (kept == 1) {
      EXPECT_GT(bounded.skipped_by_cost, 0) << "the bound was not exercised";
    }
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
    for (const Candidate& v : bounded.valid) {
      EXPECT_FALSE(v.over_cost_bound);
      // The rivets the cost counted before the FEM are the ones it set.
      EXPECT_EQ(v.rivets, v.fem.rivets + static_cast<int>(v.self_rivets.size()));
    }
  }
}

// The cost ceiling (the right-angle pass, docs/pipeline.md "Right-angle
// pass"): just above the unbounded answer's cost it finds that answer; at its
// cost it finds no part and analyses nothing that costs as much. Either way
// every valid part it reports is cheaper than the ceiling.
TEST(CostBound, ACeilingFindsOnlyCheaperParts) {
  const CornerLibrary& lib = CornerLibrary::get();
  const ComposeResult full = lib.compose(plain(0));
  ASSERT_TRUE(full.found) << full.reason;
  ComposeOptions above = plain(0);
  above.cost_ceiling = full.best.cost * (1 + 1e-9);
  const ComposeResult found = lib.compose(above);
  ASSERT_TRUE(found.found) << found.reason;
  EXPECT_EQ(found.best.segments, full.best.segments);
  EXPECT_EQ(found.best.cost, full.best.cost);
  EXPECT_GT(found.skipped_by_cost, 0) << "no candidate of the library costs more than its answer";
  EXPECT_LT(found.fem_calls, full.fem_calls);
  ComposeOptions at = plain(0);
  at.cost_ceiling = full.best.cost;
  const ComposeResult none = lib.compose(at);
  EXPECT_FALSE(none.found);
  for (const ComposeResult* r : {&found, &none})
    for (const Candidate& v : r->valid) EXPECT_LT(v.cost, r == &found ? above.cost_ceiling : at.cost_ceiling);
  std::printf("ceiling: %d and %d candidates not analysed of %d and %d; FEM calls %d and %d (no ceiling %d)\n",
              found.skipped_by_cost, none.skipped_by_cost, found.candidates, none.candidates, found.fem_calls,
              none.fem_calls, full.fem_calls);
}

TEST(Screening, KeepingEveryCandidateIsThePlainSearch) {
  const CornerLibrary& lib = CornerLibrary::get();
  const ComposeResult ref = lib.compose(plain(4));
  ComposeOptions o = plain(4);
  o.screen_element_factor = 3.0;
  o.screen_keep = 100000;
  const ComposeResult all = lib.compose(o);
  ASSERT_TRUE(ref.found);
  ASSERT_TRUE(all.found);
  EXPECT_EQ(all.screened_out, 0);
  EXPECT_GT(all.screen_fem_calls, 0);
  EXPECT_EQ(all.best.segments, ref.best.segments);
  EXPECT_EQ(all.best.cost, ref.best.cost);
  EXPECT_EQ(all.best.fem.compliance, ref.best.fem.compliance);
  EXPECT_EQ(all.candidates, ref.candidates);
  EXPECT_EQ(all.fem_calls, ref.fem_calls);
}

TEST(Screening, ValidPartsCarryTheirSearchMeshAnalysis) {
  const CornerLibrary& lib = CornerLibrary::get();
  ComposeOptions o;  // the defaults: bound and screening on
  o.screen_keep = 1;
  const ComposeResult r = lib.compose(o);
  std::printf("screening: %d analyses on the screening mesh, %d left there, %d on the search mesh, %d candidates\n",
              r.screen_fem_calls, r.screened_out, r.fem_calls, r.candidates);
  ASSERT_TRUE(r.found) << r.reason;
  EXPECT_GT(r.screened_out, 0) << "screening left nothing out";
  for (const Candidate& v : r.valid) {
    std::vector<std::vector<Vec3>> polys;
    for (const auto& t : realise(v.part).tabs) polys.push_back(t.corners);
    Candidate again = v;
    analyse_candidate(lib.problem, 0, again, 1.5 * default_element_size(polys, lib.problem.material.thickness));
    ASSERT_TRUE(again.analysed) << again.fem_error;
    EXPECT_EQ(again.fem.compliance, v.fem.compliance);
    EXPECT_EQ(again.fem.margin_of_safety, v.fem.margin_of_safety);
    EXPECT_FALSE(v.screened_out);
  }
}

// The same search, answer for answer and bit for bit.
void expect_same_search(const ComposeResult& a, const ComposeResult& b) {
  ASSERT_EQ(a.found, b.found);
  EXPECT_EQ(a.candidates, b.candidates);
  EXPECT_EQ(a.fem_calls, b.fem_calls);
  EXPECT_EQ(a.screen_fem_calls, b.screen_fem_calls);
  ASSERT_EQ(a.valid.size(), b.valid.size());
  for (size_t k = 0; k < a.valid.size(); ++k) {
    const StructuralResult &fa = a.valid[k].fem, &fb = b.valid[k].fem;
    EXPECT_EQ(a.valid[k].segments, b.valid[k].segments);
    EXPECT_EQ(a.valid[k].cost, b.valid[k].cost);
    EXPECT_EQ(fa.compliance, fb.compliance);
    EXPECT_EQ(fa.margin_of_safety, fb.margin_of_safety);
    EXPECT_EQ(fa.envelope.buckling_factor, fb.envelope.buckling_factor);
    EXPECT_EQ(fa.envelope.frequencies_hz, fb.envelope.frequencies_hz);
  }
}

TEST(AnalysisCache, GivesTheSearchWithoutItAndASecondSearchAnalysesNothingAnew) {
  const CornerLibrary& lib = CornerLibrary::get();
  const ComposeResult ref = lib.compose(ComposeOptions{});
  AnalysisCache cache;
  ComposeOptions o;
  o.analyses = &cache;
  const ComposeResult first = lib.compose(o);
  expect_same_search(first, ref);
  const size_t kept = cache.size();
  std::printf("analyses cache: %zu analyses kept, %d reused by the first search\n", kept, cache.hits());
  // Every analysis of the first search: the screening ones and those on the search mesh.
  EXPECT_EQ(static_cast<int>(kept) + cache.hits(), ref.screen_fem_calls + ref.fem_calls);
  const int hits_before = cache.hits();
  const ComposeResult second = lib.compose(o);
  expect_same_search(second, ref);
  EXPECT_EQ(cache.size(), kept) << "the second search analysed a part anew";
  EXPECT_EQ(cache.hits() - hits_before, ref.screen_fem_calls + ref.fem_calls);
}

TEST(AnalysisCache, KeyChangesWithEveryInputOfTheAnalysis) {
  const CornerLibrary& lib = CornerLibrary::get();
  const ComposeResult r = lib.compose(ComposeOptions{});
  ASSERT_TRUE(r.found) << r.reason;
  const Candidate& c = r.best;
  ASSERT_GE(c.part.size(), 2);
  const double h = 4e-3;
  const std::string key = AnalysisCache::key(lib.problem, 0, c, h);
  Candidate tagged = c;
  tagged.part.tabs[1].tag += 7;  // a caller's tag is not an input
  EXPECT_EQ(AnalysisCache::key(lib.problem, 0, tagged, h), key);

  EXPECT_NE(AnalysisCache::key(lib.problem, 1, c, h), key);
  EXPECT_NE(AnalysisCache::key(lib.problem, 0, c, std::nextafter(h, 1.0)), key);
  Problem thicker = lib.problem;
  thicker.material.thickness = std::nextafter(thicker.material.thickness, 1.0);
  EXPECT_NE(AnalysisCache::key(thicker, 0, c, h), key);
  Problem stiffer = lib.problem;
  stiffer.material.youngs_modulus = std::nextafter(stiffer.material.youngs_modulus, 1e12);
  EXPECT_NE(AnalysisCache::key(stiffer, 0, c, h), key);
  Problem floor = lib.problem;
  floor.requirements.min_frequency_hz = 30.0;
  EXPECT_NE(AnalysisCache::key(floor, 0, c, h), key);
  Problem heavier = lib.problem;
  ASSERT_FALSE(heavier.loads[0].cases.empty());
  heavier.loads[0].cases.back().force.z() = std::nextafter(heavier.loads[0].cases.back().force.z(), 1e9);
  EXPECT_NE(AnalysisCache::key(heavier, 0, c, h), key);
  Problem other_rivets = lib.problem;
  other_rivets.manufacturing.rivet_pitch *= 1.5;
  EXPECT_NE(AnalysisCache::key(other_rivets, 0, c, h), key);
  Problem other_radius = lib.problem;
  other_radius.manufacturing.bend_radius *= 1.5;
  EXPECT_NE(AnalysisCache::key(other_radius, 0, c, h), key);
  Candidate longer = c;
  longer.part.tabs.back().params.l = std::nextafter(longer.part.tabs.back().params.l, 1.0);
  EXPECT_NE(AnalysisCache::key(lib.problem, 0, longer, h), key);
  Candidate moved = c;
  moved.part.base.origin.z() += 1e-9;
  EXPECT_NE(AnalysisCache::key(lib.problem, 0, moved, h), key);
  Candidate tied = c;
  tied.self_rivets.push_back({0, 1, Vec3::Zero(), Vec3::Zero()});
  EXPECT_NE(AnalysisCache::key(lib.problem, 0, tied, h), key);
}

}  // namespace
}  // namespace sheetgen
