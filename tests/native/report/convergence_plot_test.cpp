// Convergence plot: the PNG is 8-bit RGB at the requested size, points land
// where the panel's axis mapping says (read back with libpng, a decoder
// independent of cairo), the limits are dashed lines at their values with the
// feasible side shaded, levels without a valid part carry no value, a path that
// cannot be written throws naming it and leaves nothing behind, and a sample
// is written for the Python check with PIL (tests/python/test_report_png.py).
#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "sheetgen/report/convergence_plot.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;
using C = ConvergenceColours;

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

double value(const ConvergencePoint& p, int panel) {
  return panel == 0 ? p.best_area_m2 * 1e4 : panel == 1 ? p.compliance_J : p.margin_of_safety;
}
const ConvergenceColour kCurve[3] = {C::area, C::compliance, C::margin};

struct Png {
  int width = 0, height = 0;
  bool rgb_without_alpha = false;
  std::vector<std::uint8_t> rgb;  // #height by #width by 3
  ConvergenceColour at(double x, double y) const {
    const size_t i = (static_cast<size_t>(std::floor(y)) * width + static_cast<size_t>(std::floor(x))) * 3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// libpng's simplified reader, converting to 8-bit RGB.
Png read_png(const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str())) throw std::runtime_error(path + ": " + image.message);
  Png out;
  out.rgb_without_alpha = (image.format & PNG_FORMAT_FLAG_COLOR) && !(image.format & PNG_FORMAT_FLAG_ALPHA);
  image.format = PNG_FORMAT_RGB;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr))
    throw std::runtime_error(path + ": " + image.message);
  return out;
}

// The mapping documented on ConvergencePanel, written out again here.
double map_x(const ConvergencePanel& p, double x) {
  return p.left_px + (x - p.x_min) / (p.x_max - p.x_min) * (p.right_px - p.left_px);
}
double map_y(const ConvergencePanel& p, double y) {
  return p.bottom_px - (y - p.y_min) / (p.y_max - p.y_min) * (p.bottom_px - p.top_px);
}

// Euclidean distance in RGB: anti-aliased edges blend a colour with its background.
double distance(ConvergenceColour a, ConvergenceColour b) {
  return std::hypot(a.r - b.r, std::hypot(a.g - b.g, a.b - b.b));
}

class ConvergencePlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sheetgen_report_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Writes the plot and reads it back.
  Png draw(const ConvergenceHistory& h, const ConvergenceOptions& o, ConvergencePlotLayout* layout) {
    *layout = write_convergence_png(h, o, path("convergence.png"));
    return read_png(path("convergence.png"));
  }
  fs::path dir_;
};

TEST_F(ConvergencePlotTest, PngIsRgbOfTheRequestedSizeWithStackedPanels) {
  ConvergenceOptions o;
  o.width_px = 700;
  o.height_px = 800;
  ConvergencePlotLayout layout;
  const Png png = draw(sample_history(), o, &layout);
  EXPECT_TRUE(png.rgb_without_alpha);
  EXPECT_EQ(png.width, 700);
  EXPECT_EQ(png.height, 800);
  EXPECT_EQ(layout.width_px, 700);
  EXPECT_EQ(layout.height_px, 800);
  ASSERT_EQ(layout.panels.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const auto& p = layout.panels[k];
    EXPECT_GT(p.left_px, 0);
    EXPECT_LT(p.right_px, 700);
    EXPECT_LT(p.bottom_px, 800);
    EXPECT_DOUBLE_EQ(p.x_min, 0.5);  // iterations 1..4, half a level either side
    EXPECT_DOUBLE_EQ(p.x_max, 4.5);
    if (k > 0) {
      EXPECT_GT(p.top_px, layout.panels[k - 1].bottom_px);  // stacked, not overlapping
    }
    EXPECT_EQ(p.plotted_points, 3);
    EXPECT_EQ(p.not_found_points, 1);
  }
  // Ranges hold the values and the limits: area 600..800 cm² from 0, compliance
  // 0.03..0.04 with the limit 0.05, MS 1.5..2 with the required 0.5.
  EXPECT_LE(layout.panels[0].y_min, 0.0);
  EXPECT_GE(layout.panels[0].y_max, 800.0);
  EXPECT_GE(layout.panels[1].y_max, 0.05);
  EXPECT_LE(layout.panels[2].y_min, 0.5);
  EXPECT_GE(layout.panels[2].y_max, 2.0);
  // Every file in the folder is the plot: no temporary left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(ConvergencePlotTest, PointsLandWhereTheAxisMappingSays) {
  const ConvergenceHistory h = sample_history();
  ConvergencePlotLayout layout;
  const Png png = draw(h, {}, &layout);
  for (int k = 0; k < 3; ++k) {
    const auto& p = layout.panels[k];
    for (const auto& pt : h.points) {
      if (!pt.found) continue;
      // The pixel holding the centre of a 6 px marker is covered whole: the exact colour.
      EXPECT_EQ(png.at(map_x(p, pt.iteration), map_y(p, value(pt, k))), kCurve[k]) << "panel " << k << " level " << pt.iteration;
    }
    // The 3 px curve between levels 2 and 3 covers the pixel holding its mid-point whole.
    const double mid = 0.5 * (value(h.points[1], k) + value(h.points[2], k));
    EXPECT_EQ(png.at(map_x(p, 2.5), map_y(p, mid)), kCurve[k]) << "panel " << k;
    // Near the panel's floor under that mid-point, nothing of the curve's colour.
    EXPECT_GT(distance(png.at(map_x(p, 2.5), p.bottom_px - 5), kCurve[k]), 100) << "panel " << k;
  }
}

