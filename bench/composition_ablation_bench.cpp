// Paper Fig. 14 ablation: composition over the whole segment library against
// the best part any single chain can make from its own segments. Not a Google
// Benchmark: a driver with its own main (bench/ablation_composition.py runs it).
//
//   composition_ablation_bench PROBLEM.json [--seeds 1,2,3] [--chains 10] [--iterations 1000]
// prints CSV: seed,variant,chain,found,area_m2,bends,compliance_J,limit_J,margin,segments
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sheetgen/compose/composition.hpp"
#include "sheetgen/core/problem.hpp"
#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/env/environment.hpp"

using namespace sheetgen;

namespace {

// The segments one chain contributed, renumbered (their parents are the same chain's).
SegmentLibrary chain_library(const SegmentLibrary& all, int chain) {
  SegmentLibrary lib(all.options());
  std::map<int, int> remap;
  for (const Segment& s : all.segments()) {
    if (s.chain != chain) continue;
    Segment copy = s;
    if (copy.parent >= 0) {
      auto it = remap.find(copy.parent);
      if (it == remap.end()) continue;  // grown from another chain's segment: not this chain's own part
      copy.parent = it->second;
    }
    const AdmissionResult r = lib.add(copy);
    if (r.id >= 0) remap[s.id] = r.id;
  }
  return lib;
}

void row(int seed, const char* variant, int chain, const ComposeResult& r) {
  const Candidate& c = r.found ? r.best : r.closest;
  std::string segs;
  for (int id : c.segments) segs += (segs.empty() ? "" : " ") + std::to_string(id);
  std::printf("%d,%s,%d,%d,%.6g,%d,%.6g,%.6g,%.4g,%s\n", seed, variant, chain, r.found ? 1 : 0, c.area, c.bends,
              c.analysed ? c.fem.compliance : -1.0, c.analysed ? c.fem.compliance_limit : -1.0,
              c.analysed ? c.fem.margin_of_safety : -99.0, segs.c_str());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s PROBLEM.json [--seeds 1,2,3] [--chains M] [--iterations N]\n", argv[0]);
    return 1;
  }
  const Problem problem = load_problem(argv[1]);
  std::vector<int> seeds = {1, 2, 3};
  int chains = problem.search.chains, iterations = problem.search.iterations;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string k = argv[i], v = argv[i + 1];
    if (k == "--seeds") {
      seeds.clear();
      std::stringstream ss(v);
      for (std::string t; std::getline(ss, t, ',');) seeds.push_back(std::stoi(t));
    } else if (k == "--chains") {
      chains = std::stoi(v);
    } else if (k == "--iterations") {
      iterations = std::stoi(v);
    }
  }
  const Environment env(problem);
  std::printf("seed,variant,chain,found,area_m2,bends,compliance_J,limit_J,margin,segments\n");
  for (int seed : seeds) {
    DiscoveryOptions d = DiscoveryOptions::from(problem);
    d.seed = static_cast<std::uint64_t>(seed);
    d.chains = chains;
    d.iterations = iterations;
    const DiscoveryResult found = discover_segments(problem, env, 0, d);
    ComposeOptions c;
    c.beam_width = problem.search.beam_width;
    row(seed, "composition", -1, compose_part(problem, env, 0, found.base, found.library, c));
    for (int k = 0; k < chains; ++k) {
      const SegmentLibrary lib = chain_library(found.library, k);
      if (lib.empty()) continue;
      row(seed, "single_chain", k, compose_part(problem, env, 0, found.base, lib, c));
    }
  }
  return 0;
}
