#include "sheetgen/compose/composition.hpp"
#include "sheetgen/compose/self_rivet.hpp"
#include "sheetgen/compose/stiffening_lip.hpp"

#include <cstdio>
#include <cstdlib>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <chrono>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/plate_mesher.hpp"
#include "sheetgen/part/manufacturing_plan.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

namespace {

std::string key_of(const std::vector<int>& ids) {
  std::string k;
  for (int id : ids) k += std::to_string(id) + ",";
  return k;
}

// A segment with all its ancestors (a subset must be closed under parents).
std::vector<int> closure(const SegmentLibrary& library, int id) {
  std::vector<int> out;
  for (const Segment* s = library.find(id); s; s = s->parent >= 0 ? library.find(s->parent) : nullptr) out.push_back(s->id);
  std::sort(out.begin(), out.end());
  return out;
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
  return v;
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

}  // namespace

Candidate evaluate_part(const Problem& problem, const Environment& env, int load_index, Candidate c, double element_size,
                        double bend_cost, ShellSolver* solver, double cost_bound) {
  c.geometry_ok = false;
  c.analysed = false;
  c.over_cost_bound = false;
  c.fem_error.clear();
  c.reason = ValidityReason::Ok;
  c.message.clear();
  c.bends = c.part.bend_count();
  const RealisedPart realised = realise(c.part);
  ValidityOptions vo;
  vo.stop_at_first = true;
  const ValidityReport report = check_validity(c.part, realised, env, vo);
  if (!report.valid()) {
    c.reason = report.first_reason();
    c.message = report.summary();
    return c;
  }
  const SheetSpec spec = SheetSpec::from(problem);
  const ManufacturingPlan plan = plan_manufacturing(c.part, spec);
  c.area = plan.flat.area();
  c.cost = c.area + bend_cost * c.bends;
  if (!plan.ok()) {
    c.reason = plan.status;
    c.message = plan.message;
    return c;
  }
  c.geometry_ok = true;
  if (c.cost >= cost_bound) {
    c.over_cost_bound = true;
    return c;
  }
  analyse_candidate(problem, load_index, c, element_size, solver);
  return c;
}

void analyse_candidate(const Problem& problem, int load_index, Candidate& c, double element_size, ShellSolver* solver) {
  c.analysed = false;
  c.fem_error.clear();
  try {
    PartModelOptions mo;
    mo.element_size = element_size;
    mo.self_rivets = c.self_rivets;
    c.fem = analyse_part(problem, load_index, plate_geometry(c.part, realise(c.part)), mo, solver);
    c.analysed = true;
  } catch (const FemError& e) {
    c.fem_error = e.what();
  }
}

Candidate evaluate_candidate(const Problem& problem, const Environment& env, int load_index, const Part& base,
                             const SegmentLibrary& library, std::vector<int> segments, double element_size,
                             double bend_cost, ShellSolver* solver, double cost_bound) {
  Candidate c;
  std::sort(segments.begin(), segments.end());
  c.segments = segments;
  c.part = assemble_part(base, library, segments);
  return evaluate_part(problem, env, load_index, std::move(c), element_size, bend_cost, solver, cost_bound);
}

namespace {

// Gusset variants of a part that is strong but not stiff enough (Sec. 5.2):
// for the most promising visible edge pairs, the lightest gussets that fit.
std::vector<Candidate> self_rivet_variants(const Problem& problem, const Candidate& c) {
  std::vector<Candidate> out;
  auto with_plan = [](Candidate v, const SelfRivetPlan& plan) {
    v.part = plan.part;
    for (size_t r = 0; r < plan.rivets_a.size(); ++r)
      v.self_rivets.push_back(SelfRivetTie{plan.tab_a, plan.tab_b, plan.rivets_a[r], plan.rivets_b[r]});
    return v;
  };
  // A pair whose edge is too short for a gusset gets one on the tab lengthened.
  auto plans_for = [&](const Part& part, const RealisedPart& realised, const VisiblePair& pair) {
    auto plans = gusset_plans(part, realised, pair, problem);
    return plans.empty() ? lengthened_gusset_plans(part, realised, pair, problem) : plans;
  };
  const RealisedPart rp = realise(c.part);
  static const bool dbg = std::getenv("SHEETGEN_COMPOSE_DEBUG") != nullptr;
  for (const VisiblePair& pair : visible_edge_pairs(c.part, rp, problem.material.thickness)) {
    const auto plans = plans_for(c.part, rp, pair);
    if (dbg)  // a visible pair without a plan: its edges are too short or too obtuse for a gusset
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
      const auto plans = plans_for(first.part, rp2, pair);
      if (plans.empty()) continue;
      out.push_back(with_plan(first, plans.front()));
      break;
    }
  }
  return out;
}

}  // namespace