TEST_F(ConvergencePlotTest, LevelWithoutAPartHasNoValueButAGreyMark) {
  ConvergencePlotLayout layout;
  const Png png = draw(sample_history(), {}, &layout);
  for (int k = 0; k < 3; ++k) {
    const auto& p = layout.panels[k];
    const int x = static_cast<int>(map_x(p, 1.0));
    int curve = 0, grey = 0;
    for (int y = static_cast<int>(p.top_px); y < static_cast<int>(p.bottom_px); ++y)
      for (int dx = -8; dx <= 8; ++dx) {
        curve += distance(png.at(x + dx, y), kCurve[k]) < 80;
        grey += distance(png.at(x + dx, y), C::not_found) < 20;
      }
    EXPECT_EQ(curve, 0) << "panel " << k << ": level 1 found nothing, no value may be drawn";
    EXPECT_GT(grey, 10) << "panel " << k << ": the cross";
  }
}

TEST_F(ConvergencePlotTest, LimitsAreDashedLinesAtTheirValues) {
  ConvergencePlotLayout layout;
  const Png png = draw(sample_history(), {}, &layout);
  const auto dashed_fraction = [&](const ConvergencePanel& p, double v) {
    // A 2 px line centred at y always covers the whole row floor(y).
    const double y = map_y(p, v);
    int on = 0, n = 0;
    // The middle half of the panel: clear of the label at the right end.
    for (double x = p.left_px + 0.25 * (p.right_px - p.left_px); x < p.left_px + 0.75 * (p.right_px - p.left_px);
         x += 1, ++n)
      on += png.at(x, y) == C::limit;
    return static_cast<double>(on) / n;
  };
  // 12 px on, 8 px off: 12/20 of the row, less the partly covered pixel at each dash end.
  EXPECT_NEAR(dashed_fraction(layout.panels[1], 0.05), 0.6, 0.07);
  EXPECT_NEAR(dashed_fraction(layout.panels[2], 0.5), 0.6, 0.07);
  EXPECT_EQ(dashed_fraction(layout.panels[0], 0.05), 0.0);  // no limit on the area
}

TEST_F(ConvergencePlotTest, FeasibleSideOfEachLimitIsShaded) {
  ConvergencePlotLayout layout;
  const Png png = draw(sample_history(), {}, &layout);
  // Half-way between levels 1 and 2 there is nothing but the shade, the white
  // ground and the 1 px grid rows; count each side of the limit, 4 px clear of the dashes.
  const auto fractions = [&](const ConvergencePanel& p, double limit, double* shaded_below, double* shaded_above) {
    const double x = map_x(p, 1.5), y_limit = map_y(p, limit);
    int below = 0, n_below = 0, above = 0, n_above = 0;
    for (double y = p.top_px + 2; y < p.bottom_px - 2; y += 1) {
      if (std::abs(y - y_limit) < 4) continue;
      const bool shaded = png.at(x, y) == C::feasible;
      if (y > y_limit) {
        below += shaded;
        ++n_below;
      } else {
        above += shaded;
        ++n_above;
      }
    }
    *shaded_below = static_cast<double>(below) / n_below;
    *shaded_above = static_cast<double>(above) / n_above;
  };
  double below = 0, above = 0;
  fractions(layout.panels[1], 0.05, &below, &above);  // compliance: feasible under the limit
  EXPECT_GT(below, 0.9);
  EXPECT_EQ(above, 0.0);
  fractions(layout.panels[2], 0.5, &below, &above);  // MS: feasible over the required MS
  EXPECT_EQ(below, 0.0);
  EXPECT_GT(above, 0.9);
}

TEST_F(ConvergencePlotTest, CandidatesEvaluatedAxis) {
  ConvergenceOptions o;
  o.x_axis = ConvergenceXAxis::CandidatesEvaluated;
  ConvergencePlotLayout layout;
  const Png png = draw(sample_history(), o, &layout);
  const auto& p = layout.panels[0];
  EXPECT_DOUBLE_EQ(p.x_min, 0.0);
  EXPECT_GE(p.x_max, 579.0);
  EXPECT_EQ(png.at(map_x(p, 434), map_y(p, 600.0)), C::area);
}

