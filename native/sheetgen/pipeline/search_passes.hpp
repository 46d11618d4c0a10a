#pragma once
// The searches of one load (docs/pipeline.md "Pipeline per load"), internal to
// the pipeline: discovery and composition on the search mesh, then the final
// check at the default mesh down the valid candidates, cheapest first. A load
// without a valid part is searched again with web roots, then with flat
// extensions, then with fresh seeds, and with "prefer" (the press-brake
// setting) all of that once more without the press-brake check; the answer is
// the valid one, else the one nearest to valid.
#include <optional>

#include "sheetgen/core/problem.hpp"
#include "sheetgen/discovery/segment_library.hpp"
#include "sheetgen/pipeline/generate.hpp"

namespace sheetgen {

class Environment;

struct LoadSearch {
  bool finished = false;              // false: cancelled (the answer is incomplete)
  LoadOutcome answer;                 // the load's outcome with the search's fields filled
  // The scene of the flat-extension search when the answer comes from it: the
  // answer's plan and structural model use that grammar too.
  std::optional<Problem> flat_scene;
  // The segments the answer's search composed; its seed retries pool theirs
  // into these (docs/pipeline.md, step 4d).
  SegmentLibrary library;
};

// `start` holds the load's fields known before the search (name, environment
// time); `flat_fallback` is GenerateResult::flat_fallback (the options' wish,
// off where flat extensions are already on).
LoadSearch search_load(const Environment& env, int load_index, const LoadOutcome& start, const GenerateOptions& options,
                       bool flat_fallback, GenerateProgress* progress);

// Sizing of the valid answer of a finished search (options.sizing,
// docs/pipeline.md "Sizing"), in the grammar and checks it was found with: a
// flat-extension answer keeps its flat tabs, a press-brake fallback's answer
// is not held to the tools. Fills the answer's sizing fields.
void size_load_answer(const Environment& env, int load_index, const GenerateOptions& options, LoadSearch& search);

}  // namespace sheetgen
