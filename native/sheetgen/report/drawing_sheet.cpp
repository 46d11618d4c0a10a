#include "sheetgen/report/drawing_sheet.hpp"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>

#include "sheetgen/core/atomic_file.hpp"
#include "sheetgen/report/dimension_line.hpp"
#include "sheetgen/report/drawing_scale.hpp"
#include "sheetgen/report/isometric_view.hpp"
#include "sheetgen/report/sheet_pen.hpp"
#include "sheetgen/report/sheet_table.hpp"

namespace sheetgen {
namespace {

using namespace sheet;

constexpr double kPointsPerMm = 72.0 / 25.4;

struct Rect {  // mm on the page, y down
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double w() const { return x1 - x0; }
  double h() const { return y1 - y0; }
};

// The blocks of the sheet (docs/drawing.md "Layout"). ISO 5457: a 20 mm
// filing margin on the left, 10 mm elsewhere; the title block in the
// bottom-right corner (ISO 7200).
struct Regions {
  double page_w = 0, page_h = 0;
  Rect frame, flat_view, part_data, checks, iso, right_tables, title;
};

Regions regions(PaperSize paper) {
  Regions r;
  r.page_w = paper == PaperSize::A3 ? 420 : 297;
  r.page_h = paper == PaperSize::A3 ? 297 : 210;
  r.frame = {20, 10, r.page_w - 10, r.page_h - 10};
  const double col_w = paper == PaperSize::A3 ? 140 : 112;  // the right column: picture, tables, title block
  const double col_x = r.frame.x1 - col_w;
  const double strip_h = paper == PaperSize::A3 ? 54 : 46;  // part data and checks under the flat pattern
  const double title_h = paper == PaperSize::A3 ? 38 : 34;
  const double iso_h = paper == PaperSize::A3 ? 84 : 58;
  r.title = {col_x, r.frame.y1 - title_h, r.frame.x1, r.frame.y1};
  r.iso = {col_x, r.frame.y0, r.frame.x1, r.frame.y0 + iso_h};
  r.right_tables = {col_x, r.iso.y1, r.frame.x1, r.title.y0};
  r.flat_view = {r.frame.x0, r.frame.y0, col_x, r.frame.y1 - strip_h};
  const double half = (col_x - r.frame.x0) * 0.46;
  r.part_data = {r.frame.x0, r.flat_view.y1, r.frame.x0 + half, r.frame.y1};
  r.checks = {r.part_data.x1, r.flat_view.y1, col_x, r.frame.y1};
  return r;
}

// ---- numbers as printed -----------------------------------------------------

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return std::string(buf) == "-0" ? "0" : buf;
}

// Three significant digits, no exponent: "0.0312", "1.23", "456".
std::string sig3(double v) {
  if (v == 0 || !std::isfinite(v)) return fixed(v, 0);
  const int decimals = std::clamp(2 - static_cast<int>(std::floor(std::log10(std::abs(v)))), 0, 9);
  return fixed(v, decimals);
}

std::string mm(double m, int decimals = 1) { return fixed(m * 1e3, decimals); }
std::string deg(double rad) { return fixed(rad * 180 / M_PI, 1) + "\u00B0"; }

// The rivet's shank as a shop names it: "5/32 in (3.97 mm)" when it is a
// whole number of 32nds of an inch, else millimetres.
std::string rivet_size(double d) {
  if (!(d > 0)) return "-";
  const double k = d / (25.4e-3 / 32);
  const int n = static_cast<int>(std::lround(k));
  if (std::abs(k - n) > 1e-3 || n == 0) return mm(d, 2) + " mm";
  int num = n, den = 32;
  while (num % 2 == 0 && den > 1) num /= 2, den /= 2;
  return std::to_string(num) + "/" + std::to_string(den) + " in (" + mm(d, 2) + " mm)";
}

// ---- inputs -----------------------------------------------------------------

void check_finite(double v, const std::string& field) {
  if (!std::isfinite(v)) throw std::invalid_argument("drawing sheet: " + field + " is not a finite number");
}

void check_part(const DrawingSheetPart& p, const DrawingSheetOptions& o) {
  if (o.text_height < 1.8e-3 || o.text_height > 5e-3 || !std::isfinite(o.text_height))
    throw std::invalid_argument("DrawingSheetOptions::text_height " + std::to_string(o.text_height) +
                                " m is not in 1.8e-3..5e-3");
  if (p.outline.size() < 3)
    throw std::invalid_argument("drawing sheet of '" + p.part_name + "': the flat pattern's outline has " +
                                std::to_string(p.outline.size()) + " points (at least 3 needed)");
  for (const SheetPoint& q : p.outline) check_finite(q.x + q.y, "an outline point of '" + p.part_name + "'");
  for (const SheetBend& b : p.bends) check_finite(b.a.x + b.a.y + b.b.x + b.b.y, "bend B" + std::to_string(b.number));
  for (const SheetHole& h : p.holes) check_finite(h.centre.x + h.centre.y + h.diameter, "hole " + h.label);
  for (const auto& t : p.tabs)
    for (const SheetPoint3& q : t) check_finite(q.x + q.y + q.z, "a tab corner of '" + p.part_name + "'");
}

struct Extent {
  SheetPoint lo, hi;  // m, flat frame
};

Extent outline_extent(const DrawingSheetPart& p) {
  Extent e{p.outline.front(), p.outline.front()};
  for (const SheetPoint& q : p.outline) {
    e.lo = {std::min(e.lo.x, q.x), std::min(e.lo.y, q.y)};
    e.hi = {std::max(e.hi.x, q.x), std::max(e.hi.y, q.y)};
  }
  return e;
}

// ---- the flat pattern -------------------------------------------------------

// Flat frame (m) -> page (mm) at 1:n, the outline's lower-left corner at (left, bottom).
struct FlatMap {
  Extent e;
  double n = 1, left = 0, bottom = 0;
  double x(double fx) const { return left + (fx - e.lo.x) * 1e3 / n; }
  double y(double fy) const { return bottom - (fy - e.lo.y) * 1e3 / n; }
};

// Room kept in the flat view: its title and scale bar above, the overall
// dimensions below and to the right (mm).
constexpr double kViewTop = 16, kViewBelow = 16, kViewRight = 18, kViewLeft = 6;

FlatMap place_flat(const DrawingSheetPart& p, const Rect& view, DrawingSheetLayout& layout) {
  FlatMap m;
  m.e = outline_extent(p);
  const double w = m.e.hi.x - m.e.lo.x, h = m.e.hi.y - m.e.lo.y;
  const double box_w = view.w() - kViewLeft - kViewRight, box_h = view.h() - kViewTop - kViewBelow;
  m.n = drawing_scale_denominator(w, h, box_w, box_h);
  const double pw = w * 1e3 / m.n, ph = h * 1e3 / m.n;
  m.left = view.x0 + kViewLeft + (box_w - pw) / 2;
  m.bottom = view.y0 + kViewTop + (box_h + ph) / 2;
  layout.scale_denominator = static_cast<int>(m.n);
  layout.flat_left_mm = m.left;
  layout.flat_bottom_mm = m.bottom;
  layout.flat_width_mm = pw;
  layout.flat_height_mm = ph;
  layout.extent_x_mm = w * 1e3;
  layout.extent_y_mm = h * 1e3;
  return m;
}

void draw_outline(cairo_t* cr, const DrawingSheetPart& p, const FlatMap& m) {
  for (size_t i = 0; i < p.outline.size(); ++i) {
    const double x = m.x(p.outline[i].x), y = m.y(p.outline[i].y);
    if (i == 0)
      cairo_move_to(cr, x, y);
    else
      cairo_line_to(cr, x, y);
  }
  cairo_close_path(cr);
  cairo_set_source_rgb(cr, 0.94, 0.94, 0.94);  // the sheet, lightly tinted so the part reads as one piece
  cairo_fill_preserve(cr);
  set_ink(cr, kBlack);
  set_dash(cr, {});
  cairo_set_line_width(cr, kThick);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  cairo_stroke(cr);
}

double segment_distance(double x, double y, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
  const double t = l2 > 0 ? std::clamp(((x - ax) * dx + (y - ay) * dy) / l2, 0.0, 1.0) : 0;
  return std::hypot(x - ax - t * dx, y - ay - t * dy);
}

// The flat pattern on the page (mm), to tell where a label can go: on the
// sheet clear of its holes, or off it, but not on a cut line, nor past the
// overall dimensions' lines.
struct PageSheet {
  std::vector<SheetPoint> outline;  // mm, page
  std::vector<std::pair<SheetPoint, double>> holes;  // centre, radius + margin, mm
  Rect room;  // where labels may go: the outline's box and a margin short of the dimension lines
  bool inside(double x, double y) const {
    bool in = false;  // even-odd crossing test
    for (size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
      const SheetPoint& a = outline[i];
      const SheetPoint& b = outline[j];
      if ((a.y > y) != (b.y > y) && x < (b.x - a.x) * (y - a.y) / (b.y - a.y) + a.x) in = !in;
    }
    return in;
  }
  bool free(double x, double y) const {
    if (x < room.x0 || x > room.x1 || y < room.y0 || y > room.y1) return false;
    for (size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++)
      if (segment_distance(x, y, outline[i].x, outline[i].y, outline[j].x, outline[j].y) < 0.7) return false;
    for (const auto& [c, r] : holes)
      if (std::hypot(x - c.x, y - c.y) < r) return false;
    return true;
  }
};

PageSheet page_sheet(const DrawingSheetPart& p, const FlatMap& m) {
  PageSheet s;
  for (const SheetPoint& q : p.outline) s.outline.push_back({m.x(q.x), m.y(q.y)});
  for (const SheetHole& h : p.holes) s.holes.push_back({{m.x(h.centre.x), m.y(h.centre.y)}, 0.5 * h.diameter * 1e3 / m.n + 1.2});
  s.room = {m.x(m.e.lo.x) - 6, m.y(m.e.hi.y) - 6, m.x(m.e.hi.x) + 5, m.y(m.e.lo.y) + 4};
  return s;
}

// A label's box on the page: centre, size (mm) and angle (counter-clockwise).
struct LabelBox {
  double cx = 0, cy = 0, w = 0, h = 0, angle = 0;
  double ux() const { return std::cos(angle); }
  double uy() const { return -std::sin(angle); }  // along the text on the page (y down)
  SheetPoint at(double a, double b) const { return {cx + a * ux() - b * uy(), cy + a * uy() + b * ux()}; }
  bool contains(double x, double y, double margin) const {
    const double a = (x - cx) * ux() + (y - cy) * uy(), b = -(x - cx) * uy() + (y - cy) * ux();
    return std::abs(a) <= w / 2 + margin && std::abs(b) <= h / 2 + margin;
  }
  // Whether the segment p -> q (page, mm) crosses the box grown by margin (Liang-Barsky clipping in the box's frame).
  bool crossed_by(SheetPoint p, SheetPoint q, double margin) const {
    const double pa = (p.x - cx) * ux() + (p.y - cy) * uy(), pb = -(p.x - cx) * uy() + (p.y - cy) * ux();
    const double qa = (q.x - cx) * ux() + (q.y - cy) * uy(), qb = -(q.x - cx) * uy() + (q.y - cy) * ux();
    double t0 = 0, t1 = 1;
    const double d[2] = {qa - pa, qb - pb}, lo[2] = {-w / 2 - margin - pa, -h / 2 - margin - pb},
                 hi[2] = {w / 2 + margin - pa, h / 2 + margin - pb};
    for (int k = 0; k < 2; ++k) {
      if (d[k] == 0) {
        if (lo[k] > 0 || hi[k] < 0) return false;
        continue;
      }
      double a = lo[k] / d[k], b = hi[k] / d[k];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
      if (t0 > t1) return false;
    }
    return true;
  }
};

// How good a place the box is: its 27 sample points clear of the cut lines
// and holes count for it; points on a label already placed, and cut or bend
// lines crossing it, against it.
double label_score(const PageSheet& s, const LabelBox& box, const std::vector<LabelBox>& placed,
                   const std::vector<SheetBend>& bends, const FlatMap& m) {
  double score = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 3; ++j) {
      const SheetPoint q = box.at((i / 8.0 - 0.5) * box.w, (j / 2.0 - 0.5) * box.h);
      score += s.free(q.x, q.y);
      for (const LabelBox& o : placed) score -= 20 * o.contains(q.x, q.y, 0.6);
    }
  for (const SheetBend& b : bends) score -= 6 * box.crossed_by({m.x(b.a.x), m.y(b.a.y)}, {m.x(b.b.x), m.y(b.b.y)}, 0.4);
  for (size_t i = 0, j = s.outline.size() - 1; i < s.outline.size(); j = i++)
    score -= 6 * box.crossed_by(s.outline[j], s.outline[i], 0.4);
  return score;
}

