#include "sheetgen/pipeline/output_files.hpp"

#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "sheetgen/core/sheet_gauges.hpp"
#include "sheetgen/part/exports.hpp"
#include "sheetgen/pipeline/part_drawing.hpp"
#include "sheetgen/pipeline/result_json.hpp"
#include "sheetgen/pipeline/step_files.hpp"
#include "sheetgen/report/convergence_plot.hpp"

namespace sheetgen {

namespace fs = std::filesystem;

namespace {

// The composition's history, one row per beam-search level (result.json's history[] in CSV).
std::string history_csv(const LoadOutcome& o) {
  std::ostringstream s;
  s.precision(10);
  s << "iteration,evaluated,found,best_cost_m2,best_area_m2,compliance_J,margin_of_safety\n";
  for (const auto& h : o.history)
    s << h.level << ',' << h.evaluated << ',' << (h.found ? 1 : 0) << ',' << h.best_cost << ',' << h.best_area << ','
      << h.compliance << ',' << h.margin_of_safety << '\n';
  return s.str();
}

// history.csv drawn as convergence.png (paper Fig. 8), with the load's
// compliance limit and the required MS. The only call into report/.
void write_convergence_plot(const std::string& path, const Problem& problem, const LoadOutcome& o) {
  ConvergenceHistory h;
  h.load = o.load;
  for (const auto& r : o.history)
    h.points.push_back({r.level, r.evaluated, r.found, r.best_area, r.compliance, r.margin_of_safety});
  for (const Load& l : problem.loads)
    if (l.name == o.load) h.compliance_limit_J = problem.requirements.compliance_limit(l.force.norm());
  h.min_margin_of_safety = problem.requirements.min_margin_of_safety;
  write_convergence_png(h, ConvergenceOptions{}, path);
}

// part.step and flat.step (docs/cad.md). A bent solid OpenCASCADE refuses does
// not cost the run its other files: part_step_error.txt says why instead.
void write_step_files(const fs::path& folder, const Problem& problem, const LoadOutcome& o) {
  LoadStepOptions step;
  step.keep_going = true;
  const LoadStepReport r = write_load_step(problem, o, (folder / "part.step").u8string(), (folder / "flat.step").u8string(), step);
  if (!r.part_error.empty()) write_text_file((folder / "part_step_error.txt").u8string(), r.part_error + "\n");
}

// One load's folder: the drawings and model of a valid part, the history and
// its plot; the part's in the sheet it is made of.
void write_load_folder(const fs::path& folder, const Problem& scene, const LoadOutcome& o) {
  std::optional<Problem> thicker;
  const Problem& problem = problem_at_sheet(scene, o.thickness, thicker);
  fs::create_directories(folder);
  if (o.ok) write_manufacturing_files(folder.u8string(), o.realised, o.plan);
  if (o.ok) write_part_drawing(load_result_json(problem, o), problem, (folder / "drawing.pdf").u8string());
  if (o.ok) write_step_files(folder, problem, o);
  write_text_file((folder / "history.csv").u8string(), history_csv(o));
  write_convergence_plot((folder / "convergence.png").u8string(), problem, o);
}

}  // namespace

void write_outputs(const std::string& dir, const Problem& problem, const GenerateResult& result, const std::string& problem_path) {
  const fs::path out = fs::u8path(dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw std::runtime_error(dir + ": cannot create the output folder (" + ec.message() + ")");
  const fs::path staging = out / (".sheetgen-staging-" + std::to_string(::getpid()));
  fs::remove_all(staging, ec);
  try {
    fs::create_directories(staging);
    for (const LoadOutcome& o : result.loads) write_load_folder(staging / fs::u8path(o.load), problem, o);
    // result.json names the problem relative to itself.
    std::string ref = problem_path;
    const fs::path rel = fs::relative(fs::absolute(fs::u8path(problem_path)), fs::absolute(out), ec);
    if (!ec && !rel.empty()) ref = rel.u8string();
    write_text_file((staging / "result.json").u8string(), result_json(problem, result, ref).dump(2) + "\n");
    // Move into place: load folders first, result.json last (its presence means the run finished).
    for (const LoadOutcome& o : result.loads) {
      const fs::path target = out / fs::u8path(o.load);
      fs::remove_all(target);
      fs::rename(staging / fs::u8path(o.load), target);
    }
    fs::rename(staging / "result.json", out / "result.json");
    fs::remove_all(staging);
  } catch (const std::exception& e) {
    fs::remove_all(staging, ec);
    throw std::runtime_error(std::string("writing the results failed: ") + e.what());
  }
}

}  // namespace sheetgen
