#include "sheetgen/discovery/web_roots.hpp"

#include <algorithm>
#include <cmath>

#include "sheetgen/env/environment.hpp"
#include "sheetgen/part/flat_pattern.hpp"
#include "sheetgen/part/realisation.hpp"
#include "sheetgen/part/validity.hpp"

namespace sheetgen {

std::vector<Segment> make_web_roots(const Part& base, const Environment& env, const SheetSpec& spec,
                                    const FeelerPrior& prior, const WebRootOptions& options) {
  std::vector<Segment> out;
  if (base.size() < 1) return out;
  const RealisedPart rb = realise(base);
  const auto& corners = rb.tabs[0].corners;
  const int edges = base.edge_count(0);
  double longest = 0;
  for (int e = 0; e < edges; ++e) longest = std::max(longest, (corners[(e + 1) % edges] - corners[e]).norm());
  const double max_depth = options.max_depth > 0 ? options.max_depth : longest;
  const double l_min = spec.manufacturing.min_tab_length;

  Part part = base;  // the base with the webs accepted so far (each must clear the others)
  for (int e = 0; e < edges; ++e) {
    const double edge_length = (corners[(e + 1) % edges] - corners[e]).norm();
    for (double inset : options.corner_insets) {
      const double w = edge_length - inset;
      if (w < spec.manufacturing.min_tab_width) continue;
      Part trial = part;
      const int i = trial.add_tab(0, e, TabParameters{0.0, w, l_min, 0.0, 0.0, -0.5 * M_PI});
      const CastResult cast = cast_tab_length(trial, realise(trial), i, env, spec, prior);
      const double l = std::min(cast.length, max_depth);
      if (l < l_min) continue;  // an obstacle under this corner may leave room for a narrower web
      trial.tabs[i].params.l = l;
      const RealisedPart rp = realise(trial);
      ValidityOptions vo;
      vo.only_tab = i;
      if (!check_validity(trial, rp, spec, env, vo).valid() || !unfolds_cleanly(trial, spec)) continue;
      part = std::move(trial);
      Segment s;
      Tab t = part.tabs[i];
      t.parent = -1;
      t.tag = -1;
      s.tabs.push_back(t);
      s.parent = -1;
      s.parent_tab = 0;
      s.parent_edge = e;
      s.rivet_area = -1;
      s.area = w * l;
      s.length = l;
      s.bends = 1;
      s.root_a = rp.tabs[i].bend_start();
      s.root_b = rp.tabs[i].bend_end();
      const auto& c = rp.tabs[i].corners;
      s.connect_a = c[kFarEdge];
      s.connect_b = c[(kFarEdge + 1) % 4];
      s.raw_root_mid = 0.5 * (s.root_a + s.root_b);
      s.raw_connect_mid = 0.5 * (s.connect_a + s.connect_b);
      s.regularisation = 1.0;
      out.push_back(std::move(s));
      break;
    }
  }
  return out;
}

}  // namespace sheetgen
