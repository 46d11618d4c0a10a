// Convergence plot: points land where the panel's axis mapping says, the
// limits are dashed lines at their values, levels without a valid part carry
// no value, and a sample is written for the Python check with PIL.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "sheetgen/report/convergence_plot.hpp"
#include "sheetgen/report/png_writer.hpp"

namespace sheetgen {
namespace {

using C = ConvergencePlotColours;

// Level 1 finds nothing, level 2 a part, level 3 a cheaper one that level 4 keeps.
ConvergenceHistory sample_history() {
  ConvergenceHistory h;
  h.load = "avionics_box";
  h.points = {{1, 30, false, 0, 0, 0},
              {2, 228, true, 0.08, 0.03, 2.0},
              {3, 434, true, 0.06, 0.04, 1.5},
              {4, 579, true, 0.06, 0.04, 1.5}};
  h.compliance_limit_J = 0.05;
  h.min_margin_of_safety = 0.5;
  return h;
}

// The mapping documented on ConvergencePanel, written out again here.
double map_x(const ConvergencePanel& p, double x) {
  return p.left_px + (x - p.x_min) / (p.x_max - p.x_min) * (p.right_px - p.left_px);
}
double map_y(const ConvergencePanel& p, double y) {
  return p.bottom_px - (y - p.y_min) / (p.y_max - p.y_min) * (p.bottom_px - p.top_px);
}
Rgb pixel(const ConvergencePlot& plot, double x, double y) {
  return plot.image.at(static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y)));
}

TEST(ConvergencePlot, ImageAndPanelsHaveTheRequestedLayout) {
  ConvergencePlotOptions o;
  o.width_px = 700;
  o.height_px = 800;
  const ConvergencePlot plot = draw_convergence_plot(sample_history(), o);
  EXPECT_EQ(plot.image.width_px, 700);
  EXPECT_EQ(plot.image.height_px, 800);
  ASSERT_EQ(plot.panels.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const auto& p = plot.panels[k];
    EXPECT_GT(p.left_px, 0);
    EXPECT_LT(p.right_px, 700);
    EXPECT_LT(p.bottom_px, 800);
    EXPECT_DOUBLE_EQ(p.x_min, 0.5);  // iterations 1..4, half a level either side
    EXPECT_DOUBLE_EQ(p.x_max, 4.5);
    if (k > 0) {
      EXPECT_GT(p.top_px, plot.panels[k - 1].bottom_px);  // stacked, not overlapping
    }
    EXPECT_EQ(p.plotted_points, 3);
    EXPECT_EQ(p.not_found_points, 1);
  }
  // Ranges hold the values and the limits: area 600..800 cm² from 0, compliance
  // 0.03..0.04 with the limit 0.05, MS 1.5..2 with the required 0.5.
  EXPECT_LE(plot.panels[0].y_min, 0.0);
  EXPECT_GE(plot.panels[0].y_max, 800.0);
  EXPECT_GE(plot.panels[1].y_max, 0.05);
  EXPECT_LE(plot.panels[2].y_min, 0.5);
  EXPECT_GE(plot.panels[2].y_max, 2.0);
}

TEST(ConvergencePlot, PointsLandWhereTheAxisMappingSays) {
  const ConvergenceHistory h = sample_history();
  const ConvergencePlot plot = draw_convergence_plot(h);
  const Rgb colours[3] = {C::area, C::compliance, C::margin};
  for (int k = 0; k < 3; ++k) {
    const auto& p = plot.panels[k];
    for (const auto& pt : h.points) {
      if (!pt.found) continue;
      const double v = k == 0 ? pt.best_area_m2 * 1e4 : k == 1 ? pt.compliance_J : pt.margin_of_safety;
      EXPECT_EQ(pixel(plot, map_x(p, pt.iteration), map_y(p, v)), colours[k]) << "panel " << k << " level " << pt.iteration;
    }
    // The curve between levels 2 and 3 passes through the mid-point of the two values.
    const double v2 = k == 0 ? 800.0 : k == 1 ? 0.03 : 2.0, v3 = k == 0 ? 600.0 : k == 1 ? 0.04 : 1.5;
    EXPECT_EQ(pixel(plot, map_x(p, 2.5), map_y(p, 0.5 * (v2 + v3))), colours[k]) << "panel " << k;
    // Below the curve, near the panel's floor, nothing of the curve's colour.
    EXPECT_NE(pixel(plot, map_x(p, 2.5), p.bottom_px - 5), colours[k]) << "panel " << k;
  }
}

TEST(ConvergencePlot, LevelWithoutAPartHasNoValueButAGreyMark) {
  const ConvergencePlot plot = draw_convergence_plot(sample_history());
  const Rgb colours[3] = {C::area, C::compliance, C::margin};
  for (int k = 0; k < 3; ++k) {
    const auto& p = plot.panels[k];
    const int x = static_cast<int>(map_x(p, 1.0));
    int curve = 0, grey = 0;
    for (int y = static_cast<int>(p.top_px); y < static_cast<int>(p.bottom_px); ++y)
      for (int dx = -3; dx <= 3; ++dx) {
        curve += plot.image.at(x + dx, y) == colours[k];
        grey += plot.image.at(x + dx, y) == C::not_found;
      }
    EXPECT_EQ(curve, 0) << "panel " << k << ": level 1 found nothing, no value may be drawn";
    EXPECT_GT(grey, 5) << "panel " << k;
  }
}

