// AtomicFile: the target appears only on commit, whole; a rename that fails
// reports why and leaves no temporary file; an abandoned write leaves nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sheetgen/core/atomic_file.hpp"
#include "../common/test_files.hpp"

namespace sheetgen {
namespace {

namespace fs = std::filesystem;

void write(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  out << text;
}

TEST(AtomicFile, TheTargetAppearsOnlyOnCommitAndNothingElseIsLeft) {
  const std::string dir = testing::temp_dir("atomic");
  ASSERT_FALSE(dir.empty());
  const std::string target = dir + "/out.txt";
  write(target, "old");
  {
    AtomicFile file(target);
    EXPECT_EQ(fs::path(file.temp_path()).parent_path(), fs::path(target).parent_path());  // same file system
    write(file.temp_path(), "new");
    EXPECT_EQ(testing::slurp(target), "old");  // not replaced before commit
    EXPECT_EQ(file.commit(), "");
  }
  EXPECT_EQ(testing::slurp(target), "new");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
  fs::remove_all(dir);
}

TEST(AtomicFile, AFailedRenameSaysWhyAndRemovesTheTemporaryFile) {
  const std::string dir = testing::temp_dir("atomic_bad");
  ASSERT_FALSE(dir.empty());
  const std::string target = dir + "/taken";
  fs::create_directories(target + "/inside");  // a non-empty folder cannot be replaced by a file
  {
    AtomicFile file(target);
    write(file.temp_path(), "data");
    EXPECT_NE(file.commit(), "");
    EXPECT_FALSE(fs::exists(file.temp_path()));
  }
  EXPECT_TRUE(fs::is_directory(target + "/inside"));
  fs::remove_all(dir);
}

TEST(AtomicFile, AnAbandonedWriteLeavesNothing) {
  const std::string dir = testing::temp_dir("atomic_drop");
  ASSERT_FALSE(dir.empty());
  {
    AtomicFile file(dir + "/out.txt");
    write(file.temp_path(), "half");
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sheetgen