// Dashed centre line of each bend zone (red dashed UP, blue dash-dot DOWN, so
// a black-and-white print still tells them apart).
void draw_bend_line(cairo_t* cr, const SheetBend& b, const FlatMap& m) {
  set_ink(cr, b.up ? kUp : kDown);
  if (b.up)
    set_dash(cr, {3.0, 1.5});
  else
    set_dash(cr, {6.0, 1.2, 0.8, 1.2});
  draw_line(cr, m.x(b.a.x), m.y(b.a.y), m.x(b.b.x), m.y(b.b.y), kMedium);
  set_dash(cr, {});
}

// "B<n> UP 90.0°" along its bend line, never upside down, at the first best
// of: the tab's side (as in flat.dxf), the parent's, each farther off, each
// slid along the line; best = most free sheet, clear of the labels placed
// before it and of the bend lines.
LabelBox place_bend_label(cairo_t* cr, const SheetBend& b, const std::string& label, const FlatMap& m,
                          const PageSheet& sheet, const std::vector<LabelBox>& placed,
                          const std::vector<SheetBend>& bends, double text_h) {
  const double ax = m.x(b.a.x), ay = m.y(b.a.y), bx = m.x(b.b.x), by = m.y(b.b.y);
  const double len = std::max(std::hypot(bx - ax, by - ay), 1e-9);
  // On the page (y down) the tab lies right of a -> b in the flat frame, i.e. left of it here.
  const double nx = (by - ay) / len, ny = -(bx - ax) / len, ex = (bx - ax) / len, ey = (by - ay) / len;
  double angle = std::atan2(-(by - ay), bx - ax);  // counter-clockwise on the paper
  if (angle > M_PI / 2) angle -= M_PI;
  if (angle < -M_PI / 2) angle += M_PI;
  fit_text(cr, label, text_h, std::max(len, 30.0));
  LabelBox best;
  double best_score = -1e300;
  for (double off : {1.3, 2.8})
    for (double side : {1.0, -1.0})
      for (double slide : {0.0, -0.3, 0.3}) {
        const LabelBox box{(ax + bx) / 2 - side * off * text_h * nx + slide * len * ex,
                           (ay + by) / 2 - side * off * text_h * ny + slide * len * ey, text_width(cr, label), text_h,
                           angle};
        const double score = label_score(sheet, box, placed, bends, m);
        if (score > best_score) best = box, best_score = score;
      }
  // Then on the bend line's own extension, past either end (off a crowded part).
  const double w = text_width(cr, label), ends[2][3] = {{bx, by, 1}, {ax, ay, -1}};
  for (const auto& end : ends) {
    const double d = end[2] * (w / 2 + 2.5);
    const LabelBox box{end[0] + d * ex, end[1] + d * ey, w, text_h, angle};
    const double score = label_score(sheet, box, placed, bends, m);
    if (score > best_score + 1) best = box, best_score = score;  // only when clearly better than beside the line
  }
  return best;
}