ComposeResult compose_part(const Problem& problem, const Environment& env, int load_index, const Part& base,
                           const SegmentLibrary& library, const ComposeOptions& options, ComposeProgress* progress) {
  const auto start = std::chrono::steady_clock::now();
  ComposeResult result;
  const int n = library.size();
  // The search mesh: coarser than the final one, the answer is re-checked at the default size.
  double search_h = options.search_element_size;
  if (!(search_h > 0)) search_h = 0;  // resolved per candidate below from the part's own default

  std::map<std::string, int> seen;  // subset key -> index in `all`
  std::vector<Candidate> all;
  const int threads = options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  tbb::task_arena arena(threads);
  tbb::enumerable_thread_specific<ShellSolver> solvers;

  // The cost bound (ComposeOptions::kept_valid): the cost of the kept_valid-th
  // cheapest valid part so far. Fixed for each parallel batch, so the result
  // does not depend on the thread count.
  auto cost_bound = [&] {
    const size_t k = static_cast<size_t>(std::max(0, options.kept_valid));
    if (k == 0 || result.valid.size() < k) return std::numeric_limits<double>::infinity();
    std::vector<double> costs;
    for (const Candidate& v : result.valid) costs.push_back(v.cost);
    std::nth_element(costs.begin(), costs.begin() + (k - 1), costs.end());
    return costs[k - 1];
  };

  auto default_size = [&](const Part& part) {
    std::vector<std::vector<Vec3>> polys;
    for (const auto& t : realise(part).tabs) polys.push_back(t.corners);
    return default_element_size(polys, problem.material.thickness);
  };
  auto search_size = [&](const Part& part) { return search_h > 0 ? search_h : 1.5 * default_size(part); };
  const bool screening = options.screen_element_factor > 0;

  // Screening (docs/pipeline.md "Screening"): which of a batch analysed on the
  // screening mesh are analysed again on the search mesh. Every one valid
  // there (it may be the answer or a fallback), every one the coarse model
  // could not solve, and the screen_keep * B best by the beam's score among
  // those that could still enter the beam (cheaper than the best valid part).
  auto reanalyse = [&](std::vector<Candidate>& batch) {
    std::vector<size_t> again, ranked;
    for (size_t i = 0; i < batch.size(); ++i) {
      const Candidate& c = batch[i];
      if (!c.geometry_ok || c.over_cost_bound) continue;
      ++result.screen_fem_calls;
      if (!c.analysed || c.valid()) again.push_back(i);
      else if (!result.found || c.cost < result.best.cost) ranked.push_back(i);
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [&](size_t a, size_t b) { return beam_score(batch[a], problem) < beam_score(batch[b], problem); });
    const size_t keep = static_cast<size_t>(std::max(0, options.screen_keep)) * static_cast<size_t>(std::max(1, options.beam_width));
    for (size_t r = 0; r < ranked.size(); ++r) {
      if (r < keep) {
        again.push_back(ranked[r]);
      } else {
        batch[ranked[r]].screened_out = true;  // keeps the screening result in fem, but is not analysed
        batch[ranked[r]].analysed = false;
        ++result.screened_out;
      }
    }
    arena.execute([&] {
      tbb::parallel_for(size_t(0), again.size(), [&](size_t k) {
        if (progress && progress->cancel.load()) return;
        Candidate& c = batch[again[k]];
        analyse_candidate(problem, load_index, c, search_size(c.part), &solvers.local());
      });
    });
  };

  auto evaluate = [&](const std::vector<std::vector<int>>& subsets) {
    const double bound = cost_bound();
    std::vector<Candidate> out(subsets.size());
    arena.execute([&] {
      tbb::parallel_for(size_t(0), subsets.size(), [&](size_t i) {
        if (progress && progress->cancel.load()) return;
        // Fault injection for the reliability tests: an exception on a worker
        // thread must reach the caller as an error (TBB rethrows it there).
        static const char* inject = std::getenv("SHEETGEN_INJECT_FAULT");
        if (inject && std::strcmp(inject, "composition") == 0) throw std::runtime_error("injected fault in a composition worker");
        const Part probe = assemble_part(base, library, subsets[i]);
        const double h = screening ? options.screen_element_factor * default_size(probe) : search_size(probe);
        out[i] = evaluate_candidate(problem, env, load_index, base, library, subsets[i], h, options.bend_cost, &solvers.local(),
                                    bound);
        if (progress) ++progress->evaluated;
      });
    });
    if (screening) reanalyse(out);
    std::vector<int> indices;
    for (auto& c : out) {
      result.fem_calls += c.analysed || !c.fem_error.empty();
      result.skipped_by_cost += c.over_cost_bound;
      indices.push_back(static_cast<int>(all.size()));
      seen[key_of(c.segments)] = static_cast<int>(all.size());
      all.push_back(std::move(c));
    }
    return indices;
  };

  auto better_closest = [&](const Candidate& c) {
    const Candidate& b = result.closest;
    if (b.segments.empty()) return true;
    if (c.analysed != b.analysed) return c.analysed;
    if (c.geometry_ok != b.geometry_ok) return c.geometry_ok;
    const double vc = violation(c, problem), vb = violation(b, problem);
    return vc != vb ? vc < vb : c.cost < b.cost;
  };

  // Level 1: every segment with its ancestors.
  std::vector<std::vector<int>> frontier;
  // Web roots (rivet_area < 0) reach no support: they only enter as the
  // ancestors of segments grown from them.
  for (const Segment& s : library.segments()) {
    if (s.rivet_area < 0) continue;
    auto sub = closure(library, s.id);
    if (static_cast<int>(sub.size()) <= options.max_segments && !seen.count(key_of(sub))) {
      seen[key_of(sub)] = -1;
      frontier.push_back(sub);
    }
  }
  for (int level = 1; !frontier.empty() && level <= options.max_segments; ++level) {
    if (progress) progress->level = level;
    const std::vector<int> fresh = evaluate(frontier);
    if (progress && progress->cancel.load()) {
      result.cancelled = true;
      break;
    }
    for (int i : fresh) {
      const Candidate& c = all[i];
      if (c.valid()) result.valid.push_back(c);
      if (c.valid() && (!result.found || c.cost < result.best.cost)) {
        result.found = true;
        result.best = c;
        if (progress) progress->best_cost = c.cost;
      }
      if (!c.valid() && better_closest(c)) result.closest = c;
    }
    // The beam: analysed, not yet valid, still cheaper than the best valid part
    // (adding segments only adds material), ranked by cost times how far off they are.
    std::vector<int> beam;
    for (int i : fresh) {
      const Candidate& c = all[i];
      if (!c.analysed || c.valid()) continue;
      if (result.found && c.cost >= result.best.cost) continue;
      beam.push_back(i);
    }
    std::stable_sort(beam.begin(), beam.end(),
                     [&](int a, int b) { return beam_score(all[a], problem) < beam_score(all[b], problem); });
    if (static_cast<int>(beam.size()) > options.beam_width) beam.resize(options.beam_width);
    static const bool dbg = std::getenv("SHEETGEN_COMPOSE_DEBUG") != nullptr;
    if (dbg) {  // one line per candidate of the level, beam states marked
      for (int i : fresh) {
        const Candidate& c = all[i];
        std::string segs, areas;
        for (int id : c.segments) {
          segs += " " + std::to_string(id);
          const Segment* g = library.find(id);
          areas += " " + std::to_string(g ? g->rivet_area : -9);
        }
        const bool in_beam = std::find(beam.begin(), beam.end(), i) != beam.end();
        std::fprintf(stderr, "[candidate] level %d%s segs [%s ] ra [%s ] %s%s area %.1f cm2 C/Cmax %.3g MS %.3g score %.4g\n", level,
                     in_beam ? " BEAM" : "", segs.c_str(), areas.c_str(), c.geometry_ok ? "ok" : "FAIL ",
                     c.geometry_ok ? "" : c.message.c_str(), c.area * 1e4, c.analysed ? c.fem.compliance / c.fem.compliance_limit : -1.0,
                     c.analysed ? c.fem.margin_of_safety : -9.0, c.analysed ? beam_score(c, problem) : -1.0);
      }
    }

    // Variants of beam candidates (gussets, lips): evaluated in parallel at the
    // search mesh; the valid ones are recorded, none is expanded further.
    // SHEETGEN_COMPOSE_DEBUG=1 (dbg): one stderr line per variant (why it is or is not valid).
    auto evaluate_variants = [&](std::vector<Candidate>& variants, const char* kind, int& counter) {
      const double bound = cost_bound();
      std::vector<Candidate> checked(variants.size());
      arena.execute([&] {
        tbb::parallel_for(size_t(0), variants.size(), [&](size_t k) {
          if (progress && progress->cancel.load()) return;
          const double h = search_size(variants[k].part);
          checked[k] = evaluate_part(problem, env, load_index, variants[k], h, options.bend_cost, &solvers.local(), bound);
          if (progress) ++progress->evaluated;
        });
      });
      for (Candidate& v : checked) {
        if (dbg)
          std::fprintf(stderr, "[%s] level %d: %d tabs, %zu ties, geometry %s%s, C %.4g J (limit %.4g), MS %.3g, area %.1f cm2\n",
                       kind, level, v.part.size(), v.self_rivets.size(), v.geometry_ok ? "ok" : "FAIL ",
                       v.geometry_ok ? "" : v.message.c_str(), v.analysed ? v.fem.compliance : -1.0,
                       v.analysed ? v.fem.compliance_limit : -1.0, v.analysed ? v.fem.margin_of_safety : -1.0, v.area * 1e4);
        result.fem_calls += v.analysed || !v.fem_error.empty();
        result.skipped_by_cost += v.over_cost_bound;
        ++counter;
        if (v.valid()) {
          result.valid.push_back(v);
          if (!result.found || v.cost < result.best.cost) {
            result.found = true;
            result.best = v;
            if (progress) progress->best_cost = v.cost;
          }
        }
      }
    };

    // Self-riveting where the margin of safety passes but compliance does not.
    if (options.self_rivet) {
      std::vector<Candidate> variants;
      for (int i : beam) {
        const Candidate& c = all[i];
        if (!c.fem.strong_enough || c.fem.stiff_enough || !c.self_rivets.empty()) continue;
        for (Candidate& v : self_rivet_variants(problem, c)) variants.push_back(std::move(v));
      }
      evaluate_variants(variants, "self-rivet", result.self_rivet_candidates);
    }

    // Stiffening lips on every beam candidate that misses its limits (our
    // extension, docs/pipeline.md): built in parallel, one variant each.
    if (options.stiffening_lips && !beam.empty()) {
      std::vector<Candidate> lipped(beam.size());
      std::vector<char> made(beam.size(), 0);
      arena.execute([&] {
        tbb::parallel_for(size_t(0), beam.size(), [&](size_t k) {
          if (progress && progress->cancel.load()) return;
          const Candidate& c = all[beam[k]];
          if (!c.analysed || c.valid()) return;
          LipResult lr = add_stiffening_lips(c.part, env, problem);
          if (lr.lips == 0) return;
          lipped[k] = c;
          lipped[k].part = std::move(lr.part);
          made[k] = 1;
        });
      });
      std::vector<Candidate> variants;
      for (size_t k = 0; k < beam.size(); ++k)
        if (made[k]) {
          if (dbg)
            std::fprintf(stderr, "[lips] level %d: before: %d tabs, C %.4g J, MS %.3g, area %.1f cm2\n", level,
                         all[beam[k]].part.size(), all[beam[k]].fem.compliance, all[beam[k]].fem.margin_of_safety,
                         all[beam[k]].area * 1e4);
          variants.push_back(std::move(lipped[k]));
        }
      evaluate_variants(variants, "lips", result.lip_candidates);
    }

    ComposeHistoryRow row;
    row.level = level;
    row.evaluated = static_cast<int>(all.size());
    row.found = result.found;
    if (result.found) {
      row.best_cost = result.best.cost;
      row.best_area = result.best.area;
      row.compliance = result.best.fem.compliance;
      row.margin_of_safety = result.best.fem.margin_of_safety;
    }
    result.history.push_back(row);

    frontier.clear();
    for (int i : beam)
      for (int s = 0; s < n; ++s) {
        const int id = library.segments()[s].id;
        if (library.segments()[s].rivet_area < 0) continue;
        if (std::binary_search(all[i].segments.begin(), all[i].segments.end(), id)) continue;
        auto sub = unite(all[i].segments, closure(library, id));
        if (static_cast<int>(sub.size()) > options.max_segments) continue;
        const std::string k = key_of(sub);
        if (seen.count(k)) continue;
        seen[k] = -1;
        frontier.push_back(sub);
      }
  }
  result.candidates = static_cast<int>(all.size());
  std::stable_sort(result.valid.begin(), result.valid.end(), [](const Candidate& a, const Candidate& b) { return a.cost < b.cost; });

  if (!result.found) {
    const Candidate& c = result.closest;
    std::ostringstream why;
    const bool connects = std::any_of(library.segments().begin(), library.segments().end(),
                                      [](const Segment& s) { return s.rivet_area >= 0; });
    if (!connects) {
      why << "no segment reached a rivet area (discovery found no connection from the load to any rivet area)";
    } else if (c.segments.empty()) {
      why << "no candidate could be evaluated";
    } else if (!c.geometry_ok) {
      why << "every combination of the " << n << " segments found is geometrically invalid; e.g. segments {"
          << key_of(c.segments) << "}: " << c.message;
    } else if (!c.analysed) {
      why << "the structural model failed: " << c.fem_error;
    } else {
      why << "the best candidate (" << c.segments.size() << " segments, " << c.area * 1e4 << " cm^2, " << c.bends
          << " bends)";
      if (!c.fem.stiff_enough)
        why << " has compliance " << c.fem.compliance << " J over the limit " << c.fem.compliance_limit << " J by "
            << percent(c.fem.compliance / c.fem.compliance_limit - 1.0) << " (deflection along the force " << c.fem.deflection_along_force * 1e3 << " mm)";
      if (!c.fem.strong_enough)
        why << (c.fem.stiff_enough ? "" : " and") << " has margin of safety " << c.fem.margin_of_safety << " below the required "
            << problem.requirements.min_margin_of_safety << " (max von Mises " << c.fem.max_von_mises * 1e-6 << " MPa)";
    }
    result.reason = why.str();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace sheetgen
