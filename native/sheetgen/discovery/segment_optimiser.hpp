#pragma once
// Geometry optimisation of a connected feeler (paper Sec. 4.2): contraction of
// the constant-force spring network (summed tab length minimised, every
// intermediate state valid), merging of nearly coplanar consecutive tabs, and
// widening (w up, d down until collision or the parent edge is covered).
#include <vector>

#include "sheetgen/discovery/feeler.hpp"
#include "sheetgen/part/part.hpp"

namespace sheetgen {

class Environment;

// A segment being optimised inside the part it must stay valid in (the chain's
// frozen tabs): tabs first, first + 1, ..., flange form a chain (each the child
// of the previous), the last is the rivet flange lying on `plane`.
struct SegmentWork {
  Part part;
  int first = -1;
  int flange = -1;
  RivetPlane plane;
  int feeler_count() const { return flange - first; }
  double length() const;  // m, sum of l over the segment's non-flange tabs
  double area() const;    // m^2, sum of w l over the segment's tabs (flange included)
};

struct ContractOptions {
  double step = 8e-3;          // m, initial largest change of one variable per step (angles scaled by angle_scale)
  double max_step = 64e-3;     // m, the step grows x1.5 after each accepted step up to this
  double min_step = 0.1e-3;    // m, stop when the step has been halved below this
  int max_steps = 200;         // gradient evaluations (each followed by a halving line search)
  double angle_scale = 0.05;   // m per rad: a bend angle change of 1 rad counts as 5 cm of motion
  double finite_difference = 1e-6;  // m (and m / angle_scale for angles)
  bool record_states = false;  // keep every accepted state (tests)
  bool check_unfold = true;    // a step must also keep the part unfoldable (when the start state unfolds)
};

struct ContractResult {
  bool converged = false;      // the step fell below min_step (no valid descent left)
  int steps = 0;               // accepted steps
  double length_before = 0, length_after = 0;  // m
  std::vector<double> lengths; // m, after each accepted step
  std::vector<Part> states;    // each accepted state when record_states
};

// Steepest descent of E = k_base * sum_i (l_i - l_min) (Eq. 3, the constant-force
// spring energy) over the free lengths and bend angles of the feeler tabs; the
// last feeler's (l, theta1) and the flange's theta3 follow from the rivet
// attachment (attach_flange). A step is taken only when the new state is valid
// (check_validity with the environment) and shorter; otherwise it is halved.
ContractResult contract_segment(SegmentWork& work, const Environment& env, const SheetSpec& spec,
                                const ContractOptions& options = {});

struct ShortcutOptions {
  bool enabled = true;
  int bend_samples = 8;        // |theta3| samples on [min_bend_angle, max_bend_angle] per sign (plus the current theta3)
  int max_depth = 3;           // truncation points tried: the first max_depth + 1 tabs
  int skew_samples = 3;        // theta2 samples on [-max_skew/2, max_skew/2] (plus the current theta2)
  int max_checks = 24;         // full validity checks per truncation point (cheapest candidates first)
  double max_length_ratio = 0.98;  // keep a shortcut only when it is at most this times the current length
};
struct ShortcutResult {
  int removed_tabs = 0;        // feeler tabs dropped
  double length_before = 0, length_after = 0;  // m
};
// Re-aiming (the large-scale part of the contraction): for every tab k of the
// segment, drops the tabs after k and re-aims k (theta2, theta3 sampled, then
// (l, theta1) and the flange from attach_flange) straight at the rivet plane;
// the shortest state that is valid and unfolds replaces the segment when it is
// at most max_length_ratio times as long. A feeler route that hugged obstacles
// tab by tab becomes a direct one the spring contraction then polishes.
ShortcutResult shortcut_segment(SegmentWork& work, const Environment& env, const SheetSpec& spec,
                                const ShortcutOptions& options = {});

struct MergeOptions {
  double max_angle = -1;  // rad, merge a child bent by at most this; < 0 = min(1.5 * min_bend_angle, 10 deg)
  double max_length_growth = 0.05;  // accept a merge that lengthens the segment by at most 5 %
};
// Merges consecutive tabs whose bend is nearly flat into one tab (one bend
// fewer), re-attaching the flange; a merge is kept when the result is valid.
// Returns the number of merges.
int merge_coplanar(SegmentWork& work, const Environment& env, const SheetSpec& spec, const MergeOptions& options = {});

struct WidenOptions {
  double initial_step = 16e-3;  // m, first widening per step; halved after a failed step
  double min_step = 2e-3;       // m, stop when the step falls below this
  bool reattach_flange = true;  // widening the last feeler re-attaches it and spans the flange over its far edge
};
struct WidenResult {
  int steps = 0;                     // accepted widenings
  double area_before = 0, area_after = 0;  // m^2
};
// For each tab from the root to the flange: w up and d down (symmetric, then
// towards either end) while the part stays valid and unfolds (the flat root of a
// skewed tab must stay on its parent edge: FlatJunctionOutsideEdge), keeping the
// children where they are on the widened edge.
WidenResult widen_segment(SegmentWork& work, const Environment& env, const SheetSpec& spec,
                          const WidenOptions& options = {});

// Full validity (environment included) and a clean unfold of the work part.
bool segment_valid(const SegmentWork& work, const Environment& env, const SheetSpec& spec);

// Removes tab j, hanging its children on the same edge index of j's parent at
// the same world position of their root start; indices after j shift down.
Part remove_tab_reparent(const Part& part, int j);

}  // namespace sheetgen
