#include "sheetgen/pipeline/generate.hpp"

#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include "sheetgen/core/cancelled.hpp"
#include "sheetgen/core/cost_model.hpp"
#include "sheetgen/core/geometry.hpp"
#include "sheetgen/core/sheet_gauges.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/fem/rivet_layout.hpp"
#include "sheetgen/part/validity.hpp"
#include "sheetgen/pipeline/load_environments.hpp"
#include "sheetgen/pipeline/search_passes.hpp"
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

bool cancel_requested(const GenerateProgress* progress) { return progress && progress->cancel.load(); }

// The problem with the options' overrides of its search settings and, in
// right-angle mode, its manufacturing limits.
Problem with_options(const Problem& input, const GenerateOptions& options) {
  Problem problem = input;
  if (options.chains) problem.search.chains = *options.chains;
  if (options.iterations) problem.search.iterations = *options.iterations;
  if (options.beam_width) problem.search.beam_width = *options.beam_width;
  if (options.threads) problem.search.threads = *options.threads;
  if (options.seed) problem.search.seed = *options.seed;
  if (options.right_angles) problem.manufacturing.restrict_to_right_angles();  // flat extensions included
  if (options.flat_extensions) problem.manufacturing.flat_extensions = true;
  return problem;
}

// A result with the settings of the run and no loads yet.
GenerateResult result_settings(const Problem& problem, const GenerateOptions& options) {
  GenerateResult result;
  result.search = problem.search;
  result.right_angles = options.right_angles;
  result.flat_extensions = problem.manufacturing.flat_extensions;
  result.self_rivet = options.compose.self_rivet;
  result.stiffening_lips = options.compose.stiffening_lips;
  result.web_fallback = options.web_fallback;
  result.flat_fallback = options.flat_fallback && !problem.manufacturing.flat_extensions;
  result.right_angle_pass = options.right_angle_pass && problem.manufacturing.admits_right_angle_pass();
  result.right_angle_search = options.right_angle_search && problem.manufacturing.admits_right_angle_pass();
  result.seed_retries = options.seed_retries;
  result.sizing = options.sizing;
  return result;
}

// A base tab that is not clear (the load sits in or on an obstacle) cannot
// carry any part: why, or empty when the base tab is clear.
std::string blocked_load_reason(const Environment& env, int li, const std::string& load) {
  const Problem& scene = env.problem();
  const Part base = make_base_part(scene.loads[li], li, scene.material.thickness);
  ValidityOptions vo;
  vo.stop_at_first = true;
  const ValidityReport report = check_validity(base, realise(base), env, vo);
  if (env.inside_closed_obstacle(scene.loads[li].center))
    return "load '" + load + "' lies inside a closed obstacle of the environment: no part can reach it";
  if (!report.valid())
    return "the base tab under load '" + load + "' is not clear of the environment (" + report.summary() +
           "): the load overlaps or touches an obstacle";
  return {};
}

// The rivets of a valid answer (the FEM's, on the rivet flanges) and the holes
// of its drawings: polygon k is tab k; a self-rivet makes a hole in both sheets.
void place_rivets(const Problem& answer_scene, int li, LoadOutcome& out) {
  PartModelOptions mo;
  mo.self_rivets = out.part.self_rivets;
  const PartModel pm = build_part_model(answer_scene, li, plate_geometry(out.part.part, out.realised), mo);
  out.rivets = pm.rivets;
  std::vector<PlacedRivet> flange;
  for (size_t r = 0; r < pm.rivets.size(); ++r) flange.push_back({pm.rivet_polygon[r], pm.rivets[r]});
  std::vector<PlacedSelfRivet> self;
  for (const auto& tie : out.part.self_rivets)
    self.push_back({{tie.polygon_a, tie.point_a}, {tie.polygon_b, tie.point_b}});
  RivetLayoutOptions ro;
  ro.thickness = answer_scene.material.thickness;
  ro.diameter = answer_scene.manufacturing.rivet_diameter;
  RivetHoleOptions ho;
  ho.rivet_diameter = rivet_diameter(ro);
  set_rivet_holes(out.plan, out.realised, flange, self, ho);
}

