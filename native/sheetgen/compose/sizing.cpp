#include "sheetgen/compose/sizing.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

bool narrow_tab(Part& target, int tab, double cut_start, double cut_end, double min_width) {
  const RealisedPart before = realise(target);
  Part part = target;
  TabParameters& p = part.tabs[tab].params;
  if (p.w - cut_start - cut_end < min_width - 1e-12) return false;
  p.d += cut_start;
  p.w -= cut_start + cut_end;
  // Children come after their parents (Part's invariant), so one pass re-hangs
  // every descendant of the narrowed tab on its parent's new edge.
  std::vector<char> moved(part.size(), 0);
  moved[tab] = 1;
  for (int c = tab + 1; c < part.size(); ++c) {
    Tab& t = part.tabs[c];
    if (t.parent < 0 || !moved[t.parent]) continue;
    moved[c] = 1;
    const RealisedPart now = realise(part);
    const auto& pc = now.tabs[t.parent].corners;
    const Vec3 a = pc[t.parent_edge], b = pc[(t.parent_edge + 1) % pc.size()];
    const double length = (b - a).norm();
    const double start = (before.tabs[c].origin - a).dot((b - a) / length);
    const double lo = std::max(0.0, start), hi = std::min(length, start + t.params.w);
    if (hi - lo < min_width - 1e-12) return false;
    t.params.d = lo;
    t.params.w = hi - lo;
  }
  target = std::move(part);
  return true;
}

namespace {

// A tab sizing may narrow: not the base, not a rivet flange (it follows its
// parent), not a gusset (parts with gussets are not sized at all: size_part).
bool sizable(const Part& part, int tab) {
  const Tab& t = part.tabs[tab];
  return tab > 0 && t.rivet_area < 0 && t.riveted_to < 0;
}

struct Trials {
  const Problem& problem;
  const Environment& env;
  int load_index;
  const SizingOptions& options;
  tbb::task_arena& arena;
  int evaluated = 0;

  // The three placements of one cut (centred, at the start, at the end); the
  // first valid one in that order that is cheaper than `current`, if any. They
  // are analysed in waves of as many as the arena has threads, and a wave
  // that gives the answer ends the search: the third placement of a cut whose
  // first or second passes is never analysed on two threads (before, it ran
  // alone on one thread while the other waited). The same answer for any
  // number of threads. `evaluated` counts every placement that can be cut,
  // analysed or not, so the trial budget (max_trials) ends the cuts where it
  // did when all three were analysed.
  std::optional<Candidate> first_cheaper(const Candidate& current, int tab, double cut) {
    const double min_w = problem.manufacturing.min_tab_width;
    const std::array<std::array<double, 2>, 3> cuts{{{cut / 2, cut / 2}, {cut, 0.0}, {0.0, cut}}};
    std::array<std::optional<Candidate>, 3> trial;
    for (int k = 0; k < 3; ++k) {
      Candidate t = current;
      if (narrow_tab(t.part, tab, cuts[k][0], cuts[k][1], min_w)) trial[k] = std::move(t);
      evaluated += trial[k].has_value();
    }
    const int wave = std::max(1, arena.max_concurrency());
    for (int first = 0; first < 3; first += wave) {
      const int last = std::min(3, first + wave);
      arena.execute([&] {
        tbb::parallel_for(first, last, [&](int k) {
          if (!trial[k]) return;
          const double h = options.trial_element_factor * part_default_element_size(trial[k]->part, problem.material.thickness);
          trial[k] = evaluate_part(problem, env, load_index, std::move(*trial[k]), h, nullptr, current.cost);
        });
      });
      for (int k = first; k < last; ++k)
        if (trial[k] && trial[k]->valid() && trial[k]->cost < current.cost) return std::move(trial[k]);
    }
    return std::nullopt;
  }
};

}  // namespace

SizingResult size_part(const Problem& problem, const Environment& env, int load_index, const Candidate& answer,
                       const SizingOptions& options) {
  SizingResult r;
  r.part = answer;
  r.cost_before = answer.cost;
  r.area_before = answer.area;
  if (!answer.self_rivets.empty()) return r;
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency());
  Trials trials{problem, env, load_index, options, arena};
  const double min_w = problem.manufacturing.min_tab_width;
  Candidate current = answer;
  // Largest tabs first (w l; ties by index): where the sheet is.
  std::vector<int> order;
  for (int tab = 1; tab < current.part.size(); ++tab)
    if (sizable(current.part, tab)) order.push_back(tab);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    const TabParameters &pa = current.part.tabs[a].params, &pb = current.part.tabs[b].params;
    return pa.w * pa.l > pb.w * pb.l;
  });
  std::vector<Candidate> kept;  // the part after each cut, in order
  for (double share : options.shares)
    for (int tab : order) {
      if (trials.evaluated >= options.max_trials) break;
      const double cut = share * (current.part.tabs[tab].params.w - min_w);
      if (cut < options.min_cut) continue;
      if (auto better = trials.first_cheaper(current, tab, cut)) {
        current = std::move(*better);
        kept.push_back(current);
      }
    }
  r.trials = trials.evaluated;
  // The default mesh is finer than the search mesh, so the last cut may pass
  // on the one and not on the other: step back through the cuts, at most
  // final_checks of them, and keep the first that passes there.
  for (int k = static_cast<int>(kept.size()) - 1; k >= 0 && r.final_checks < options.final_checks; --k) {
    Candidate checked = evaluate_part(problem, env, load_index, kept[k], 0.0);
    ++r.final_checks;
    if (checked.valid()) {
      r.part = std::move(checked);
      r.cuts = k + 1;
      return r;
    }
  }
  r.final_check_failed = !kept.empty();
  return r;
}

}  // namespace sheetgen
