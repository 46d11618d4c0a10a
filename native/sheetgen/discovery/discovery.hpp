#pragma once
// Segment discovery (paper Sec. 4, docs/architecture.md "Discovery"): M communicating
// reversible-jump Metropolis-Hastings chains grow feelers from their parts;
// every connection to a rivet area is optimised (contraction, merging,
// widening) and offered to the Segment Library. Deterministic: the same
// problem, options and seed give the same library for any thread count
// (chains step in rounds, see docs/discovery.md).
#include <atomic>
#include <cstdint>
#include <vector>
#include <string>

#include "sheetgen/discovery/feeler.hpp"
#include "sheetgen/discovery/segment_library.hpp"
#include "sheetgen/discovery/segment_optimiser.hpp"
#include "sheetgen/discovery/target.hpp"
#include "sheetgen/discovery/web_roots.hpp"

namespace sheetgen {

class Environment;

// Edge selection for jumps (paper Sec. 6.4.1): Eq. 2 weights, always the free
// edge nearest to a rivet area, or uniform over free edges.
enum class EdgePolicy { Ours, GreedyNearest, Uniform };
// Which connections are optimised and admitted: the library's distance /
// regularisation rule (ours), every one (greedy), or one per chain and round
// drawn uniformly from those found (uniform). All respect the per-area cap.
enum class SegmentPolicy { Ours, Greedy, Uniform };
const char* to_string(EdgePolicy p);
const char* to_string(SegmentPolicy p);

struct DiscoveryOptions {
  int chains = 10;           // M
  int iterations = 1000;     // N per chain
  std::uint64_t seed = 1;
  int threads = 0;           // 0 = all cores
  int round_length = 10;     // iterations between exchanges of counts c(RA_i) and library admissions
  double diffuse_probability = 0.4;  // else jump
  int max_feeler_tabs = 12;  // feeler tabs a chain may hold
  int cast_rays = 3;         // rays across the root edge per cast
  // Environment::polygon_contact spacing for feeler tabs, in voxels (a feeler is a
  // probe; candidates and segments are checked at the default voxel / 2).
  double feeler_contact_spacing = 2.0;
  bool optimise = true;      // contraction + merging + widening (off: raw connections)
  EdgePolicy edge_policy = EdgePolicy::Ours;
  SegmentPolicy segment_policy = SegmentPolicy::Ours;
  TargetOptions target;      // alpha, beta, scene unit (Eq. 1-2)
  FeelerPrior prior;
  LibraryOptions library;
  ShortcutOptions shortcut;
  ContractOptions contract;
  MergeOptions merge;
  WidenOptions widen;
  // Web roots (docs/discovery.md "Web roots"): hang a web from every base edge
  // before the chains start, frozen into every chain, so feelers can also leave
  // the load edge-on. generate() turns this on for a second pass when the first
  // finds no valid part.
  bool web_roots = false;
  WebRootOptions webs;
  // chains, iterations, seed, threads, alpha, beta, scene_unit from Problem::search.
  static DiscoveryOptions from(const Problem& problem);
};

// Shared with a caller on another thread: read the counters, set `cancel`.
struct DiscoveryProgress {
  std::atomic<long long> iterations{0};  // chain iterations done (all chains)
  std::atomic<long long> total{0};       // chains * iterations, set at start
  std::atomic<int> segments{0};          // library size after the last round
  std::atomic<bool> cancel{false};       // set to stop; discovery returns within a round's iteration
};

struct DiscoveryStats {
  long long jumps = 0, jumps_accepted = 0;
  long long diffusions = 0, diffusions_accepted = 0;
  long long candidates = 0;   // connections found in accepted states
  long long optimised = 0;    // candidates that went through geometry optimisation
  long long optimise_failed = 0;  // optimised segment invalid or not unfoldable: dropped
  long long press_rejected = 0;   // optimised segment the press brake cannot bend (bendable.hpp): dropped
  std::string press_example;      // why the first of those (in chain order) cannot be bent
  long long admitted = 0, replaced = 0, rejected = 0, full = 0;
  int rounds = 0;
  double seconds = 0;
  std::vector<int> per_rivet_area;  // library segments per rivet area at the end
  // per rivet area: connections found (accepted states), optimised, optimisation failed,
  // not bendable (press_rejected), admitted
  std::vector<long long> found_per_ra, optimised_per_ra, failed_per_ra, press_rejected_per_ra, admitted_per_ra;
  double acceptance_rate() const {
    const long long n = jumps + diffusions;
    return n ? static_cast<double>(jumps_accepted + diffusions_accepted) / n : 0.0;
  }
};

struct DiscoveryResult {
  SegmentLibrary library;  // compacted: ids 0..n-1, parents before children
  Part base;               // the base part (make_base_part under the load); assemble_part(base, library, ids)
  DiscoveryStats stats;
  bool cancelled = false;
};

// Throws std::invalid_argument for a bad load index or non-positive chains/iterations.
DiscoveryResult discover_segments(const Problem& problem, const Environment& env, int load_index,
                                  const DiscoveryOptions& options, DiscoveryProgress* progress = nullptr);

// Chain-part surgery, exposed for tests: removes the subtrees rooted at `roots`.
Part remove_subtrees(const Part& part, const std::vector<int>& roots);

// Converts an optimised work segment to a library Segment (tabs, area, edges,
// regularisation; attachment and raw features are left to the caller).
Segment make_segment(const SegmentWork& work);

}  // namespace sheetgen
