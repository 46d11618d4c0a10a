#include "sheetgen/pipeline/generate.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <thread>

#include "sheetgen/core/cancelled.hpp"
#include "sheetgen/core/geometry.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/fem/rivet_layout.hpp"
#include "sheetgen/part/validity.hpp"
#include "sheetgen/structure/part_model.hpp"

namespace sheetgen {

const char* to_string(Stage s) {
  switch (s) {
    case Stage::Idle: return "idle";
    case Stage::Environment: return "environment";
    case Stage::Discovery: return "discovery";
    case Stage::Composition: return "composition";
    case Stage::Plan: return "manufacturing plan";
    case Stage::Done: return "done";
  }
  return "?";
}

bool GenerateResult::all_ok() const {
  if (cancelled || loads.empty()) return false;
  for (const auto& l : loads)
    if (!l.ok) return false;
  return true;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// A finished part as an obstacle for the loads after it: both faces of the
// sheet (mid-surface +- t/2), so the next part keeps its clearance from the metal.
EnvironmentMesh part_as_obstacle(const std::string& name, const RealisedPart& realised, double thickness) {
  EnvironmentMesh m;
  m.name = "part:" + name;
  m.source = "<generated>";
  for (const auto& tab : realised.tabs) {
    for (double side : {-0.5, 0.5}) {
      const int base = static_cast<int>(m.mesh.vertices.size());
      for (const Vec3& c : tab.corners) m.mesh.vertices.push_back(c + side * thickness * tab.normal);
      for (int k = 1; k + 1 < static_cast<int>(tab.corners.size()); ++k) m.mesh.triangles.push_back({base, base + k, base + k + 1});
    }
  }
  return m;
}

// Watches the caller's cancel flag and forwards it to the stage that runs.
struct CancelRelay {
  GenerateProgress* p;
  std::atomic<bool> done{false};
  std::thread thread;
  explicit CancelRelay(GenerateProgress* progress) : p(progress) {
    if (!p) return;
    thread = std::thread([this] {
      while (!done.load()) {
        if (p->cancel.load()) {
          p->discovery.cancel = true;
          p->compose.cancel = true;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
  }
  ~CancelRelay() {
    done = true;
    if (thread.joinable()) thread.join();
  }
};

// One search for one load: discovery, composition on the search mesh, then the
// final check at the default mesh down the list of valid candidates, cheapest
// first. Fills the search's fields of `out` (answer or closest candidate,
// reason, statistics, history, times); false when it was cancelled.
bool search_pass(const Problem& scene, const Environment& env, int li, const GenerateOptions& options, bool web_roots,
                 GenerateProgress* progress, LoadOutcome& out) {
  out.web_roots = web_roots;
  if (progress) {
    progress->web_roots = web_roots;
    progress->stage = static_cast<int>(Stage::Discovery);
  }
  DiscoveryOptions dopt = DiscoveryOptions::from(scene);
  dopt.web_roots = web_roots;
  auto t0 = std::chrono::steady_clock::now();
  DiscoveryResult found = discover_segments(scene, env, li, dopt, progress ? &progress->discovery : nullptr);
  out.discovery_seconds = seconds_since(t0);
  out.discovery = found.stats;
  out.library_size = found.library.size();
  if (found.cancelled || (progress && progress->cancel.load())) return false;

  if (progress) progress->stage = static_cast<int>(Stage::Composition);
  ComposeOptions copt = options.compose;
  copt.beam_width = scene.search.beam_width;
  copt.threads = scene.search.threads;
  t0 = std::chrono::steady_clock::now();
  ComposeResult composed = compose_part(scene, env, li, found.base, found.library, copt, progress ? &progress->compose : nullptr);
  if (composed.cancelled || (progress && progress->cancel.load())) return false;
  std::string final_reason;
  std::set<std::pair<std::vector<int>, double>> failed;  // (segments, cost) of parts the final check rejected
  auto final_check = [&](const std::vector<Candidate>& valid) {
    for (const Candidate& c : valid) {
      if (failed.count({c.segments, c.cost})) continue;
      const auto tc = std::chrono::steady_clock::now();
      Candidate checked = evaluate_part(scene, env, li, c, 0.0, copt.bend_cost);
      ++out.fem_calls;
      if (std::getenv("SHEETGEN_COMPOSE_DEBUG"))
        std::fprintf(stderr, "[final check] %s%s: %s in %.2f s\n", out.load.c_str(), web_roots ? " (web roots)" : "",
                     checked.valid() ? "valid" : "fails", seconds_since(tc));
      if (checked.valid()) {
        out.part = checked;
        out.ok = true;
        return;
      }
      failed.insert({c.segments, c.cost});
      if (final_reason.empty() && checked.analysed)
        final_reason = "at the default mesh the cheapest part misses its limits (compliance " + std::to_string(checked.fem.compliance) +
                       " J, limit " + std::to_string(checked.fem.compliance_limit) + " J, MS " + std::to_string(checked.fem.margin_of_safety) + ")";
    }
  };
  final_check(composed.valid);
  out.skipped_by_cost = composed.skipped_by_cost;
  out.screen_fem_calls = composed.screen_fem_calls;
  out.screened_out = composed.screened_out;
  // Every kept part failed at the default mesh while the cost bound left dearer
  // ones unanalysed: search again without the bound, which finds exactly the
  // valid parts of an unbounded search (docs/pipeline.md "Cost bound").
  if (!out.ok && composed.skipped_by_cost > 0) {
    ComposeOptions unbounded = copt;
    unbounded.kept_valid = 0;
    ComposeResult again = compose_part(scene, env, li, found.base, found.library, unbounded, progress ? &progress->compose : nullptr);
    if (again.cancelled || (progress && progress->cancel.load())) return false;
    out.fem_calls += composed.fem_calls;
    out.screen_fem_calls += again.screen_fem_calls;
    out.composition_reruns = 1;
    composed = std::move(again);
    final_check(composed.valid);
  }
  out.history = composed.history;
  out.fem_calls += composed.fem_calls;
  out.self_rivet_candidates = composed.self_rivet_candidates;
  out.lip_candidates = composed.lip_candidates;
  out.composition_seconds = seconds_since(t0);
  if (!out.ok) {
    out.part = composed.found ? composed.valid.front() : composed.closest;
    out.reason = composed.found ? final_reason : composed.reason;
  }
  return true;
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
    return std::max(stiff, strong);
  };
  return over(a) < over(b);
}

// A later search of the same load (web roots, flat extensions) against the
// best so far: times and FEM calls count both; the later answer is kept when it
// is valid or nearer to valid. True when it was kept.
bool merge_pass(LoadOutcome& best, LoadOutcome&& pass, const Problem& scene) {
  const double discovery_s = best.discovery_seconds + pass.discovery_seconds;
  const double composition_s = best.composition_seconds + pass.composition_seconds;
  const int fem_calls = best.fem_calls + pass.fem_calls;
  const bool keep = pass.ok || closer(pass.part, best.part, scene);
  if (keep) best = std::move(pass);
  best.discovery_seconds = discovery_s;
  best.composition_seconds = composition_s;
  best.fem_calls = fem_calls;
  return keep;
}

}  // namespace

GenerateResult generate(const Problem& input, const GenerateOptions& options, GenerateProgress* progress) {
  const auto start = std::chrono::steady_clock::now();
  GenerateResult result;
  Problem problem = input;
  if (options.chains) problem.search.chains = *options.chains;
  if (options.iterations) problem.search.iterations = *options.iterations;
  if (options.beam_width) problem.search.beam_width = *options.beam_width;
  if (options.threads) problem.search.threads = *options.threads;
  if (options.seed) problem.search.seed = *options.seed;
  if (options.right_angles) {
    // The expert's practice (paper Sec. 1): every bend 90 deg, no skew. Set as
    // manufacturing limits, so sampling, optimisation and validity all obey it
    // (+-0.5 deg and 1 mrad absorb rounding in the angles that are solved for).
    problem.manufacturing.min_bend_angle = (90.0 - 0.5) * M_PI / 180.0;
    problem.manufacturing.max_bend_angle = (90.0 + 0.5) * M_PI / 180.0;
    problem.manufacturing.max_skew = 1e-3;
  }
  // An expert widens a right-angle bracket's plate by cutting it larger, not by
  // bending it: without flat extensions the right-angle grammar can only turn
  // 90 deg at every tab (docs/grammar.md "Flat extensions").
  if (options.right_angles || options.flat_extensions) problem.manufacturing.flat_extensions = true;
  result.search = problem.search;
  result.right_angles = options.right_angles;
  result.flat_extensions = problem.manufacturing.flat_extensions;
  result.self_rivet = options.compose.self_rivet;
  result.stiffening_lips = options.compose.stiffening_lips;
  result.web_fallback = options.web_fallback;
  result.flat_fallback = options.flat_fallback && !problem.manufacturing.flat_extensions;
  if (progress) progress->loads = static_cast<int>(problem.loads.size());
  CancelRelay relay(progress);
  auto cancelled = [&] { return progress && progress->cancel.load(); };

  // The scene's fields are built once; each load's environment adds the part
  // of the load before it (one small field) to the previous load's.
  std::vector<EnvironmentMesh> new_parts;  // made since `env_ptr` was built
  std::unique_ptr<Environment> env_ptr;
  for (int li = 0; li < static_cast<int>(problem.loads.size()); ++li) {
    const auto load_start = std::chrono::steady_clock::now();
    LoadOutcome out;
    out.load = problem.loads[li].name;
    if (progress) {
      progress->load = li;
      progress->stage = static_cast<int>(Stage::Environment);
    }
    EnvironmentOptions eo;
    if (progress) eo.cancel = &progress->cancel;
    try {
      if (!env_ptr) env_ptr = std::make_unique<Environment>(problem, eo);
      else if (!new_parts.empty()) env_ptr = std::make_unique<Environment>(*env_ptr, new_parts, eo);
      new_parts.clear();
    } catch (const Cancelled&) {
      result.cancelled = true;
      break;
    }
    const Environment& env = *env_ptr;
    const Problem& scene = env.problem();
    out.environment_seconds = seconds_since(load_start);
    if (cancelled()) {
      result.cancelled = true;
      break;
    }

    // A base tab that is not clear (the load sits in or on an obstacle) cannot
    // carry any part: say so instead of searching.
    {
      const Part base = make_base_part(scene.loads[li], li, scene.material.thickness);
      ValidityOptions vo;
      vo.stop_at_first = true;
      const ValidityReport report = check_validity(base, realise(base), env, vo);
      if (env.inside_closed_obstacle(scene.loads[li].center)) {
        out.reason = "load '" + out.load + "' lies inside a closed obstacle of the environment: no part can reach it";
        out.total_seconds = seconds_since(load_start);
        result.loads.push_back(std::move(out));
        continue;
      }
      if (!report.valid()) {
        out.reason = "the base tab under load '" + out.load + "' is not clear of the environment (" + report.summary() +
                     "): the load overlaps or touches an obstacle";
        out.total_seconds = seconds_since(load_start);
        result.loads.push_back(std::move(out));
        continue;
      }
    }

    // Discovery and composition; when that finds no valid part, once more with
    // web roots (docs/discovery.md "Web roots"): the plates of the first pass
    // may be too soft where the way to the rivet areas is narrow.
    LoadOutcome first = out;
    bool finished = search_pass(scene, env, li, options, /*web_roots=*/false, progress, first);
    if (finished && !first.ok && options.web_fallback && !cancelled()) {
      LoadOutcome webbed = out;
      finished = search_pass(scene, env, li, options, /*web_roots=*/true, progress, webbed);
      webbed.web_pass_tried = first.web_pass_tried = true;
      merge_pass(first, std::move(webbed), scene);
    }
    // Still nothing: once more with flat extensions (a tab may continue its
    // parent flat). Measured on the bay's data_recorder (docs/pipeline.md): the
    // plain and web searches stay 26 % over its compliance limit, this one finds
    // a valid part. The answer's plan and model then use that grammar too.
    Problem flat_scene;
    const Problem* answer_scene = &scene;
    if (finished && !first.ok && result.flat_fallback && !cancelled()) {
      flat_scene = scene;
      flat_scene.manufacturing.flat_extensions = true;
      LoadOutcome flat = out;
      if (progress) progress->flat_pass = true;
      finished = search_pass(flat_scene, env, li, options, /*web_roots=*/false, progress, flat);
      if (progress) progress->flat_pass = false;
      flat.web_pass_tried = first.web_pass_tried;
      flat.flat_pass_tried = first.flat_pass_tried = flat.flat_pass = true;
      if (merge_pass(first, std::move(flat), scene)) answer_scene = &flat_scene;
    }
    if (!finished || cancelled()) {
      result.cancelled = true;
      break;
    }
    out = std::move(first);

    // Manufacturing plan and rivets of the answer.
    if (progress) progress->stage = static_cast<int>(Stage::Plan);
    if (!out.part.segments.empty()) {
      out.realised = realise(out.part.part);
      out.plan = plan_manufacturing(out.part.part, SheetSpec::from(*answer_scene));
      if (out.ok) {
        PartModelOptions mo;
        mo.self_rivets = out.part.self_rivets;
        const PartModel pm = build_part_model(*answer_scene, li, plate_geometry(out.part.part, out.realised), mo);
        out.rivets = pm.rivets;
        // The holes of the drawings: the FEM's rivets (polygon k is tab k) and the self-rivets' two sheets.
        std::vector<PlacedRivet> flange;
        for (size_t r = 0; r < pm.rivets.size(); ++r) flange.push_back({pm.rivet_polygon[r], pm.rivets[r]});
        std::vector<PlacedSelfRivet> self;
        for (const auto& tie : out.part.self_rivets)
          self.push_back({{tie.polygon_a, tie.point_a}, {tie.polygon_b, tie.point_b}});
        RivetLayoutOptions ro;
        ro.thickness = answer_scene->material.thickness;
        ro.diameter = answer_scene->manufacturing.rivet_diameter;
        RivetHoleOptions ho;
        ho.rivet_diameter = rivet_diameter(ro);
        set_rivet_holes(out.plan, out.realised, flange, self, ho);
        new_parts.push_back(part_as_obstacle(out.load, out.realised, scene.material.thickness));
      }
    }
    out.total_seconds = seconds_since(load_start);
    result.loads.push_back(std::move(out));
  }
  if (progress) progress->stage = static_cast<int>(Stage::Done);
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace sheetgen