TEST(ConvergencePlot, LimitsAreDashedLinesAtTheirValues) {
  const ConvergencePlot plot = draw_convergence_plot(sample_history());
  const auto dashed_fraction = [&](const ConvergencePanel& p, double value) {
    const int y = static_cast<int>(std::floor(map_y(p, value)));
    int on = 0, n = 0;
    // The middle half of the panel: clear of the label at the right end.
    for (int x = static_cast<int>(p.left_px + 0.25 * (p.right_px - p.left_px));
         x < static_cast<int>(p.left_px + 0.75 * (p.right_px - p.left_px)); ++x, ++n)
      on += plot.image.at(x, y) == C::limit;
    return static_cast<double>(on) / n;
  };
  // 12 px dash, 8 px gap, and round caps of 1 px: about 13/20 of the line is painted.
  EXPECT_NEAR(dashed_fraction(plot.panels[1], 0.05), 0.65, 0.1);
  EXPECT_NEAR(dashed_fraction(plot.panels[2], 0.5), 0.65, 0.1);
  EXPECT_EQ(dashed_fraction(plot.panels[0], 0.05), 0.0);  // no limit on the area
}

TEST(ConvergencePlot, CandidatesEvaluatedAxis) {
  const ConvergenceHistory h = sample_history();
  ConvergencePlotOptions o;
  o.x_axis = ConvergenceXAxis::CandidatesEvaluated;
  const ConvergencePlot plot = draw_convergence_plot(h, o);
  const auto& p = plot.panels[0];
  EXPECT_DOUBLE_EQ(p.x_min, 0.0);
  EXPECT_GE(p.x_max, 579.0);
  EXPECT_EQ(pixel(plot, map_x(p, 434), map_y(p, 600.0)), C::area);
}

TEST(ConvergencePlot, NonFiniteValuesAreSkippedPerPanel) {
  ConvergenceHistory h = sample_history();
  h.points[2].compliance_J = std::nan("");
  const ConvergencePlot plot = draw_convergence_plot(h);
  EXPECT_EQ(plot.panels[0].plotted_points, 3);
  EXPECT_EQ(plot.panels[1].plotted_points, 2);
}

TEST(ConvergencePlot, NothingFoundAndEmptyHistoriesStillDraw) {
  ConvergenceHistory none;
  none.load = "battery";
  none.points = {{1, 30, false, 0, 0, 0}, {2, 90, false, 0, 0, 0}};
  const ConvergencePlot a = draw_convergence_plot(none);
  for (const auto& p : a.panels) {
    EXPECT_EQ(p.plotted_points, 0);
    EXPECT_EQ(p.not_found_points, 2);
  }
  const ConvergencePlot b = draw_convergence_plot(ConvergenceHistory{});
  EXPECT_EQ(b.panels.size(), 3u);
  EXPECT_EQ(b.panels[0].not_found_points, 0);
}

TEST(ConvergencePlot, RefusesBadOptionsByName) {
  ConvergencePlotOptions o;
  o.width_px = 100;
  try {
    draw_convergence_plot(sample_history(), o);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("width_px 100"), std::string::npos) << e.what();
  }
  o = {};
  o.font_scale = 0;
  EXPECT_THROW(draw_convergence_plot(sample_history(), o), std::invalid_argument);
  o = {};
  o.height_px = 400;
  o.font_scale = 8;  // no room left for three panels
  EXPECT_THROW(draw_convergence_plot(sample_history(), o), std::invalid_argument);
}

// Writes the sample plot for tests/python/test_report_png.py: the PNG, the same
// pixels as a binary PPM (read there without PIL) and the panels as JSON.
TEST(ConvergencePlot, WritesSamplePngForPython) {
  const char* out = std::getenv("SHEETGEN_REPORT_PNG_OUT");
  if (!out) GTEST_SKIP() << "SHEETGEN_REPORT_PNG_OUT not set";
  const ConvergenceHistory h = sample_history();
  const ConvergencePlot plot = draw_convergence_plot(h);
  const std::string png = out;
  write_png_file(png, plot.image);
  {
    std::ofstream ppm(png + ".ppm", std::ios::binary);
    ppm << "P6\n" << plot.image.width_px << ' ' << plot.image.height_px << "\n255\n";
    ppm.write(reinterpret_cast<const char*>(plot.image.pixels.data()), static_cast<std::streamsize>(plot.image.pixels.size()));
  }
  std::ofstream js(png + ".json");
  js.precision(17);
  js << "{\"panels\": [";
  const Rgb colours[3] = {C::area, C::compliance, C::margin};
  for (int k = 0; k < 3; ++k) {
    const auto& p = plot.panels[k];
    js << (k ? ", " : "") << "{\"left_px\": " << p.left_px << ", \"right_px\": " << p.right_px << ", \"top_px\": "
       << p.top_px << ", \"bottom_px\": " << p.bottom_px << ", \"x_min\": " << p.x_min << ", \"x_max\": " << p.x_max
       << ", \"y_min\": " << p.y_min << ", \"y_max\": " << p.y_max << ", \"colour\": [" << int(colours[k].r) << ", "
       << int(colours[k].g) << ", " << int(colours[k].b) << "], \"points\": [";
    bool first = true;
    for (const auto& pt : h.points) {
      if (!pt.found) continue;
      const double v = k == 0 ? pt.best_area_m2 * 1e4 : k == 1 ? pt.compliance_J : pt.margin_of_safety;
      js << (first ? "" : ", ") << "[" << pt.iteration << ", " << v << "]";
      first = false;
    }
    js << "]}";
  }
  js << "]}\n";
}

}  // namespace
}  // namespace sheetgen
