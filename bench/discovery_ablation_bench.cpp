// Ablation of the discovery policies (paper Sec. 6.4.1, Fig. 13): not a Google
// Benchmark but a driver with its own main, run by bench/ablation_edge_policies.py.
// Usage: discovery_ablation_bench PROBLEM.json ITERATIONS CHAINS SEED [SEED...]
// Prints CSV: policy,seed,segments,distinct,ra_1..ra_n,seconds
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"

using namespace sheetgen;

namespace {

struct Pair {
  const char* name;
  EdgePolicy edge;
  SegmentPolicy segment;
};

// Segments farther than `radius` (m, segment distance) from every earlier one.
int distinct(const SegmentLibrary& lib, double radius) {
  std::vector<const Segment*> kept;
  for (const Segment& s : lib.segments()) {
    bool fresh = true;
    for (const Segment* k : kept)
      if (segment_distance(s, *k) < radius) { fresh = false; break; }
    if (fresh) kept.push_back(&s);
  }
  return static_cast<int>(kept.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s PROBLEM.json ITERATIONS CHAINS SEED [SEED...]\n", argv[0]);
    return 1;
  }
  const Problem problem = load_problem(argv[1]);
  const Environment env(problem);
  const int iterations = std::atoi(argv[2]), chains = std::atoi(argv[3]);
  const Pair pairs[] = {{"ours", EdgePolicy::Ours, SegmentPolicy::Ours},
                        {"segment_greedy", EdgePolicy::Ours, SegmentPolicy::Greedy},
                        {"segment_uniform", EdgePolicy::Ours, SegmentPolicy::Uniform},
                        {"edge_greedy", EdgePolicy::GreedyNearest, SegmentPolicy::Ours},
                        {"edge_uniform", EdgePolicy::Uniform, SegmentPolicy::Ours}};
  std::printf("policy,seed,segments,distinct");
  for (int i = 0; i < env.rivet_area_count(); ++i) std::printf(",ra_%d", i + 1);
  std::printf(",seconds\n");
  for (int a = 4; a < argc; ++a) {
    for (const Pair& p : pairs) {
      // SHEETGEN_ABL_ONLY=name[,name]: run only these pairs (quick experiments)
      if (const char* only = std::getenv("SHEETGEN_ABL_ONLY"))
        if (std::string(",") .append(only).append(",").find(std::string(",") + p.name + ",") == std::string::npos) continue;
      DiscoveryOptions o = DiscoveryOptions::from(problem);
      o.iterations = iterations;
      o.chains = chains;
      o.seed = std::strtoull(argv[a], nullptr, 10);
      o.threads = 0;
      o.edge_policy = p.edge;
      o.segment_policy = p.segment;
      // SHEETGEN_ABL_SE=0..3: Eq. 2 se reading (TargetOptions::SeReading: Printed, Multiply, Divide, Plus)
      if (const char* se = std::getenv("SHEETGEN_ABL_SE")) o.target.se_reading = static_cast<TargetOptions::SeReading>(std::atoi(se));
      const DiscoveryResult r = discover_segments(problem, env, 0, o);
      std::printf("%s,%llu,%d,%d", p.name, static_cast<unsigned long long>(o.seed), r.library.size(),
                  distinct(r.library, 0.05));
      for (int c : r.stats.per_rivet_area) std::printf(",%d", c);
      std::printf(",%.2f\n", r.stats.seconds);
      auto v = [](const std::vector<long long>& x) {
        std::string s;
        for (long long c : x) s += " " + std::to_string(c);
        return s;
      };
      std::fprintf(stderr, "%s seed %s: found%s | optimised%s | failed%s | not bendable%s | admitted%s | jumps %lld acc %.2f\n",
                   p.name, argv[a], v(r.stats.found_per_ra).c_str(), v(r.stats.optimised_per_ra).c_str(),
                   v(r.stats.failed_per_ra).c_str(), v(r.stats.press_rejected_per_ra).c_str(),
                   v(r.stats.admitted_per_ra).c_str(), r.stats.jumps, r.stats.acceptance_rate());
      std::fflush(stdout);
    }
  }
  return 0;
}