// Where a crowded bend's label goes when nothing beside its line is clear:
// level text on a ring around the line's middle, joined to it by a leader.
LabelBox place_leader_label(cairo_t* cr, const std::string& label, double mx, double my, const PageSheet& sheet,
                            const std::vector<LabelBox>& placed, const std::vector<SheetBend>& bends,
                            const FlatMap& m, double text_h) {
  const double w = text_width(cr, label);
  LabelBox best{mx, my, w, text_h, 0};
  double best_score = -1e300;
  for (double r : {8.0, 14.0, 22.0, 32.0, 45.0})
    for (int k = 0; k < 16; ++k) {
      const double a = k * M_PI / 8;
      const LabelBox box{mx + (r + w / 2) * std::cos(a), my - (r + text_h) * std::sin(a), w, text_h, 0};
      double score = label_score(sheet, box, placed, bends, m) - 0.02 * r;  // nearer wins a tie
      for (double u : {-0.5, 0.0, 0.5})
        score -= sheet.inside(box.at(u * w, 0).x, box.at(u * w, 0).y);  // off the part, where the lines are
      if (score > best_score) best = box, best_score = score;
    }
  return best;
}

void draw_bend_lines(cairo_t* cr, const DrawingSheetPart& p, const FlatMap& m, double text_h) {
  const PageSheet sheet = page_sheet(p, m);
  for (const SheetBend& b : p.bends) draw_bend_line(cr, b, m);
  std::vector<LabelBox> placed;
  for (const SheetBend& b : p.bends) {
    const std::string label = "B" + std::to_string(b.number) + (b.up ? " UP " : " DOWN ") + deg(b.angle);
    LabelBox box = place_bend_label(cr, b, label, m, sheet, placed, p.bends, text_h);
    set_ink(cr, b.up ? kUp : kDown);
    if (label_score(sheet, box, placed, p.bends, m) < 27) {  // some of it on a line or another label
      const double mx = m.x((b.a.x + b.b.x) / 2), my = m.y((b.a.y + b.b.y) / 2);
      box = place_leader_label(cr, label, mx, my, sheet, placed, p.bends, m, text_h);
      const double ex = std::clamp(mx, box.cx - box.w / 2, box.cx + box.w / 2);  // the box's nearest point
      const double ey = std::clamp(my, box.cy - box.h / 2 - 0.6, box.cy + box.h / 2 + 0.6);
      draw_line(cr, mx, my, ex, ey, kThin);
      cairo_arc(cr, mx, my, 0.5, 0, 2 * M_PI);
      cairo_fill(cr);
    }
    draw_text(cr, box.cx, box.cy, label, 0.5, 0.5, box.angle);
    placed.push_back(box);
  }
}

