#pragma once
// Where the tests find the `sheetgen` command line they drive, and how they run it.
#include <sys/wait.h>

#include <cstdio>
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

// What a run of the CLI gave: its exit code (-1 when it did not exit) and
// what reached the pipe.
struct CliRun {
  int exit_code = -1;
  std::string output;
};

// Runs `sheetgen <args>` through the shell. `args` carries the redirections
// that choose what reaches the pipe (" 2>&1", " 2>&1 >/dev/null", ...).
inline CliRun run_cli(const std::string& args) {
  FILE* pipe = popen((sheetgen_cli() + " " + args).c_str(), "r");
  CliRun run;
  char buf[4096];
  while (pipe && fgets(buf, sizeof buf, pipe)) run.output += buf;
  const int status = pipe ? pclose(pipe) : -1;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

}  // namespace sheetgen::testing
