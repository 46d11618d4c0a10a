// Segment discovery time (docs/discovery.md "Performance"): M = 10 chains x
// N = 1000 iterations on each sample problem with 1 and 2 threads
// (goal: <= 20 s with 2 threads). One run per case: each takes seconds.
#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"

namespace {

using namespace sheetgen;

const char* kScenes[] = {"corner", "corner_obstacle", "slanted"};

void BM_Discovery(benchmark::State& state) {
  const std::string name = kScenes[state.range(0)];
  const Problem problem = load_problem(std::string(SHEETGEN_SOURCE_DIR) + "/sample_scenes/" + name + "/problem.json");
  const Environment env(problem);
  DiscoveryOptions o = DiscoveryOptions::from(problem);
  o.chains = 10;
  o.iterations = 1000;
  o.threads = static_cast<int>(state.range(1));
  DiscoveryResult r;
  for (auto _ : state) r = discover_segments(problem, env, 0, o);
  state.SetLabel(name + " threads=" + std::to_string(o.threads));
  state.counters["segments"] = r.library.size();
  state.counters["candidates"] = static_cast<double>(r.stats.candidates);
  state.counters["acceptance"] = r.stats.acceptance_rate();
}

BENCHMARK(BM_Discovery)
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