// Each hole as its circle with a centre mark; a self-rivet's holes carry their label.
void draw_holes(cairo_t* cr, const DrawingSheetPart& p, const FlatMap& m, double text_h) {
  set_dash(cr, {});
  for (const SheetHole& h : p.holes) {
    const double x = m.x(h.centre.x), y = m.y(h.centre.y), r = 0.5 * h.diameter * 1e3 / m.n;
    set_ink(cr, kBlack);
    cairo_new_sub_path(cr);
    cairo_arc(cr, x, y, r, 0, 2 * M_PI);
    cairo_set_line_width(cr, kMedium);
    cairo_stroke(cr);
    draw_line(cr, x - r - 0.8, y, x + r + 0.8, y, kThin);
    draw_line(cr, x, y - r - 0.8, x, y + r + 0.8, kThin);
    if (h.self_rivet) {
      set_text_height(cr, 0.8 * text_h);
      draw_text(cr, x + r + 1.0, y - r - 0.5, h.label, 0, 1);
    }
  }
}

// A bar of five equal parts a round number of true millimetres long, about
// 40 mm on the paper: a print scaled to another paper size can still be measured.
void draw_scale_bar(cairo_t* cr, double right, double top, int n, double text_h) {
  double step = 1;  // true mm per part, 1-2-5
  for (double s : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0, 10000.0})
    if (5 * s / n <= 45) step = s;
  const double part = step / n, x0 = right - 5 * part - 6, y = top + 2;
  for (int k = 0; k < 5; ++k) {
    cairo_rectangle(cr, x0 + k * part, y, part, 1.5);
    if (k % 2 == 0) {
      set_ink(cr, kBlack);
      cairo_fill_preserve(cr);
    }
    set_ink(cr, kBlack);
    cairo_set_line_width(cr, kThin);
    cairo_stroke(cr);
  }
  set_text_height(cr, 0.8 * text_h);
  draw_text(cr, x0, y + 2.5, "0", 0.5, 0);
  draw_text(cr, x0 + 5 * part, y + 2.5, fixed(5 * step, 0) + " mm", 0.5, 0);
}

