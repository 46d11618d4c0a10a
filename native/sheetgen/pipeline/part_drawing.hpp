#pragma once
// A load's drawing sheet (drawing.pdf, docs/drawing.md) from its entry in
// result.json (an element of parts[] of sheetgen-result/1) and the problem
// (material, K-factor, kerf, rivet size, requirements). One path for the
// CLI's drawing.pdf and for the add-on, which holds result.json and the
// problem after a run.
#include <string>

#include <nlohmann/json.hpp>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/report/drawing_sheet.hpp"

namespace sheetgen {

// The sheet's content. Throws InputError (file "result.json", the field, what
// is wrong) when the entry lacks a field the sheet needs or has no part.
DrawingSheetPart drawing_sheet_part(const nlohmann::json& part_entry, const Problem& problem);

// The entry of load `load` in a result document; throws InputError naming the
// load (and the loads there are) when it has none, or when that load has no
// valid part (a shop gets no drawing of a part that misses its checks).
const nlohmann::json& drawable_part_entry(const nlohmann::json& result_doc, const std::string& load);

// drawing_sheet_part + write_drawing_pdf: the PDF of one part at `path`
// (written beside it and renamed; std::runtime_error naming `path` when it
// cannot be written).
DrawingSheetLayout write_part_drawing(const nlohmann::json& part_entry, const Problem& problem, const std::string& path,
                                      const DrawingSheetOptions& options = {});

// The same from result.json's text and a load's name (the add-on's "Export
// drawing"): InputError when the text is not JSON, the load is not there or
// has no valid part.
DrawingSheetLayout write_load_drawing(const std::string& result_json_text, const std::string& load,
                                      const Problem& problem, const std::string& path,
                                      const DrawingSheetOptions& options = {});

// How the title block names the problem: "<folder>/<file>" of a problem
// file's path (the same wherever the run's folder is, so outputs stay
// byte-identical), anything else (e.g. "scene 'Scene'") as it is.
std::string problem_label(const std::string& source);

}  // namespace sheetgen
