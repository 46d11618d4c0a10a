#include "sheetgen/structure/envelope_analysis.hpp"

#include <algorithm>
#include <chrono>

#include "sheetgen/fem/buckling.hpp"
#include "sheetgen/fem/vibration.hpp"

namespace sheetgen {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The requirements' limit of a model case: the problem's case of that name
// (its own max_deflection), else the limit for its force.
double case_compliance_limit(const Problem& problem, const Load* load, const std::string& name, const Vec3& force) {
  if (load)
    for (const LoadCase& c : load->cases)
      if (c.name == name) return problem.requirements.compliance_limit(c);
  return problem.requirements.compliance_limit(force.norm());
}

CaseResult case_result(const Problem& problem, const Load* load, const ShellLoadCase& lc, const ShellResult& r) {
  CaseResult c;
  c.name = lc.name;
  for (const NodalLoad& f : lc.loads) c.force += f.force;
  c.compliance = r.compliance;
  c.deflection = r.load_deflection;
  c.deflection_along_force = r.deflection_along_load;
  c.max_von_mises = r.max_von_mises;
  c.margin_of_safety = r.margin_of_safety;
  c.compliance_limit = case_compliance_limit(problem, load, lc.name, c.force);
  c.stiff_enough = c.compliance <= c.compliance_limit;
  c.strong_enough = c.margin_of_safety >= problem.requirements.min_margin_of_safety;
  return c;
}

void find_governing_cases(EnvelopeResult& res) {
  for (int k = 0; k < static_cast<int>(res.cases.size()); ++k) {
    const CaseResult& c = res.cases[k];
    auto ratio = [](const CaseResult& x) { return x.compliance / x.compliance_limit; };
    if (res.governing_stiffness < 0 || ratio(c) > ratio(res.cases[res.governing_stiffness])) res.governing_stiffness = k;
    if (res.governing_strength < 0 || c.margin_of_safety < res.cases[res.governing_strength].margin_of_safety)
      res.governing_strength = k;
  }
}

// alpha > 0 when case b's loads are -alpha times case a's (same nodes, forces
// and moments to 1e-12 of a's largest), else 0: the envelope's opposite
// factors (left and right 3 g; forward 9 g and rearward 1.5 g; down 6 g and
// up 3 g) are such pairs, since their forces act at one centre of mass.
double opposite_ratio(const ShellLoadCase& a, const ShellLoadCase& b) {
  if (a.loads.size() != b.loads.size() || a.loads.empty()) return 0;
  double na = 0, nb = 0;
  for (size_t i = 0; i < a.loads.size(); ++i) {
    if (a.loads[i].node != b.loads[i].node) return 0;
    na = std::max({na, a.loads[i].force.norm(), a.loads[i].moment.norm()});
    nb = std::max({nb, b.loads[i].force.norm(), b.loads[i].moment.norm()});
  }
  if (na <= 0 || nb <= 0) return 0;
  const double alpha = nb / na;
  for (size_t i = 0; i < a.loads.size(); ++i)
    if ((b.loads[i].force + alpha * a.loads[i].force).norm() > 1e-12 * nb ||
        (b.loads[i].moment + alpha * a.loads[i].moment).norm() > 1e-12 * nb)
      return 0;
  return alpha;
}

void record_buckling(const BucklingResult& b, double scale, size_t k, const EnvelopeOptions& options,
                     std::vector<std::vector<Vector6d>>& modes, EnvelopeResult& res) {
  res.cases[k].buckling_checked = true;
  res.cases[k].buckling_factor = b.factor() * scale;
  if (res.cases[k].buckling_factor < res.buckling_factor) {
    res.buckling_factor = res.cases[k].buckling_factor;
    res.governing_buckling = static_cast<int>(k);
  }
  if (options.keep_mode_shapes && !b.mode_shapes.empty()) modes[k] = b.mode_shapes.front();
}

// The buckling factor of every case (each solve skips a case that compresses
// nothing), the governing one, and its mode when kept. A case and its
// opposite share one eigen solve (analyse_buckling_both_ways): K_G is linear
// in the load, so the opposite case's factor is the negated load's over the
// ratio of their magnitudes.
void buckle_every_case(const ShellModel& m, const std::vector<ShellLoadCase>& cases,
                       const std::vector<ShellResult>& statics, const ShellSolveOptions& so,
                       const EnvelopeOptions& options, ShellSolver& solver, EnvelopeResult& res) {
  const auto t0 = Clock::now();
  std::vector<std::vector<Vector6d>> modes(statics.size());
  std::vector<bool> done(statics.size(), false);
  for (size_t k = 0; k < statics.size(); ++k) {
    if (done[k]) continue;
    size_t partner = k;
    double alpha = 0;
    for (size_t j = k + 1; j < statics.size() && alpha <= 0; ++j)
      if (!done[j] && (alpha = opposite_ratio(cases[k], cases[j])) > 0) partner = j;
    if (partner == k) {
      record_buckling(analyse_buckling(solver, m, statics[k], so), 1.0, k, options, modes, res);
    } else {
      const BucklingPair pair = analyse_buckling_both_ways(solver, m, statics[k], so);
      record_buckling(pair.first, 1.0, k, options, modes, res);
      record_buckling(pair.second, 1.0 / alpha, partner, options, modes, res);
      done[partner] = true;
    }
  }
  if (options.keep_mode_shapes && res.governing_buckling >= 0) res.buckling_mode = modes[res.governing_buckling];
  res.buckling_seconds = seconds_since(t0);
}

void vibrate(const ShellModel& m, const ShellSolveOptions& so, const EnvelopeOptions& options, ShellSolver& solver,
             EnvelopeResult& res) {
  VibrationOptions vo;
  vo.modes = options.frequencies;
  const VibrationResult v = analyse_vibration(solver, m, so, vo);
  res.frequencies_hz = v.frequencies_hz;
  res.sheet_mass = v.sheet_mass;
  res.box_mass = v.point_mass;
  res.vibration_seconds = v.seconds;
  if (options.keep_mode_shapes && !v.mode_shapes.empty()) res.vibration_mode = v.mode_shapes.front();
}

// The eigen checks against the requirements, where the problem asks for them,
// with the model's reserve (Requirements::buckling_model_reserve).
void judge_eigen_checks(const Requirements& req, const EnvelopeOptions& options, EnvelopeResult& res) {
  if (!req.eigen_checks) return;
  if (options.buckling) res.stable_enough = res.buckling_factor >= req.design_buckling_factor();
  if (const auto floor = req.design_frequency_hz())
    res.frequency_ok = !res.frequencies_hz.empty() && res.frequencies_hz.front() >= *floor;
}

}  // namespace