// Manufacturing plan and rivets of the answer, in the grammar of the search it came from.
void plan_answer(const Problem& answer_scene, int li, LoadOutcome& out) {
  if (out.part.segments.empty()) return;
  out.realised = realise(out.part.part);
  ManufacturingPlanOptions mo;
  mo.press_brake = true;
  mo.press_brake_tools = answer_scene.manufacturing.press_brake_tools;
  out.plan = plan_manufacturing(out.part.part, SheetSpec::from(answer_scene), mo);
  if (out.ok) place_rivets(answer_scene, li, out);
}

// The search of one load at the sheet of `env`'s problem: the blocked-base
// test, every pass, and the answer's manufacturing plan; `blocked` says the
// base tab itself is not clear. False when cancelled.
bool search_sheet(const Environment& env, int li, const GenerateOptions& options, SearchRound round,
                  GenerateProgress* progress, LoadSearch& search, bool& blocked) {
  LoadOutcome& out = search.answer;
  out.thickness = env.problem().material.thickness;
  out.reason = blocked_load_reason(env, li, out.load);
  blocked = !out.reason.empty();
  if (blocked) return true;
  LoadSearch found = search_load(env, li, out, options, round, progress);
  if (!found.finished || cancel_requested(progress)) return false;
  search = std::move(found);
  search.answer.thickness = env.problem().material.thickness;
  if (progress) progress->stage = static_cast<int>(Stage::Plan);
  plan_answer(search.answer_scene ? *search.answer_scene : env.problem(), li, search.answer);
  return true;
}

// The work of another search of the same load, added to `to`: environment,
// discovery and composition time, FEM calls.
void add_search_work(LoadOutcome& to, const LoadOutcome& from) {
  to.environment_time += from.environment_time;
  to.discovery_time += from.discovery_time;
  to.composition_time += from.composition_time;
  to.fem_calls += from.fem_calls;
}

// Thicker gauges (docs/pipeline.md "Thicker gauges"): a load that the
// problem's sheet gives no valid part is searched again at each of
// material.gauges in turn, as a designer takes the next gauge up for a bracket
// that is too soft; the first valid answer is kept, with `gauge_env` the
// environment of its sheet. When none gives one the answer stays the
// problem's sheet's nearest candidate, and its reason names the gauges tried.
// A base tab that is blocked at one gauge is blocked at every thicker one.
bool search_gauges(const Problem& problem, LoadEnvironments& environments, int li, const GenerateOptions& options,
                   SearchRound round, GenerateProgress* progress, LoadSearch& search,
                   std::unique_ptr<Environment>& gauge_env) {
  const std::vector<double>& gauges = problem.material.gauges;
  LoadOutcome& first = search.answer;  // the problem's sheet's, which the work of every gauge is added to
  std::string tried;
  for (size_t k = 0; k < gauges.size() && !cancel_requested(progress); ++k) {
    const Stopwatch clock;
    if (progress) progress->stage = static_cast<int>(Stage::Environment);
    environments.release();  // the problem's sheet's fields are not needed while a gauge's are
    std::unique_ptr<Environment> sheet = environments.at_sheet(at_gauge(problem, gauges[k]));
    if (!sheet) return false;
    LoadSearch thick;
    thick.answer.load = first.load;
    thick.answer.environment_time = clock.elapsed();
    if (progress) progress->gauge = static_cast<int>(k + 1);
    bool blocked = false;
    const bool finished = search_sheet(*sheet, li, options, round, progress, thick, blocked);
    if (progress) progress->gauge = 0;
    if (!finished) return false;
    add_search_work(first, thick.answer);
    first.gauges_tried = static_cast<int>(k + 1);
    char mm[32];
    std::snprintf(mm, sizeof mm, "%s%.3g", tried.empty() ? "" : ", ", gauges[k] * 1e3);
    tried += mm;
    if (blocked) break;
    if (thick.answer.ok) {
      LoadOutcome& found = thick.answer;
      found.environment_time = found.discovery_time = found.composition_time = {};
      found.fem_calls = 0;
      add_search_work(found, first);  // every sheet's work, this one's included
      found.gauges_tried = first.gauges_tried;
      search = std::move(thick);
      gauge_env = std::move(sheet);
      return true;
    }
  }
  if (!tried.empty()) first.reason += " (no valid part at the thicker gauges tried either: " + tried + " mm)";
  return true;
}

