#!/usr/bin/env bash
# The main job on a sample scene: install, build, then validate the problem and
# run the environment queries on it. SCENE defaults to sample_scenes/corner.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
SCENE="${1:-$ROOT/sample_scenes/corner/problem.json}"
bash "$ROOT/scripts/install_deps.sh"
BUILD_DIR="$BUILD_DIR" bash "$ROOT/scripts/build.sh"
"$BUILD_DIR/native/cli/sheetgen" check "$SCENE" --env
