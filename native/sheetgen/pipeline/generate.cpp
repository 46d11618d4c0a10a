#include "sheetgen/pipeline/generate.hpp"

#include <chrono>
#include <memory>
#include <string>
#include <thread>

#include "sheetgen/core/cancelled.hpp"
#include "sheetgen/core/geometry.hpp"
#include "sheetgen/env/environment.hpp"
#include "sheetgen/fem/rivet_layout.hpp"
#include "sheetgen/part/validity.hpp"
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

// The environments of the loads, one after another: the scene's fields are
// built once; each load's environment adds the parts made since the previous
// load (one small field each) to the previous load's.
class LoadEnvironments {
 public:
  // The next load's environment; nullptr when building it was cancelled.
  const Environment* next(const Problem& problem, GenerateProgress* progress) {
    EnvironmentOptions eo;
    if (progress) eo.cancel = &progress->cancel;
    try {
      if (!env_) env_ = std::make_unique<Environment>(problem, eo);
      else if (!new_parts_.empty()) env_ = std::make_unique<Environment>(*env_, new_parts_, eo);
      new_parts_.clear();
    } catch (const Cancelled&) {
      return nullptr;
    }
    return env_.get();
  }
  // A finished part: an obstacle from the next load on.
  void add_part(EnvironmentMesh part) { new_parts_.push_back(std::move(part)); }

 private:
  std::vector<EnvironmentMesh> new_parts_;  // made since `env_` was built
  std::unique_ptr<Environment> env_;
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

}  // namespace

GenerateResult generate(const Problem& input, const GenerateOptions& options, GenerateProgress* progress) {
  const auto start = std::chrono::steady_clock::now();
  const Problem problem = with_options(input, options);
  GenerateResult result = result_settings(problem, options);
  if (progress) progress->loads = static_cast<int>(problem.loads.size());
  CancelRelay relay(progress);
  LoadEnvironments environments;
  for (int li = 0; li < static_cast<int>(problem.loads.size()); ++li) {
    const auto load_start = std::chrono::steady_clock::now();
    LoadOutcome out;
    out.load = problem.loads[li].name;
    if (progress) {
      progress->load = li;
      progress->stage = static_cast<int>(Stage::Environment);
    }
    const Environment* env = environments.next(problem, progress);
    if (env) out.environment_seconds = seconds_since(load_start);
    if (!env || cancel_requested(progress)) {
      result.cancelled = true;
      break;
    }
    out.reason = blocked_load_reason(*env, li, out.load);
    if (out.reason.empty()) {
      LoadSearch search = search_load(*env, li, out, options, result.flat_fallback, progress);
      if (!search.finished || cancel_requested(progress)) {
        result.cancelled = true;
        break;
      }
      out = std::move(search.answer);
      if (progress) progress->stage = static_cast<int>(Stage::Plan);
      const Problem& answer_scene = search.flat_scene ? *search.flat_scene : env->problem();
      plan_answer(answer_scene, li, out);
      if (out.ok && !out.part.segments.empty())
        environments.add_part(part_as_obstacle(out.load, out.realised, env->problem().material.thickness));
      // Sizing after the part joined the environment as the search left it:
      // the later loads search around that sheet, so their searches are the
      // same with and without sizing, and the sized part, which only loses
      // sheet, stays clear of everything they build (docs/pipeline.md "Sizing").
      if (out.ok && options.sizing) {
        search.answer = std::move(out);
        size_load_answer(*env, li, options, search);
        out = std::move(search.answer);
        if (out.sizing_cuts > 0) plan_answer(answer_scene, li, out);
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
