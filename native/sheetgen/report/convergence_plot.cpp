#include "sheetgen/report/convergence_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "sheetgen/report/raster_canvas.hpp"

namespace sheetgen {
namespace {

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kInk{30, 30, 30};        // text, frames
constexpr Rgb kTickInk{70, 70, 70};
constexpr Rgb kGrid{228, 228, 228};

struct Axis {
  double min = 0, max = 1, step = 1;
  std::vector<double> ticks;
  int decimals = 0;
};

// 1, 2 or 5 times a power of ten, near span / target.
double nice_step(double span, int target) {
  const double raw = span / std::max(target, 1);
  if (!(raw > 0) || !std::isfinite(raw)) return 1.0;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  return (norm < 1.5 ? 1.0 : norm < 3.0 ? 2.0 : norm < 7.0 ? 5.0 : 10.0) * mag;
}

int decimals_for(double step) { return std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9))); }

std::string format_tick(double v, const Axis& a) {
  if (std::abs(v) < a.step * 1e-6) v = 0;  // no "-0.0"
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", a.decimals, v);
  return buf;
}

std::string format_value(double v, int significant) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", significant, v);
  return buf;
}

void fill_ticks(Axis& a) {
  a.decimals = decimals_for(a.step);
  a.ticks.clear();
  const double first = std::ceil(a.min / a.step - 1e-9) * a.step;
  for (double t = first; t <= a.max + a.step * 1e-9; t += a.step) a.ticks.push_back(t);
}

// Values plus reference lines (limits, zero) padded and rounded out to whole ticks.
Axis value_axis(std::vector<double> values, bool non_negative, int target) {
  Axis a;
  if (values.empty()) values = {0.0, 1.0};
  double lo = *std::min_element(values.begin(), values.end());
  double hi = *std::max_element(values.begin(), values.end());
  if (hi - lo <= 1e-12 * std::max(1.0, std::abs(hi))) {
    const double pad = hi != 0 ? std::abs(hi) * 0.1 : 1.0;  // one value: +-10 %; only zero: +-1
    lo -= pad;
    hi += pad;
  }
  const double span = hi - lo;
  hi += 0.06 * span;  // keeps the highest point off the frame
  if (!(non_negative && lo >= 0 && lo <= 0.25 * span)) lo -= 0.06 * span;
  if (non_negative) lo = std::max(lo, 0.0);
  a.step = nice_step(hi - lo, target);
  a.min = std::floor(lo / a.step + 1e-9) * a.step;
  a.max = std::ceil(hi / a.step - 1e-9) * a.step;
  fill_ticks(a);
  return a;
}

Axis x_axis_for(const ConvergenceHistory& h, const ConvergencePlotOptions& o) {
  Axis a;
  if (o.x_axis == ConvergenceXAxis::Iteration) {
    int lo = 1, hi = 1;
    if (!h.points.empty()) {
      lo = hi = h.points.front().iteration;
      for (const auto& p : h.points) {
        lo = std::min(lo, p.iteration);
        hi = std::max(hi, p.iteration);
      }
    }
    a.min = lo - 0.5;  // half a level either side, so the end points sit inside the frame
    a.max = hi + 0.5;
    a.step = std::max(1.0, std::round(nice_step(a.max - a.min, o.target_ticks)));
    fill_ticks(a);
    return a;
  }
  int hi = 0;
  for (const auto& p : h.points) hi = std::max(hi, p.evaluated);
  a.min = 0;
  a.step = nice_step(std::max(hi, 1) * 1.04, o.target_ticks);
  a.step = std::max(1.0, a.step);
  a.max = std::ceil(std::max(hi, 1) * 1.04 / a.step) * a.step;
  fill_ticks(a);
  return a;
}

double x_value(const ConvergencePoint& p, ConvergenceXAxis axis) {
  return axis == ConvergenceXAxis::Iteration ? p.iteration : p.evaluated;
}

struct Box {  // px, x0 <= x < x1, y0 <= y < y1
  int x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

struct PanelSpec {
  std::string y_label;
  Rgb colour;
  std::vector<double> values;  // per point, NaN where not plotted
  double reference = std::numeric_limits<double>::quiet_NaN();
  std::string reference_label;
  std::string unit_suffix;     // after the last value, e.g. " J"
  bool non_negative = true;
};

void check_option(bool ok, const std::string& field, double value, const std::string& range) {
  if (!ok)
    throw std::invalid_argument("ConvergencePlotOptions::" + field + " " + format_value(value, 10) + " is not in " + range);
}

// Draws text, shrinking the scale until it fits max_width_px (down to 1).
void fitted_text(RasterCanvas& c, int x, int y, const std::string& s, Rgb colour, TextStyle style, int max_width_px) {
  while (style.scale > 1 && RasterCanvas::text_width_px(s, style.scale) > max_width_px) --style.scale;
  c.text(x, y, s, colour, style);
}

}  // namespace

