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
