#pragma once
// Where on a free edge a new tab may start. Shared by the tabs composition
// adds after the search (gussets for self-riveting, stiffening lips): both
// must leave the bend zones at the edge's ends and, on the side edge of a bent
// tab, that tab's own root bend zone alone (validity: BendZonesOverlap).
#include <optional>

#include "sheetgen/part/part.hpp"
#include "sheetgen/part/realisation.hpp"

namespace sheetgen {

struct EdgeSpan {
  double lo = 0, hi = 0;  // m, along the edge from FreeEdge::a
  double width() const { return hi - lo; }
};

// The stretch of `edge` a tab bent by theta3 (rad) may use: end_margin (m)
// kept at both ends, and on a non-base tab the part where the new tab's bend
// zone clears the tab's root bend zone (plus 0.5 mm). nullopt when nothing is left.
std::optional<EdgeSpan> free_edge_span(const Part& part, const RealisedPart& realised, const FreeEdge& edge, double theta3,
                                       double end_margin, const SheetSpec& spec);

}  // namespace sheetgen
