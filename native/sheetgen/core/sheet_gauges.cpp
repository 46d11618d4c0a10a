#include "sheetgen/core/sheet_gauges.hpp"

#include <algorithm>
#include <cmath>

namespace sheetgen {

namespace {
constexpr double kInch = 0.0254;  // m
}

const std::vector<double>& standard_gauges() {
  static const std::vector<double> gauges = [] {
    std::vector<double> g;
    for (double in : {0.016, 0.020, 0.025, 0.032, 0.040, 0.050, 0.063, 0.071, 0.080, 0.090, 0.100, 0.125, 0.160})
      g.push_back(in * kInch);
    return g;
  }();
  return gauges;
}

std::vector<double> default_gauges(double thickness) {
  std::vector<double> out;
  // 1 um: a thickness given as 1.6e-3 m is the 0.063 in gauge (1.6002 mm), not below it.
  for (double g : standard_gauges())
    if (g > thickness + 1e-6) out.push_back(g);
  return out;
}

void derive_thickness_defaults(Manufacturing& mf, double t) {
  const ThicknessScaledInput& in = mf.given;
  mf.bend_radius = in.bend_radius.value_or(4.0 * t);
  mf.min_flange = in.min_flange.value_or(4.0 * t + mf.bend_radius);
  mf.min_tab_width = in.min_tab_width.value_or(10.0 * t);
  mf.min_tab_length = in.min_tab_length.value_or(2.0 * mf.bend_radius + 2.0 * t);
  // 1/8 in (3.175 mm) rivets are the smallest structural size; thicker sheet
  // takes D >= 2 t, rounded up to 1/32 in.
  const double rivet = std::max(3.175e-3, std::ceil(2.0 * t / 0.79375e-3) * 0.79375e-3);
  mf.rivet_diameter = in.rivet_diameter.value_or(rivet);
  mf.rivet_edge_distance = in.rivet_edge_distance.value_or(2.0 * mf.rivet_diameter);
  mf.rivet_pitch = in.rivet_pitch.value_or(6.0 * mf.rivet_diameter);
}

Problem at_gauge(const Problem& problem, double thickness) {
  Problem p = problem;
  p.material.thickness = thickness;
  derive_thickness_defaults(p.manufacturing, thickness);
  return p;
}

const Problem& problem_at_sheet(const Problem& problem, double thickness, std::optional<Problem>& storage) {
  if (!(thickness > 0) || std::abs(thickness - problem.material.thickness) <= 1e-12) return problem;
  storage = at_gauge(problem, thickness);
  return *storage;
}

}  // namespace sheetgen