ConvergencePlot draw_convergence_plot(const ConvergenceHistory& history, const ConvergencePlotOptions& o) {
  check_option(o.width_px >= 320 && o.width_px <= 8192, "width_px", o.width_px, "320..8192");
  check_option(o.height_px >= 360 && o.height_px <= 8192, "height_px", o.height_px, "360..8192");
  check_option(o.font_scale >= 1 && o.font_scale <= 8, "font_scale", o.font_scale, "1..8");
  check_option(o.title_font_scale >= 1 && o.title_font_scale <= 8, "title_font_scale", o.title_font_scale, "1..8");
  check_option(o.target_ticks >= 2 && o.target_ticks <= 20, "target_ticks", o.target_ticks, "2..20");
  check_option(o.line_thickness_px > 0 && o.line_thickness_px <= 50, "line_thickness_px", o.line_thickness_px, "(0, 50]");
  check_option(o.marker_radius_px >= 0 && o.marker_radius_px <= 50, "marker_radius_px", o.marker_radius_px, "0..50");

  const auto& pts = history.points;
  const auto plotted = [](const ConvergencePoint& p, double v) { return p.found && std::isfinite(v); };
  const double nan = std::numeric_limits<double>::quiet_NaN();

  std::vector<PanelSpec> specs(3);
  specs[0].y_label = "best flat area (cm\u00B2)";
  specs[0].colour = ConvergencePlotColours::area;
  specs[0].unit_suffix = " cm\u00B2";
  specs[1].y_label = "compliance (J)";
  specs[1].colour = ConvergencePlotColours::compliance;
  specs[1].unit_suffix = " J";
  specs[1].reference = history.compliance_limit_J;
  specs[1].reference_label = "limit " + format_value(history.compliance_limit_J, 3) + " J";
  specs[2].y_label = "margin of safety (-)";
  specs[2].colour = ConvergencePlotColours::margin;
  specs[2].reference = history.min_margin_of_safety;
  specs[2].reference_label = "required MS " + format_value(history.min_margin_of_safety, 3);
  specs[2].non_negative = false;
  for (const auto& p : pts) {
    const double area_cm2 = p.best_area_m2 * 1e4;
    specs[0].values.push_back(plotted(p, area_cm2) ? area_cm2 : nan);
    specs[1].values.push_back(plotted(p, p.compliance_J) ? p.compliance_J : nan);
    specs[2].values.push_back(plotted(p, p.margin_of_safety) ? p.margin_of_safety : nan);
  }

  std::vector<Axis> y_axes;
  for (const auto& s : specs) {
    std::vector<double> range;
    for (double v : s.values)
      if (std::isfinite(v)) range.push_back(v);
    if (std::isfinite(s.reference)) range.push_back(s.reference);
    if (s.non_negative && !range.empty()) range.push_back(0.0);
    y_axes.push_back(value_axis(range, s.non_negative, o.target_ticks));
  }
  const Axis x_axis = x_axis_for(history, o);

  // Layout, px.
  const int fs = o.font_scale;
  const int char_h = RasterCanvas::text_height_px(fs);
  const int margin = 16;
  const int title_h = RasterCanvas::text_height_px(o.title_font_scale);
  const int subtitle_top = margin + title_h + 10;
  const int panels_top = subtitle_top + char_h + 22;
  int tick_label_w = 0;
  for (const Axis& a : y_axes)
    for (double t : a.ticks) tick_label_w = std::max(tick_label_w, RasterCanvas::text_width_px(format_tick(t, a), fs));
  const int left = margin + char_h + 14 + tick_label_w + 12;
  const int right = o.width_px - 2 * margin;
  // Under the panels: tick labels, the x label, the legend line.
  const int panels_bottom = o.height_px - (margin + 3 * char_h + 34);
  const int gap = std::max(24, 2 * char_h);  // keeps one panel's lowest tick label clear of the next one's highest
  const int panel_h = (panels_bottom - panels_top - 2 * gap) / 3;
  if (panel_h < 40 || right - left < 80)
    throw std::invalid_argument("ConvergencePlotOptions: " + std::to_string(o.width_px) + " x " +
                                std::to_string(o.height_px) + " px leaves no room for the panels at font_scale " +
                                std::to_string(fs));

  RasterCanvas canvas(o.width_px, o.height_px, kWhite);
  ConvergencePlot plot;
  {
    TextStyle title;
    title.scale = o.title_font_scale;
    title.h_align = HAlign::Center;
    fitted_text(canvas, o.width_px / 2, margin, "Convergence: " + history.load, kInk, title, o.width_px - 2 * margin);
    std::string subtitle;
    const auto first = std::find_if(pts.begin(), pts.end(), [](const ConvergencePoint& p) { return p.found; });
    const int evaluated = pts.empty() ? 0 : pts.back().evaluated;
    if (pts.empty())
      subtitle = "no iterations recorded";
    else if (first == pts.end())
      subtitle = "no valid part in " + std::to_string(pts.size()) + " iterations (" + std::to_string(evaluated) +
                 " candidates)";
    else
      subtitle = "first valid part: iteration " + std::to_string(first->iteration) + ", " +
                 std::to_string(first->evaluated) + " of " + std::to_string(evaluated) + " candidates";
    TextStyle sub;
    sub.scale = fs;
    sub.h_align = HAlign::Center;
    fitted_text(canvas, o.width_px / 2, subtitle_top, subtitle, kTickInk, sub, o.width_px - 2 * margin);
  }

  for (int k = 0; k < 3; ++k) {
    const PanelSpec& spec = specs[k];
    const Axis& ya = y_axes[k];
    ConvergencePanel panel;
    panel.y_label = spec.y_label;
    panel.left_px = left;
    panel.right_px = right;
    panel.top_px = panels_top + k * (panel_h + gap);
    panel.bottom_px = panel.top_px + panel_h;
    panel.x_min = x_axis.min;
    panel.x_max = x_axis.max;
    panel.y_min = ya.min;
    panel.y_max = ya.max;
    const auto px_x = [&](double x) {
      return panel.left_px + (x - panel.x_min) / (panel.x_max - panel.x_min) * (panel.right_px - panel.left_px);
    };
    const auto px_y = [&](double y) {
      return panel.bottom_px - (y - panel.y_min) / (panel.y_max - panel.y_min) * (panel.bottom_px - panel.top_px);
    };
    const int top = static_cast<int>(panel.top_px), bottom = static_cast<int>(panel.bottom_px);

    // Grid and ticks.
    TextStyle tick_text;
    tick_text.scale = fs;
    tick_text.h_align = HAlign::Right;
    tick_text.v_align = VAlign::Middle;
    for (double t : ya.ticks) {
      const double y = std::floor(px_y(t)) + 0.5;
      canvas.line(left, y, right, y, kGrid);
      canvas.line(left - 7, y, left, y, kTickInk, {2.0});
      canvas.text(left - 12, static_cast<int>(y) + fs, format_tick(t, ya), kInk, tick_text);  // + fs: the 7-row cap height sits above the descender rows
    }
    for (double t : x_axis.ticks) {
      const double x = std::floor(px_x(t)) + 0.5;
      canvas.line(x, top, x, bottom, kGrid);
      canvas.line(x, bottom, x, bottom + 7, kTickInk, {2.0});
      if (k == 2) {
        TextStyle xt;
        xt.scale = fs;
        xt.h_align = HAlign::Center;
        canvas.text(static_cast<int>(x), bottom + 12, format_tick(t, x_axis), kInk, xt);
      }
    }
    // Frame.
    canvas.line(left + 0.5, top + 0.5, right - 0.5, top + 0.5, kInk, {1.0});
    canvas.line(left + 0.5, bottom - 0.5, right - 0.5, bottom - 0.5, kInk, {1.0});
    canvas.line(left + 0.5, top + 0.5, left + 0.5, bottom - 0.5, kInk, {1.0});
    canvas.line(right - 0.5, top + 0.5, right - 0.5, bottom - 0.5, kInk, {1.0});
    // Y label, rotated, centred on the panel.
    TextStyle yl;
    yl.scale = fs;
    yl.vertical = true;
    yl.v_align = VAlign::Middle;
    while (yl.scale > 1 && RasterCanvas::text_width_px(spec.y_label, yl.scale) > panel_h) --yl.scale;
    canvas.text(margin, (top + bottom) / 2, spec.y_label, kInk, yl);

    // Reference line (limit), dashed, with its label on a white box at the top right.
    std::vector<Box> keep_out;  // what the value label must not cover
    if (std::isfinite(spec.reference)) {
      const double y = px_y(spec.reference);
      canvas.line(left + 1, y, right - 1, y, ConvergencePlotColours::limit, {2.0, 12.0, 8.0});
      TextStyle lt;
      lt.scale = fs;
      lt.h_align = HAlign::Right;
      const int w = RasterCanvas::text_width_px(spec.reference_label, fs);
      // Above the line when there is room in the panel, else below it.
      const int ly = y - char_h - 6 > top + 2 ? static_cast<int>(y) - char_h - 5 : static_cast<int>(y) + 6;
      canvas.fill_rect(right - 10 - w - 4, ly - 2, right - 6, ly + char_h + 1, kWhite);
      keep_out.push_back({right - 10 - w - 4, ly - 2, right - 6, ly + char_h + 1});
      keep_out.push_back({left, static_cast<int>(y) - 3, right, static_cast<int>(y) + 4});
      canvas.text(right - 10, ly, spec.reference_label, ConvergencePlotColours::limit, lt);
    }

    // Curve: segments between consecutive plotted points, then the markers on top.
    const ConvergencePoint* prev = nullptr;
    double prev_v = 0;
    for (size_t i = 0; i < pts.size(); ++i) {
      const double v = spec.values[i];
      if (!std::isfinite(v)) continue;
      if (prev)
        canvas.line(px_x(x_value(*prev, o.x_axis)), px_y(prev_v), px_x(x_value(pts[i], o.x_axis)), px_y(v), spec.colour,
                    {o.line_thickness_px});
      prev = &pts[i];
      prev_v = v;
    }
    for (size_t i = 0; i < pts.size(); ++i) {
      const double x = px_x(x_value(pts[i], o.x_axis));
      const double v = spec.values[i];
      if (std::isfinite(v)) {
        canvas.marker(x, px_y(v), MarkerShape::FilledCircle, o.marker_radius_px, spec.colour);
        ++panel.plotted_points;
      } else {
        const double r = std::max(o.marker_radius_px, 4.0);
        canvas.marker(x, panel.bottom_px - r - 4, MarkerShape::Cross, r, ConvergencePlotColours::not_found);
        ++panel.not_found_points;
      }
    }
    // The last value in numbers, since a curve far below its limit is hard to read off.
    if (prev) {
      TextStyle vt;
      vt.scale = fs;
      vt.h_align = HAlign::Right;
      const int x = static_cast<int>(px_x(x_value(*prev, o.x_axis)));
      const int y = static_cast<int>(px_y(prev_v));
      const int r = static_cast<int>(std::ceil(o.marker_radius_px));
      const std::string label = format_value(prev_v, 3) + spec.unit_suffix;
      const int w = RasterCanvas::text_width_px(label, fs);
      // Above the point, else below: the first place inside the panel clear of the limit and its label.
      int ty = y - r - 6 - char_h;
      for (int candidate : {y - r - 6 - char_h, y + r + 6}) {
        const Box b{x - w, candidate, x, candidate + char_h};
        const bool inside = b.y0 > top + 2 && b.y1 < bottom - 2;
        const bool clear = std::none_of(keep_out.begin(), keep_out.end(), [&](const Box& k) { return k.overlaps(b); });
        if (inside && clear) {
          ty = candidate;
          break;
        }
      }
      canvas.text(x, ty, label, spec.colour, vt);
    }
    if (panel.plotted_points == 0) {
      TextStyle nt;
      nt.scale = fs;
      nt.h_align = HAlign::Center;
      nt.v_align = VAlign::Middle;
      // A third of the way down: clear of a limit line at mid-height.
      canvas.text((left + right) / 2, top + (bottom - top) / 3, "no valid part found", ConvergencePlotColours::not_found, nt);
    }
    plot.panels.push_back(panel);
  }

  // X label under the bottom panel; the legend of the grey crosses at its right.
  {
    const int y = static_cast<int>(plot.panels.back().bottom_px) + 12 + char_h + 10;
    TextStyle xl;
    xl.scale = fs;
    xl.h_align = HAlign::Center;
    canvas.text((left + right) / 2, y,
                o.x_axis == ConvergenceXAxis::Iteration ? "iteration (beam-search level)" : "candidates evaluated", kInk,
                xl);
    const bool any_not_found = std::any_of(plot.panels.begin(), plot.panels.end(),
                                           [](const ConvergencePanel& p) { return p.not_found_points > 0; });
    if (any_not_found) {
      const std::string legend = "no valid part yet";
      TextStyle lg;
      lg.scale = fs;
      lg.h_align = HAlign::Right;
      const int ly = y + char_h + 8;
      canvas.text(right, ly, legend, ConvergencePlotColours::not_found, lg);
      const double r = std::max(o.marker_radius_px, 4.0);
      canvas.marker(right - RasterCanvas::text_width_px(legend, fs) - r - 10, ly + 3.5 * fs, MarkerShape::Cross, r,
                    ConvergencePlotColours::not_found);
    }
  }
  plot.image = canvas.image();
  return plot;
}

}  // namespace sheetgen
