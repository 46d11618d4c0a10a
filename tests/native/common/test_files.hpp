#pragma once
// Small file helpers the tests share (one definition, so that test files can
// share a unity batch: tests/native/CMakeLists.txt).
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sheetgen::testing {

// The whole file as bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// CalculiX's executable, or "" when it is not installed.
inline std::string ccx_path() {
  for (const char* p : {"/usr/bin/ccx", "/usr/local/bin/ccx"})
    if (std::filesystem::exists(p)) return p;
  return "";
}

// A new folder sheetgen_<name>_XXXXXX under the temporary directory ("" on failure).
inline std::string temp_dir(const std::string& name) {
  std::string pattern = (std::filesystem::temp_directory_path() / ("sheetgen_" + name + "_XXXXXX")).string();
  if (!mkdtemp(pattern.data())) return "";
  return pattern;
}

}  // namespace sheetgen::testing
