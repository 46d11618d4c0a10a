#pragma once
// Axis ranges and tick positions for the report's charts: ticks every 1, 2 or
// 5 times a power of ten (Heckbert, "Nice numbers for graph labels", Graphics
// Gems, 1990), ranges rounded out to whole ticks.
#include <string>
#include <vector>

namespace sheetgen {

struct PlotAxis {
  double min = 0, max = 1;    // values at the axis' ends, in the data's unit
  double step = 1;            // between ticks
  std::vector<double> ticks;  // min <= tick <= max, ascending
  int decimals = 0;           // printed after the point: enough to tell ticks `step` apart

  // A tick value as printed on the axis ("0.30"; never "-0.0").
  std::string label(double value) const;
};

// 1, 2 or 5 times a power of ten near span / target_ticks (1 for an empty or non-finite span).
double nice_step(double span, int target_ticks);

// An axis holding every value (NaNs ignored), 6 % of the span clear above and
// below the extremes, then rounded out to whole ticks. With from_zero the axis
// is clipped at 0 and starts at 0 when the lowest value is within a quarter of
// the span from it. A single value gets +-10 % (+-1 for 0); no value gives 0..1.
PlotAxis value_axis(const std::vector<double>& values, bool from_zero, int target_ticks);

// Integer levels first..last, half a level of room either side so the end
// points sit inside the frame; ticks on whole levels, at least 1 apart.
PlotAxis level_axis(int first, int last, int target_ticks);

// Counts 0..largest (at least 1), with 4 % of room after the largest.
PlotAxis count_axis(int largest, int target_ticks);

}  // namespace sheetgen
