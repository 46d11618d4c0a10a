#include "sheetgen/pipeline/search_passes.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sheetgen/compose/sizing.hpp"
#include "sheetgen/discovery/feeler.hpp"
#include "sheetgen/env/environment.hpp"

namespace sheetgen {

namespace {

constexpr double kNoCostBound = std::numeric_limits<double>::infinity();

bool cancel_requested(const GenerateProgress* progress) { return progress && progress->cancel.load(); }

ComposeProgress* compose_progress(GenerateProgress* progress) { return progress ? &progress->compose : nullptr; }

// Why the cheapest part failed at the default mesh: the check, its case and by how much.
std::string final_check_failure(const Candidate& c, const Requirements& req) {
  const StructuralResult& f = c.fem;
  const EnvelopeResult& env = f.envelope;
  char buf[512];
  if (!f.stiff_enough || !f.strong_enough) {
    std::snprintf(buf, sizeof buf,
                  "at the default mesh the cheapest part misses its limits (compliance %.6g J in case '%s', limit %.6g J; "
                  "MS %.4g in case '%s')",
                  f.compliance, env.cases[env.governing_stiffness].name.c_str(), f.compliance_limit, f.margin_of_safety,
                  env.cases[env.governing_strength].name.c_str());
  } else if (!f.stable_enough) {
    std::snprintf(buf, sizeof buf,
                  "at the default mesh the cheapest part buckles in case '%s' at %.4g times its load (held to %.4g: "
                  "required %.4g with the model's reserve)",
                  env.cases[env.governing_buckling].name.c_str(), env.buckling_factor, req.design_buckling_factor(),
                  req.min_buckling_factor);
  } else {
    std::snprintf(buf, sizeof buf,
                  "at the default mesh the cheapest part's first natural frequency is %.4g Hz (held to %.4g Hz: floor "
                  "%.4g Hz with the model's reserve)",
                  env.frequencies_hz.empty() ? 0.0 : env.frequencies_hz.front(), req.design_frequency_hz().value_or(0.0),
                  req.min_frequency_hz.value_or(0.0));
  }
  return buf;
}

// The final check at the default mesh, down a list of valid candidates,
// cheapest first: the first that passes is the answer. Remembers the parts it
// rejected, so the list of a rerun skips them.
struct FinalCheck {
  const Problem& scene;
  const Environment& env;
  int load_index;
  bool web_roots;    // for the debug line
  AnalysisCache* analyses;  // the load's analyses so far (ComposeOptions::analyses)
  std::set<std::pair<std::vector<int>, double>> failed;  // (segments, cost) of parts rejected
  std::string reason;  // why the cheapest analysed part failed, when one did