// The problem's sheet's environment for a search of the current load, built
// again when a gauge's search released it; the build's time counts as the
// load's environment time. nullptr when cancelled.
const Environment* problem_sheet(LoadEnvironments& environments, GenerateProgress* progress, LoadOutcome& out) {
  const Stopwatch clock;
  if (progress) progress->stage = static_cast<int>(Stage::Environment);
  const Environment* env = environments.current();
  out.environment_time += clock.elapsed();
  return env;
}

// One round over the sheets: the problem's, then its thicker gauges while none
// gave a valid part. Only a part that exists and is not strong, stiff or
// stable enough is helped by thicker sheet: where no candidate was analysed
// (no way to a rivet area, nothing the press brake bends) a thicker one fits
// no better.
bool search_round(const Problem& problem, LoadEnvironments& environments, int li, const GenerateOptions& options,
                  SearchRound round, GenerateProgress* progress, LoadSearch& search,
                  std::unique_ptr<Environment>& gauge_env, bool& blocked) {
  const Environment* env = problem_sheet(environments, progress, search.answer);
  if (!env || !search_sheet(*env, li, options, round, progress, search, blocked)) return false;
  if (blocked || search.answer.ok || !search.answer.part.analysed) return true;
  return search_gauges(problem, environments, li, options, round, progress, search, gauge_env);
}

// Every sheet with the press-brake check, then, with "prefer"
// (docs/manufacturing.md "Press brake") and no part the tools bend on any
// sheet, every sheet again without it: a shop takes the next gauge up before
// it takes a part its standard tools cannot bend. The fallback's answer needs
// other tools, and its plan names the bend and why. `right_angles`: every
// pass in the right-angle grammar. False when cancelled.
bool search_rounds(const Problem& problem, LoadEnvironments& environments, int li, const GenerateOptions& options,
                   bool flat_fallback, bool right_angles, GenerateProgress* progress, LoadSearch& search,
                   std::unique_ptr<Environment>& gauge_env) {
  bool blocked = false;
  if (!search_round(problem, environments, li, options, {flat_fallback, false, right_angles}, progress, search,
                    gauge_env, blocked))
    return false;
  const Manufacturing& mf = problem.manufacturing;
  if (blocked || search.answer.ok || !mf.press_brake_required || !mf.press_brake_fallback || cancel_requested(progress))
    return true;
  LoadSearch fallback;
  fallback.answer.load = search.answer.load;
  std::unique_ptr<Environment> fallback_env;
  if (!search_round(problem, environments, li, options, {flat_fallback, true, right_angles}, progress, fallback,
                    fallback_env, blocked))
    return false;
  if (keep_press_fallback(search, std::move(fallback), problem)) gauge_env = std::move(fallback_env);
  return true;
}

// What a valid answer costs, comparable across sheets: its search score
// (square metres of its own sheet) times the price of a square metre of that
// sheet when the problem ranks by cost; the score itself (area and bends,
// whatever the sheet) when it ranks by area (docs/cost.md).
double answer_price(const Problem& problem, const LoadOutcome& answer) {
  if (!problem.cost.rank_by_cost) return answer.part.cost;
  Material sheet = problem.material;
  sheet.thickness = answer.thickness;
  return answer.part.cost * sheet_price_per_m2(problem.cost, sheet);
}

