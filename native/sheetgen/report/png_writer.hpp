#pragma once
// Transitional (issue 31): the names compose/generate.cpp used before
// write_convergence_png, so the CLI keeps building until its caller calls that
// directly; delete this file then. There is no PNG code here: the "image" is
// the history, drawn with cairo when it is written.
#include <string>

#include "sheetgen/report/convergence_plot.hpp"

namespace sheetgen {

using RgbImage = ConvergenceHistory;
struct ConvergencePlot {
  ConvergenceHistory image;
};
inline ConvergencePlot draw_convergence_plot(const ConvergenceHistory& history) { return {history}; }
inline void write_png_file(const std::string& path, const RgbImage& history) {
  write_convergence_png(history, ConvergenceOptions{}, path);
}

}  // namespace sheetgen
