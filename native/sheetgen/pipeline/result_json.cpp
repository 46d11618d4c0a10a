#include "sheetgen/pipeline/result_json.hpp"

#include <cmath>

#include "sheetgen/core/sheet_gauges.hpp"
#include "sheetgen/part/exports.hpp"

namespace sheetgen {

namespace {

using nlohmann::json;

json v3(const Vec3& p) { return json::array({p.x(), p.y(), p.z()}); }

// A number that may be +inf (no buckling possible) or absent: null in JSON.
json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Every case of the load with its checks, the governing case of each check,
// the buckling factor and the first frequencies (docs/pipeline.md "result.json").
json envelope_json(const EnvelopeResult& env, const Requirements& req) {
  json cases = json::array();
  for (const CaseResult& c : env.cases)
    cases.push_back({{"name", c.name}, {"force_n", v3(c.force)}, {"compliance", c.compliance},
                     {"compliance_limit", c.compliance_limit}, {"deflection_along_force_m", c.deflection_along_force},
                     {"deflection_m", c.deflection}, {"max_von_mises_pa", c.max_von_mises},
                     {"margin_of_safety", c.margin_of_safety},
                     {"buckling_factor", c.buckling_checked ? finite_or_null(c.buckling_factor) : json(nullptr)}});
  auto name = [&](int k) { return k >= 0 ? json(env.cases[k].name) : json(nullptr); };
  json e = {{"cases", cases},
            {"governing", {{"stiffness", name(env.governing_stiffness)}, {"strength", name(env.governing_strength)},
                           {"buckling", name(env.governing_buckling)}}},
            {"eigen_checked", env.eigen_checked},
            {"buckling_factor", env.eigen_checked ? finite_or_null(env.buckling_factor) : json(nullptr)},
            {"frequencies_hz", env.frequencies_hz},
            {"box_mass_kg", env.box_mass},
            {"required", {{"checked", req.eigen_checks},
                          {"min_buckling_factor", req.min_buckling_factor},
                          {"min_frequency_hz", req.min_frequency_hz ? json(*req.min_frequency_hz) : json(nullptr)},
                          // What the search held the part to: the floors times the model's reserve.
                          {"held_to_buckling_factor", req.design_buckling_factor()},
                          {"held_to_frequency_hz", req.min_frequency_hz ? json(*req.design_frequency_hz()) : json(nullptr)}}}};
  return e;
}

// What the part costs to make, by the problem's cost model (core/cost_model.hpp).
json cost_json(const Problem& problem, double area_m2, int bends, int rivets) {
  const PartCost pc = part_cost(problem.cost, problem.material, area_m2, bends, rivets);
  return {{"currency", problem.cost.currency}, {"material", pc.material}, {"bends", pc.bends},
          {"rivets", pc.rivets}, {"rivet_count", rivets}, {"setup", pc.setup}, {"total", pc.total()}};
}

// The part of a load that has one (valid or the closest candidate): size,
// cost, FEM at the default mesh, tabs, rivets and flat pattern.
void add_part_fields(json& p, const Problem& problem, const LoadOutcome& o) {
  const Candidate& c = o.part;
  p["area_m2"] = c.area;
  p["mass_kg"] = c.area * problem.material.thickness * problem.material.density;
  p["bends"] = c.bends;
  p["cost_m2"] = c.cost;
  p["cost"] = cost_json(problem, c.area, c.bends, static_cast<int>(o.rivets.size() + c.self_rivets.size()));
  if (c.analysed) {
    p["compliance"] = c.fem.compliance;
    p["compliance_limit"] = c.fem.compliance_limit;
    p["deflection_m"] = c.fem.deflection;
    p["deflection_along_force_m"] = c.fem.deflection_along_force;
    p["max_von_mises_pa"] = c.fem.max_von_mises;
    p["margin_of_safety"] = c.fem.margin_of_safety;
    p["fem_elements"] = c.fem.elements;
    p["envelope"] = envelope_json(c.fem.envelope, problem.requirements);
  }
  p["tabs"] = part_json(c.part, o.realised);
  json rivets = json::array();
  for (const Vec3& r : o.rivets) rivets.push_back(v3(r));
  p["rivets"] = rivets;
  json self_rivets = json::array();
  for (const auto& t : c.self_rivets)
    self_rivets.push_back({{"tabs", {t.polygon_a, t.polygon_b}}, {"points", {v3(t.point_a), v3(t.point_b)}}});
  p["self_rivets"] = self_rivets;
  p["bend_sequence"] = o.plan.sequence.order;
  if (o.plan.press_checked) {
    json tools = json::array();
    for (const BendToolRow& r : bend_tool_rows(o.plan))
      tools.push_back({{"tab", r.tab}, {"punch", r.punch}, {"die", r.die}, {"turned_over", r.turned_over}});
    p["press_brake"] = {{"ok", o.plan.press.ok}, {"message", o.plan.press.message}, {"tools", tools}};
  }
  p["flat_pattern"] = flat_pattern_json(o.plan.flat, o.plan.sequence.order, o.plan.holes);
}

// The search of a load: history.csv's rows, statistics and times.
void add_search_fields(json& p, const LoadOutcome& o) {
  json history = json::array();
  for (const auto& h : o.history)
    history.push_back({{"iteration", h.level}, {"evaluated", h.evaluated}, {"found", h.found}, {"best_cost_m2", h.best_cost},
                       {"best_area_m2", h.best_area}, {"compliance", h.compliance}, {"margin_of_safety", h.margin_of_safety}});
  p["history"] = history;
  p["library_segments"] = o.library_size;
  p["fem_calls"] = o.fem_calls;
  p["self_rivet_candidates"] = o.self_rivet_candidates;
  p["lip_candidates"] = o.lip_candidates;
  p["skipped_by_cost"] = o.skipped_by_cost;
  p["screen_fem_calls"] = o.screen_fem_calls;
  p["screened_out"] = o.screened_out;
  p["analyses_reused"] = o.analyses_reused;
  p["composition_reruns"] = o.composition_reruns;
  p["web_pass_tried"] = o.web_pass_tried;
  p["web_roots"] = o.web_roots;
  p["flat_pass_tried"] = o.flat_pass_tried;
  p["flat_pass"] = o.flat_pass;
  p["seed_retries_tried"] = o.seed_retries_tried;
  p["seed_retry"] = o.seed_retry;
  p["right_angle_pass_tried"] = o.right_angle_pass_tried;
  p["right_angle_pass"] = o.right_angle_pass;
  p["right_angle_search_tried"] = o.right_angle_search_tried;
  p["right_angle_search"] = o.right_angle_search;
  p["press_fallback"] = o.press_fallback;
  p["press_rejected"] = o.press_rejected;
  p["press_rejected_segments"] = o.press_rejected_segments;
  if (o.sized)
    p["sizing"] = {{"trials", o.sizing_trials},
                   {"cuts", o.sizing_cuts},
                   {"area_before_m2", o.sizing_area_before},
                   {"search_score_before_m2", o.sizing_cost_before},
                   {"final_check_failed", o.sizing_final_check_failed}};
  // Wall seconds per stage (the keys of old files), and the process's CPU
  // seconds beside them: CPU over wall is how many cores a stage kept busy.
  p["timing"] = {{"environment_s", o.environment_time.wall_seconds},
                 {"discovery_s", o.discovery_time.wall_seconds},
                 {"composition_s", o.composition_time.wall_seconds},
                 {"sizing_s", o.sizing_time.wall_seconds},
                 {"total_s", o.total_time.wall_seconds},
                 {"environment_cpu_s", o.environment_time.cpu_seconds},
                 {"discovery_cpu_s", o.discovery_time.cpu_seconds},
                 {"composition_cpu_s", o.composition_time.cpu_seconds},
                 {"sizing_cpu_s", o.sizing_time.cpu_seconds},
                 {"total_cpu_s", o.total_time.cpu_seconds}};
}

// One entry of parts[]: the part's fields in the sheet it is made of.
json load_entry(const Problem& problem, const LoadOutcome& o) {
  json p;
  p["load"] = o.load;
  p["status"] = o.ok ? "ok" : "no_valid_part";
  if (!o.ok) p["reason"] = o.reason;
  p["segments"] = o.part.segments;
  std::optional<Problem> thicker;
  const Problem& sheet = problem_at_sheet(problem, o.thickness, thicker);
  p["thickness_m"] = sheet.material.thickness;
  p["gauges_tried"] = o.gauges_tried;
  if (!o.part.segments.empty()) add_part_fields(p, sheet, o);
  add_search_fields(p, o);
  return p;
}

}  // namespace

json load_result_json(const Problem& problem, const LoadOutcome& outcome) { return load_entry(problem, outcome); }

json result_json(const Problem& problem, const GenerateResult& result, const std::string& problem_ref) {
  json parts = json::array();
  for (const LoadOutcome& o : result.loads) parts.push_back(load_entry(problem, o));
  json doc;
  doc["format"] = "sheetgen-result/1";
  doc["problem"] = problem_ref;
  doc["parts"] = parts;
  doc["search"] = {{"chains", result.search.chains},         {"iterations", result.search.iterations},
                   {"beam_width", result.search.beam_width}, {"seed", result.search.seed},
                   {"threads", result.search.threads},       {"right_angles", result.right_angles},
                   {"flat_extensions", result.flat_extensions},
                   {"self_rivet", result.self_rivet},         {"stiffening_lips", result.stiffening_lips},
                   {"web_fallback", result.web_fallback},
                   {"flat_fallback", result.flat_fallback},
                   {"seed_retries", result.seed_retries},
                   {"right_angle_pass", result.right_angle_pass},
                   {"right_angle_search", result.right_angle_search},
                   {"sizing", result.sizing}};
  doc["timing"] = {{"total_s", result.seconds}};
  return doc;
}

}  // namespace sheetgen