// The right-angle search (docs/pipeline.md step 4h): a load whose answer is a
// press-brake fallback is searched once more as a right-angle solve would
// search it, every pass, sheet and round in that grammar. Its answer replaces
// the fallback when the tools bend it, or when it is a fallback too and
// cheaper. The right-angle pass of each sheet (step 4e) is one plain pass; on
// the fallback scenes the right-angle solve's parts came from its retries, its
// web pass or a thicker gauge (docs/ablation_composition.md), so only the whole
// search dominates it. False when cancelled.
bool right_angle_search(const Problem& problem, LoadEnvironments& environments, int li, const GenerateOptions& options,
                        GenerateProgress* progress, LoadSearch& search, std::unique_ptr<Environment>& gauge_env) {
  LoadOutcome& best = search.answer;
  if (!best.ok || !best.press_fallback || !options.right_angle_search ||
      !problem.manufacturing.admits_right_angle_pass() || cancel_requested(progress))
    return true;
  // One environment alive at a time: the answer's gauge is built again below
  // if the answer stays.
  gauge_env.reset();
  LoadSearch square;
  square.answer.load = best.load;
  std::unique_ptr<Environment> square_env;
  if (progress) progress->right_angle_pass = true;
  const bool finished = search_rounds(problem, environments, li, options, false, true, progress, square, square_env);
  if (progress) progress->right_angle_pass = false;
  if (!finished) return false;
  LoadOutcome& found = square.answer;
  const bool keep =
      found.ok && (!found.press_fallback || answer_price(problem, found) < answer_price(problem, best));
  best.right_angle_search_tried = found.right_angle_search_tried = true;
  found.right_angle_search = keep;
  LoadSearch& kept = keep ? square : search;
  add_search_work(kept.answer, (keep ? search : square).answer);
  if (keep) {
    search = std::move(square);
    gauge_env = std::move(square_env);
    return true;
  }
  if (best.thickness == problem.material.thickness) return true;
  const Stopwatch clock;
  gauge_env = environments.at_sheet(at_gauge(problem, best.thickness));
  best.environment_time += clock.elapsed();
  return gauge_env != nullptr;
}

// Every round of a load (search_rounds), then the right-angle search when the
// answer is a press-brake fallback. False when cancelled.
bool search_load_sheets(const Problem& problem, LoadEnvironments& environments, int li,
                        const GenerateOptions& options, bool flat_fallback, GenerateProgress* progress,
                        LoadSearch& search, std::unique_ptr<Environment>& gauge_env) {
  return search_rounds(problem, environments, li, options, flat_fallback, false, progress, search, gauge_env) &&
         right_angle_search(problem, environments, li, options, progress, search, gauge_env);
}

}  // namespace

GenerateResult generate(const Problem& input, const GenerateOptions& options, GenerateProgress* progress) {
  const Stopwatch clock;
  const Problem problem = with_options(input, options);
  GenerateResult result = result_settings(problem, options);
  if (progress) progress->loads = static_cast<int>(problem.loads.size());
  CancelRelay relay(progress);
  LoadEnvironments environments(problem, progress);
  for (int li = 0; li < static_cast<int>(problem.loads.size()); ++li) {
    const Stopwatch load_clock;
    LoadSearch search;
    LoadOutcome& first = search.answer;
    first.load = problem.loads[li].name;
    if (progress) {
      progress->load = li;
      progress->stage = static_cast<int>(Stage::Environment);
    }
    const Environment* env = environments.next();
    if (env) first.environment_time = load_clock.elapsed();
    if (!env || cancel_requested(progress)) {
      result.cancelled = true;
      break;
    }
    std::unique_ptr<Environment> gauge_env;  // the answer's sheet's, when thicker than the problem's
    // Every pass, sheet and round of this load shares its analyses.
    AnalysisCache analyses;
    GenerateOptions load_options = options;
    load_options.compose.analyses = &analyses;
    const bool finished =
        search_load_sheets(problem, environments, li, load_options, result.flat_fallback, progress, search, gauge_env);
    LoadOutcome& out = search.answer;
    out.analyses_reused = analyses.hits();
    // The answer's sheet's environment: a gauge's, or the problem's (built
    // again when a gauge's search released it).
    const Environment* sheet_env =
        !finished ? nullptr : gauge_env ? gauge_env.get() : problem_sheet(environments, progress, out);
    if (!sheet_env || cancel_requested(progress)) {
      result.cancelled = true;
      break;
    }
    if (out.ok && !out.part.segments.empty())
      environments.add_part(part_as_obstacle(out.load, out.realised, out.thickness));
    // Sizing after the part joined the environment as the search left it:
    // the later loads search around that sheet, so their searches are the
    // same with and without sizing, and the sized part, which only loses
    // sheet, stays clear of everything they build (docs/pipeline.md "Sizing").
    if (out.ok && options.sizing) {
      size_load_answer(*sheet_env, li, options, search);
      if (out.sizing_cuts > 0) plan_answer(search.answer_scene ? *search.answer_scene : sheet_env->problem(), li, out);
    }
    out.total_time = load_clock.elapsed();
    result.loads.push_back(std::move(out));
  }
  if (progress) progress->stage = static_cast<int>(Stage::Done);
  result.seconds = clock.wall_seconds();
  return result;
}

}  // namespace sheetgen
