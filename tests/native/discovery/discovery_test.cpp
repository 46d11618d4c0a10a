// End-to-end discovery on the sample problems, determinism and cancellation.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <thread>

#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/validity.hpp"

namespace sheetgen {
namespace {

std::string scene(const std::string& name) { return std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/" + name + "/problem.json"; }

// Byte-level fingerprint of a library: every number printed with 17 digits.
std::string fingerprint(const SegmentLibrary& lib) {
  std::ostringstream s;
  s.precision(17);
  for (const Segment& g : lib.segments()) {
    s << g.id << ' ' << g.parent << ' ' << g.parent_tab << ' ' << g.parent_edge << ' ' << g.rivet_area << ' ' << g.chain
      << ' ' << g.iteration << ' ' << g.area << '\n';
    for (const Tab& t : g.tabs)
      s << ' ' << t.parent << ' ' << t.parent_edge << ' ' << t.params.d << ' ' << t.params.w << ' ' << t.params.l << ' '
        << t.params.theta1 << ' ' << t.params.theta2 << ' ' << t.params.theta3 << ' ' << t.rivet_area << '\n';
  }
  return s.str();
}

DiscoveryOptions small_options(const Problem& p, int chains, int iterations, int threads) {
  DiscoveryOptions o = DiscoveryOptions::from(p);
  o.chains = chains;
  o.iterations = iterations;
  o.threads = threads;
  return o;
}

// Every segment of the library assembled alone (with its ancestors) is a valid part that unfolds.
void expect_segments_valid(const Problem& problem, const Environment& env, const DiscoveryResult& r) {
  const SheetSpec spec = SheetSpec::from(problem);
  for (const Segment& s : r.library.segments()) {
    std::vector<int> ids;
    for (const Segment* g = &s; g; g = g->parent >= 0 ? r.library.find(g->parent) : nullptr) ids.push_back(g->id);
    const Part part = assemble_part(r.base, r.library, ids);
    const ValidityReport v = check_validity(part, realise(part), env);
    EXPECT_TRUE(v.valid()) << "segment " << s.id << ": " << v.summary();
    EXPECT_TRUE(unfold(part, spec).ok()) << "segment " << s.id;
    EXPECT_GE(s.tabs.back().rivet_area, 0);
    EXPECT_EQ(s.tabs.back().rivet_area, s.rivet_area);
  }
}

void expect_reaches_all(const std::string& name, int chains, int iterations) {
  const Problem problem = load_problem(scene(name));
  const Environment env(problem);
  const DiscoveryResult r = discover_segments(problem, env, 0, small_options(problem, chains, iterations, 2));
  ASSERT_EQ(static_cast<int>(r.stats.per_rivet_area.size()), env.rivet_area_count());
  for (int i = 0; i < env.rivet_area_count(); ++i)
    EXPECT_GE(r.stats.per_rivet_area[i], 1) << name << ": no segment to " << problem.rivet_areas[i].name;
  expect_segments_valid(problem, env, r);
  std::printf("[%s] %d segments (", name.c_str(), r.library.size());
  for (int c : r.stats.per_rivet_area) std::printf(" %d", c);
  std::printf(" ) in %.2f s, acceptance %.2f, candidates %lld\n", r.stats.seconds, r.stats.acceptance_rate(), r.stats.candidates);
}

TEST(Discovery, CornerReachesEveryRivetArea) { expect_reaches_all("corner", 6, 150); }
TEST(Discovery, CornerObstacleReachesEveryRivetArea) { expect_reaches_all("corner_obstacle", 10, 300); }
// slanted at 10 x 300, seed 1: the floor is reached with the printed Eq. 2 (4 segments) but not with the
// default se reading (12 candidates, all 12 fail optimisation); at 400 iterations 4 segments (printed 7).
TEST(Discovery, SlantedReachesEveryRivetArea) { expect_reaches_all("slanted", 10, 400); }

// Same problem + seed => byte-identical library for 1 and 2 threads and across
// runs; another seed gives another library.
TEST(Discovery, DeterministicAcrossThreadCounts) {
  const Problem problem = load_problem(scene("corner"));
  const Environment env(problem);
  const auto run = [&](int threads, std::uint64_t seed) {
    DiscoveryOptions o = small_options(problem, 4, 80, threads);
    o.seed = seed;
    return discover_segments(problem, env, 0, o);
  };
  const DiscoveryResult one = run(1, 7), two = run(2, 7), again = run(2, 7), other = run(2, 8);
  ASSERT_GT(one.library.size(), 0);
  EXPECT_EQ(fingerprint(one.library), fingerprint(two.library));
  EXPECT_EQ(fingerprint(two.library), fingerprint(again.library));
  EXPECT_NE(fingerprint(one.library), fingerprint(other.library));
  EXPECT_EQ(one.stats.jumps, two.stats.jumps);
}

TEST(Discovery, CancelReturnsWithinASecond) {
  const Problem problem = load_problem(scene("corner"));
  const Environment env(problem);
  DiscoveryProgress progress;
  DiscoveryResult r;
  const auto t0 = std::chrono::steady_clock::now();
  std::thread worker([&] { r = discover_segments(problem, env, 0, small_options(problem, 10, 100000, 2), &progress); });
  while (progress.iterations.load() < 200) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const auto t_cancel = std::chrono::steady_clock::now();
  progress.cancel = true;
  worker.join();
  const double wait = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_cancel).count();
  EXPECT_TRUE(r.cancelled);
  EXPECT_LT(wait, 1.0);
  EXPECT_EQ(progress.total.load(), 1000000);
  EXPECT_LT(progress.iterations.load(), 1000000);
  (void)t0;
}

}  // namespace
}  // namespace sheetgen
