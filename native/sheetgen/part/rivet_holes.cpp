#include "sheetgen/part/rivet_holes.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "sheetgen/part/exports.hpp"

namespace sheetgen {

Vec2 flat_position(const FlatPattern& flat, const RealisedPart& realised, int tab, const Vec3& world) {
  const RealisedTab& rt = realised.tabs.at(tab);
  const FlatPiece& pc = flat.pieces.at(tab);
  // Local coordinates are what bending leaves unchanged; the out-of-plane part
  // (a self-rivet point up to 1.5 t off a gusset's mid-surface) is dropped.
  const Vec3 r = world - rt.origin;
  const double x = r.dot(rt.x_axis), y = r.dot(rt.y_axis);
  if (tab == 0) return Vec2(x, y);  // the flat frame is the base tab's
  return pc.origin + x * pc.x_axis + (y + pc.shift) * pc.y_axis;
}

namespace {

// The last bend (largest number) on the way from the base to `tab`, inclusive.
int last_bend_to(const FlatPattern& flat, const std::vector<int>& number, int tab) {
  int last = 0;
  for (int k = tab; k > 0; k = flat.pieces[k].parent) last = std::max(last, number[k]);
  return last;
}

}  // namespace

std::vector<RivetHole> rivet_holes(const FlatPattern& flat, const RealisedPart& realised,
                                   const std::vector<PlacedRivet>& flange_rivets,
                                   const std::vector<PlacedSelfRivet>& self_rivets, const std::vector<int>& bend_order,
                                   const RivetHoleOptions& o) {
  const int n = static_cast<int>(flat.pieces.size());
  if (static_cast<int>(realised.tabs.size()) != n)
    throw std::invalid_argument("rivet holes: the flat pattern has " + std::to_string(n) + " pieces but the part " +
                                std::to_string(realised.tabs.size()) + " tabs");
  auto check = [&](int tab, const std::string& what) {
    if (tab < 0 || tab >= n)
      throw std::invalid_argument(what + " names tab " + std::to_string(tab) + " of a part with " + std::to_string(n) +
                                  " tabs");
  };
  const std::vector<int> number = bend_numbers(flat, bend_order);
  const double diameter = o.rivet_diameter + o.clearance;
  std::vector<RivetHole> holes;
  for (size_t i = 0; i < flange_rivets.size(); ++i) {
    const PlacedRivet& r = flange_rivets[i];
    check(r.tab, "rivet " + std::to_string(i + 1));
    RivetHole h;
    h.kind = RivetKind::Flange;
    h.number = static_cast<int>(i) + 1;
    h.tab = r.tab;
    h.world = r.centre;
    h.flat = flat_position(flat, realised, r.tab, r.centre);
    h.diameter = diameter;
    holes.push_back(h);
  }
  for (size_t i = 0; i < self_rivets.size(); ++i) {
    const PlacedSelfRivet& s = self_rivets[i];
    check(s.a.tab, "self-rivet " + std::to_string(i + 1));
    check(s.b.tab, "self-rivet " + std::to_string(i + 1));
    const int after = std::max(last_bend_to(flat, number, s.a.tab), last_bend_to(flat, number, s.b.tab));
    for (const auto& [own, other] : {std::pair{&s.a, &s.b}, std::pair{&s.b, &s.a}}) {
      RivetHole h;
      h.kind = RivetKind::Self;
      h.number = static_cast<int>(i) + 1;
      h.tab = own->tab;
      h.other_tab = other->tab;
      h.world = own->centre;
      h.flat = flat_position(flat, realised, own->tab, own->centre);
      h.diameter = diameter;
      h.after_bend = after;
      holes.push_back(h);
    }
  }
  return holes;
}

std::string hole_label(const RivetHole& hole) {
  return (hole.kind == RivetKind::Self ? "S" : "R") + std::to_string(hole.number);
}

}  // namespace sheetgen
