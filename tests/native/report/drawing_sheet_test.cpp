// The drawing sheet: the ISO scale that fits, the isometric projection's
// orientation and painter's order, the page and the scale of a written PDF,
// byte-identical output, rows left to the CSV when a table does not fit, and
// a path that cannot be written named with nothing left behind. Its text and
// vector content are read back by poppler in tests/python/test_drawing_pdf.py.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "sheetgen/report/drawing_scale.hpp"
#include "sheetgen/report/drawing_sheet.hpp"
#include "sheetgen/report/isometric_view.hpp"
#include "../common/test_files.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;

TEST(DrawingScale, LargestIsoReductionThatFits) {
  EXPECT_EQ(drawing_scale_denominator(0.200, 0.150, 226, 190), 1);
  EXPECT_EQ(drawing_scale_denominator(0.227, 0.100, 226, 190), 2);   // 1 mm too wide at 1:1
  EXPECT_EQ(drawing_scale_denominator(0.452, 0.380, 226, 190), 2);   // exactly the box at 1:2
  EXPECT_EQ(drawing_scale_denominator(0.675, 0.637, 226, 190), 5);
  EXPECT_EQ(drawing_scale_denominator(3.0, 0.1, 226, 190), 20);      // 1:10 would need 300 mm
  EXPECT_EQ(scale_label(5), "1:5");
  EXPECT_THROW(drawing_scale_denominator(NAN, 0.1, 226, 190), std::invalid_argument);
  EXPECT_THROW(drawing_scale_denominator(0.1, 0.1, 0, 190), std::invalid_argument);
}

TEST(IsometricView, WorldUpIsUpAndFarFacesComeFirst) {
  // A floor plate and a wall standing on its far side.
  const std::vector<std::vector<SheetPoint3>> tabs = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                                                       {{0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1}}};
  const IsometricView v = isometric_view(tabs);
  ASSERT_EQ(v.faces.size(), 2u);
  EXPECT_GT(v.project({0, 0, 1}).y - v.project({0, 0, 0}).y, 0.8);  // sqrt(2/3) = 0.816 for an isometric view
  EXPECT_NEAR(std::abs(v.view[0]), 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(v.view[2], -1 / std::sqrt(3.0), 1e-12);               // looking down
  EXPECT_GE(v.faces[0].depth, v.faces[1].depth);                     // painter's order: far first
  for (const IsometricFace& f : v.faces) EXPECT_TRUE(f.shade >= 0 && f.shade <= 1);
}

// A 300 x 100 mm strip with one 90 degree bend across it and two holes.
DrawingSheetPart strip() {
  DrawingSheetPart p;
  p.part_name = "strip";
  p.problem_name = "test/problem.json";
  p.status = "valid part: every check met";
  p.outline = {{0, 0}, {0.3, 0}, {0.3, 0.1}, {0, 0.1}};
  SheetBend b;
  b.number = 1;
  b.tab = 1;
  b.a = {0.2, 0};
  b.b = {0.2, 0.1};
  b.angle = M_PI / 2;
  b.inside_radius = 6.4e-3;
  b.length = 0.1;
  p.bends = {b};
  p.holes = {{"R1", false, 1, -1, {0.28, 0.02}, 4.069e-3, 0}, {"R2", false, 1, -1, {0.28, 0.08}, 4.069e-3, 0}};
  p.tabs = {{{0, 0, 0}, {0.2, 0, 0}, {0.2, 0.1, 0}, {0, 0.1, 0}}, {{0.2, 0.1, 0}, {0.2, 0, 0}, {0.2, 0, 0.1}, {0.2, 0.1, 0.1}}};
  p.material = {"Al 2024-T3 sheet", 1.6e-3, 2780, 73.1e9, 345e6, 483e6};
  p.flat_area = 0.03;
  p.mass = 0.03 * 1.6e-3 * 2780;
  p.k_factor = 0.45;
  p.kerf = 0.2e-3;
  p.rivet_diameter = 5 * 25.4e-3 / 32;
  return p;
}

