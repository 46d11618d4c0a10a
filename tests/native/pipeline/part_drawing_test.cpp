// The drawing sheet from result.json: the content read from a part's entry
// (mass, area, outline, the governing case of each check, buckling without
// compression), the loads that have no drawing, the problem's label, and
// write_outputs writing drawing.pdf for a load with a part only.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "hand_made_result.hpp"
#include "sheetgen/core/input_error.hpp"
#include "sheetgen/pipeline/output_files.hpp"
#include "sheetgen/pipeline/part_drawing.hpp"
#include "sheetgen/pipeline/result_json.hpp"
#include "../common/test_files.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TEST(PartDrawing, ReadsTheEntryOfTheBareBaseTab) {
  const Problem p = test::two_load_corner();
  const GenerateResult r = test::hand_made_result(p);
  const json entry = load_result_json(p, r.loads[0]);
  const DrawingSheetPart d = drawing_sheet_part(entry, p);
  EXPECT_EQ(d.part_name, "avionics_box");
  EXPECT_EQ(d.problem_name, "corner/problem.json");
  EXPECT_EQ(d.material.name, "Al 2024-T3 sheet");
  EXPECT_DOUBLE_EQ(d.mass, entry["mass_kg"].get<double>());
  EXPECT_DOUBLE_EQ(d.flat_area, 0.01);
  EXPECT_EQ(d.outline.size(), entry["flat_pattern"]["outline"][0].size());
  EXPECT_EQ(d.tabs.size(), 1u);
  EXPECT_TRUE(d.bends.empty());
  EXPECT_TRUE(std::isnan(d.checks.compliance));  // not analysed: nothing to show
}

TEST(PartDrawing, TakesEachCheckFromItsGoverningCase) {
  const Problem p = test::two_load_corner();
  json entry = load_result_json(p, test::hand_made_result(p).loads[0]);
  entry["envelope"] = json::parse(R"({
    "cases": [{"name": "up", "compliance": 0.1, "compliance_limit": 0.4, "margin_of_safety": 0.2},
              {"name": "fwd", "compliance": 0.3, "compliance_limit": 0.5, "margin_of_safety": 0.9}],
    "governing": {"stiffness": "fwd", "strength": "up", "buckling": null},
    "eigen_checked": true, "buckling_factor": null, "frequencies_hz": [41.5, 80.0],
    "required": {"checked": true, "min_buckling_factor": 1.5, "min_frequency_hz": 30.0}})");
  const SheetChecks c = drawing_sheet_part(entry, p).checks;
  EXPECT_EQ(c.stiffness_case, "fwd");
  EXPECT_DOUBLE_EQ(c.compliance, 0.3);
  EXPECT_DOUBLE_EQ(c.compliance_limit, 0.5);
  EXPECT_EQ(c.strength_case, "up");
  EXPECT_DOUBLE_EQ(c.margin_of_safety, 0.2);
  EXPECT_TRUE(std::isinf(c.buckling_factor));  // checked, and no case compresses the sheet
  EXPECT_DOUBLE_EQ(c.min_buckling_factor, 1.5);
  EXPECT_DOUBLE_EQ(c.frequency_hz, 41.5);
  EXPECT_DOUBLE_EQ(c.min_frequency_hz, 30.0);
}

TEST(PartDrawing, OnlyALoadWithAValidPartHasADrawing) {
  const Problem p = test::two_load_corner();
  const json doc = result_json(p, test::hand_made_result(p), "problem.json");
  EXPECT_EQ(drawable_part_entry(doc, "avionics_box")["load"], "avionics_box");
  try {
    drawable_part_entry(doc, "nope");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("avionics_box, second box"), std::string::npos) << e.what();
  }
  EXPECT_THROW(drawable_part_entry(doc, "second box"), InputError);
  EXPECT_THROW(write_load_drawing("{not json", "avionics_box", p, "/tmp/x.pdf"), InputError);
}

TEST(PartDrawing, ProblemLabelIsTheFolderAndFile) {
  EXPECT_EQ(problem_label("/a/b/sample_scenes/corner/problem.json"), "corner/problem.json");
  EXPECT_EQ(problem_label("problem.json"), "problem.json");
  EXPECT_EQ(problem_label("scene 'Scene'"), "scene 'Scene'");
}

TEST(PartDrawing, WriteOutputsDrawsTheLoadWithAPartOnly) {
  const fs::path dir = fs::temp_directory_path() / ("sheetgen part drawing " + std::to_string(::getpid()));
  fs::remove_all(dir);
  const Problem p = test::two_load_corner();
  write_outputs(dir.u8string(), p, test::hand_made_result(p), "problem.json");
  EXPECT_EQ(testing::slurp(dir / "avionics_box" / "drawing.pdf").substr(0, 5), "%PDF-");
  EXPECT_FALSE(fs::exists(dir / "second box" / "drawing.pdf"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sheetgen