double EnvelopeResult::worst_compliance_ratio() const {
  return governing_stiffness < 0 ? 0.0
                                 : cases[governing_stiffness].compliance / cases[governing_stiffness].compliance_limit;
}

double EnvelopeResult::lowest_margin_of_safety() const {
  return governing_strength < 0 ? std::numeric_limits<double>::infinity() : cases[governing_strength].margin_of_safety;
}

EnvelopeResult analyse_envelope(const Problem& problem, const PartModel& part, const EnvelopeOptions& options,
                                const ShellElementOptions& element, ShellSolver& solver) {
  const auto start = Clock::now();
  const ShellModel& m = part.model;
  const ShellSolveOptions so = part_solve_options(problem, element);
  const Load* load = part.load_index >= 0 ? &problem.loads.at(part.load_index) : nullptr;
  EnvelopeResult res;
  res.elements = static_cast<int>(m.triangles.size());
  auto t0 = Clock::now();
  const std::vector<ShellLoadCase> cases = m.cases();
  const std::vector<ShellResult> statics = solver.solve_cases(m, so);
  res.static_seconds = seconds_since(t0);
  res.dofs = statics.front().reduced_dofs;
  for (size_t k = 0; k < cases.size(); ++k) res.cases.push_back(case_result(problem, load, cases[k], statics[k]));

  find_governing_cases(res);
  const bool static_pass = std::all_of(res.cases.begin(), res.cases.end(),
                                       [](const CaseResult& c) { return c.stiff_enough && c.strong_enough; });
  if (options.eigen_only_if_static_passes && !static_pass) {
    res.seconds = seconds_since(start);
    return res;
  }
  res.eigen_checked = options.buckling || options.frequencies > 0;
  if (options.buckling) buckle_every_case(m, cases, statics, so, options, solver, res);
  if (options.frequencies > 0) vibrate(m, so, options, solver, res);
  judge_eigen_checks(problem.requirements, options, res);
  res.seconds = seconds_since(start);
  return res;
}

EnvelopeResult analyse_part_envelope(const Problem& problem, int load_index, const PlateGeometry& geometry,
                                     const PartModelOptions& model_options, const EnvelopeOptions& options,
                                     ShellSolver* solver) {
  const PartModel pm = build_part_model(problem, load_index, geometry, model_options);
  ShellSolver own;
  return analyse_envelope(problem, pm, options, model_options.element, solver ? *solver : own);
}

}  // namespace sheetgen