void draw_flat_view(cairo_t* cr, const DrawingSheetPart& p, const Rect& view, double text_h,
                    DrawingSheetLayout& layout) {
  const FlatMap m = place_flat(p, view, layout);
  draw_outline(cr, p, m);
  draw_holes(cr, p, m, text_h);
  draw_bend_lines(cr, p, m, text_h);
  const double x0 = m.x(m.e.lo.x), x1 = m.x(m.e.hi.x), y0 = m.y(m.e.lo.y), y1 = m.y(m.e.hi.y);
  draw_dimension(cr, x0, y0, x1, y0, true, 9, fixed(layout.extent_x_mm, 1));
  draw_dimension(cr, x1, y0, x1, y1, false, 11, fixed(layout.extent_y_mm, 1));
  set_ink(cr, kBlack);
  set_text_height(cr, 1.4 * text_h, true);
  draw_text(cr, view.x0 + 4, view.y0 + 4, "FLAT PATTERN  " + scale_label(layout.scale_denominator), 0, 0);
  const char* notes[] = {"seen from the top side (the base's side facing the load)",
                         "x, y as in flat.dxf and rivets.csv: from the lower-left corner of the overall dimensions"};
  for (int k = 0; k < 2; ++k) {
    fit_text(cr, notes[k], 0.8 * text_h, view.w() - 70);
    draw_text(cr, view.x0 + 4, view.y0 + 4 + 1.4 * text_h + 2 + k * 1.6 * text_h, notes[k], 0, 0);
  }
  draw_scale_bar(cr, view.x1, view.y0 + 2, layout.scale_denominator, text_h);
}

// ---- the isometric view ------------------------------------------------------

void draw_iso_faces(cairo_t* cr, const IsometricView& v, double x0, double y0, double k) {
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const IsometricFace& f : v.faces) {
    for (size_t i = 0; i < f.polygon.size(); ++i) {
      const double x = x0 + (f.polygon[i].x - v.min.x) * k, y = y0 - (f.polygon[i].y - v.min.y) * k;
      if (i == 0)
        cairo_move_to(cr, x, y);
      else
        cairo_line_to(cr, x, y);
    }
    cairo_close_path(cr);
    const double g = 0.55 + 0.4 * f.shade;  // light greys: the edges stay readable on every face
    cairo_set_source_rgb(cr, g * 0.96, g * 0.97, g);
    cairo_fill_preserve(cr);
    set_ink(cr, kBlack);
    cairo_set_line_width(cr, 0.25);
    cairo_stroke(cr);
  }
}

// The bent part in the top of the right column, fitted to its box, with each
// bend's number at the middle of its bend line.
void draw_iso_view(cairo_t* cr, const DrawingSheetPart& p, const Rect& box, double text_h) {
  set_ink(cr, kBlack);
  set_text_height(cr, 1.2 * text_h, true);
  draw_text(cr, box.x0 + 2, box.y0 + 3, "BENT PART", 0, 0);
  set_text_height(cr, 0.8 * text_h);
  draw_text(cr, box.x1 - 2, box.y0 + 3, "isometric, no scale", 1, 0);
  const IsometricView v = isometric_view(p.tabs);
  const double w = v.max.x - v.min.x, h = v.max.y - v.min.y;
  const Rect area{box.x0 + 6, box.y0 + 4 + 2.5 * text_h, box.x1 - 6, box.y1 - 4};
  if (v.faces.empty() || !(w > 0 || h > 0)) return;
  const double k = std::min(w > 0 ? area.w() / w : 1e9, h > 0 ? area.h() / h : 1e9);  // mm per m
  const double x0 = area.x0 + (area.w() - w * k) / 2, y0 = area.y1 - (area.h() - h * k) / 2;
  draw_iso_faces(cr, v, x0, y0, k);
  set_text_height(cr, 0.8 * text_h, true);
  for (const SheetBend& b : p.bends) {
    if (b.tab < 0 || b.tab >= static_cast<int>(p.tabs.size()) || p.tabs[b.tab].size() < 2) continue;
    const SheetPoint3& a = p.tabs[b.tab][0];
    const SheetPoint3& c = p.tabs[b.tab][1];  // [P1, P0, ...]: the sharp bend line
    const SheetPoint q = v.project({(a.x + c.x) / 2, (a.y + c.y) / 2, (a.z + c.z) / 2});
    set_ink(cr, b.up ? kUp : kDown);
    draw_text(cr, x0 + (q.x - v.min.x) * k, y0 - (q.y - v.min.y) * k, "B" + std::to_string(b.number), 0.5, 0.5);
  }
}

// ---- the tables ----------------------------------------------------------------

