#include "sheetgen/compose/candidate.hpp"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/fem/fem_error.hpp"
#include "sheetgen/fem/plate_mesher.hpp"
#include "sheetgen/part/manufacturing_plan.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

namespace {
// The candidate's rivets, before its FEM: the self-rivets and the flange
// rivets laid out as the FEM will lay them out, so the cost is exact before
// the analysis and the cost bound as tight as it can be. A part whose flanges
// hold no rivet fails in the FEM; its cost counts the self-rivets only.
int count_rivets(const Problem& problem, const Candidate& c, const RealisedPart& realised) {
  int flange = 0;
  try {
    flange = flange_rivet_count(problem, plate_geometry(c.part, realised));
  } catch (const FemError&) {
  }
  return flange + static_cast<int>(c.self_rivets.size());
}
}  // namespace

double part_default_element_size(const Part& part, double thickness) {
  std::vector<std::vector<Vec3>> polys;
  for (const auto& t : realise(part).tabs) polys.push_back(t.corners);
  return default_element_size(polys, thickness);
}

Candidate evaluate_part(const Problem& problem, const Environment& env, int load_index, Candidate c, double element_size,
                        ShellSolver* solver, double cost_bound, AnalysisCache* cache) {
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
  const SheetSpec spec = SheetSpec::from(problem);  // the grammar of the search, which may not be env's problem's
  const ValidityReport report = check_validity(c.part, realised, spec, env, vo);
  if (!report.valid()) {
    c.reason = report.first_reason();
    c.message = report.summary();
    return c;
  }
  ManufacturingPlan plan = plan_manufacturing(c.part, spec);
  c.area = plan.flat.area();
  c.rivets = count_rivets(problem, c, realised);
  c.cost = search_score(problem.cost, problem.material, c.area, c.bends, c.rivets);
  if (!plan.ok()) {
    c.reason = plan.status;
    c.message = plan.message;
    return c;
  }
  if (c.cost >= cost_bound) {
    c.geometry_ok = true;
    c.over_cost_bound = true;
    return c;
  }
  // After the cost bound: a candidate the bound drops is never bent.
  if (problem.manufacturing.press_brake_required) {
    plan_press_brake(plan, c.part, spec, problem.manufacturing.press_brake_tools, {}, kSearchPressBrakeSweeps);
    if (!plan.press.ok) {
      c.reason = ValidityReason::PressBrake;
      c.message = "no bend order the press brake's tools make: " + plan.press.message;
      return c;
    }
  }
  c.geometry_ok = true;
  analyse_candidate(problem, load_index, c, element_size, solver, cache);
  return c;
}

namespace {
// The candidate's FEM on its own: sets analysed and fem, or fem_error.
void analyse_fresh(const Problem& problem, int load_index, Candidate& c, double element_size, ShellSolver* solver) {
  try {
    PartModelOptions mo;
    mo.element_size = element_size;
    mo.self_rivets = c.self_rivets;
    // Buckling and frequencies after the static cases pass: in the search only
    // when the problem requires them; at the default mesh (the final check)
    // always, so every answer reports them.
    mo.eigen_checks = problem.requirements.eigen_checks || element_size <= 0;
    c.fem = analyse_part(problem, load_index, plate_geometry(c.part, realise(c.part)), mo, solver);
    c.analysed = true;
  } catch (const FemError& e) {
    c.fem_error = e.what();
  }
}
}  // namespace

void analyse_candidate(const Problem& problem, int load_index, Candidate& c, double element_size, ShellSolver* solver,
                       AnalysisCache* cache) {
  c.analysed = false;
  c.fem_error.clear();
  std::string key;
  if (cache) {
    key = AnalysisCache::key(problem, load_index, c, element_size);
    if (std::optional<AnalysisCache::Analysis> known = cache->find(key)) {
      // As a fresh analysis would: a failed one leaves c.fem as it was.
      c.analysed = known->analysed;
      if (known->analysed) c.fem = std::move(known->fem);
      c.fem_error = std::move(known->fem_error);
      return;
    }
  }
  analyse_fresh(problem, load_index, c, element_size, solver);
  if (cache) cache->insert(key, {c.analysed, c.analysed ? c.fem : StructuralResult{}, c.fem_error});
}

Candidate evaluate_candidate(const Problem& problem, const Environment& env, int load_index, const Part& base,
                             const SegmentLibrary& library, std::vector<int> segments, double element_size,
                             ShellSolver* solver, double cost_bound, AnalysisCache* cache) {
  Candidate c;
  std::sort(segments.begin(), segments.end());
  c.segments = segments;
  c.part = assemble_part(base, library, segments);
  return evaluate_part(problem, env, load_index, std::move(c), element_size, solver, cost_bound, cache);
}

}  // namespace sheetgen
