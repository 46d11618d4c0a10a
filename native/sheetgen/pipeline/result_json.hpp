#pragma once
// result.json, the "sheetgen-result/1" document of a run (docs/architecture.md
// "Interfaces", docs/pipeline.md "result.json"): the search settings, timing
// and one entry per load (status, part, FEM numbers, flat pattern, history,
// search statistics).
#include <string>

#include <nlohmann/json.hpp>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/pipeline/generate.hpp"

namespace sheetgen {

// `problem_ref` is stored as "problem" (a path relative to the result file) so
// export-ccx can rebuild the loads.
nlohmann::json result_json(const Problem& problem, const GenerateResult& result, const std::string& problem_ref);

// One load's entry of parts[] (what result_json writes for it): the drawing
// sheet is drawn from it (pipeline/part_drawing.hpp).
nlohmann::json load_result_json(const Problem& problem, const LoadOutcome& outcome);

}  // namespace sheetgen
