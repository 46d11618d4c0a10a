#include "sheetgen/report/plot_axis.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sheetgen {
namespace {

int decimals_for(double step) { return std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9))); }

// Ticks at whole multiples of the step inside [min, max]; the 1e-9 steps of
// slack keep an end that is a multiple up to rounding.
void fill_ticks(PlotAxis& a) {
  a.decimals = decimals_for(a.step);
  a.ticks.clear();
  const long first = std::lround(std::ceil(a.min / a.step - 1e-9));
  const long last = std::lround(std::floor(a.max / a.step + 1e-9));
  for (long k = first; k <= last; ++k) a.ticks.push_back(k * a.step);
}

}  // namespace

std::string PlotAxis::label(double value) const {
  if (std::abs(value) < step * 1e-6) value = 0;  // no "-0.0"
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

double nice_step(double span, int target_ticks) {
  const double raw = span / std::max(target_ticks, 1);
  if (!(raw > 0) || !std::isfinite(raw)) return 1.0;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / magnitude;
  // Heckbert's rounding thresholds: nearest of 1, 2, 5, 10 on a log-ish scale.
  return (norm < 1.5 ? 1.0 : norm < 3.0 ? 2.0 : norm < 7.0 ? 5.0 : 10.0) * magnitude;
}

PlotAxis value_axis(const std::vector<double>& values, bool from_zero, int target_ticks) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  if (finite.empty()) finite = {0.0, 1.0};
  double lo = *std::min_element(finite.begin(), finite.end());
  double hi = *std::max_element(finite.begin(), finite.end());
  if (hi - lo <= 1e-12 * std::max(1.0, std::abs(hi))) {
    const double pad = hi != 0 ? std::abs(hi) * 0.1 : 1.0;
    lo -= pad;
    hi += pad;
  }
  const double span = hi - lo;
  hi += 0.06 * span;
  if (!(from_zero && lo >= 0 && lo <= 0.25 * span)) lo -= 0.06 * span;
  if (from_zero) lo = std::max(lo, 0.0);
  PlotAxis a;
  a.step = nice_step(hi - lo, target_ticks);
  a.min = std::floor(lo / a.step + 1e-9) * a.step;
  a.max = std::ceil(hi / a.step - 1e-9) * a.step;
  fill_ticks(a);
  return a;
}

PlotAxis level_axis(int first, int last, int target_ticks) {
  PlotAxis a;
  a.min = std::min(first, last) - 0.5;
  a.max = std::max(first, last) + 0.5;
  a.step = std::max(1.0, std::round(nice_step(a.max - a.min, target_ticks)));
  fill_ticks(a);
  return a;
}

PlotAxis count_axis(int largest, int target_ticks) {
  const double end = std::max(largest, 1) * 1.04;
  PlotAxis a;
  a.min = 0;
  a.step = std::max(1.0, nice_step(end, target_ticks));
  a.max = std::ceil(end / a.step) * a.step;
  fill_ticks(a);
  return a;
}

}  // namespace sheetgen