SheetTable bend_table(const DrawingSheetPart& p, double width) {
  SheetTable t;
  t.title = "BEND TABLE (" + std::to_string(p.bends.size()) + (p.bends.size() == 1 ? " bend)" : " bends)");
  const double f = width / 140;
  t.widths = {10 * f, 19 * f, 17 * f, 18 * f, 13 * f, 21 * f, 12 * f, 30 * f};
  t.align = {0.5, 1, 0.5, 1, 1, 1, 0.5, 0.5};
  t.header = {"no.", "angle", "dir.", "R in. mm", "K", "line mm", "tab", "tool"};
  std::vector<SheetBend> bends = p.bends;
  std::stable_sort(bends.begin(), bends.end(), [](const SheetBend& a, const SheetBend& b) { return a.number < b.number; });
  for (const SheetBend& b : bends)
    t.rows.push_back({"B" + std::to_string(b.number), deg(b.angle), b.up ? "UP" : "DOWN", mm(b.inside_radius),
                      fixed(p.k_factor, 2), mm(b.length), std::to_string(b.tab), "not planned"});
  t.notes = {"In this order. UP: the tab folds towards the viewer of the flat pattern.",
             "Bend lines: centre of the bend zone; red dashed UP, blue dash-dot DOWN.",
             "Tool: not chosen by sheetgen; the order is checked for collisions of the part only."};
  t.more_rows_in = "bends.csv";
  return t;
}

SheetTable rivet_schedule(const DrawingSheetPart& p, double width) {
  SheetTable t;
  t.title = "RIVET SCHEDULE";
  const double f = width / 140;
  t.widths = {15 * f, 38 * f, 16 * f, 31 * f, 12 * f, 28 * f};
  t.align = {0, 0, 1, 0, 1, 0};
  t.header = {"holes", "kind", "hole \u00D8", "rivet", "count", "set"};
  std::map<double, std::vector<const SheetHole*>> flange;  // by hole diameter
  for (const SheetHole& h : p.holes)
    if (!h.self_rivet) flange[h.diameter].push_back(&h);
  for (const auto& [d, holes] : flange) {
    const std::string range = holes.size() == 1 ? holes.front()->label : holes.front()->label + "\u2013" + holes.back()->label;
    t.rows.push_back({range, "flange rivet", mm(d, 3), rivet_size(p.rivet_diameter), std::to_string(holes.size()),
                      "at installation"});
  }
  for (const SheetHole& h : p.holes) {  // one row per self-rivet, from its first hole
    if (!h.self_rivet || h.tab > h.other_tab) continue;
    t.rows.push_back({h.label, "self-rivet, tabs " + std::to_string(h.tab) + " + " + std::to_string(h.other_tab),
                      mm(h.diameter, 3), rivet_size(p.rivet_diameter), "2",
                      h.after_bend > 0 ? "after B" + std::to_string(h.after_bend) : "before bending"});
  }
  if (t.rows.empty()) t.rows.push_back({"-", "no holes", "", "", "0", ""});
  t.notes = {"Hole \u00D8 mm: rivet + 0.1 mm. Positions: rivets.csv; flat.dxf layers RIVET_HOLES, SELF_RIVET_HOLES."};
  t.more_rows_in = "rivets.csv";
  return t;
}

std::string material_text(const SheetMaterial& m) {
  const std::string props = "E " + sig3(m.youngs_modulus * 1e-9) + " GPa, F_ty " + sig3(m.yield_strength * 1e-6) +
                            " MPa, F_tu " + sig3(m.ultimate_strength * 1e-6) + " MPa";
  return props + ", \u03C1 " + sig3(m.density) + " kg/m\u00B3";
}

SheetTable part_data(const DrawingSheetPart& p, double width, const DrawingSheetLayout& layout) {
  SheetTable t;
  t.title = "PART";
  t.widths = {0.22 * width, 0.78 * width};
  t.header = {"item", "value"};
  int self = 0, flange = 0;
  for (const SheetHole& h : p.holes) (h.self_rivet ? self : flange) += 1;
  t.rows = {{"material", p.material.name.empty() ? "as in the problem file" : p.material.name},
            {"properties", material_text(p.material)},
            {"thickness", mm(p.material.thickness, 2) + " mm (" + fixed(p.material.thickness / 25.4e-3, 3) + " in)"},
            {"flat area", fixed(p.flat_area * 1e4, 1) + " cm\u00B2 (blank " + fixed(layout.extent_x_mm, 1) + " \u00D7 " +
                              fixed(layout.extent_y_mm, 1) + " mm)"},
            {"mass", fixed(p.mass, 3) + " kg (flat area \u00D7 t \u00D7 \u03C1, holes not subtracted)"},
            {"bends", std::to_string(p.bends.size()) + "; K-factor " + fixed(p.k_factor, 2) + "; kerf " + mm(p.kerf, 2) + " mm"},
            {"holes", std::to_string(flange) + " rivet holes, " + std::to_string(self / 2) + " self-rivets (" +
                          std::to_string(self) + " holes)"}};
  return t;
}