struct DrawingSheet : ::testing::Test {
  fs::path dir = fs::temp_directory_path() / ("sheetgen drawing " + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(DrawingSheet, OnePageOfA3AtTheScaleThatFits) {
  const DrawingSheetLayout l = write_drawing_pdf(strip(), {}, (dir / "drawing.pdf").u8string());
  EXPECT_EQ(l.page_width_mm, 420);
  EXPECT_EQ(l.page_height_mm, 297);
  EXPECT_EQ(l.scale_denominator, 2);  // 300 mm is wider than the flat view (226 mm) at 1:1
  EXPECT_NEAR(l.flat_width_mm, 150, 1e-9);
  EXPECT_NEAR(l.flat_height_mm, 50, 1e-9);
  EXPECT_NEAR(l.extent_x_mm, 300, 1e-9);
  EXPECT_EQ(l.bend_rows, 1);
  EXPECT_EQ(l.bend_rows_omitted, 0);
  const std::string pdf = testing::slurp(dir / "drawing.pdf");
  EXPECT_EQ(pdf.substr(0, 5), "%PDF-");
  EXPECT_NE(pdf.find("/Count 1"), std::string::npos);  // one page
  EXPECT_NE(pdf.find("/MediaBox [ 0 0 1190.55"), std::string::npos);  // 420 mm in points
  EXPECT_EQ(pdf.find("CreationDate"), std::string::npos);
}

TEST_F(DrawingSheet, SamePartSameBytes) {
  write_drawing_pdf(strip(), {}, (dir / "a.pdf").u8string());
  write_drawing_pdf(strip(), {}, (dir / "b.pdf").u8string());
  EXPECT_EQ(testing::slurp(dir / "a.pdf"), testing::slurp(dir / "b.pdf"));
}

TEST_F(DrawingSheet, A4IsSmallerAndScalesFurther) {
  DrawingSheetOptions o;
  o.paper = PaperSize::A4;
  const DrawingSheetLayout l = write_drawing_pdf(strip(), o, (dir / "a4.pdf").u8string());
  EXPECT_EQ(l.page_width_mm, 297);
  EXPECT_EQ(l.page_height_mm, 210);
  EXPECT_EQ(l.scale_denominator, 5);  // the A4 flat view is 131 mm wide: 300 mm at 1:2 (150 mm) does not fit
}

TEST_F(DrawingSheet, RowsThatDoNotFitAreLeftToTheCsv) {
  DrawingSheetPart p = strip();
  for (int k = 2; k <= 60; ++k) {
    SheetBend b = p.bends.front();
    b.number = k;
    p.bends.push_back(b);
  }
  const DrawingSheetLayout l = write_drawing_pdf(p, {}, (dir / "many.pdf").u8string());
  EXPECT_GT(l.bend_rows, 10);
  EXPECT_GT(l.bend_rows_omitted, 0);
  EXPECT_EQ(l.bend_rows + l.bend_rows_omitted, 60);
}

TEST_F(DrawingSheet, UnwritablePathIsNamedAndNothingIsLeft) {
  std::ofstream(dir / "a file") << "x";
  const std::string path = (dir / "a file" / "drawing.pdf").u8string();  // a file is no folder, even for root
  try {
    write_drawing_pdf(strip(), {}, path);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += (void(e), 1);
  EXPECT_EQ(entries, 1);  // only "a file"
}

TEST_F(DrawingSheet, BadInputNamesTheField) {
  DrawingSheetPart p = strip();
  p.outline.resize(2);
  EXPECT_THROW(write_drawing_pdf(p, {}, (dir / "x.pdf").u8string()), std::invalid_argument);
  p = strip();
  p.holes[0].centre.x = NAN;
  try {
    write_drawing_pdf(p, {}, (dir / "x.pdf").u8string());
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("hole R1"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "x.pdf"));
}

}  // namespace
}  // namespace sheetgen
