#include "sheetgen/compose/stiffening_lip.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "sheetgen/compose/edge_span.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/realisation.hpp"
#include "sheetgen/part/validity.hpp"

namespace sheetgen {

namespace {

bool edge_has_child(const Part& part, int tab, int edge) {
  for (int c : part.children(tab))
    if (part.tabs[c].parent_edge == edge) return true;
  return false;
}

}  // namespace

LipResult add_stiffening_lips(const Part& part, const Environment& env, const Problem& problem, const LipOptions& o) {
  LipResult out;
  out.part = part;
  const SheetSpec spec = SheetSpec::from(problem);
  const Manufacturing& mf = problem.manufacturing;
  const RealisedPart rp = realise(part);

  std::vector<FreeEdge> edges;
  for (const FreeEdge& e : rp.free_edges()) {
    const Tab& t = part.tabs[e.tab];
    if (e.tab == 0 || t.rivet_area >= 0 || t.riveted_to >= 0) continue;
    if (e.length < o.min_edge_length || edge_has_child(part, e.tab, e.edge)) continue;
    edges.push_back(e);
  }
  // Longest first; ties by (tab, edge) so the order does not depend on anything else.
  std::stable_sort(edges.begin(), edges.end(), [](const FreeEdge& a, const FreeEdge& b) {
    if (a.length != b.length) return a.length > b.length;
    return a.tab != b.tab ? a.tab < b.tab : a.edge < b.edge;
  });

  std::map<int, double> side_of_tab;  // tab -> sign of theta3 of its first lip
  const double lengths[] = {o.length_factor * mf.min_tab_length, mf.min_tab_length};
  for (const FreeEdge& e : edges) {
    if (out.lips >= o.max_lips) break;
    std::vector<double> signs = {1.0, -1.0};
    if (auto it = side_of_tab.find(e.tab); it != side_of_tab.end() && it->second < 0) signs = {-1.0, 1.0};
    bool placed = false;
    for (double sign : signs) {
      if (placed) break;
      const double theta3 = sign * M_PI / 2;
      // The realised edge of the current part (the input's: lips never change other tabs).
      const double margin = bend_zone_depth(theta3, spec) + 0.5e-3;
      const std::optional<EdgeSpan> span = free_edge_span(out.part, rp, e, theta3, margin, spec);
      if (!span || span->width() < mf.min_tab_width) continue;
      for (double l : lengths) {
        if (l < mf.min_tab_length || l > mf.max_tab_length) continue;
        Part q = out.part;
        const int idx = q.add_tab(e.tab, e.edge, TabParameters{span->lo, span->width(), l, 0, 0, theta3});
        const RealisedPart rq = realise(q);
        ValidityOptions vo;
        vo.only_tab = idx;
        if (!check_validity(q, rq, spec, env, vo).valid()) continue;
        if (!unfolds_cleanly(q, spec)) continue;
        out.part = std::move(q);
        out.added_area += span->width() * l;
        ++out.lips;
        side_of_tab.emplace(e.tab, sign);
        placed = true;
        break;
      }
    }
  }
  return out;
}

}  // namespace sheetgen
