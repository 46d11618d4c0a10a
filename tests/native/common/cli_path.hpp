#pragma once
// Where the tests find the `sheetgen` command line they drive.
#include <cstdlib>
#include <string>

namespace sheetgen::testing {

// The CLI of this build, unless SHEETGEN_CLI names another one. The fast
// tier's sanitizer run sets it to the Release build's CLI: the sanitized test
// executables then check the in-process code under ASan/UBSan without compiling
// every search area sanitized (the full tier sanitizes the CLI itself).
inline std::string sheetgen_cli() {
  if (const char* path = std::getenv("SHEETGEN_CLI"); path && *path) return path;
  return std::string(SHEETGEN_BINARY_DIR) + "/native/cli/sheetgen";
}

}  // namespace sheetgen::testing
