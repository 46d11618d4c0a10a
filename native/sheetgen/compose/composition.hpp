#pragma once
// Segment composition (paper Sec. 5.1, docs/architecture.md "Composition"): a
// beam search over subsets of the segment library that are closed under
// parents. Every candidate is assembled, checked (self-intersection across
// segments, environment, flat pattern, bend sequence), analysed by the shell
// FEM, and scored by its cost (core/cost_model.hpp). The answer is
// the cheapest candidate that is stiff and strong enough.
#include <atomic>
#include <limits>
#include <string>
#include <vector>

#include "sheetgen/compose/candidate.hpp"
#include "sheetgen/core/problem.hpp"
#include "sheetgen/discovery/segment_library.hpp"
#include "sheetgen/part/part.hpp"

namespace sheetgen {

class Environment;

struct ComposeOptions {
  int beam_width = 8;              // B: states kept per level (quality/time knob)
  int max_segments = 6;            // segments in one part
  double search_element_size = 0;  // m, FEM mesh during the search; <= 0: 1.5x the default size
  bool self_rivet = true;          // try self-riveting when MS passes but compliance does not
  bool stiffening_lips = true;     // try lips on the free edges of candidates that miss their limits
  // Valid parts kept as fallbacks for the final check at the default mesh. Once
  // this many are known, a candidate costing at least the dearest of them is
  // not analysed: it can be neither the answer nor a beam state (docs/pipeline.md
  // "Cost bound"). 0 analyses every candidate.
  int kept_valid = 4;
  // A candidate costing at least this is not analysed either: a search that
  // can only replace an answer in hand if it finds a cheaper part (the
  // right-angle pass, docs/pipeline.md "Right-angle pass"). Infinity: no ceiling.
  double cost_ceiling = std::numeric_limits<double>::infinity();
  // Screening (docs/pipeline.md "Screening"): a level's candidates are first
  // analysed on a mesh this many times the default size; only the
  // screen_keep * beam_width best of them by the beam's score, and every one
  // valid there, are analysed again on the search mesh. <= 0: no screening.
  double screen_element_factor = 3.0;
  int screen_keep = 2;
  int threads = 0;                 // 0 = all cores; results do not depend on it
  // The analyses of the load's earlier searches, shared with this one and
  // added to (compose/analysis_cache.hpp); nullptr: every candidate is analysed.
  // Results do not depend on it.
  AnalysisCache* analyses = nullptr;
};

struct ComposeHistoryRow {
  int level = 0;                   // beam-search iteration (segments per candidate)
  int evaluated = 0;               // candidates evaluated so far
  bool found = false;              // a valid part exists so far
  double best_cost = 0, best_area = 0, compliance = 0, margin_of_safety = 0;  // of the best so far
};

struct ComposeProgress {
  std::atomic<int> level{0};
  std::atomic<int> evaluated{0};
  std::atomic<double> best_cost{0};  // m^2; 0 until a valid part is found
  std::atomic<bool> cancel{false};
};

struct ComposeResult {
  bool found = false;
  Candidate best;                  // the cheapest valid candidate, when found
  std::vector<Candidate> valid;    // every valid candidate found, cheapest first (the final check walks it)
  Candidate closest;               // otherwise: the candidate nearest to valid (for the user's reason)
  std::string reason;              // when not found: which constraint failed, by how much
  std::vector<ComposeHistoryRow> history;
  int fem_calls = 0;
  int candidates = 0;
  int self_rivet_candidates = 0;   // gusset variants evaluated
  int lip_candidates = 0;          // lipped variants evaluated
  int skipped_by_cost = 0;         // candidates not analysed (ComposeOptions::kept_valid, cost_ceiling)
  int screen_fem_calls = 0;        // analyses on the screening mesh (not in fem_calls)
  int screened_out = 0;            // candidates analysed on the screening mesh only
  int press_rejected = 0;          // candidates no bend order of the press brake's tools makes (not analysed)
  bool cancelled = false;
  double seconds = 0;
};

ComposeResult compose_part(const Problem& problem, const Environment& env, int load_index, const Part& base,
                           const SegmentLibrary& library, const ComposeOptions& options = {},
                           ComposeProgress* progress = nullptr);

}  // namespace sheetgen
