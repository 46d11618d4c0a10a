#pragma once
// The whole pipeline for every load of a problem (docs/architecture.md "Pipeline"):
// environment -> segment discovery -> segment composition -> final check at the
// default mesh -> manufacturing plan. Parts of earlier loads become obstacles
// for later ones. Progress and cancel through one object another thread reads
// and sets.
#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "sheetgen/compose/composition.hpp"
#include "sheetgen/core/problem.hpp"
#include "sheetgen/core/stopwatch.hpp"
#include "sheetgen/discovery/discovery.hpp"
#include "sheetgen/part/manufacturing_plan.hpp"

namespace sheetgen {

struct GenerateOptions {
  // Overrides of the problem's search settings (unset: the problem's value).
  std::optional<int> chains, iterations, beam_width, threads;
  std::optional<std::uint64_t> seed;
  bool right_angles = false;   // the expert's practice: theta3 = +-90 deg or flat, no skew (--right-angles)
  // Tabs may continue their parent flat (Manufacturing::flat_extensions,
  // --flat-extensions); right-angle mode turns it on by itself.
  bool flat_extensions = false;
  // A load whose first search finds no valid part is searched again with web
  // roots (docs/discovery.md "Web roots"); off: --no-web-roots.
  bool web_fallback = true;
  // A load that still has no valid part is searched once more with flat
  // extensions (unless they are already on): a plate cut larger where a bend
  // alone cannot stiffen it (docs/pipeline.md); off: --no-flat-fallback.
  bool flat_fallback = true;
  // A load that no pass above gave a valid part is searched again, at most
  // this many times, each with a fresh seed; one whose own segments give no
  // part composes them pooled with those found before it (docs/pipeline.md
  // step 4d); --seed-retries N.
  int seed_retries = 2;
  // Every load is searched once more in the right-angle grammar, and a valid
  // part cheaper than the answer replaces it (docs/pipeline.md "Right-angle
  // pass"); off: --no-right-angle-pass. Not run where the problem's limits are
  // right angles already or exclude 90 deg.
  bool right_angle_pass = true;
  // A load whose answer is a press-brake fallback is searched again as a
  // right-angle solve searches it, and its part replaces the fallback when the
  // tools bend it or it is cheaper (docs/pipeline.md step 4h); off:
  // --no-right-angle-search. Not run where the problem's limits are right
  // angles already or exclude 90 deg.
  bool right_angle_search = true;
  // The answer of each load is narrowed tab by tab while it stays valid
  // (docs/pipeline.md "Sizing"); off: --no-sizing.
  bool sizing = true;
  ComposeOptions compose;      // beam_width and threads are taken from the settings above
};

enum class Stage : int { Idle = 0, Environment, Discovery, Composition, Plan, Done };
const char* to_string(Stage s);

struct GenerateProgress {
  std::atomic<int> stage{0};          // Stage
  std::atomic<int> load{0};           // index of the load being worked on
  std::atomic<int> loads{0};          // how many
  std::atomic<bool> web_roots{false}; // the current load's second search (with web roots) is running
  std::atomic<bool> flat_pass{false}; // the current load's third search (with flat extensions) is running
  std::atomic<bool> right_angle_pass{false};  // the current load's right-angle pass is running
  std::atomic<int> gauge{0};          // 0: the problem's sheet; k: the current load is searched at its k-th thicker gauge
  DiscoveryProgress discovery;        // iterations / total of the current load
  ComposeProgress compose;            // level, evaluated, best cost
  std::atomic<bool> cancel{false};    // set from any thread; honoured within a second
};

struct LoadOutcome {
  std::string load;
  bool ok = false;
  std::string reason;                 // when not ok: what failed, by how much
  Candidate part;                     // the answer (checked at the default mesh) or the closest candidate
  RealisedPart realised;
  ManufacturingPlan plan;
  std::vector<Vec3> rivets;           // m, rivet centres
  std::vector<ComposeHistoryRow> history;
  DiscoveryStats discovery;
  int library_size = 0;
  int fem_calls = 0;
  int self_rivet_candidates = 0;     // gusset variants the composition tried
  int lip_candidates = 0;            // lipped variants the composition tried
  int skipped_by_cost = 0;           // candidates the cost bound left unanalysed (ComposeOptions::kept_valid)
  int screen_fem_calls = 0;          // analyses on the composition's screening mesh (not in fem_calls)
  int screened_out = 0;              // candidates analysed on the screening mesh only
  int analyses_reused = 0;           // analyses (fem_calls and screening) taken from an earlier identical one of the load
  int composition_reruns = 0;        // 1: every kept part failed the final check, searched again without the bound
  bool web_pass_tried = false;       // the first search found no valid part, a second ran with web roots
  bool web_roots = false;            // the answer comes from that second search
  bool flat_pass_tried = false;      // no search so far found a valid part, a third ran with flat extensions
  bool flat_pass = false;            // the answer comes from that third search
  int seed_retries_tried = 0;        // plain searches with fresh seeds after every other pass found no valid part
  int seed_retry = 0;                // 1-based: the answer comes from that retry; 0: from an earlier pass
  bool right_angle_pass_tried = false;  // the load was searched once more in the right-angle grammar
  bool right_angle_pass = false;     // the answer comes from that search (cheaper, or the only valid one)
  // The answer was a press-brake fallback, so the load was searched again as a right-angle solve
  // searches it (every pass, sheet and round; docs/pipeline.md step 4h), and the answer comes from it.
  bool right_angle_search_tried = false;
  bool right_angle_search = false;
  // "prefer" (Manufacturing::press_brake_fallback): no search with the press-brake check found a valid
  // part, so the load was searched again without it, and the answer comes from that search.
  bool press_fallback = false;
  int press_rejected = 0;            // candidates the press-brake check rejected (not analysed), over every pass
  long long press_rejected_segments = 0;  // segments discovery's press-brake filter dropped, over every pass
  // Sizing (docs/pipeline.md "Sizing"): whether it ran on this answer, trial
  // parts analysed, cuts kept, and the answer's cost (m^2, search score) and
  // area (m^2) before it.
  bool sized = false;
  int sizing_trials = 0, sizing_cuts = 0;
  double sizing_cost_before = 0, sizing_area_before = 0;
  bool sizing_final_check_failed = false;
  // The sheet the answer is made of, m: the problem's thickness, or the first
  // of material.gauges that gave the load a valid part when the problem's
  // sheet gave none (docs/pipeline.md "Thicker gauges"). Mass, drawings, the
  // flat pattern and the FEM of the part use it.
  double thickness = 0;
  int gauges_tried = 0;              // thicker gauges searched in the answer's round (0: the problem's sheet only)
  // Where the load's time went, wall and the process's CPU, over every pass
  // and gauge of the load: the environment, discovery, composition (with the
  // final check), sizing, and the whole load (planning included).
  Elapsed environment_time, discovery_time, composition_time, sizing_time, total_time;
};

struct GenerateResult {
  std::vector<LoadOutcome> loads;
  SearchSettings search;              // the settings used (the problem's, with the options' overrides)
  bool right_angles = false;
  bool flat_extensions = false;       // tabs could continue their parent flat (theta3 = 0)
  bool self_rivet = true, stiffening_lips = true;  // the composition's variants that were on
  bool web_fallback = true;           // a second search with web roots where the first found no part
  bool flat_fallback = true;          // a third search with flat extensions where neither found one
  int seed_retries = 2;               // at most this many searches with fresh seeds where no pass found a part
  bool right_angle_pass = true;       // every load searched once more in the right-angle grammar
  bool right_angle_search = true;     // press-brake fallbacks searched again as a right-angle solve would
  bool sizing = true;                 // answers narrowed to their limits
  bool cancelled = false;
  double seconds = 0;
  bool all_ok() const;
};

GenerateResult generate(const Problem& problem, const GenerateOptions& options = {}, GenerateProgress* progress = nullptr);

}  // namespace sheetgen
