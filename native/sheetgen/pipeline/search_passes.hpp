#pragma once
// The searches of one load (docs/pipeline.md "Pipeline per load"), internal to
// the pipeline: discovery and composition on the search mesh, then the final
// check at the default mesh down the valid candidates, cheapest first. A load
// without a valid part is searched again with web roots, then with flat
// extensions, then with fresh seeds; the answer is the valid one, else the
// one nearest to valid. Last, the right-angle pass replaces it by a cheaper
// part in the right-angle grammar when it finds one. The caller runs all of
// that on each sheet, and with "prefer" (the press-brake setting) once more
// on each sheet without the press-brake check (docs/pipeline.md).
#include <optional>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/discovery/segment_library.hpp"
#include "sheetgen/pipeline/generate.hpp"

namespace sheetgen {

class Environment;

struct LoadSearch {
  bool finished = false;              // false: cancelled (the answer is incomplete)
  LoadOutcome answer;                 // the load's outcome with the search's fields filled
  // The scene of the search the answer comes from when its grammar is not the
  // problem's (the flat-extension search, the right-angle pass): the answer's
  // plan, sizing and structural model use that grammar too.
  std::optional<Problem> answer_scene;
  // The segments the answer's search composed; its seed retries pool theirs
  // into these (docs/pipeline.md, step 4d).
  SegmentLibrary library;
};

// How a load is searched on one sheet (docs/pipeline.md "Pipeline per load").
struct SearchRound {
  bool flat_fallback = true;    // a pass with flat extensions where the others give no part (GenerateResult::flat_fallback)
  bool press_fallback = false;  // every pass without the press-brake check, the answer marked LoadOutcome::press_fallback
  // Every pass in the right-angle grammar (the right-angle search, step 4h):
  // no flat-extension pass (the grammar has them) and no right-angle pass.
  bool right_angles = false;
};

// `start` holds the load's fields known before the search (name, environment
// time).
LoadSearch search_load(const Environment& env, int load_index, const LoadOutcome& start, const GenerateOptions& options,
                       SearchRound round, GenerateProgress* progress);

// The press-brake fallback's search (every sheet again without the check)
// against the checked one's answer: the work of both counts; the fallback's
// answer is kept when it is valid or nearer to valid, with the gauges its own
// round tried. True when it was kept.
bool keep_press_fallback(LoadSearch& checked, LoadSearch&& fallback, const Problem& scene);

// Sizing of the valid answer of a finished search (options.sizing,
// docs/pipeline.md "Sizing"), in the grammar and checks it was found with: a
// flat-extension answer keeps its flat tabs, a press-brake fallback's answer
// is not held to the tools. Fills the answer's sizing fields.
void size_load_answer(const Environment& env, int load_index, const GenerateOptions& options, LoadSearch& search);

}  // namespace sheetgen
