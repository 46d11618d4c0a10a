#pragma once
// Bend sequence (docs/architecture.md "Manufacturing plan", paper Sec. 3.1 C_M): starting
// from the flat sheet, bends are made one at a time, each swept from 0 to its
// angle. Every sampled intermediate state of the sharp mid-surface model must
// keep non-adjacent tabs t + gap apart. Only the part's own collisions are
// checked here; part/press_brake.hpp checks the tools and the machine.
#include <string>
#include <vector>

#include "sheetgen/part/press_brake.hpp"
#include "sheetgen/part/validity.hpp"

namespace sheetgen {

struct BendSequenceOptions {
  double max_step = M_PI / 180.0;  // rad, largest angle increment between sampled states of a sweep
  double gap = 0.2e-3;             // m, kept beyond t between non-adjacent tabs (as ValidityOptions::self_gap)
  int max_sweeps = 5000;           // search budget: bend sweeps simulated by plan_bend_sequence
  // Skip the states of a sweep in which a pair of tabs is provably clear
  // (docs/manufacturing.md "Bend sequence"): the same answers as checking
  // every state, which `false` does (the reference the tests compare with).
  bool skip_clear_states = true;
  // plan_bend_sequence only: when set, a bend is taken next only if one of
  // these press-brake tools makes it in that state (part/press_brake.hpp).
  const ToolSet* tools = nullptr;
};

struct BendCollision {
  int bend_tab = -1;    // the tab being bent when it happened (-1: already in the flat sheet)
  double fraction = 0;  // of that bend's angle, (0, 1]
  double angle = 0;     // rad, that bend's angle at the collision
  int tab_a = -1, tab_b = -1;  // the tabs that came too close (tab_a moves)
  double distance = 0;  // m
};

struct BendSequenceResult {
  ValidityReason status = ValidityReason::Ok;  // Ok or NoBendSequence
  std::string message;
  std::vector<int> order;     // tab indices in bending order (every bent tab when ok; flat extensions are not bent)
  std::vector<BendTooling> tooling;  // with options.tools and ok: the punch and die of each bend of `order`
  BendCollision collision;    // when not ok: the collision of the checked order / the deepest failure of the search
  int sweeps = 0;             // bend sweeps simulated
  bool exhausted = false;     // plan_bend_sequence stopped at max_sweeps
  bool ok() const { return status == ValidityReason::Ok; }
};

// Simulates one order (a permutation of the bent tabs' indices).
// Throws std::invalid_argument when `order` is not such a permutation.
BendSequenceResult check_bend_order(const Part& part, const std::vector<int>& order, const SheetSpec& spec,
                                    const BendSequenceOptions& options = {});

// Depth-first search over orders, shallow bends first, pruning sets of done
// bends already known to be dead ends; with options.tools, over the orders the
// press brake can make. Deterministic.
BendSequenceResult plan_bend_sequence(const Part& part, const SheetSpec& spec, const BendSequenceOptions& options = {});

}  // namespace sheetgen