  // Sets out.part and out.ok when a candidate passes; counts the analyses.
  void run(const std::vector<Candidate>& valid, LoadOutcome& out) {
    for (const Candidate& c : valid) {
      if (failed.count({c.segments, c.cost})) continue;
      const Stopwatch tc;
      Candidate checked = evaluate_part(scene, env, load_index, c, 0.0, nullptr, kNoCostBound, analyses);
      ++out.fem_calls;
      if (std::getenv("SHEETGEN_COMPOSE_DEBUG"))
        std::fprintf(stderr, "[final check] %s%s: %s in %.2f s\n", out.load.c_str(), web_roots ? " (web roots)" : "",
                     checked.valid() ? "valid" : "fails", tc.wall_seconds());
      if (checked.valid()) {
        out.part = checked;
        out.ok = true;
        return;
      }
      failed.insert({c.segments, c.cost});
      out.press_rejected += checked.reason == ValidityReason::PressBrake;
      if (reason.empty() && checked.analysed) reason = final_check_failure(checked, scene.requirements);
    }
  }
};

// Composition of the discovered library and the final check of its valid
// parts; fills the composition's fields of `out`. False when cancelled.
bool compose_and_check(const Problem& scene, const Environment& env, int li, const Part& base,
                       const SegmentLibrary& library, const GenerateOptions& options, bool web_roots,
                       GenerateProgress* progress, LoadOutcome& out) {
  ComposeOptions copt = options.compose;
  copt.beam_width = scene.search.beam_width;
  copt.threads = scene.search.threads;
  const Stopwatch clock;
  ComposeResult composed = compose_part(scene, env, li, base, library, copt, compose_progress(progress));
  if (composed.cancelled || cancel_requested(progress)) return false;
  FinalCheck check{scene, env, li, web_roots, copt.analyses, {}, {}};
  check.run(composed.valid, out);
  out.skipped_by_cost = composed.skipped_by_cost;
  out.screen_fem_calls = composed.screen_fem_calls;
  out.screened_out = composed.screened_out;
  out.press_rejected += composed.press_rejected;
  // Every kept part failed at the default mesh while the cost bound left dearer
  // ones unanalysed: search again without the bound, which finds exactly the
  // valid parts of an unbounded search (docs/pipeline.md "Cost bound"). The
  // bound of kept parts acts only once that many are known; what a ceiling
  // alone skipped (the right-angle pass) stays skipped.
  const bool kept_bound_acted = copt.kept_valid > 0 && composed.valid.size() >= static_cast<size_t>(copt.kept_valid);
  if (!out.ok && composed.skipped_by_cost > 0 && kept_bound_acted) {
    ComposeOptions unbounded = copt;
    unbounded.kept_valid = 0;
    ComposeResult again = compose_part(scene, env, li, base, library, unbounded, compose_progress(progress));
    if (again.cancelled || cancel_requested(progress)) return false;
    out.fem_calls += composed.fem_calls;
    out.screen_fem_calls += again.screen_fem_calls;
    out.composition_reruns = 1;
    out.press_rejected += again.press_rejected;
    composed = std::move(again);
    check.run(composed.valid, out);
  }
  out.history = composed.history;
  out.fem_calls += composed.fem_calls;
  out.self_rivet_candidates = composed.self_rivet_candidates;
  out.lip_candidates = composed.lip_candidates;
  out.composition_time = clock.elapsed();
  if (!out.ok) {
    out.part = composed.found ? composed.valid.front() : composed.closest;
    out.reason = composed.found ? check.reason : composed.reason;
  }
  return true;
}

// Discovery reached rivet areas, but its press-brake filter dropped every
// connection (docs/discovery.md "Press-brake filter"): the library holds no
// segment that ends on a rivet area.
bool unbendable_library(const DiscoveryResult& found, const SegmentLibrary& pool) {
  if (found.stats.press_rejected == 0) return false;
  const auto& segs = pool.segments();
  return std::none_of(segs.begin(), segs.end(), [](const Segment& s) { return s.rivet_area >= 0; });
}

// The reason of such a load: what the tools could not do to its connections.
std::string no_bendable_segment(const DiscoveryResult& found) {
  return "no segment the press brake's tools can bend reached a rivet area: discovery dropped " +
         std::to_string(found.stats.press_rejected) + " that reached one (e.g. " + found.stats.press_example + ")";
}

// Of two answers without a valid part, is `a` nearer to valid than `b`? An
// analysed candidate beats one that is not; then the larger of the compliance
// and strength ratios (how far over the limits) decides.
bool closer(const Candidate& a, const Candidate& b, const Problem& scene) {
  if (a.analysed != b.analysed) return a.analysed;
  if (!a.analysed) return false;
  auto over = [&](const Candidate& c) {
    const double stiff = c.fem.compliance_limit > 0 ? c.fem.compliance / c.fem.compliance_limit : 0.0;
    const double ms_req = scene.requirements.min_margin_of_safety;
    const double strong = (1.0 + ms_req) / std::max(1e-12, 1.0 + c.fem.margin_of_safety);
    // The eigen checks, when they ran: the floor over the value (> 1 = failed).
    const EnvelopeResult& env = c.fem.envelope;
    double stable = 0, vibration = 0;
    if (env.eigen_checked && scene.requirements.eigen_checks) {
      stable = scene.requirements.design_buckling_factor() / std::max(1e-12, env.buckling_factor);
      if (scene.requirements.min_frequency_hz && !env.frequencies_hz.empty())
        vibration = *scene.requirements.design_frequency_hz() / std::max(1e-12, env.frequencies_hz.front());
    }
    return std::max({stiff, strong, stable, vibration});
  };
  return over(a) < over(b);
}

// A later search of the same load added to the best so far: times, FEM calls
// and press-brake rejections count both; the later answer replaces the best
// when `keep`. Returns `keep`.
bool add_pass(LoadOutcome& best, LoadOutcome&& pass, bool keep) {
  Elapsed discovery = best.discovery_time, composition = best.composition_time;
  discovery += pass.discovery_time;
  composition += pass.composition_time;
  const int fem_calls = best.fem_calls + pass.fem_calls;
  const int press_rejected = best.press_rejected + pass.press_rejected;
  const long long press_rejected_segments = best.press_rejected_segments + pass.press_rejected_segments;
  if (keep) best = std::move(pass);
  best.discovery_time = discovery;
  best.composition_time = composition;
  best.fem_calls = fem_calls;
  best.press_rejected = press_rejected;
  best.press_rejected_segments = press_rejected_segments;
  return keep;
}

// A later search of the same load (web roots, flat extensions, a seed retry)
// against the best so far: the later answer is kept when it is valid or
// nearer to valid. True when it was kept.
bool merge_pass(LoadOutcome& best, LoadOutcome&& pass, const Problem& scene) {
  const bool keep = pass.ok || closer(pass.part, best.part, scene);
  return add_pass(best, std::move(pass), keep);
}

// One search for one load: discovery, then composition and the final check.
// Fills the search's fields of `out` (answer or closest candidate, reason,
// statistics, history, times); false when it was cancelled. The discovered
// segments join `pool`. A first search (empty pool) composes its library. A
// later one (a retry, step 4d, or the web pass, which starts from the first
// pass's segments) composes its own library first, exactly as a search with
// its seed alone would, and only when that gives no valid part the whole pool:
// the earlier searches' segments with its own. Why both: a beam search
// is not monotone in its library; on the larger pool the beam may keep other
// states and lose the part the smaller library leads to.
bool search_pass(const Problem& scene, const Environment& env, int li, const GenerateOptions& options, bool web_roots,
                 GenerateProgress* progress, LoadOutcome& out, SegmentLibrary& pool) {
  out.web_roots = web_roots;
  if (progress) {
    progress->web_roots = web_roots;
    progress->stage = static_cast<int>(Stage::Discovery);
  }
  DiscoveryOptions dopt = DiscoveryOptions::from(scene);
  dopt.web_roots = web_roots;
  const Stopwatch clock;
  const DiscoveryResult found = discover_segments(scene, env, li, dopt, progress ? &progress->discovery : nullptr);
  out.discovery_time = clock.elapsed();
  out.discovery = found.stats;
  if (found.cancelled || cancel_requested(progress)) return false;

  const bool later = !pool.empty();  // a retry or the web pass: there are earlier segments
  pool.absorb(found.library);
  out.library_size = found.library.size();
  out.press_rejected_segments = found.stats.press_rejected;
  if (progress) progress->stage = static_cast<int>(Stage::Composition);
  std::optional<LoadOutcome> pooled;  // a later search's fields known before composition, for the pool's
  if (later) pooled = out;
  bool finished = compose_and_check(scene, env, li, found.base, found.library, options, web_roots, progress, out);
  if (finished && !out.ok && later && pool.size() > found.library.size() && !cancel_requested(progress)) {
    pooled->discovery_time = {};  // counted once, in `out`
    pooled->press_rejected_segments = 0;
    pooled->library_size = pool.size();
    finished = compose_and_check(scene, env, li, found.base, pool, options, web_roots, progress, *pooled);
    merge_pass(out, std::move(*pooled), scene);
  }
  if (finished && !out.ok && unbendable_library(found, pool)) out.reason = no_bendable_segment(found);
  if (std::getenv("SHEETGEN_COMPOSE_DEBUG"))  // where a load's time goes, pass by pass
    std::fprintf(stderr, "[pass] %s web %d flat %d right angles %d press %d seed %llu: discovery %.1f s, composition %.1f s, "
                 "%d analyses, library %d, %s\n",
                 out.load.c_str(), web_roots, scene.manufacturing.flat_extensions, scene.manufacturing.right_angles_only(),
                 scene.manufacturing.press_brake_required,
                 static_cast<unsigned long long>(scene.search.seed), out.discovery_time.wall_seconds, out.composition_time.wall_seconds,
                 out.fem_calls, out.library_size, out.ok ? "valid part" : "no part");
  return finished;
}

// The scene of a load's seed retry k (1, 2, ...): its own random numbers,
// derived from the problem's seed (docs/pipeline.md, step 4d).
Problem retry_scene_of(const Problem& scene, int k) {
  Problem p = scene;
  p.search.seed = ChainRng::seed_for(scene.search.seed, 1000 + k);
  return p;
}

// Seed retries (docs/pipeline.md, step 4d): while no pass has a valid part,
// the pass whose candidate came nearest to valid again (its roots and grammar)
// with a fresh seed, up to options.seed_retries times. Which part a search
// finds depends on its seed: a load that one seed leaves without a part,
// another often solves. A retry whose own segments give no part composes
// them again pooled with those of the searches before it in that grammar
// (search_pass), so a part may join connections that different seeds found.
// Only loads without a part pay for them.
void retry_with_fresh_seeds(const Problem& scene, const Environment& env, int li, const LoadOutcome& start,
                            const GenerateOptions& options, GenerateProgress* progress, LoadSearch& s) {
  LoadOutcome& best = s.answer;
  SegmentLibrary& pool = s.library;  // a retry searches the kept pass's roots and grammar
  for (int k = 1; k <= options.seed_retries && s.finished && !best.ok && !cancel_requested(progress); ++k) {
    const bool web_roots = best.web_roots, flat = s.answer_scene.has_value();
    Problem retry_scene = retry_scene_of(flat ? *s.answer_scene : scene, k);
    LoadOutcome retry = start;
    if (progress) progress->flat_pass = flat;
    s.finished = search_pass(retry_scene, env, li, options, web_roots, progress, retry, pool);
    if (progress) progress->flat_pass = false;
    retry.web_pass_tried = best.web_pass_tried;
    retry.flat_pass_tried = best.flat_pass_tried;
    retry.flat_pass = flat;
    retry.seed_retries_tried = best.seed_retries_tried = k;
    retry.seed_retry = k;
    if (merge_pass(best, std::move(retry), scene) && flat) s.answer_scene = std::move(retry_scene);
  }
}
}  // namespace

namespace {

// Every pass of one load in the grammar and checks of `scene`.
LoadSearch search_passes(const Problem& scene, const Environment& env, int li, const LoadOutcome& start,
                         const GenerateOptions& options, bool flat_fallback, GenerateProgress* progress) {
  LoadSearch s;
  LoadOutcome& first = s.answer;
  first = start;
  // Discovery and composition; when that finds no valid part, once more with
  // web roots (docs/discovery.md "Web roots"): the plates of the first pass
  // may be too soft where the way to the rivet areas is narrow. The web pass
  // starts from the first pass's segments, so that when its own give no part
  // it composes both: a plate from the base beside webs to another support
  // (boxed_in's answer, docs/discovery.md "Web roots") needs segments of each.
  s.finished = search_pass(scene, env, li, options, /*web_roots=*/false, progress, first, s.library);
  if (s.finished && !first.ok && options.web_fallback && !cancel_requested(progress)) {
    LoadOutcome webbed = start;
    SegmentLibrary pool = s.library;
    s.finished = search_pass(scene, env, li, options, /*web_roots=*/true, progress, webbed, pool);
    webbed.web_pass_tried = first.web_pass_tried = true;
    if (merge_pass(first, std::move(webbed), scene)) s.library = std::move(pool);
  }
  // Still nothing: once more with flat extensions (a tab may continue its
  // parent flat), a plate cut larger where a bend alone cannot stiffen it.
  // Measured (docs/pipeline.md step 4c): corner_obstacle's and slanted's
  // parts come from this pass.
  if (s.finished && !first.ok && flat_fallback && !cancel_requested(progress)) {
    Problem flat_grammar = scene;
    flat_grammar.manufacturing.flat_extensions = true;
    LoadOutcome flat = start;
    SegmentLibrary pool;
    if (progress) progress->flat_pass = true;
    s.finished = search_pass(flat_grammar, env, li, options, /*web_roots=*/false, progress, flat, pool);
    if (progress) progress->flat_pass = false;
    flat.web_pass_tried = first.web_pass_tried;
    flat.flat_pass_tried = first.flat_pass_tried = flat.flat_pass = true;
    if (merge_pass(first, std::move(flat), scene)) {
      s.answer_scene = std::move(flat_grammar);
      s.library = std::move(pool);
    }
  }
  retry_with_fresh_seeds(scene, env, li, start, options, progress, s);
  return s;
}

}  // namespace

void size_load_answer(const Environment& env, int li, const GenerateOptions& options, LoadSearch& s) {
  const Problem& scene = env.problem();
  LoadOutcome& out = s.answer;
  if (!options.sizing || !s.finished || !out.ok) return;
  Problem searched = s.answer_scene ? *s.answer_scene : scene;
  if (out.press_fallback) searched.manufacturing.press_brake_required = false;
  SizingOptions so;
  so.threads = scene.search.threads;
  const Stopwatch clock;
  SizingResult sized = size_part(searched, env, li, out.part, so);
  out.sized = true;
  out.sizing_trials = sized.trials;
  out.sizing_cuts = sized.cuts;
  out.sizing_cost_before = sized.cost_before;
  out.sizing_area_before = sized.area_before;
  out.sizing_final_check_failed = sized.final_check_failed;
  out.fem_calls += sized.trials + sized.final_checks;
  out.part = std::move(sized.part);
  out.sizing_time = clock.elapsed();
  if (std::getenv("SHEETGEN_COMPOSE_DEBUG"))
    std::fprintf(stderr, "[sizing] %s: %d trials, %d cuts%s, cost %.5g -> %.5g m2, area %.1f -> %.1f cm2, %.1f s\n",
                 out.load.c_str(), sized.trials, sized.cuts, sized.final_check_failed ? " (failed at the default mesh)" : "",
                 sized.cost_before, out.part.cost, sized.area_before * 1e4, out.part.area * 1e4, out.sizing_time.wall_seconds);
}

namespace {

// The right-angle pass (docs/pipeline.md "Right-angle pass"): the load
// searched once more in the right-angle grammar, a subset of the problem's
// that the free search does not always reach (docs/ablation_composition.md).
// Only a part cheaper than the answer in hand can replace it, so the
// composition analyses no candidate costing as much (its cost ceiling); any
// valid part replaces an answer that is not valid.
void right_angle_pass(const Problem& scene, const Environment& env, int li, const LoadOutcome& start,
                      const GenerateOptions& options, GenerateProgress* progress, LoadSearch& s) {
  if (!options.right_angle_pass || !scene.manufacturing.admits_right_angle_pass() || !s.finished ||
      cancel_requested(progress))
    return;
  LoadOutcome& best = s.answer;
  Problem square = scene;
  square.manufacturing.restrict_to_right_angles();
  GenerateOptions bounded = options;
  if (best.ok) bounded.compose.cost_ceiling = best.part.cost;
  LoadOutcome pass = start;  // press_fallback as the round set it (search_load)
  SegmentLibrary pool;
  if (progress) progress->right_angle_pass = true;
  s.finished = search_pass(square, env, li, bounded, /*web_roots=*/false, progress, pass, pool);
  if (progress) progress->right_angle_pass = false;
  pass.web_pass_tried = best.web_pass_tried;
  pass.flat_pass_tried = best.flat_pass_tried;
  pass.seed_retries_tried = best.seed_retries_tried;
  pass.right_angle_pass_tried = best.right_angle_pass_tried = true;
  pass.right_angle_pass = true;
  const bool keep = s.finished && pass.ok && (!best.ok || pass.part.cost < best.part.cost);
  if (add_pass(best, std::move(pass), keep)) {
    s.answer_scene = std::move(square);
    s.library = std::move(pool);
  }
}

}  // namespace

LoadSearch search_load(const Environment& env, int li, const LoadOutcome& start, const GenerateOptions& options,
                       SearchRound round, GenerateProgress* progress) {
  Problem scene = env.problem();
  if (round.press_fallback) scene.manufacturing.press_brake_required = false;
  if (round.right_angles) scene.manufacturing.restrict_to_right_angles();  // flat extensions included
  LoadOutcome first = start;
  first.press_fallback = round.press_fallback;
  LoadSearch s = search_passes(scene, env, li, first, options, round.flat_fallback && !round.right_angles, progress);
  if (!round.right_angles) {
    right_angle_pass(scene, env, li, first, options, progress, s);
    return s;
  }
  // The answer's plan, sizing and model use the grammar it was found in.
  if (!s.answer_scene) s.answer_scene = std::move(scene);
  return s;
}

bool keep_press_fallback(LoadSearch& checked, LoadSearch&& fallback, const Problem& scene) {
  LoadOutcome& best = checked.answer;
  Elapsed environment = best.environment_time;
  environment += fallback.answer.environment_time;
  // gauges_tried stays the kept answer's own round's count, which readers take
  // for "made of a thicker gauge" when it is not 0.
  const bool keep = merge_pass(best, std::move(fallback.answer), scene);
  best.environment_time = environment;
  if (keep) {
    checked.answer_scene = std::move(fallback.answer_scene);
    checked.library = std::move(fallback.library);
  }
  checked.finished = fallback.finished;
  return keep;
}

}  // namespace sheetgen
