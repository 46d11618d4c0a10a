#include "sheetgen/core/press_brake_tooling.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>

#include "sheetgen/core/json_reader.hpp"

namespace sheetgen {

namespace {

constexpr double kDeg = M_PI / 180.0;

// An angle of a tool (rad): strictly between 0 and 180 deg.
double tool_angle_or(const JsonNode& node, const char* key, double fallback) {
  const double a = node.positive_or(key, fallback);
  if (a >= M_PI) node.at(key).fail("must lie between 0 and pi (radians), got " + std::to_string(a));
  return a;
}

PunchSpec parse_punch(const JsonNode& node) {
  node.expect_object();
  reject_unknown(node, {"name", "kind", "tip_angle", "height", "body_width", "throat_bottom", "throat_top"});
  PunchSpec p;
  if (auto n = node.find("name")) p.name = n->as_string();
  if (auto k = node.find("kind")) {
    const std::string kind = k->as_string();
    if (kind != "straight" && kind != "gooseneck") k->fail("must be \"straight\" or \"gooseneck\", got \"" + kind + "\"");
    p.kind = kind == "straight" ? PunchKind::Straight : PunchKind::Gooseneck;
  }
  p.tip_angle = tool_angle_or(node, "tip_angle", p.tip_angle);
  p.height = node.positive_or("height", p.height);
  p.body_width = node.positive_or("body_width", p.body_width);
  p.throat_bottom = node.positive_or("throat_bottom", p.throat_bottom);
  p.throat_top = node.positive_or("throat_top", p.throat_top);
  if (p.kind == PunchKind::Gooseneck && !(p.throat_bottom < p.throat_top && p.throat_top < p.height))
    node.fail("a gooseneck needs throat_bottom < throat_top < height (m above the tip)");
  return p;
}

DieSpec parse_die(const JsonNode& node) {
  node.expect_object();
  reject_unknown(node, {"name", "v_opening", "v_per_thickness", "angle", "height", "width", "min_flange_ratio"});
  DieSpec d;
  if (auto n = node.find("name")) d.name = n->as_string();
  if (node.has("v_opening") && node.has("v_per_thickness")) node.fail("give v_opening or v_per_thickness, not both");
  if (auto v = node.find("v_opening")) d.v_opening = v->as_positive();
  d.v_per_thickness = node.positive_or("v_per_thickness", d.v_per_thickness);
  d.angle = tool_angle_or(node, "angle", d.angle);
  d.height = node.positive_or("height", d.height);
  if (auto w = node.find("width")) d.width = w->as_positive();
  d.min_flange_ratio = node.positive_or("min_flange_ratio", d.min_flange_ratio);
  return d;
}

template <class T, class Parse>
std::vector<T> parse_list(const JsonNode& node, const char* what, Parse parse) {
  node.expect_array();
  if (node.size() == 0) node.fail(std::string("must list at least one ") + what);
  std::vector<T> out;
  for (size_t i = 0; i < node.size(); ++i) out.push_back(parse(node.at(i)));
  return out;
}

}  // namespace

PressBrakeTooling default_press_brake_tooling() {
  PressBrakeTooling t;
  PunchSpec straight, gooseneck, tall;
  gooseneck.kind = PunchKind::Gooseneck;
  // A box of depth H needs a punch taller than H (its sides pass under the
  // ram) and H of room under that punch before the bend (a side stands under
  // it): open height >= die + 2 H. H = 175 mm, the deepest four-sided box of
  // shop tooling (docs/manufacturing.md "Press brake"), with the clearance:
  // a 180 mm punch and 420 mm of open height.
  tall.height = 0.180;
  t.punches = {straight, gooseneck, tall};
  t.open_height = 0.42;
  // 8 t first (the usual choice for aluminium sheet), then the narrower and
  // the wider; the acute die last, for bends past 90 deg.
  for (double m : {8.0, 6.0, 10.0, 12.0}) {
    DieSpec d;
    d.v_per_thickness = m;
    t.dies.push_back(d);
  }
  DieSpec acute;
  acute.angle = 30 * kDeg;
  acute.min_flange_ratio = 1.1;
  t.dies.push_back(acute);
  return t;
}

double die_opening(const PressBrakeTooling& tooling, const DieSpec& die, double thickness) {
  if (die.v_opening > 0) return die.v_opening;
  return std::max(tooling.min_v_opening, die.v_per_thickness * thickness);
}

void parse_press_brake_tooling(const JsonNode& node, PressBrakeTooling& t) {
  node.expect_object();
  reject_unknown(node, {"punches", "dies", "open_height", "ram_width", "bed_width", "springback", "min_v_opening"});
  if (auto p = node.find("punches")) t.punches = parse_list<PunchSpec>(*p, "punch", parse_punch);
  if (auto d = node.find("dies")) t.dies = parse_list<DieSpec>(*d, "die", parse_die);
  t.open_height = node.positive_or("open_height", t.open_height);
  t.ram_width = node.positive_or("ram_width", t.ram_width);
  t.bed_width = node.positive_or("bed_width", t.bed_width);
  t.springback = node.non_negative_or("springback", t.springback);
  if (t.springback >= 0.5 * M_PI) node.at("springback").fail("must be below pi/2 (radians)");
  t.min_v_opening = node.positive_or("min_v_opening", t.min_v_opening);
  // A punch that leaves no room under it even on the lowest die could never
  // bend anything: that is a typing error, not a tool.
  double lowest_die = std::numeric_limits<double>::infinity();
  for (const DieSpec& d : t.dies) lowest_die = std::min(lowest_die, d.height);
  for (size_t i = 0; i < t.punches.size(); ++i)
    if (t.punches[i].height + lowest_die >= t.open_height) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "open_height %.3f m leaves no room under punches[%zu] (%.3f m high) on the lowest die (%.3f m)",
                    t.open_height, i, t.punches[i].height, lowest_die);
      node.fail(buf);
    }
}

}  // namespace sheetgen
