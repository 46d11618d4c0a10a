#pragma once
// Sizing (our extension, docs/pipeline.md "Sizing"): the answer of a load is
// cut down to what its limits need. Discovery widens every segment as far as
// the environment lets it (docs/discovery.md "Geometry optimisation"), because
// a wide plate is a stiff one, and the composition only chooses among those
// segments; so a valid part often carries material its cases do not need
// (the bay's power_supply ends at a quarter of its compliance limit). A stress
// engineer sizes such a bracket to its margins: here each tab is narrowed in
// turn while the part stays valid, which lowers the sheet and, through the
// shorter rivet flanges, the rivets.
#include <vector>

#include "sheetgen/compose/candidate.hpp"
#include "sheetgen/core/problem.hpp"

namespace sheetgen {

class Environment;

struct SizingOptions {
  // A trial cuts this share of a tab's width above min_tab_width, centred on
  // the tab or at either end; the shares are tried largest first, each over
  // every tab, largest tab first.
  std::vector<double> shares{0.5, 0.25, 0.125};
  double min_cut = 1e-3;  // m: a smaller cut is not tried
  // No new cut is started once this many trials were evaluated (a cut is up
  // to three trials). The tabs are tried largest (w l) first, so the
  // budget goes where the sheet is; it bounds the time on large parts, where
  // each trial is a large analysis (docs/pipeline.md "Sizing").
  int max_trials = 24;
  // Trials are analysed on the search mesh (this many times the default
  // element size, as in the composition); the sized part is checked once more
  // at the default mesh, and kept only if it passes there. When it does not,
  // the part before its last cut is checked, and so on, at most final_checks
  // times; then the answer stays as it was.
  double trial_element_factor = 1.5;
  int final_checks = 3;
  int threads = 0;  // 0 = all cores; the result does not depend on it
};

struct SizingResult {
  Candidate part;           // the sized part, valid at the default mesh (the input when nothing was cut)
  int trials = 0;           // trial parts evaluated (geometry, cost and FEM)
  int cuts = 0;             // cuts in the sized part
  int final_checks = 0;     // analyses at the default mesh
  double cost_before = 0;   // m^2, search score (core/cost_model.hpp) of the input
  double area_before = 0;   // m^2, flat-pattern material of the input
  bool final_check_failed = false;  // every sized part checked missed a limit at the default mesh: the input was kept
};

// Narrows tab `tab` of `part` by cut_start (m) at its root start and cut_end at
// its root end. Its children keep their root start in the world and are
// clipped to their parent's edge; false (and `part` unchanged) when a tab
// would fall below min_width.
bool narrow_tab(Part& part, int tab, double cut_start, double cut_end, double min_width);

// Sizes `answer`, a valid part of load `load_index` checked at the default
// mesh. Parts with gussets (self-rivets) are returned as they are: a gusset's
// rivets sit at fixed points of both tabs.
SizingResult size_part(const Problem& problem, const Environment& env, int load_index, const Candidate& answer,
                       const SizingOptions& options = {});

}  // namespace sheetgen