// "0.0312 J = 0.64 C_max" / "<= 0.0490 J" / "OK" rows of the checks.
std::vector<std::vector<std::string>> check_rows(const SheetChecks& c) {
  auto verdict = [](bool known, bool ok) { return !known ? std::string("-") : ok ? "OK" : "FAILS"; };
  std::vector<std::vector<std::string>> rows;
  const bool c_known = std::isfinite(c.compliance) && std::isfinite(c.compliance_limit) && c.compliance_limit > 0;
  rows.push_back({"stiffness C/C_max", c.stiffness_case,
                  c_known ? sig3(c.compliance / c.compliance_limit) + " (C " + sig3(c.compliance) + " J)" : "-",
                  std::isfinite(c.compliance_limit) ? "\u2264 1 (C_max " + sig3(c.compliance_limit) + " J)" : "-",
                  verdict(c_known, c_known && c.compliance <= c.compliance_limit)});
  const bool ms_known = std::isfinite(c.margin_of_safety) && std::isfinite(c.min_margin_of_safety);
  rows.push_back({"margin of safety MS", c.strength_case, std::isfinite(c.margin_of_safety) ? sig3(c.margin_of_safety) : "-",
                  std::isfinite(c.min_margin_of_safety)
                      ? "\u2265 " + sig3(c.min_margin_of_safety) + (std::isfinite(c.safety_factor) ? " (SF " + sig3(c.safety_factor) + ")" : "")
                      : "-",
                  verdict(ms_known, ms_known && c.margin_of_safety >= c.min_margin_of_safety)});
  const bool b_req = std::isfinite(c.min_buckling_factor);
  const std::string b_val = !c.eigen_checked ? "not computed"
                            : std::isinf(c.buckling_factor) ? "none (no compression)"
                                                            : sig3(c.buckling_factor);
  rows.push_back({"buckling factor", c.buckling_case, b_val, b_req ? "\u2265 " + sig3(c.min_buckling_factor) : "not required",
                  verdict(c.eigen_checked && b_req, c.buckling_factor >= c.min_buckling_factor)});
  const bool f_req = std::isfinite(c.min_frequency_hz), f_known = std::isfinite(c.frequency_hz);
  rows.push_back({"1st frequency", "", f_known ? sig3(c.frequency_hz) + " Hz" : "not computed",
                  f_req ? "\u2265 " + sig3(c.min_frequency_hz) + " Hz" : "not required",
                  verdict(f_known && f_req, c.frequency_hz >= c.min_frequency_hz)});
  return rows;
}

SheetTable checks_table(const DrawingSheetPart& p, double width) {
  SheetTable t;
  t.title = "GOVERNING CHECKS";
  const double f = width / 100;
  t.widths = {24 * f, 14 * f, 27 * f, 27 * f, 8 * f};
  t.align = {0, 0, 0, 0, 0.5};
  t.header = {"check", "case", "value", "required", ""};
  t.rows = check_rows(p.checks);
  return t;
}

// ---- the title block and the frame ---------------------------------------------

// Label small and grey at the top of its cell, the value under it.
void draw_cell(cairo_t* cr, const Rect& cell, const std::string& label, const std::string& value, double text_h,
               double value_h) {
  cairo_set_line_width(cr, kThin);
  set_ink(cr, kBlack);
  cairo_rectangle(cr, cell.x0, cell.y0, cell.w(), cell.h());
  cairo_stroke(cr);
  set_ink(cr, kGrey);
  set_text_height(cr, 0.7 * text_h);
  draw_text(cr, cell.x0 + 1.2, cell.y0 + 1.2, label, 0, 0);
  set_ink(cr, kBlack);
  fit_text(cr, value, value_h, cell.w() - 2.4, value_h > text_h);
  draw_text(cr, cell.x0 + 1.2, cell.y1 - 1.4, value, 0, 1);
}

void draw_title_block(cairo_t* cr, const DrawingSheetPart& p, const Rect& r, const DrawingSheetLayout& layout,
                      PaperSize paper, double text_h) {
  const double row = r.h() / 4;
  const double cx = r.x0 + r.w() * 0.25, cx2 = r.x0 + r.w() * 0.5, cx3 = r.x0 + r.w() * 0.75;
  draw_cell(cr, {r.x0, r.y0, r.x1, r.y0 + row}, "part (load)", p.part_name, text_h, 1.6 * text_h);
  draw_cell(cr, {r.x0, r.y0 + row, r.x1, r.y0 + 2 * row}, "problem", p.problem_name, text_h, text_h);
  draw_cell(cr, {r.x0, r.y0 + 2 * row, r.x1, r.y0 + 3 * row}, "status", p.status, text_h, text_h);
  const double y = r.y0 + 3 * row;
  draw_cell(cr, {r.x0, y, cx, r.y1}, "scale", scale_label(layout.scale_denominator), text_h, text_h);
  draw_cell(cr, {cx, y, cx2, r.y1}, "sheet", paper == PaperSize::A3 ? "A3 landscape" : "A4 landscape", text_h, text_h);
  draw_cell(cr, {cx2, y, cx3, r.y1}, "units", "mm, degrees", text_h, text_h);
  draw_cell(cr, {cx3, y, r.x1, r.y1}, "drawn by", "sheetgen", text_h, text_h);
  set_ink(cr, kBlack);
  cairo_set_line_width(cr, kThick);
  cairo_rectangle(cr, r.x0, r.y0, r.w(), r.h());
  cairo_stroke(cr);
}

