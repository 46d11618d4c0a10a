#include "sheetgen/compose/edge_span.hpp"

#include <algorithm>
#include <cmath>

namespace sheetgen {

std::optional<EdgeSpan> free_edge_span(const Part& part, const RealisedPart& rp, const FreeEdge& e, double theta3,
                                       double end_margin, const SheetSpec& spec) {
  EdgeSpan span{end_margin, e.length - end_margin};
  if (e.tab != 0) {
    // The tab's root bend zone reaches sb into it from its root edge; the new
    // tab's zone reaches back by its own setback projected on the tab's y axis.
    const RealisedTab& t = rp.tabs[e.tab];
    const Vec3 dir = (e.b - e.a).normalized();
    const double sb = bend_setback(part.tabs[e.tab].params.theta3, spec);
    const double reach_back = bend_setback(theta3, spec) * std::abs(t.normal.cross(dir).dot(t.y_axis));
    const double need = sb + reach_back + 0.5e-3;
    const double y0 = (e.a - t.origin).dot(t.y_axis), dy = dir.dot(t.y_axis);  // y(s) = y0 + s dy
    if (std::abs(dy) < 1e-9) {
      if (y0 < need) return std::nullopt;
    } else if (dy > 0) {
      span.lo = std::max(span.lo, (need - y0) / dy);
    } else {
      span.hi = std::min(span.hi, (need - y0) / dy);
    }
  }
  if (!(span.width() > 0)) return std::nullopt;
  return span;
}

}  // namespace sheetgen
