#include "sheetgen/part/exports.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace sheetgen {

namespace {

std::string f6(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

std::string f9(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9f", v);
  return buf;
}

std::string f3(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

double deg(double rad) { return rad * 180.0 / M_PI; }

// Lower-left corner of the outline's bounding box: drawings start at (0, 0).
Vec2 drawing_origin(const FlatPattern& flat) {
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity());
  for (const Vec2& q : flat.outline) lo = lo.cwiseMin(q);
  return flat.outline.empty() ? Vec2::Zero() : lo;
}

Vec2 drawing_size(const FlatPattern& flat) {
  Vec2 lo = drawing_origin(flat), hi = lo;
  for (const Vec2& q : flat.outline) hi = hi.cwiseMax(q);
  return hi - lo;
}

std::string label(const FlatBend& b, int number) {
  return "B" + std::to_string(number) + (b.direction == BendDirection::Up ? " UP " : " DOWN ") + f3(deg(std::abs(b.angle)));
}

// Where a bend's label goes (m, flat frame) and its rotation (deg).
void label_place(const FlatBend& b, double text_height, Vec2& at, double& rotation_deg) {
  const Vec2 mid = 0.5 * (b.a + b.b);
  at = mid + 1.5 * text_height * b.outward;
  const Vec2 e = b.b - b.a;
  rotation_deg = deg(std::atan2(e.y(), e.x()));
  // Keep text readable (never upside down).
  if (rotation_deg > 90.0) rotation_deg -= 180.0;
  if (rotation_deg < -90.0) rotation_deg += 180.0;
}

class Dxf {
 public:
  void pair(int code, const std::string& value) { s_ << code << "\n" << value << "\n"; }
  void pair(int code, int value) { pair(code, std::to_string(value)); }
  void num(int code, double value) { pair(code, f6(value)); }
  // A point's codes: x at `code`, y at code + 10, z (always 0) at code + 20.
  void point(int code, const Vec2& p) {
    num(code, p.x());
    num(code + 10, p.y());
    num(code + 20, 0);
  }
  std::string str() const { return s_.str(); }

 private:
  std::ostringstream s_;
};

}  // namespace

std::vector<int> bend_numbers(const FlatPattern& flat, const std::vector<int>& order) {
  const int n = static_cast<int>(flat.pieces.size());
  std::vector<int> num(n, 0);
  if (order.empty()) {
    int k = 0;
    for (const FlatBend& b : flat.bends) num[b.tab] = ++k;  // flat extensions have no bend and no number
  } else {
    for (size_t k = 0; k < order.size(); ++k)
      if (order[k] > 0 && order[k] < n) num[order[k]] = static_cast<int>(k) + 1;
  }
  return num;
}

namespace {

// A self-rivet hole's note: which self-rivet and the bend after which it can be set.
std::string self_rivet_note(const RivetHole& h) {
  return hole_label(h) + (h.after_bend > 0 ? " AFTER B" + std::to_string(h.after_bend) : "");
}

// Where a hole's note goes (m, flat frame): beside the hole, clear of its rim.
Vec2 note_place(const RivetHole& h, double text_height) {
  return h.flat + Vec2(0.5 * h.diameter + 0.5 * text_height, 0.5 * h.diameter + 0.5 * text_height);
}

// DXF drawing coordinates: mm from the lower-left corner of the outline.
struct DxfFrame {
  Vec2 org;  // m, flat frame
  Vec2 operator()(const Vec2& q) const { return Vec2(1e3 * (q - org)); }
};

void dxf_header(Dxf& d, const Vec2& size_mm) {
  d.pair(0, "SECTION");
  d.pair(2, "HEADER");
  d.pair(9, "$ACADVER");
  d.pair(1, "AC1009");
  d.pair(9, "$INSUNITS");
  d.pair(70, 4);  // millimetres
  d.pair(9, "$INSBASE");
  d.point(10, Vec2::Zero());
  d.pair(9, "$EXTMIN");
  d.point(10, Vec2::Zero());
  d.pair(9, "$EXTMAX");
  d.point(10, size_mm);
  d.pair(9, "$LTSCALE");
  d.num(40, 1.0);
  d.pair(0, "ENDSEC");
}

void dxf_line_types(Dxf& d, const DrawingOptions& o) {
  d.pair(0, "TABLE");
  d.pair(2, "LTYPE");
  d.pair(70, 2);
  d.pair(0, "LTYPE");
  d.pair(2, "CONTINUOUS");
  d.pair(70, 0);
  d.pair(3, "Solid line");
  d.pair(72, 65);
  d.pair(73, 0);
  d.num(40, 0.0);
  d.pair(0, "LTYPE");
  d.pair(2, "DASHED");
  d.pair(70, 0);
  d.pair(3, "Dashed __ __ __");
  d.pair(72, 65);
  d.pair(73, 2);
  d.num(40, 1e3 * (o.dash + o.gap));
  d.num(49, 1e3 * o.dash);
  d.num(49, -1e3 * o.gap);
  d.pair(0, "ENDTAB");
}

void dxf_layers(Dxf& d) {
  struct Layer { const char* name; int color; const char* ltype; };
  const Layer layers[] = {{"0", 7, "CONTINUOUS"}, {"CUT", 7, "CONTINUOUS"}, {"BEND_UP", 1, "DASHED"},
                          {"BEND_DOWN", 5, "DASHED"}, {"RIVET_HOLES", 6, "CONTINUOUS"},
                          {"SELF_RIVET_HOLES", 4, "CONTINUOUS"}, {"ANNOTATION", 3, "CONTINUOUS"}};
  d.pair(0, "TABLE");
  d.pair(2, "LAYER");
  d.pair(70, static_cast<int>(std::size(layers)));
  for (const Layer& l : layers) {
    d.pair(0, "LAYER");
    d.pair(2, l.name);
    d.pair(70, 0);
    d.pair(62, l.color);
    d.pair(6, l.ltype);
  }
  d.pair(0, "ENDTAB");
}

void dxf_text_style(Dxf& d, const DrawingOptions& o) {
  d.pair(0, "TABLE");
  d.pair(2, "STYLE");
  d.pair(70, 1);
  d.pair(0, "STYLE");
  d.pair(2, "STANDARD");
  d.pair(70, 0);
  d.num(40, 0.0);
  d.num(41, 1.0);
  d.num(50, 0.0);
  d.pair(71, 0);
  d.num(42, 1e3 * o.text_height);
  d.pair(3, "txt");
  d.pair(4, "");
  d.pair(0, "ENDTAB");
}

void dxf_tables(Dxf& d, const DrawingOptions& o) {
  d.pair(0, "SECTION");
  d.pair(2, "TABLES");
  dxf_line_types(d, o);
  dxf_layers(d);
  dxf_text_style(d, o);
  d.pair(0, "ENDSEC");
}

// Empty, but some R12 readers expect the section.
void dxf_blocks(Dxf& d) {
  d.pair(0, "SECTION");
  d.pair(2, "BLOCKS");
  d.pair(0, "ENDSEC");
}

void dxf_closed_polyline(Dxf& d, const DxfFrame& X, const std::vector<Vec2>& pts, const char* layer) {
  d.pair(0, "POLYLINE");
  d.pair(8, layer);
  d.pair(66, 1);
  d.point(10, Vec2::Zero());
  d.pair(70, 1);  // closed
  for (const Vec2& q : pts) {
    d.pair(0, "VERTEX");
    d.pair(8, layer);
    d.point(10, X(q));
  }
  d.pair(0, "SEQEND");
  d.pair(8, layer);
}

void dxf_bend_lines(Dxf& d, const DxfFrame& X, const FlatPattern& flat) {
  for (const FlatBend& b : flat.bends) {
    const char* layer = b.direction == BendDirection::Up ? "BEND_UP" : "BEND_DOWN";
    d.pair(0, "LINE");
    d.pair(8, layer);
    d.pair(6, "DASHED");
    d.point(10, X(b.a));
    d.point(11, X(b.b));
  }
}

void dxf_bend_labels(Dxf& d, const DxfFrame& X, const FlatPattern& flat, const DrawingOptions& o) {
  const std::vector<int> number = bend_numbers(flat, o.bend_order);
  for (const FlatBend& b : flat.bends) {
    Vec2 at;
    double rot;
    label_place(b, o.text_height, at, rot);
    const Vec2 p = X(at);
    d.pair(0, "TEXT");
    d.pair(8, "ANNOTATION");
    d.point(10, p);
    d.num(40, 1e3 * o.text_height);
    d.pair(1, label(b, number[b.tab]) + "%%d");
    d.num(50, rot);
    d.pair(7, "STANDARD");
    d.pair(72, 1);  // centred on the alignment point
    d.point(11, p);
  }
}

void dxf_holes(Dxf& d, const DxfFrame& X, const std::vector<RivetHole>& holes) {
  for (const RivetHole& h : holes) {
    d.pair(0, "CIRCLE");
    d.pair(8, h.kind == RivetKind::Self ? "SELF_RIVET_HOLES" : "RIVET_HOLES");
    d.point(10, X(h.flat));
    d.num(40, 0.5e3 * h.diameter);
  }
}

void dxf_self_rivet_notes(Dxf& d, const DxfFrame& X, const std::vector<RivetHole>& holes, const DrawingOptions& o) {
  for (const RivetHole& h : holes) {
    if (h.kind != RivetKind::Self) continue;
    d.pair(0, "TEXT");
    d.pair(8, "ANNOTATION");
    d.point(10, X(note_place(h, o.text_height)));
    d.num(40, 1e3 * o.text_height);
    d.pair(1, self_rivet_note(h));
    d.pair(7, "STANDARD");
  }
}

}  // namespace

std::string flat_pattern_dxf(const FlatPattern& flat, const DrawingOptions& o, const std::vector<RivetHole>& holes) {
  const DxfFrame X{drawing_origin(flat)};
  Dxf d;
  dxf_header(d, 1e3 * drawing_size(flat));
  dxf_tables(d, o);
  dxf_blocks(d);
  d.pair(0, "SECTION");
  d.pair(2, "ENTITIES");
  dxf_closed_polyline(d, X, flat.outline, "CUT");
  dxf_bend_lines(d, X, flat);
  dxf_bend_labels(d, X, flat, o);
  dxf_holes(d, X, holes);
  dxf_self_rivet_notes(d, X, holes, o);
  d.pair(0, "ENDSEC");
  d.pair(0, "EOF");
  return d.str();
}

std::string flat_pattern_svg(const FlatPattern& flat, const DrawingOptions& o, const std::vector<RivetHole>& holes) {
  const Vec2 org = drawing_origin(flat);
  const Vec2 size = 1e3 * drawing_size(flat);
  const double margin = 5.0;  // mm
  const double W = size.x() + 2 * margin, H = size.y() + 2 * margin;
  auto X = [&](const Vec2& q) {  // mm, y down
    const Vec2 p = 1e3 * (q - org);
    return Vec2(p.x() + margin, H - margin - p.y());
  };
  const std::vector<int> number = bend_numbers(flat, o.bend_order);
  std::ostringstream s;
  s << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << f3(W) << "mm\" height=\"" << f3(H) << "mm\" viewBox=\"0 0 "
    << f3(W) << " " << f3(H) << "\">\n";
  s << "<!-- sheetgen flat pattern, millimetres, seen from the sheet's top side -->\n";
  s << "<g id=\"CUT\" fill=\"none\" stroke=\"black\" stroke-width=\"0.2\">\n<path d=\"";
  for (size_t i = 0; i < flat.outline.size(); ++i) {
    const Vec2 p = X(flat.outline[i]);
    s << (i == 0 ? "M" : " L") << f3(p.x()) << "," << f3(p.y());
  }
  s << " Z\"/>\n</g>\n";
  for (const char* layer : {"BEND_UP", "BEND_DOWN"}) {
    const bool up = std::string(layer) == "BEND_UP";
    s << "<g id=\"" << layer << "\" stroke=\"" << (up ? "red" : "blue") << "\" stroke-width=\"0.2\" stroke-dasharray=\""
      << f3(1e3 * o.dash) << "," << f3(1e3 * o.gap) << "\">\n";
    for (const FlatBend& b : flat.bends) {
      if ((b.direction == BendDirection::Up) != up) continue;
      const Vec2 a = X(b.a), c = X(b.b);
      s << "<line x1=\"" << f3(a.x()) << "\" y1=\"" << f3(a.y()) << "\" x2=\"" << f3(c.x()) << "\" y2=\"" << f3(c.y())
        << "\"/>\n";
    }
    s << "</g>\n";
  }
  for (const RivetKind kind : {RivetKind::Flange, RivetKind::Self}) {
    s << "<g id=\"" << (kind == RivetKind::Self ? "SELF_RIVET_HOLES" : "RIVET_HOLES") << "\" fill=\"none\" stroke=\""
      << (kind == RivetKind::Self ? "darkcyan" : "magenta") << "\" stroke-width=\"0.2\">\n";
    for (const RivetHole& h : holes) {
      if (h.kind != kind) continue;
      const Vec2 c = X(h.flat);
      s << "<circle cx=\"" << f3(c.x()) << "\" cy=\"" << f3(c.y()) << "\" r=\"" << f3(0.5e3 * h.diameter) << "\"/>\n";
    }
    s << "</g>\n";
  }
  s << "<g id=\"ANNOTATION\" fill=\"green\" font-family=\"sans-serif\" font-size=\"" << f3(1e3 * o.text_height)
    << "\" text-anchor=\"middle\" dominant-baseline=\"middle\">\n";
  for (const FlatBend& b : flat.bends) {
    Vec2 at;
    double rot;
    label_place(b, o.text_height, at, rot);
    const Vec2 p = X(at);
    s << "<text x=\"" << f3(p.x()) << "\" y=\"" << f3(p.y()) << "\" transform=\"rotate(" << f3(-rot) << " " << f3(p.x())
      << " " << f3(p.y()) << ")\">" << label(b, number[b.tab]) << "&#176;</text>\n";
  }
  for (const RivetHole& h : holes) {
    if (h.kind != RivetKind::Self) continue;
    const Vec2 p = X(note_place(h, o.text_height));
    s << "<text x=\"" << f3(p.x()) << "\" y=\"" << f3(p.y()) << "\" text-anchor=\"start\">" << self_rivet_note(h)
      << "</text>\n";
  }
  s << "</g>\n</svg>\n";
  return s.str();
}

std::string bend_table_csv(const FlatPattern& flat, const std::vector<int>& order,
                           const std::vector<BendToolRow>& tools) {
  std::vector<int> seq = order;
  if (seq.empty())
    for (const FlatBend& b : flat.bends) seq.push_back(b.tab);
  std::ostringstream s;
  s << "order,angle_deg,direction,inside_radius_mm,length_mm,tab,punch,die,turned_over\n";
  std::vector<const FlatBend*> bend_of(flat.pieces.size(), nullptr);
  for (const FlatBend& b : flat.bends) bend_of[b.tab] = &b;
  int k = 0;
  for (int t : seq) {
    if (t <= 0 || t >= static_cast<int>(bend_of.size()) || !bend_of[t]) continue;
    const FlatBend& b = *bend_of[t];
    s << ++k << "," << f6(deg(std::abs(b.angle))) << "," << (b.direction == BendDirection::Up ? "UP" : "DOWN") << ","
      << f6(1e3 * b.inside_radius) << "," << f6(1e3 * b.length) << "," << t;
    const auto tool = std::find_if(tools.begin(), tools.end(), [&](const BendToolRow& r) { return r.tab == t; });
    if (tool == tools.end())
      s << ",,,\n";
    else
      s << "," << tool->punch << "," << tool->die << "," << (tool->turned_over ? "yes" : "no") << "\n";
  }
  return s.str();
}

std::string rivet_table_csv(const FlatPattern& flat, const std::vector<RivetHole>& holes) {
  const Vec2 org = drawing_origin(flat);
  std::ostringstream s;
  s << "label,kind,tab,other_tab,x_mm,y_mm,diameter_mm,after_bend,world_x_m,world_y_m,world_z_m\n";
  for (const RivetHole& h : holes) {
    const Vec2 q = 1e3 * (h.flat - org);
    const bool self = h.kind == RivetKind::Self;
    s << hole_label(h) << "," << (self ? "self" : "flange") << "," << h.tab << ","
      << (self ? std::to_string(h.other_tab) : "") << "," << f6(q.x()) << "," << f6(q.y()) << "," << f6(1e3 * h.diameter)
      << "," << (self ? std::to_string(h.after_bend) : "") << "," << f9(h.world.x()) << "," << f9(h.world.y()) << ","
      << f9(h.world.z()) << "\n";
  }
  return s.str();
}

std::string part_obj(const RealisedPart& rp) {
  std::ostringstream s;
  s << "# sheetgen bent mid-surface, metres\n";
  int base = 1;
  for (size_t i = 0; i < rp.tabs.size(); ++i) {
    const auto& c = rp.tabs[i].corners;
    s << "o tab_" << i << "\n";
    for (const Vec3& p : c) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "v %.9f %.9f %.9f\n", p.x(), p.y(), p.z());
      s << buf;
    }
    s << "f";
    for (size_t k = 0; k < c.size(); ++k) s << " " << base + static_cast<int>(k);
    s << "\n";
    base += static_cast<int>(c.size());
  }
  return s.str();
}