void draw_frame(cairo_t* cr, const Regions& g) {
  set_ink(cr, kBlack);
  set_dash(cr, {});
  cairo_set_line_width(cr, kThick);
  cairo_rectangle(cr, g.frame.x0, g.frame.y0, g.frame.w(), g.frame.h());
  cairo_stroke(cr);
  cairo_set_line_width(cr, kThin);
  draw_line(cr, g.iso.x0, g.frame.y0, g.iso.x0, g.frame.y1, kThin);     // the right column
  draw_line(cr, g.iso.x0, g.iso.y1, g.frame.x1, g.iso.y1, kThin);       // under the picture
  draw_line(cr, g.frame.x0, g.flat_view.y1, g.iso.x0, g.flat_view.y1, kThin);  // over the part data
}

// The right column's tables: the bend table first, the rivet schedule under
// it; when both do not fit, the schedule keeps at most 40 % of the room.
void draw_right_tables(cairo_t* cr, const DrawingSheetPart& p, const Rect& r, double text_h,
                       DrawingSheetLayout& layout) {
  const double pad = 3, width = r.w() - 2 * pad, room = r.h() - 2 * pad;
  const SheetTable bends = bend_table(p, width), rivets = rivet_schedule(p, width);
  const double hb = table_height(bends, text_h), hr = table_height(rivets, text_h);
  const double rivet_room = hb + hr + 4 <= room ? hr : std::max(room - hb - 4, std::min(hr, 0.4 * room));
  const TableFit fb = draw_table(cr, bends, r.x0 + pad, r.y0 + pad, room - rivet_room - 4, text_h);
  const TableFit fr = draw_table(cr, rivets, r.x0 + pad, r.y0 + pad + fb.height + 4, rivet_room, text_h);
  layout.bend_rows = fb.rows_drawn;
  layout.bend_rows_omitted = fb.rows_omitted;
  layout.hole_rows = fr.rows_drawn;
  layout.hole_rows_omitted = fr.rows_omitted;
}

void draw_sheet(cairo_t* cr, const DrawingSheetPart& p, const DrawingSheetOptions& o, const Regions& g,
                DrawingSheetLayout& layout) {
  const double text_h = o.text_height * 1e3;
  draw_frame(cr, g);
  draw_flat_view(cr, p, g.flat_view, text_h, layout);
  draw_iso_view(cr, p, g.iso, text_h);
  draw_right_tables(cr, p, g.right_tables, text_h, layout);
  const double pad = 3;
  draw_table(cr, part_data(p, g.part_data.w() - 2 * pad, layout), g.part_data.x0 + pad, g.part_data.y0 + pad,
             g.part_data.h() - 2 * pad, text_h);
  draw_table(cr, checks_table(p, g.checks.w() - 2 * pad), g.checks.x0 + pad, g.checks.y0 + pad, g.checks.h() - 2 * pad,
             text_h);
  draw_title_block(cr, p, g.title, layout, o.paper, text_h);
}

// ---- writing -------------------------------------------------------------------

[[noreturn]] void cannot_write(const std::string& path, const std::string& why) {
  throw std::runtime_error(path + ": cannot write the drawing sheet (" + why + ")");
}

// Ends the PDF (cairo writes its tail and closes the file) and moves it over
// the target; on failure `file` removes the temporary file as it goes.
void finish_atomically(cairo_surface_t* surface, AtomicFile& file) {
  errno = 0;
  cairo_surface_finish(surface);
  const cairo_status_t status = cairo_surface_status(surface);
  if (status != CAIRO_STATUS_SUCCESS) cannot_write(file.path(), errno ? std::strerror(errno) : cairo_status_to_string(status));
  const std::string why = file.commit();
  if (!why.empty()) cannot_write(file.path(), why);
}

}  // namespace

DrawingSheetLayout write_drawing_pdf(const DrawingSheetPart& part, const DrawingSheetOptions& options,
                                     const std::string& path) {
  check_part(part, options);
  const Regions g = regions(options.paper);
  DrawingSheetLayout layout;
  layout.page_width_mm = g.page_w;
  layout.page_height_mm = g.page_h;
  AtomicFile file(path);
  errno = 0;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_pdf_surface_create(file.temp_path().c_str(), g.page_w * kPointsPerMm, g.page_h * kPointsPerMm), cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    cannot_write(path, errno ? std::strerror(errno) : cairo_status_to_string(cairo_surface_status(surface.get())));
  // No creation date (an empty one is left out): the same part gives the same bytes.
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "");
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, (part.part_name + " - drawing sheet").c_str());
  cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "sheetgen");
  {
    std::unique_ptr<cairo_t, decltype(&cairo_destroy)> context(cairo_create(surface.get()), cairo_destroy);
    cairo_t* cr = context.get();
    cairo_scale(cr, kPointsPerMm, kPointsPerMm);  // user unit: the millimetre
    cairo_font_options_t* fo = cairo_font_options_create();
    cairo_font_options_set_hint_metrics(fo, CAIRO_HINT_METRICS_OFF);  // text widths scale exactly
    cairo_set_font_options(cr, fo);
    cairo_font_options_destroy(fo);
    draw_sheet(cr, part, options, g, layout);
    cairo_show_page(cr);
    if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) cannot_write(path, cairo_status_to_string(cairo_status(cr)));
  }
  finish_atomically(surface.get(), file);
  return layout;
}

}  // namespace sheetgen
