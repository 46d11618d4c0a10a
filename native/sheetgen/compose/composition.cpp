#include "sheetgen/compose/composition.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "sheetgen/compose/self_rivet.hpp"
#include "sheetgen/compose/stiffening_lip.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

namespace {

std::string key_of(const std::vector<int>& ids) {
  std::string k;
  for (int id : ids) k += std::to_string(id) + ",";
  return k;
}

std::vector<int> unite(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// How far a stiff-and-strong requirement is missed (0 = met).
double violation(const Candidate& c, const Problem& problem) {
  if (!c.analysed) return std::numeric_limits<double>::infinity();
  double v = std::max(0.0, c.fem.compliance / c.fem.compliance_limit - 1.0);
  v += std::max(0.0, problem.requirements.min_margin_of_safety - c.fem.margin_of_safety);
  // The eigen checks, when they ran: how far below the floors, relative.
  const EnvelopeResult& env = c.fem.envelope;
  if (env.eigen_checked && !c.fem.stable_enough)
    v += std::max(0.0, problem.requirements.design_buckling_factor() / env.buckling_factor - 1.0);
  if (env.eigen_checked && !c.fem.frequency_ok && !env.frequencies_hz.empty())
    v += std::max(0.0, *problem.requirements.design_frequency_hz() / env.frequencies_hz.front() - 1.0);
  return v;
}

// The name of the case that governs stiffness (or strength).
std::string governing_name(const StructuralResult& fem, bool stiffness) {
  const int k = stiffness ? fem.envelope.governing_stiffness : fem.envelope.governing_strength;
  return k >= 0 ? fem.envelope.cases[k].name : std::string("design");
}

// The failed eigen checks of an analysed candidate, as a clause of a sentence ("" when none).
std::string eigen_failure(const StructuralResult& fem, const Requirements& req) {
  std::ostringstream why;
  const EnvelopeResult& env = fem.envelope;
  // The eigen checks run only on parts that pass every static case, so these
  // are the candidate's only failures.
  if (!fem.stable_enough)
    why << " buckles in case '" << env.cases[env.governing_buckling].name << "' at " << env.buckling_factor
        << " times its load, below the " << req.design_buckling_factor() << " the search holds it to (required "
        << req.min_buckling_factor << " with the model's reserve)";
  if (!fem.frequency_ok && !env.frequencies_hz.empty())
    why << (fem.stable_enough ? "" : " and") << " has its first natural frequency at " << env.frequencies_hz.front()
        << " Hz, below the " << *req.design_frequency_hz() << " Hz the search holds it to (floor "
        << *req.min_frequency_hz << " Hz with the model's reserve)";
  return why.str();
}

// The beam's rank: cost times how far off the limits, squared (lower is better).
double beam_score(const Candidate& c, const Problem& problem) {
  return c.cost * std::pow(1.0 + violation(c, problem), 2);
}

std::string percent(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x * 100 << " %";
  return s.str();
}

// SHEETGEN_COMPOSE_DEBUG=1: one stderr line per candidate, variant and visible pair.
bool debug_on() {
  static const bool on = std::getenv("SHEETGEN_COMPOSE_DEBUG") != nullptr;
  return on;
}

// A candidate with one gusset pair added: its part and its rivet ties.
Candidate with_plan(Candidate v, const SelfRivetPlan& plan) {
  v.part = plan.part;
  for (size_t r = 0; r < plan.rivets_a.size(); ++r)
    v.self_rivets.push_back(SelfRivetTie{plan.tab_a, plan.tab_b, plan.rivets_a[r], plan.rivets_b[r]});
  return v;
}

// The gussets of a pair; a pair whose edge is too short for a gusset gets one
// on the tab lengthened.
std::vector<SelfRivetPlan> plans_for(const Part& part, const RealisedPart& realised, const VisiblePair& pair,
                                     const Problem& problem) {
  auto plans = gusset_plans(part, realised, pair, problem);
  return plans.empty() ? lengthened_gusset_plans(part, realised, pair, problem) : plans;
}

// Gusset variants of a part that is strong but not stiff enough (Sec. 5.2):
// for the most promising visible edge pairs, the lightest gussets that fit.
std::vector<Candidate> self_rivet_variants(const Problem& problem, const Candidate& c) {
  std::vector<Candidate> out;
  const RealisedPart rp = realise(c.part);
  for (const VisiblePair& pair : visible_edge_pairs(c.part, rp, problem.material.thickness)) {
    const auto plans = plans_for(c.part, rp, pair, problem);
    if (debug_on())  // a visible pair without a plan: its edges are too short or too obtuse for a gusset
      std::fprintf(stderr, "[self-rivet] pair tabs %d/%d edges %d/%d, gap %.1f mm, tree distance %d: %zu plans\n", pair.a.tab,
                   pair.b.tab, pair.a.edge, pair.b.edge, pair.gap * 1e3, pair.tree_distance, plans.size());
    for (size_t k = 0; k < plans.size() && k < 2; ++k) out.push_back(with_plan(c, plans[k]));
  }
  // One gusset pair often stiffens one corner of a bend only (a leg has two
  // sides): also the lightest single variant with the lightest gusset of the
  // first pair still visible on it (riveted tabs are no longer free).
  if (!out.empty()) {
    const Candidate& first = out.front();
    const RealisedPart rp2 = realise(first.part);
    for (const VisiblePair& pair : visible_edge_pairs(first.part, rp2, problem.material.thickness)) {
      const auto plans = plans_for(first.part, rp2, pair, problem);
      if (plans.empty()) continue;
      out.push_back(with_plan(first, plans.front()));
      break;
    }
  }
  return out;
}

// The state of one compose_part() call: every candidate evaluated so far (the
// beam holds indices into it), the subsets already seen, the answer so far,
// and the worker arena with one FEM solver per thread. run() goes level by
// level: evaluate the frontier, keep the B best as the beam, try their
// variants (gussets, lips), grow the beam by one segment.
class BeamSearch {
 public:
  BeamSearch(const Problem& problem, const Environment& env, int load_index, const Part& base, const SegmentLibrary& library,
             const ComposeOptions& options, ComposeProgress* progress)
      : problem_(problem), env_(env), load_index_(load_index), base_(base), library_(library), options_(options),
        progress_(progress), n_(library.size()),
        arena_(options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency()) {
    // The search mesh: coarser than the final one, the answer is re-checked at
    // the default size. <= 0: resolved per candidate from the part's own default.
    search_h_ = options.search_element_size;
    if (!(search_h_ > 0)) search_h_ = 0;
  }

  ComposeResult run();

 private:
  bool cancel_requested() const { return progress_ && progress_->cancel.load(); }
  double cost_bound() const;
  double default_size(const Part& part) const;
  double search_size(const Part& part) const { return search_h_ > 0 ? search_h_ : 1.5 * default_size(part); }
  std::vector<std::vector<int>> first_level();
  std::vector<int> evaluate(const std::vector<std::vector<int>>& subsets);
  void reanalyse(std::vector<Candidate>& batch);
  void record_valid(const Candidate& c);
  void record(const std::vector<int>& fresh);
  bool better_closest(const Candidate& c) const;
  std::vector<int> select_beam(const std::vector<int>& fresh) const;
  void print_level(int level, const std::vector<int>& fresh, const std::vector<int>& beam) const;
  void evaluate_variants(int level, std::vector<Candidate>& variants, const char* kind, int& counter);
  void try_self_rivets(int level, const std::vector<int>& beam);
  void try_lips(int level, const std::vector<int>& beam);
  void add_history_row(int level);
  std::vector<std::vector<int>> expand(const std::vector<int>& beam);
  std::string failure_reason() const;

  const Problem& problem_;
  const Environment& env_;
  const int load_index_;
  const Part& base_;
  const SegmentLibrary& library_;
  const ComposeOptions& options_;
  ComposeProgress* const progress_;
  const int n_;                     // segments in the library
  double search_h_ = 0;             // m, ComposeOptions::search_element_size, 0 when per part
  const bool screening_ = options_.screen_element_factor > 0;
  ComposeResult result_;
  std::map<std::string, int> seen_;  // subset key -> index in `all_` (-1: on the frontier)
  std::vector<Candidate> all_;
  tbb::task_arena arena_;
  tbb::enumerable_thread_specific<ShellSolver> solvers_;
};

// The cost bound (ComposeOptions::kept_valid): the cost of the kept_valid-th
// cheapest valid part so far, or the options' ceiling when that is lower.
// Fixed for each parallel batch, so the result does not depend on the thread
// count.
double BeamSearch::cost_bound() const {
  const size_t k = static_cast<size_t>(std::max(0, options_.kept_valid));
  if (k == 0 || result_.valid.size() < k) return options_.cost_ceiling;
  std::vector<double> costs;
  for (const Candidate& v : result_.valid) costs.push_back(v.cost);
  std::nth_element(costs.begin(), costs.begin() + (k - 1), costs.end());
  return std::min(costs[k - 1], options_.cost_ceiling);
}

double BeamSearch::default_size(const Part& part) const {
  return part_default_element_size(part, problem_.material.thickness);
}

// Level 1: every segment with its ancestors. Web roots (rivet_area < 0) reach
// no support: they only enter as the ancestors of segments grown from them.
std::vector<std::vector<int>> BeamSearch::first_level() {
  std::vector<std::vector<int>> frontier;
  for (const Segment& s : library_.segments()) {
    if (s.rivet_area < 0) continue;
    auto sub = segment_closure(library_, s.id);
    if (static_cast<int>(sub.size()) <= options_.max_segments && !seen_.count(key_of(sub))) {
      seen_[key_of(sub)] = -1;
      frontier.push_back(sub);
    }
  }
  return frontier;
}

// Evaluates a level's subsets in parallel (on the screening mesh when
// screening, else the search mesh) and appends them to all_; their indices.
std::vector<int> BeamSearch::evaluate(const std::vector<std::vector<int>>& subsets) {
  const double bound = cost_bound();
  std::vector<Candidate> out(subsets.size());
  arena_.execute([&] {
    tbb::parallel_for(size_t(0), subsets.size(), [&](size_t i) {
      if (cancel_requested()) return;
      // Fault injection for the reliability tests: an exception on a worker
      // thread must reach the caller as an error (TBB rethrows it there).
      static const char* inject = std::getenv("SHEETGEN_INJECT_FAULT");
      if (inject && std::strcmp(inject, "composition") == 0) throw std::runtime_error("injected fault in a composition worker");
      const Part probe = assemble_part(base_, library_, subsets[i]);
      const double h = screening_ ? options_.screen_element_factor * default_size(probe) : search_size(probe);
      out[i] = evaluate_candidate(problem_, env_, load_index_, base_, library_, subsets[i], h,
                                  &solvers_.local(), bound, options_.analyses);
      if (progress_) ++progress_->evaluated;
    });
  });
  if (screening_) reanalyse(out);
  std::vector<int> indices;
  for (auto& c : out) {
    result_.fem_calls += c.analysed || !c.fem_error.empty();
    result_.skipped_by_cost += c.over_cost_bound;
    result_.press_rejected += c.reason == ValidityReason::PressBrake;
    indices.push_back(static_cast<int>(all_.size()));
    seen_[key_of(c.segments)] = static_cast<int>(all_.size());
    all_.push_back(std::move(c));
  }
  return indices;
}

// Screening (docs/pipeline.md "Screening"): which of a batch analysed on the
// screening mesh are analysed again on the search mesh. Every one valid
// there (it may be the answer or a fallback), every one the coarse model
// could not solve, and the screen_keep * B best by the beam's score among
// those that could still enter the beam (cheaper than the best valid part).
void BeamSearch::reanalyse(std::vector<Candidate>& batch) {
  std::vector<size_t> again, ranked;
  for (size_t i = 0; i < batch.size(); ++i) {
    const Candidate& c = batch[i];
    if (!c.geometry_ok || c.over_cost_bound) continue;
    ++result_.screen_fem_calls;
    if (!c.analysed || c.valid()) again.push_back(i);
    else if (!result_.found || c.cost < result_.best.cost) ranked.push_back(i);
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [&](size_t a, size_t b) { return beam_score(batch[a], problem_) < beam_score(batch[b], problem_); });
  const size_t keep = static_cast<size_t>(std::max(0, options_.screen_keep)) * static_cast<size_t>(std::max(1, options_.beam_width));
  for (size_t r = 0; r < ranked.size(); ++r) {
    if (r < keep) {
      again.push_back(ranked[r]);
    } else {
      batch[ranked[r]].screened_out = true;  // keeps the screening result in fem, but is not analysed
      batch[ranked[r]].analysed = false;
      ++result_.screened_out;
    }
  }
  arena_.execute([&] {
    tbb::parallel_for(size_t(0), again.size(), [&](size_t k) {
      if (cancel_requested()) return;
      Candidate& c = batch[again[k]];
      analyse_candidate(problem_, load_index_, c, search_size(c.part), &solvers_.local(), options_.analyses);
    });
  });
}

// A valid candidate: a fallback for the final check, the answer when cheapest.
void BeamSearch::record_valid(const Candidate& c) {
  result_.valid.push_back(c);
  if (!result_.found || c.cost < result_.best.cost) {
    result_.found = true;
    result_.best = c;
    if (progress_) progress_->best_cost = c.cost;
  }
}

// A level's candidates: the valid ones recorded, the others kept when nearer to valid.
void BeamSearch::record(const std::vector<int>& fresh) {
  for (int i : fresh) {
    const Candidate& c = all_[i];
    if (c.valid()) record_valid(c);
    else if (better_closest(c)) result_.closest = c;
  }
}

bool BeamSearch::better_closest(const Candidate& c) const {
  const Candidate& b = result_.closest;
  if (b.segments.empty()) return true;
  if (c.analysed != b.analysed) return c.analysed;
  if (c.geometry_ok != b.geometry_ok) return c.geometry_ok;
  const double vc = violation(c, problem_), vb = violation(b, problem_);
  return vc != vb ? vc < vb : c.cost < b.cost;
}

// The beam: analysed, not yet valid, still cheaper than the best valid part
// (adding segments only adds material), ranked by cost times how far off they
// are; the B best.
std::vector<int> BeamSearch::select_beam(const std::vector<int>& fresh) const {
  std::vector<int> beam;
  for (int i : fresh) {
    const Candidate& c = all_[i];
    if (!c.analysed || c.valid()) continue;
    if (result_.found && c.cost >= result_.best.cost) continue;
    beam.push_back(i);
  }
  std::stable_sort(beam.begin(), beam.end(),
                   [&](int a, int b) { return beam_score(all_[a], problem_) < beam_score(all_[b], problem_); });
  if (static_cast<int>(beam.size()) > options_.beam_width) beam.resize(options_.beam_width);
  return beam;
}

// Debug: one line per candidate of the level, beam states marked.
void BeamSearch::print_level(int level, const std::vector<int>& fresh, const std::vector<int>& beam) const {
  for (int i : fresh) {
    const Candidate& c = all_[i];
    std::string segs, areas;
    for (int id : c.segments) {
      segs += " " + std::to_string(id);
      const Segment* g = library_.find(id);
      areas += " " + std::to_string(g ? g->rivet_area : -9);
    }
    const bool in_beam = std::find(beam.begin(), beam.end(), i) != beam.end();
    std::fprintf(stderr,
                 "[candidate] level %d%s segs [%s ] ra [%s ] %s%s area %.1f cm2 C/Cmax %.3g MS %.3g score %.4g cost %.4g%s%s\n",
                 level,
                 in_beam ? " BEAM" : "", segs.c_str(), areas.c_str(), c.geometry_ok ? "ok" : "FAIL ",
                 c.geometry_ok ? "" : c.message.c_str(), c.area * 1e4, c.analysed ? c.fem.compliance / c.fem.compliance_limit : -1.0,
                 c.analysed ? c.fem.margin_of_safety : -9.0, c.analysed ? beam_score(c, problem_) : -1.0, c.cost,
                 c.over_cost_bound ? " OVER-COST-BOUND" : "", c.screened_out ? " SCREENED-OUT" : "");
  }
}

// Variants of beam candidates (gussets, lips): evaluated in parallel at the
// search mesh; the valid ones are recorded, none is expanded further.
// `counter` counts them (ComposeResult::self_rivet_candidates or lip_candidates).
void BeamSearch::evaluate_variants(int level, std::vector<Candidate>& variants, const char* kind, int& counter) {
  const double bound = cost_bound();
  std::vector<Candidate> checked(variants.size());
  arena_.execute([&] {
    tbb::parallel_for(size_t(0), variants.size(), [&](size_t k) {
      if (cancel_requested()) return;
      const double h = search_size(variants[k].part);
      checked[k] = evaluate_part(problem_, env_, load_index_, variants[k], h, &solvers_.local(), bound,
                                 options_.analyses);
      if (progress_) ++progress_->evaluated;
    });
  });
  for (Candidate& v : checked) {
    if (debug_on())  // why the variant is or is not valid
      std::fprintf(stderr, "[%s] level %d: %d tabs, %zu ties, geometry %s%s, C %.4g J (limit %.4g), MS %.3g, area %.1f cm2\n",
                   kind, level, v.part.size(), v.self_rivets.size(), v.geometry_ok ? "ok" : "FAIL ",
                   v.geometry_ok ? "" : v.message.c_str(), v.analysed ? v.fem.compliance : -1.0,
                   v.analysed ? v.fem.compliance_limit : -1.0, v.analysed ? v.fem.margin_of_safety : -1.0, v.area * 1e4);
    result_.fem_calls += v.analysed || !v.fem_error.empty();
    result_.skipped_by_cost += v.over_cost_bound;
    result_.press_rejected += v.reason == ValidityReason::PressBrake;
    ++counter;
    if (v.valid()) record_valid(v);
  }
}

// Self-riveting where the margin of safety passes but compliance or buckling
// does not: a gusset stiffens and braces the sheet.
void BeamSearch::try_self_rivets(int level, const std::vector<int>& beam) {
  std::vector<Candidate> variants;
  for (int i : beam) {
    const Candidate& c = all_[i];
    const bool stiff_and_stable = c.fem.stiff_enough && c.fem.stable_enough;
    if (!c.fem.strong_enough || stiff_and_stable || !c.self_rivets.empty()) continue;
    for (Candidate& v : self_rivet_variants(problem_, c)) variants.push_back(std::move(v));
  }
  evaluate_variants(level, variants, "self-rivet", result_.self_rivet_candidates);
}

// Stiffening lips on every beam candidate that misses its limits (our
// extension, docs/pipeline.md): built in parallel, one variant each.
void BeamSearch::try_lips(int level, const std::vector<int>& beam) {
  std::vector<Candidate> lipped(beam.size());
  std::vector<char> made(beam.size(), 0);
  arena_.execute([&] {
    tbb::parallel_for(size_t(0), beam.size(), [&](size_t k) {
      if (cancel_requested()) return;
      const Candidate& c = all_[beam[k]];
      if (!c.analysed || c.valid()) return;
      LipResult lr = add_stiffening_lips(c.part, env_, problem_);
      if (lr.lips == 0) return;
      lipped[k] = c;
      lipped[k].part = std::move(lr.part);
      made[k] = 1;
    });
  });
  std::vector<Candidate> variants;
  for (size_t k = 0; k < beam.size(); ++k)
    if (made[k]) {
      const Candidate& before = all_[beam[k]];
      if (debug_on())
        std::fprintf(stderr, "[lips] level %d: before: %d tabs, C %.4g J, MS %.3g, area %.1f cm2\n", level, before.part.size(),
                     before.fem.compliance, before.fem.margin_of_safety, before.area * 1e4);
      variants.push_back(std::move(lipped[k]));
    }
  evaluate_variants(level, variants, "lips", result_.lip_candidates);
}

// history.csv's row of the level: candidates so far and the best part so far.
void BeamSearch::add_history_row(int level) {
  ComposeHistoryRow row;
  row.level = level;
  row.evaluated = static_cast<int>(all_.size());
  row.found = result_.found;
  if (result_.found) {
    row.best_cost = result_.best.cost;
    row.best_area = result_.best.area;
    row.compliance = result_.best.fem.compliance;
    row.margin_of_safety = result_.best.fem.margin_of_safety;
  }
  result_.history.push_back(row);
}

// The next level: each beam state with one more segment (and its ancestors),
// subsets not seen before and within max_segments.
std::vector<std::vector<int>> BeamSearch::expand(const std::vector<int>& beam) {
  std::vector<std::vector<int>> frontier;
  for (int i : beam)
    for (int s = 0; s < n_; ++s) {
      const int id = library_.segments()[s].id;
      if (library_.segments()[s].rivet_area < 0) continue;
      if (std::binary_search(all_[i].segments.begin(), all_[i].segments.end(), id)) continue;
      auto sub = unite(all_[i].segments, segment_closure(library_, id));
      if (static_cast<int>(sub.size()) > options_.max_segments) continue;
      const std::string k = key_of(sub);
      if (seen_.count(k)) continue;
      seen_[k] = -1;
      frontier.push_back(sub);
    }
  return frontier;
}

// Why no valid part was found: which constraint the closest candidate missed, by how much.
std::string BeamSearch::failure_reason() const {
  const Candidate& c = result_.closest;
  std::ostringstream why;
  const bool connects = std::any_of(library_.segments().begin(), library_.segments().end(),
                                    [](const Segment& s) { return s.rivet_area >= 0; });
  if (!connects) {
    why << "no segment reached a rivet area (discovery found no connection from the load to any rivet area)";
  } else if (c.segments.empty()) {
    why << "no candidate could be evaluated";
  } else if (!c.geometry_ok) {
    why << "every combination of the " << n_ << " segments found is geometrically invalid; e.g. segments {"
        << key_of(c.segments) << "}: " << c.message;
  } else if (!c.analysed) {
    why << "the structural model failed: " << c.fem_error;
  } else {
    why << "the best candidate (" << c.segments.size() << " segments, " << c.area * 1e4 << " cm^2, " << c.bends
        << " bends)";
    if (!c.fem.stiff_enough)
      why << " has compliance " << c.fem.compliance << " J in case '" << governing_name(c.fem, true) << "' over the limit " << c.fem.compliance_limit << " J by "
          << percent(c.fem.compliance / c.fem.compliance_limit - 1.0) << " (deflection along the force " << c.fem.deflection_along_force * 1e3 << " mm)";
    if (!c.fem.strong_enough)
      why << (c.fem.stiff_enough ? "" : " and") << " has margin of safety " << c.fem.margin_of_safety << " below the required "
          << problem_.requirements.min_margin_of_safety << " (max von Mises " << c.fem.max_von_mises * 1e-6 << " MPa)";
    why << eigen_failure(c.fem, problem_.requirements);
  }
  return why.str();
}

ComposeResult BeamSearch::run() {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::vector<int>> frontier = first_level();
  for (int level = 1; !frontier.empty() && level <= options_.max_segments; ++level) {
    if (progress_) progress_->level = level;
    const std::vector<int> fresh = evaluate(frontier);
    if (cancel_requested()) {
      result_.cancelled = true;
      break;
    }
    record(fresh);
    const std::vector<int> beam = select_beam(fresh);
    if (debug_on()) print_level(level, fresh, beam);
    if (options_.self_rivet) try_self_rivets(level, beam);
    if (options_.stiffening_lips && !beam.empty()) try_lips(level, beam);
    add_history_row(level);
    frontier = expand(beam);
  }
  result_.candidates = static_cast<int>(all_.size());
  std::stable_sort(result_.valid.begin(), result_.valid.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });
  if (!result_.found) result_.reason = failure_reason();
  result_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return std::move(result_);
}

}  // namespace

ComposeResult compose_part(const Problem& problem, const Environment& env, int load_index, const Part& base,
                           const SegmentLibrary& library, const ComposeOptions& options, ComposeProgress* progress) {
  return BeamSearch(problem, env, load_index, base, library, options, progress).run();
}

}  // namespace sheetgen
