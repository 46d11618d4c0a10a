// write_outputs of a hand-made run: the files of each load, result.json last,
// the problem named relative to it, and no staging folder left behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hand_made_result.hpp"
#include "sheetgen/pipeline/output_files.hpp"
#include "../common/test_files.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;

using testing::slurp;

struct OutputFiles : ::testing::Test {
  fs::path dir = fs::temp_directory_path() / ("sheetgen output files " + std::to_string(::getpid()));
  void SetUp() override { fs::remove_all(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(OutputFiles, EveryLoadHasItsFolderAndOnlyAnAnswerHasDrawings) {
  const Problem p = test::two_load_corner();
  write_outputs(dir.u8string(), p, test::hand_made_result(p), (dir / "problem.json").u8string());
  for (const char* f : {"part.obj", "flat.dxf", "flat.svg", "bends.csv", "history.csv", "convergence.png"})
    EXPECT_TRUE(fs::exists(dir / "avionics_box" / f)) << f;
  EXPECT_TRUE(fs::exists(dir / "second box" / "history.csv"));
  EXPECT_TRUE(fs::exists(dir / "second box" / "convergence.png"));
  EXPECT_FALSE(fs::exists(dir / "second box" / "part.obj"));
  EXPECT_EQ(slurp(dir / "second box" / "convergence.png").substr(1, 3), "PNG");
  // Written under .sheetgen-staging-<pid> and renamed: nothing else is left.
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    ++entries;
    EXPECT_EQ(e.path().filename().u8string().rfind(".sheetgen-staging", 0), std::string::npos) << e.path();
  }
  EXPECT_EQ(entries, 3);  // two load folders and result.json
}

TEST_F(OutputFiles, HistoryCsvHasOneRowPerLevel) {
  const Problem p = test::two_load_corner();
  write_outputs(dir.u8string(), p, test::hand_made_result(p), "problem.json");
  EXPECT_EQ(slurp(dir / "second box" / "history.csv"),
            "iteration,evaluated,found,best_cost_m2,best_area_m2,compliance_J,margin_of_safety\n"
            "1,10,0,0,0,0,0\n"
            "2,25,1,0.0125,0.0105,0.25,0.5\n");
}

TEST_F(OutputFiles, ResultJsonNamesTheProblemRelativeToItself) {
  const Problem p = test::two_load_corner();
  fs::create_directories(dir / "runs");
  write_outputs((dir / "runs" / "a").u8string(), p, test::hand_made_result(p), (dir / "scene" / "problem.json").u8string());
  const nlohmann::json doc = nlohmann::json::parse(slurp(dir / "runs" / "a" / "result.json"));
  EXPECT_EQ(doc["problem"], "../../scene/problem.json");
  EXPECT_EQ(doc["parts"].size(), 2u);
}

}  // namespace
}  // namespace sheetgen
