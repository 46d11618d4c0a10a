#pragma once
// Rivet holes of the flat pattern (docs/manufacturing.md "Rivet holes"): every
// rivet of the bent part mapped into its tab's flat piece, so the laser cuts
// (or marks) the holes and the shop knows where each self-rivet goes. A
// self-rivet is two holes, one in each sheet it joins, that meet when the part
// is bent; it can be set once both sheets are in place, after the last bend
// on the way from the base to either of them.
#include <cstdint>
#include <string>
#include <vector>

#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

enum class RivetKind : std::uint8_t {
  Flange,  // holds a rivet flange to the structure (the rivet area)
  Self     // one sheet of a self-rivet (paper Sec. 5.2): joins two tabs of the part
};

// A rivet on the bent part: the tab it goes through and its centre there (m, world).
struct PlacedRivet {
  int tab = -1;
  Vec3 centre = Vec3::Zero();
};

// The two sheets of one self-rivet.
struct PlacedSelfRivet {
  PlacedRivet a, b;
};

struct RivetHoleOptions {
  double rivet_diameter = 3.175e-3;  // m, shank diameter d
  // m, hole diameter - d. 0.1 mm puts a 1/8 in rivet's hole at 3.275 mm, about
  // the #30 drill (3.264 mm) the rivet is installed in.
  double clearance = 0.1e-3;
};

struct RivetHole {
  RivetKind kind = RivetKind::Flange;
  int number = 0;          // 1-based, per kind: R1.. for flange rivets, S1.. for self-rivets (both holes of S<n>)
  int tab = -1;            // the tab the hole is in
  int other_tab = -1;      // self-rivet: the tab of the other hole; else -1
  Vec3 world = Vec3::Zero();  // m, centre on the bent part (in the tab's plane)
  Vec2 flat = Vec2::Zero();   // m, centre in the flat pattern's frame
  double diameter = 0;     // m, of the hole
  // Self-rivet: the bend (1-based, in bending order) after which both sheets
  // are in place; 0 when neither sheet is bent. Flange rivets: 0 (set at installation).
  int after_bend = 0;
};

// Where a point of tab `tab` (m, world; projected into the tab's plane) lies in
// the flat pattern (m, flat frame): the tab's local coordinates carried by its
// flat piece's rigid map.
Vec2 flat_position(const FlatPattern& flat, const RealisedPart& realised, int tab, const Vec3& world);

// The holes of every rivet, flange rivets first (in the given order), then per
// self-rivet its hole in a and its hole in b. `bend_order` numbers the bends as
// the drawings do (empty = tab order). Throws std::invalid_argument naming the
// rivet when a tab index is not a tab of the part.
std::vector<RivetHole> rivet_holes(const FlatPattern& flat, const RealisedPart& realised,
                                   const std::vector<PlacedRivet>& flange_rivets,
                                   const std::vector<PlacedSelfRivet>& self_rivets, const std::vector<int>& bend_order,
                                   const RivetHoleOptions& options = {});

// "R<n>" or "S<n>".
std::string hole_label(const RivetHole& hole);

}  // namespace sheetgen
