#pragma once
// The files of a run (docs/pipeline.md "`sheetgen solve`"): DIR/result.json and
// per load DIR/<load>/{part.obj, flat.dxf, flat.svg, bends.csv, rivets.csv,
// history.csv, convergence.png, drawing.pdf (docs/drawing.md)}.
#include <string>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/pipeline/generate.hpp"

namespace sheetgen {

// Everything is written under temporary names first and renamed into place at
// the end (load folders first, result.json last), so a failed or cancelled run
// never leaves files claiming success. `problem_path` is stored in result.json
// relative to DIR. Throws std::runtime_error naming the file on failure.
void write_outputs(const std::string& dir, const Problem& problem, const GenerateResult& result,
                   const std::string& problem_path);

}  // namespace sheetgen
