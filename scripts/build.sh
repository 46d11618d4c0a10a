#!/usr/bin/env bash
# Configure and build everything (core, CLI, Python module, tests, benchmarks)
# in Release into BUILD_DIR (default: build/). Uses ccache and Ninja.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
JOBS="${JOBS:-$(nproc)}"
# shellcheck source=scripts/ccache_env.sh
source "$ROOT/scripts/ccache_env.sh"
cmake -S "$ROOT" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${BUILD_TYPE:-Release}" "$@" >/dev/null
cmake --build "$BUILD_DIR" -j "$JOBS"
