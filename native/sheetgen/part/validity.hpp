#pragma once
// Validity of a realised part (docs/architecture.md "Manufacturing plan", paper Sec. 3.1
// C_E and C_M): tab limits, bend-zone room, self-intersection, obstacle
// clearance and rivet-flange attachment. Every failure names a reason, the tab(s)
// and a one-sentence message. Flat-pattern and bend-order failures use the same
// reasons (flat_pattern.hpp, bend_sequence.hpp).
#include <cmath>
#include <string>
#include <vector>

#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

class Environment;

enum class ValidityReason : std::uint8_t {
  Ok = 0,
  DegenerateTab,          // far edge undefined (|theta1 + theta2| >= 90 deg) or a side of length <= 0
  RootOutsideParentEdge,  // d < 0 or d + w > parent edge length
  TabTooNarrow,           // w < min_tab_width
  TabTooShort,            // l < min_tab_length (plain tabs)
  TabTooLong,             // l > max_tab_length
  BendAngleTooSmall,      // |theta3| < min_bend_angle
  BendAngleTooLarge,      // |theta3| > max_bend_angle
  SkewTooLarge,           // |theta1| or |theta2| > max_skew
  BendZonesOverlap,       // a child's bend zone reaches into this tab's root bend zone
  FlangeTooShort,         // rivet flange l < min_flange
  SelfIntersection,       // two non-adjacent tabs closer than t + self_gap
  ObstacleCollision,      // mid-surface closer than t/2 + clearance to a non-allowed obstacle
  BadRivetArea,           // rivet flange names a rivet area that does not exist
  FlangeNotFlush,         // rivet-area face under the flange not parallel / not at t/2
  FlangeOffRivetArea,     // part of the flange does not project onto its rivet area
  NoRoomForRivet,         // no point of the flat flange keeps the rivet edge distance from every edge
  FlatJunctionOutsideEdge,// the tab's flat root does not lie within its parent's flat edge
  ReliefDoesNotFit,       // a bend relief leaves its parent or the bend ends too close to a corner
  FlatPatternOverlap,     // flat pieces overlap or come closer than the kerf
  NoBendSequence,         // every bend order examined collides while folding
  PressBrake,             // no bend order examined can be made with the press brake's tools
};
const char* to_string(ValidityReason reason);

struct Violation {
  ValidityReason reason = ValidityReason::Ok;
  int tab = -1;       // the tab at fault
  int other = -1;     // the other tab (self-intersection, overlap), obstacle-free otherwise
  double value = 0;   // the offending number in SI units (the distance, length or angle checked)
  std::string message;
};

struct ValidityReport {
  std::vector<Violation> violations;
  bool valid() const { return violations.empty(); }
  ValidityReason first_reason() const { return violations.empty() ? ValidityReason::Ok : violations.front().reason; }
  bool has(ValidityReason r) const;
  std::string summary() const;  // first message, or "valid"
};

struct ValidityOptions {
  bool stop_at_first = true;       // return after the first violation (the search only needs yes/no)
  int only_tab = -1;               // >= 0: only checks involving this tab (incremental checks during growth)
  double self_gap = 0.2e-3;        // m, gap kept beyond t between non-adjacent tabs
  double length_tolerance = 1e-9;  // m, slack on d, d + w and length limits (round-off of the search)
  double angle_tolerance = 1e-9;   // rad, slack on angle limits
  double flush_distance_tolerance = 0.25e-3;     // m, |flange-to-face distance - t/2| allowed
  double flush_angle_tolerance = M_PI / 180.0;   // rad, flange vs rivet-area face normal
  double contact_sample_spacing = 0;             // m, Environment::polygon_contact spacing (0 = its default)
};

// Parameter limits, degenerate shapes, roots on their parent edges, bend-zone room.
ValidityReport check_limits(const Part& part, const RealisedPart& realised, const SheetSpec& spec,
                            const ValidityOptions& options = {});
// Non-adjacent tab pairs (adjacent = parent and child) keep t + self_gap.
ValidityReport check_self_intersection(const Part& part, const RealisedPart& realised, const SheetSpec& spec,
                                       const ValidityOptions& options = {});
// Rivet flanges flush on their rivet areas with room for a rivet, then obstacle clearance.
ValidityReport check_environment(const Part& part, const RealisedPart& realised, const Environment& env,
                                 const ValidityOptions& options = {});
// All of the above, cheapest first: the limits of `spec`, the grammar of the
// search that asks (a pass with flat extensions or right angles differs from
// the environment's problem there), and the environment's scene.
ValidityReport check_validity(const Part& part, const RealisedPart& realised, const SheetSpec& spec,
                              const Environment& env, const ValidityOptions& options = {});
// The same in the grammar of the environment's own problem.
ValidityReport check_validity(const Part& part, const RealisedPart& realised, const Environment& env,
                              const ValidityOptions& options = {});
// Everything that needs no environment (limits + self-intersection).
ValidityReport check_validity(const Part& part, const RealisedPart& realised, const SheetSpec& spec,
                              const ValidityOptions& options = {});

}  // namespace sheetgen
