#!/usr/bin/env bash
# The whole test suite on a fresh Debian bookworm machine: installs what the
# project needs, builds, and runs every test (GoogleTest through ctest, the
# Python tests, and the tests inside `blender -b`). Exit status 0 = all passed.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
bash "$ROOT/scripts/install_deps.sh"
echo "== build ($BUILD_DIR)"
time BUILD_DIR="$BUILD_DIR" bash "$ROOT/scripts/build.sh"
echo "== tests"
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" </dev/null
# The sanitizer build runs the fast areas; the search areas (discovery, structure,
# compose) take over 20 minutes under ASan and are run by `scripts/sanitize.sh` alone.
echo "== sanitizers (ASan + UBSan, build-sanitize/)"
SANITIZE_TARGETS="sheetgen sheetgen_core_tests sheetgen_env_tests sheetgen_part_tests sheetgen_fem_tests" \
  bash "$ROOT/scripts/sanitize.sh" -L "core|env|part|fem" </dev/null
echo "== fuzzers (${FUZZ_SECONDS:-60} s per target, build-fuzz/)"
FUZZ_SECONDS="${FUZZ_SECONDS:-60}" bash "$ROOT/scripts/fuzz.sh" </dev/null
