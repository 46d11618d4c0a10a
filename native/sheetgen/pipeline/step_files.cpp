#include "sheetgen/pipeline/step_files.hpp"

#include <filesystem>

#include "sheetgen/core/input_error.hpp"

namespace sheetgen {

LoadStepReport write_load_step(const Problem& problem, const LoadOutcome& load, const std::string& part_path,
                               const std::string& flat_path, const LoadStepOptions& options) {
  if (!load.ok) throw InputError("the run", "load '" + load.load + "'", "has no valid part to write as STEP");
  StepExportOptions o;
  o.thickness = SheetSpec::from(problem).thickness;
  o.product = load.load;
  LoadStepReport r;
  try {
    r.part = write_part_step(part_path, load.plan.flat, load.plan.holes, o);
  } catch (const StepGeometryError& e) {
    if (!options.keep_going) throw;
    // Named by the file's name: the folder may be a staging folder that is renamed afterwards.
    r.part_error = e.what();
    const std::string name = std::filesystem::u8path(part_path).filename().u8string();
    for (size_t at = r.part_error.find(part_path); at != std::string::npos; at = r.part_error.find(part_path, at))
      r.part_error.replace(at, part_path.size(), name);
  }
  if (!flat_path.empty()) {
    o.product = load.load + " flat pattern";
    r.flat = write_flat_step(flat_path, load.plan.flat, load.plan.holes, o);
  }
  return r;
}

LoadStepReport write_load_step(const Problem& problem, const GenerateResult& result, const std::string& load,
                               const std::string& part_path, const std::string& flat_path) {
  for (const LoadOutcome& o : result.loads)
    if (o.load == load) return write_load_step(problem, o, part_path, flat_path, LoadStepOptions{});
  throw InputError("the run", "load '" + load + "'", "is not a load of this run");
}

}  // namespace sheetgen
