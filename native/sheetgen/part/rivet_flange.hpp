#pragma once
// Rivet flanges: a tab that lies flush on a rivet area and carries rivets.
// Flush = every face of the rivet area under the flange is parallel to it within
// an angle tolerance and at distance t/2 (mid-surface to surface) within a
// distance tolerance, and those faces cover the whole flange (exact: clipped
// areas of the non-overlapping faces sum to the flange area).
#include <vector>

#include "sheetgen/part/validity.hpp"

namespace sheetgen {

struct FlangeAttachment {
  ValidityReason reason = ValidityReason::Ok;  // Ok, BadRivetArea, FlangeNotFlush, FlangeOffRivetArea or NoRoomForRivet
  std::string message;
  double covered_fraction = 0;     // area of the flange over flush rivet-area faces / flange area
  double max_distance_error = 0;   // m, largest |distance - t/2| over the flush faces
  double max_angle = 0;            // rad, largest normal deviation over faces under the flange
  std::vector<Vec3> rivets;        // world, m: rivet centres (at least one when ok)
  bool ok() const { return reason == ValidityReason::Ok; }
};

// Checks tab `tab` (which must have rivet_area >= 0) against problem.rivet_areas[tab.rivet_area].
FlangeAttachment check_rivet_flange(const Part& part, const RealisedPart& realised, int tab, const Problem& problem,
                                    const ValidityOptions& options = {});

// Region of a flange where rivet centres may go, in the flange's local frame
// (m): the flange minus its root bend zone (y >= setback), inset by the rivet
// edge distance on every edge. Empty when there is no room.
std::vector<Vec2> rivet_region(const Part& part, const RealisedPart& realised, int tab, const SheetSpec& spec);
// Rivet centres (world, m): a row along the flange's root direction through the
// middle of rivet_region, spaced at the rivet pitch and centred; one rivet at the
// region's centroid when the row holds only one. Empty when there is no room.
std::vector<Vec3> rivet_positions(const Part& part, const RealisedPart& realised, int tab, const SheetSpec& spec);

}  // namespace sheetgen
