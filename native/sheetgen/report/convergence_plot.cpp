#include "sheetgen/report/convergence_plot.hpp"

#include <cairo.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "sheetgen/core/atomic_file.hpp"
#include "sheetgen/report/plot_axis.hpp"

namespace sheetgen {
namespace {

using C = ConvergenceColours;

constexpr ConvergenceColour kWhite{255, 255, 255};
constexpr ConvergenceColour kInk{30, 30, 30};      // text, frames
constexpr ConvergenceColour kTickInk{70, 70, 70};  // tick marks, the subtitle
constexpr double kGridAlpha = 0.1;                  // grid lines: black at 10 %, seen on white and on the shade alike
constexpr double kMargin = 16;      // px around the figure
constexpr double kTickLength = 7;   // px
constexpr double kTickGap = 5;      // px between a tick mark and its label
constexpr double kDash[] = {12, 8};  // px on, px off: the limit lines
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// What one panel shows.
struct PanelSpec {
  std::string y_label;
  ConvergenceColour colour;
  std::vector<double> values;  // per point, NaN where nothing is plotted
  double reference = kNaN;     // the limit, dashed, when finite
  std::string reference_label;
  bool feasible_above = false;  // the feasible side of the reference: above (MS) or below (compliance)
  std::string unit_suffix;      // after the last value, e.g. " J"
  bool from_zero = true;        // the axis starts at 0: a quantity that cannot be negative
};

// The figure in px: the panels, their axes and the text rows around them.
struct Figure {
  ConvergencePlotLayout layout;
  std::vector<PlotAxis> y_axes;  // one per panel
  PlotAxis x_axis;
  double subtitle_top = 0;  // px, top of the capitals of each text row
  double x_label_top = 0;
  double legend_top = 0;
};

struct Box {  // px, x0 <= x < x1, y0 <= y < y1
  double x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

// Three significant digits, no exponent, no trailing zeros: "1226", "0.176", "0.05".
std::string format_value(double v) {
  char buf[64];
  if (v == 0 || !std::isfinite(v)) {
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
  }
  const int decimals = std::clamp(2 - static_cast<int>(std::floor(std::log10(std::abs(v)))), 0, 9);
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  if (decimals > 0) {
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

void check_option(bool ok, const std::string& field, double value, const std::string& range) {
  if (!ok) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g", value);
    throw std::invalid_argument("ConvergenceOptions::" + field + " " + buf + " is not in " + range);
  }
}

void check_options(const ConvergenceOptions& o) {
  check_option(o.width_px >= 320 && o.width_px <= 8192, "width_px", o.width_px, "320..8192");
  check_option(o.height_px >= 360 && o.height_px <= 8192, "height_px", o.height_px, "360..8192");
  check_option(o.font_size_px >= 6 && o.font_size_px <= 72, "font_size_px", o.font_size_px, "6..72");
  check_option(o.line_width_px > 0 && o.line_width_px <= 50, "line_width_px", o.line_width_px, "(0, 50]");
  check_option(o.marker_radius_px >= 0 && o.marker_radius_px <= 50, "marker_radius_px", o.marker_radius_px, "0..50");
  check_option(o.target_ticks >= 2 && o.target_ticks <= 20, "target_ticks", o.target_ticks, "2..20");
}

std::vector<PanelSpec> panel_specs(const ConvergenceHistory& h) {
  std::vector<PanelSpec> s(3);
  s[0].y_label = "best flat area (cm\u00B2)";
  s[0].colour = C::area;
  s[0].unit_suffix = " cm\u00B2";
  s[1].y_label = "compliance (J)";
  s[1].colour = C::compliance;
  s[1].unit_suffix = " J";
  s[1].reference = h.compliance_limit_J;
  s[1].reference_label = "limit " + format_value(h.compliance_limit_J) + " J";
  s[2].y_label = "margin of safety (-)";
  s[2].colour = C::margin;
  s[2].reference = h.min_margin_of_safety;
  s[2].reference_label = "required MS " + format_value(h.min_margin_of_safety);
  s[2].feasible_above = true;
  s[2].from_zero = false;
  for (const ConvergencePoint& p : h.points) {
    const double v[3] = {p.best_area_m2 * 1e4, p.compliance_J, p.margin_of_safety};
    for (int k = 0; k < 3; ++k) s[k].values.push_back(p.found && std::isfinite(v[k]) ? v[k] : kNaN);
  }
  return s;
}

double x_value(const ConvergencePoint& p, ConvergenceXAxis axis) {
  return axis == ConvergenceXAxis::Iteration ? p.iteration : p.evaluated;
}

PlotAxis x_axis_for(const ConvergenceHistory& h, const ConvergenceOptions& o) {
  if (o.x_axis == ConvergenceXAxis::CandidatesEvaluated) {
    int largest = 0;
    for (const auto& p : h.points) largest = std::max(largest, p.evaluated);
    return count_axis(largest, o.target_ticks);
  }
  if (h.points.empty()) return level_axis(1, 1, o.target_ticks);
  const auto [lo, hi] = std::minmax_element(h.points.begin(), h.points.end(),
                                            [](const auto& a, const auto& b) { return a.iteration < b.iteration; });
  return level_axis(lo->iteration, hi->iteration, o.target_ticks);
}

double px_x(const ConvergencePanel& p, double x) {
  return p.left_px + (x - p.x_min) / (p.x_max - p.x_min) * (p.right_px - p.left_px);
}
double px_y(const ConvergencePanel& p, double y) {
  return p.bottom_px - (y - p.y_min) / (p.y_max - p.y_min) * (p.bottom_px - p.top_px);
}

// ---- cairo: text, lines, markers ---------------------------------------------

void set_colour(cairo_t* cr, ConvergenceColour c) { cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0); }

double text_width(cairo_t* cr, const std::string& s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

double cap_height(cairo_t* cr) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, "H", &e);
  return e.height;
}

// Sets the font to size_px, or smaller so that s fits max_width_px.
void set_font_fitting(cairo_t* cr, const std::string& s, double size_px, double max_width_px) {
  cairo_set_font_size(cr, size_px);
  const double w = text_width(cr, s);
  if (w > max_width_px) cairo_set_font_size(cr, size_px * max_width_px / w);
}

// Draws s in the current font with the point (ax, ay) of its box at (x, y):
// ax 0 / 0.5 / 1 is the left / centre / right of the text, ay 0 / 0.5 / 1 the
// top / middle / foot of a capital.
void draw_text(cairo_t* cr, double x, double y, const std::string& s, double ax, double ay, ConvergenceColour c) {
  cairo_move_to(cr, x - ax * text_width(cr, s), y + (1 - ay) * cap_height(cr));
  set_colour(cr, c);
  cairo_show_text(cr, s.c_str());
}

void draw_line(cairo_t* cr, double x0, double y0, double x1, double y1, ConvergenceColour c, double width_px) {
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  set_colour(cr, c);
  cairo_set_line_width(cr, width_px);
  cairo_stroke(cr);
}

void draw_grid_line(cairo_t* cr, double x0, double y0, double x1, double y1) {
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  cairo_set_source_rgba(cr, 0, 0, 0, kGridAlpha);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
}

void draw_cross(cairo_t* cr, double x, double y, double half_px, ConvergenceColour c) {
  draw_line(cr, x - half_px, y - half_px, x + half_px, y + half_px, c, 2);
  draw_line(cr, x - half_px, y + half_px, x + half_px, y - half_px, c, 2);
}

void draw_dashed(cairo_t* cr, double x0, double x1, double y, ConvergenceColour c) {
  cairo_set_dash(cr, kDash, 2, 0);
  draw_line(cr, x0, y, x1, y, c, 2);
  cairo_set_dash(cr, nullptr, 0, 0);
}

// ---- layout ------------------------------------------------------------------

std::vector<PlotAxis> y_axes_for(const std::vector<PanelSpec>& specs, const ConvergenceOptions& o) {
  std::vector<PlotAxis> axes;
  for (const PanelSpec& s : specs) {
    std::vector<double> range = s.values;  // NaNs are ignored by value_axis
    range.push_back(s.reference);
    const bool any = std::any_of(range.begin(), range.end(), [](double v) { return std::isfinite(v); });
    if (s.from_zero && any) range.push_back(0.0);
    axes.push_back(value_axis(range, s.from_zero, o.target_ticks));
  }
  return axes;
}

// Text rows from the top: title, subtitle, the three panels; under them the
// x tick labels, the x label and the legend. The y label and tick labels sit
// left of the panels.
Figure lay_out(cairo_t* cr, const ConvergenceHistory& h, const std::vector<PanelSpec>& specs,
               const ConvergenceOptions& o) {
  Figure f;
  f.y_axes = y_axes_for(specs, o);
  f.x_axis = x_axis_for(h, o);
  const double fs = o.font_size_px;
  cairo_set_font_size(cr, fs);
  const double cap = cap_height(cr);
  double tick_label_w = 0;
  for (const PlotAxis& a : f.y_axes)
    for (double t : a.ticks) tick_label_w = std::max(tick_label_w, text_width(cr, a.label(t)));

  f.subtitle_top = kMargin + 1.5 * cap + 0.8 * fs;
  const double top = std::round(f.subtitle_top + cap + 1.4 * fs);
  const double left = std::round(kMargin + 1.3 * fs + 10 + tick_label_w + kTickLength + kTickGap);
  const double right = o.width_px - 2 * kMargin;
  const double below = kTickLength + kTickGap + 3 * cap + 2 * 0.9 * fs + 0.5 * fs;  // tick labels, x label, legend
  const double bottom = o.height_px - kMargin - below;
  const double gap = std::max(24.0, 2 * fs);  // one panel's lowest tick label clear of the next one's highest
  const double panel_h = std::floor((bottom - top - 2 * gap) / 3);
  if (panel_h < 40 || right - left < 80)
    throw std::invalid_argument("ConvergenceOptions: " + std::to_string(o.width_px) + " x " +
                                std::to_string(o.height_px) + " px leaves no room for the panels at font_size_px " +
                                format_value(fs));
  f.layout.width_px = o.width_px;
  f.layout.height_px = o.height_px;
  for (int k = 0; k < 3; ++k) {
    ConvergencePanel p;
    p.y_label = specs[k].y_label;
    p.left_px = left;
    p.right_px = right;
    p.top_px = top + k * (panel_h + gap);
    p.bottom_px = p.top_px + panel_h;
    p.x_min = f.x_axis.min;
    p.x_max = f.x_axis.max;
    p.y_min = f.y_axes[k].min;
    p.y_max = f.y_axes[k].max;
    f.layout.panels.push_back(p);
  }
  f.x_label_top = bottom + kTickLength + kTickGap + cap + 0.9 * fs;
  f.legend_top = f.x_label_top + cap + 0.9 * fs;
  return f;
}

// ---- drawing -----------------------------------------------------------------

std::string subtitle(const ConvergenceHistory& h) {
  const auto& pts = h.points;
  if (pts.empty()) return "no iterations recorded";
  const int evaluated = pts.back().evaluated;
  const auto first = std::find_if(pts.begin(), pts.end(), [](const ConvergencePoint& p) { return p.found; });
  if (first == pts.end())
    return "no valid part in " + std::to_string(pts.size()) + " iterations (" + std::to_string(evaluated) +
           " candidates)";
  return "first valid part: iteration " + std::to_string(first->iteration) + ", " + std::to_string(first->evaluated) +
         " of " + std::to_string(evaluated) + " candidates";
}

void draw_title(cairo_t* cr, const ConvergenceHistory& h, const Figure& f, const ConvergenceOptions& o) {
  const double centre = o.width_px / 2.0, room = o.width_px - 2 * kMargin;
  const std::string title = "Convergence: " + h.load;
  set_font_fitting(cr, title, 1.5 * o.font_size_px, room);
  draw_text(cr, centre, kMargin, title, 0.5, 0, kInk);
  const std::string sub = subtitle(h);
  set_font_fitting(cr, sub, o.font_size_px, room);
  draw_text(cr, centre, f.subtitle_top, sub, 0.5, 0, kTickInk);
  cairo_set_font_size(cr, o.font_size_px);
}

// The feasible side of the limit, shaded under everything else.
void draw_feasible_side(cairo_t* cr, const ConvergencePanel& p, const PanelSpec& s) {
  if (!std::isfinite(s.reference)) return;
  const double y = px_y(p, s.reference);
  if (s.feasible_above)
    cairo_rectangle(cr, p.left_px, p.top_px, p.right_px - p.left_px, y - p.top_px);
  else
    cairo_rectangle(cr, p.left_px, y, p.right_px - p.left_px, p.bottom_px - y);
  set_colour(cr, C::feasible);
  cairo_fill(cr);
}

// Grid lines on the ticks, tick marks, tick labels (x only on the bottom panel), the frame.
void draw_axes(cairo_t* cr, const ConvergencePanel& p, const PlotAxis& ya, const PlotAxis& xa, bool x_labels) {
  for (double t : ya.ticks) {
    const double y = std::floor(px_y(p, t)) + 0.5;  // 1 px lines on the pixel grid
    draw_grid_line(cr, p.left_px, y, p.right_px, y);
    draw_line(cr, p.left_px - kTickLength, y, p.left_px, y, kTickInk, 2);
    draw_text(cr, p.left_px - kTickLength - kTickGap, y, ya.label(t), 1, 0.5, kInk);
  }
  for (double t : xa.ticks) {
    const double x = std::floor(px_x(p, t)) + 0.5;
    draw_grid_line(cr, x, p.top_px, x, p.bottom_px);
    draw_line(cr, x, p.bottom_px, x, p.bottom_px + kTickLength, kTickInk, 2);
    if (x_labels) draw_text(cr, x, p.bottom_px + kTickLength + kTickGap, xa.label(t), 0.5, 0, kInk);
  }
  cairo_rectangle(cr, p.left_px + 0.5, p.top_px + 0.5, p.right_px - p.left_px - 1, p.bottom_px - p.top_px - 1);
  set_colour(cr, kInk);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
}

// The y label, reading bottom to top, centred on the panel at the figure's left edge.
void draw_y_label(cairo_t* cr, const ConvergencePanel& p, const ConvergenceOptions& o) {
  cairo_save(cr);
  set_font_fitting(cr, p.y_label, o.font_size_px, p.bottom_px - p.top_px);
  cairo_translate(cr, kMargin, (p.top_px + p.bottom_px) / 2);
  cairo_rotate(cr, -M_PI / 2);  // the text's top now faces left
  draw_text(cr, 0, 0, p.y_label, 0.5, 0, kInk);
  cairo_restore(cr);
}

// The limit, dashed, with its label on a white box at the right: above the
// line when there is room in the panel, else below. Returns what the
// last-value label must not cover.
std::vector<Box> draw_reference(cairo_t* cr, const ConvergencePanel& p, const PanelSpec& s) {
  if (!std::isfinite(s.reference)) return {};
  const double y = px_y(p, s.reference);
  draw_dashed(cr, p.left_px + 1, p.right_px - 1, y, C::limit);
  const double cap = cap_height(cr), w = text_width(cr, s.reference_label);
  const double label_top = y - cap - 7 > p.top_px + 3 ? y - cap - 7 : y + 7;
  const Box box{p.right_px - 10 - w - 4, label_top - 4, p.right_px - 6, label_top + cap + 4};
  cairo_rectangle(cr, box.x0, box.y0, box.x1 - box.x0, box.y1 - box.y0);
  set_colour(cr, kWhite);
  cairo_fill(cr);
  draw_text(cr, p.right_px - 10, label_top, s.reference_label, 1, 0, C::limit);
  return {box, Box{p.left_px, y - 3, p.right_px, y + 4}};
}

// Segments between consecutive plotted points, then the markers on top; a
// grey cross on the bottom edge for a point without a value. Counts both.
void draw_curve(cairo_t* cr, ConvergencePanel& p, const PanelSpec& s, const std::vector<ConvergencePoint>& pts,
                const ConvergenceOptions& o) {
  bool open = false;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (!std::isfinite(s.values[i])) continue;
    const double x = px_x(p, x_value(pts[i], o.x_axis)), y = px_y(p, s.values[i]);
    if (open)
      cairo_line_to(cr, x, y);
    else
      cairo_move_to(cr, x, y);
    open = true;
  }
  set_colour(cr, s.colour);
  cairo_set_line_width(cr, o.line_width_px);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_stroke(cr);
  const double cross = std::max(o.marker_radius_px, 4.0);
  for (size_t i = 0; i < pts.size(); ++i) {
    const double x = px_x(p, x_value(pts[i], o.x_axis));
    if (std::isfinite(s.values[i])) {
      cairo_new_sub_path(cr);
      cairo_arc(cr, x, px_y(p, s.values[i]), o.marker_radius_px, 0, 2 * M_PI);
      set_colour(cr, s.colour);
      cairo_fill(cr);
      ++p.plotted_points;
    } else {
      draw_cross(cr, x, p.bottom_px - cross - 4, cross, C::not_found);
      ++p.not_found_points;
    }
  }
}

// The last value in numbers, since a curve far below its limit is hard to read
// off: above the point, else below, the first place inside the panel clear of
// the limit and its label.
void draw_last_value(cairo_t* cr, const ConvergencePanel& p, const PanelSpec& s,
                     const std::vector<ConvergencePoint>& pts, const std::vector<Box>& keep_out,
                     const ConvergenceOptions& o) {
  int last = -1;
  for (size_t i = 0; i < pts.size(); ++i)
    if (std::isfinite(s.values[i])) last = static_cast<int>(i);
  if (last < 0) return;
  const double x = px_x(p, x_value(pts[last], o.x_axis)), y = px_y(p, s.values[last]);
  const std::string label = format_value(s.values[last]) + s.unit_suffix;
  const double cap = cap_height(cr), w = text_width(cr, label), r = o.marker_radius_px;
  double top = y - r - 8 - cap;
  for (double candidate : {y - r - 8 - cap, y + r + 8}) {
    const Box b{x - w, candidate - 2, x, candidate + cap + 2};
    const bool inside = b.y0 > p.top_px + 2 && b.y1 < p.bottom_px - 2;
    if (inside && std::none_of(keep_out.begin(), keep_out.end(), [&](const Box& k) { return k.overlaps(b); })) {
      top = candidate;
      break;
    }
  }
  draw_text(cr, x, top, label, 1, 0, s.colour);
}

void draw_panel(cairo_t* cr, Figure& f, int k, const PanelSpec& s, const std::vector<ConvergencePoint>& pts,
                const ConvergenceOptions& o) {
  ConvergencePanel& p = f.layout.panels[k];
  draw_feasible_side(cr, p, s);
  draw_axes(cr, p, f.y_axes[k], f.x_axis, k == 2);
  draw_y_label(cr, p, o);
  const std::vector<Box> keep_out = draw_reference(cr, p, s);
  draw_curve(cr, p, s, pts, o);
  draw_last_value(cr, p, s, pts, keep_out, o);
  if (p.plotted_points == 0)  // a third of the way down: clear of a limit line at mid-height
    draw_text(cr, (p.left_px + p.right_px) / 2, p.top_px + (p.bottom_px - p.top_px) / 3, "no valid part found", 0.5,
              0.5, C::not_found);
}

enum class LegendKey { Limit, Feasible, NotFound };

// A legend entry's sample, sample_px wide, centred on y.
void draw_legend_sample(cairo_t* cr, LegendKey key, double x, double y, double sample_px, const ConvergenceOptions& o) {
  if (key == LegendKey::Limit) draw_dashed(cr, x, x + sample_px, y, C::limit);
  if (key == LegendKey::NotFound) draw_cross(cr, x + sample_px / 2, y, std::max(o.marker_radius_px, 4.0), C::not_found);
  if (key == LegendKey::Feasible) {
    const double h = 1.4 * cap_height(cr);
    cairo_rectangle(cr, x, y - h / 2, sample_px, h);
    set_colour(cr, C::feasible);
    cairo_fill(cr);
  }
}

// Under the bottom panel: the x label, then one legend row for the limit
// lines, the feasible side and the grey crosses (those drawn at all), centred.
void draw_footer(cairo_t* cr, const Figure& f, const std::vector<PanelSpec>& specs, const ConvergenceOptions& o) {
  const ConvergencePanel& bottom = f.layout.panels.back();
  const double centre = (bottom.left_px + bottom.right_px) / 2;
  draw_text(cr, centre, f.x_label_top,
            o.x_axis == ConvergenceXAxis::Iteration ? "iteration (beam-search level)" : "candidates evaluated", 0.5, 0,
            kInk);
  std::vector<std::pair<LegendKey, std::string>> items;
  if (std::any_of(specs.begin(), specs.end(), [](const PanelSpec& s) { return std::isfinite(s.reference); })) {
    items.push_back({LegendKey::Limit, "limit"});
    items.push_back({LegendKey::Feasible, "feasible side"});
  }
  if (std::any_of(f.layout.panels.begin(), f.layout.panels.end(),
                  [](const ConvergencePanel& p) { return p.not_found_points > 0; }))
    items.push_back({LegendKey::NotFound, "no valid part yet"});
  const double sample = 28, pad = 8, spacing = 28;  // px
  double width = -spacing;
  for (const auto& item : items) width += sample + pad + text_width(cr, item.second) + spacing;
  double x = centre - width / 2;
  const double y = f.legend_top + cap_height(cr) / 2;
  for (const auto& [key, text] : items) {
    draw_legend_sample(cr, key, x, y, sample, o);
    draw_text(cr, x + sample + pad, y, text, 0, 0.5, kInk);
    x += sample + pad + text_width(cr, text) + spacing;
  }
}

// ---- writing -----------------------------------------------------------------

[[noreturn]] void cannot_write(const std::string& path, const std::string& why) {
  throw std::runtime_error(path + ": cannot write the convergence plot (" + why + ")");
}

// Through a temporary file in the same folder, renamed over path on success.
void write_png_atomically(cairo_surface_t* surface, const std::string& path) {
  AtomicFile file(path);
  errno = 0;
  const cairo_status_t status = cairo_surface_write_to_png(surface, file.temp_path().c_str());
  if (status != CAIRO_STATUS_SUCCESS) cannot_write(path, errno ? std::strerror(errno) : cairo_status_to_string(status));
  const std::string why = file.commit();
  if (!why.empty()) cannot_write(path, why);
}

}  // namespace

ConvergencePlotLayout write_convergence_png(const ConvergenceHistory& history, const ConvergenceOptions& options,
                                            const std::string& path) {
  check_options(options);
  const std::vector<PanelSpec> specs = panel_specs(history);
  // RGB24: the PNG is 8-bit RGB, no alpha.
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, options.width_px, options.height_px), cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> context(cairo_create(surface.get()), cairo_destroy);
  cairo_t* cr = context.get();
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  Figure f = lay_out(cr, history, specs, options);
  set_colour(cr, kWhite);
  cairo_paint(cr);
  draw_title(cr, history, f, options);
  for (int k = 0; k < 3; ++k) draw_panel(cr, f, k, specs[k], history.points, options);
  draw_footer(cr, f, specs, options);
  cairo_surface_flush(surface.get());
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS) cannot_write(path, cairo_status_to_string(cairo_status(cr)));
  write_png_atomically(surface.get(), path);
  return f.layout;
}

}  // namespace sheetgen