nlohmann::json part_json(const Part& part, const RealisedPart& rp) {
  auto v3 = [](const Vec3& p) { return nlohmann::json::array({p.x(), p.y(), p.z()}); };
  nlohmann::json tabs = nlohmann::json::array();
  for (int i = 0; i < part.size(); ++i) {
    const Tab& t = part.tabs[i];
    nlohmann::json j;
    j["index"] = i;
    j["parent"] = t.parent;
    j["parent_edge"] = t.parent_edge;
    j["rivet_area"] = t.rivet_area;
    if (i > 0) {
      j["parameters"] = {{"d", t.params.d},           {"w", t.params.w},           {"l", t.params.l},
                         {"theta1", t.params.theta1}, {"theta2", t.params.theta2}, {"theta3", t.params.theta3}};
    } else {
      j["parameters"] = nullptr;
    }
    nlohmann::json corners = nlohmann::json::array();
    for (const Vec3& p : rp.tabs[i].corners) corners.push_back(v3(p));
    j["corners"] = corners;
    j["normal"] = v3(rp.tabs[i].normal);
    tabs.push_back(j);
  }
  return tabs;
}

nlohmann::json flat_pattern_json(const FlatPattern& flat, const std::vector<int>& order,
                                 const std::vector<RivetHole>& holes) {
  auto v2 = [](const Vec2& p) { return nlohmann::json::array({p.x(), p.y()}); };
  const std::vector<int> number = bend_numbers(flat, order);
  nlohmann::json j;
  nlohmann::json outline = nlohmann::json::array();
  for (const Vec2& q : flat.outline) outline.push_back(v2(q));
  j["outline"] = nlohmann::json::array({outline});
  nlohmann::json bends = nlohmann::json::array();
  for (const FlatBend& b : flat.bends) {
    bends.push_back({{"tab", b.tab},
                     {"parent", b.parent},
                     {"number", number[b.tab]},
                     {"a", v2(b.a)},
                     {"b", v2(b.b)},
                     {"angle", b.angle},
                     {"direction", b.direction == BendDirection::Up ? "up" : "down"},
                     {"length", b.length},
                     {"inside_radius", b.inside_radius},
                     {"allowance", b.allowance},
                     {"setback", b.setback}});
  }
  j["bends"] = bends;
  nlohmann::json reliefs = nlohmann::json::array();
  for (const FlatRelief& r : flat.reliefs) {
    nlohmann::json poly = nlohmann::json::array();
    for (const Vec2& q : r.polygon) poly.push_back(v2(q));
    reliefs.push_back({{"parent", r.parent}, {"tab", r.tab}, {"polygon", poly}, {"width", r.width}, {"depth", r.depth}});
  }
  j["reliefs"] = reliefs;
  nlohmann::json hole_list = nlohmann::json::array();
  for (const RivetHole& h : holes) {
    const bool self = h.kind == RivetKind::Self;
    hole_list.push_back({{"label", hole_label(h)},
                         {"kind", self ? "self" : "flange"},
                         {"tab", h.tab},
                         {"other_tab", h.other_tab},
                         {"centre", v2(h.flat)},
                         {"diameter", h.diameter},
                         {"after_bend", h.after_bend}});
  }
  j["holes"] = hole_list;
  j["area_m2"] = flat.area();
  j["frame"] = {{"origin", {flat.frame.origin.x(), flat.frame.origin.y(), flat.frame.origin.z()}},
                {"x_axis", {flat.frame.x_axis.x(), flat.frame.x_axis.y(), flat.frame.x_axis.z()}},
                {"y_axis", {flat.frame.y_axis.x(), flat.frame.y_axis.y(), flat.frame.y_axis.z()}}};
  return j;
}

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error("cannot open " + path + " for writing");
  f << text;
  f.close();  // a full disk often shows only when the buffer is flushed
  if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace sheetgen