TEST_F(ConvergencePlotTest, NonFiniteValuesAreSkippedPerPanel) {
  ConvergenceHistory h = sample_history();
  h.points[2].compliance_J = std::nan("");
  const ConvergencePlotLayout layout = write_convergence_png(h, {}, path("convergence.png"));
  EXPECT_EQ(layout.panels[0].plotted_points, 3);
  EXPECT_EQ(layout.panels[1].plotted_points, 2);
}

TEST_F(ConvergencePlotTest, NothingFoundAndEmptyHistoriesStillDraw) {
  ConvergenceHistory none;
  none.load = "battery";
  none.points = {{1, 30, false, 0, 0, 0}, {2, 90, false, 0, 0, 0}};
  ConvergencePlotLayout a;
  const Png png = draw(none, {}, &a);
  EXPECT_EQ(png.width, 900);
  EXPECT_EQ(png.height, 1000);
  for (const auto& p : a.panels) {
    EXPECT_EQ(p.plotted_points, 0);
    EXPECT_EQ(p.not_found_points, 2);
  }
  const ConvergencePlotLayout b = write_convergence_png(ConvergenceHistory{}, {}, path("empty.png"));
  EXPECT_EQ(b.panels.size(), 3u);
  EXPECT_EQ(b.panels[0].not_found_points, 0);
  EXPECT_EQ(read_png(path("empty.png")).width, 900);
}

TEST_F(ConvergencePlotTest, RefusesBadOptionsByNameAndWritesNothing) {
  ConvergenceOptions o;
  o.width_px = 100;
  try {
    write_convergence_png(sample_history(), o, path("convergence.png"));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("width_px 100"), std::string::npos) << e.what();
  }
  o = {};
  o.font_size_px = 0;
  EXPECT_THROW(write_convergence_png(sample_history(), o, path("convergence.png")), std::invalid_argument);
  o = {};
  o.height_px = 400;
  o.font_size_px = 60;  // no room left for three panels
  EXPECT_THROW(write_convergence_png(sample_history(), o, path("convergence.png")), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir_));
}

// Expects write_convergence_png to throw std::runtime_error naming target.
void expect_write_error(const std::string& target) {
  try {
    write_convergence_png(sample_history(), {}, target);
    FAIL() << "no exception for " << target;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
  }
}

TEST_F(ConvergencePlotTest, UnwritablePathThrowsNamingItAndLeavesNoFile) {
  // A folder that does not exist.
  expect_write_error(path("missing/convergence.png"));
  EXPECT_FALSE(fs::exists(path("missing")));
  // A folder where the file should go: the temporary is written, the rename
  // fails, and the temporary is removed again.
  fs::create_directories(path("convergence.png/inside"));
  expect_write_error(path("convergence.png"));
  EXPECT_TRUE(fs::is_directory(path("convergence.png")));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

TEST_F(ConvergencePlotTest, RewritingReplacesTheWholeFile) {
  ConvergenceOptions small;
  small.width_px = 400;
  small.height_px = 500;
  write_convergence_png(sample_history(), {}, path("convergence.png"));
  write_convergence_png(sample_history(), small, path("convergence.png"));
  const Png png = read_png(path("convergence.png"));
  EXPECT_EQ(png.width, 400);
  EXPECT_EQ(png.height, 500);
}

// Writes the sample plot for tests/python/test_report_png.py: the PNG and,
// beside it, the panels and the points each should show, as JSON.
TEST(ConvergencePlotSample, WritesSamplePngForPython) {
  const char* out = std::getenv("SHEETGEN_REPORT_PNG_OUT");
  if (!out) GTEST_SKIP() << "SHEETGEN_REPORT_PNG_OUT not set";
  const ConvergenceHistory h = sample_history();
  const ConvergenceOptions o;
  const ConvergencePlotLayout layout = write_convergence_png(h, o, out);
  std::ofstream js(std::string(out) + ".json");
  js.precision(17);
  js << "{\"width_px\": " << o.width_px << ", \"height_px\": " << o.height_px << ", \"panels\": [";
  for (int k = 0; k < 3; ++k) {
    const auto& p = layout.panels[k];
    js << (k ? ", " : "") << "{\"left_px\": " << p.left_px << ", \"right_px\": " << p.right_px << ", \"top_px\": "
       << p.top_px << ", \"bottom_px\": " << p.bottom_px << ", \"x_min\": " << p.x_min << ", \"x_max\": " << p.x_max
       << ", \"y_min\": " << p.y_min << ", \"y_max\": " << p.y_max << ", \"colour\": [" << int(kCurve[k].r) << ", "
       << int(kCurve[k].g) << ", " << int(kCurve[k].b) << "], \"points\": [";
    bool first = true;
    for (const auto& pt : h.points) {
      if (!pt.found) continue;
      js << (first ? "" : ", ") << "[" << pt.iteration << ", " << value(pt, k) << "]";
      first = false;
    }
    js << "]}";
  }
  js << "]}\n";
}

}  // namespace
}  // namespace sheetgen
