#!/usr/bin/env bash
# The main job on a sample scene: install, build, validate the problem, then
# design its bracket inside a headless Blender run of the scene's .blend (the
# add-on's Generate, result objects, exports and a presentation render) into
# out/<scene>/. SCENE defaults to corner; extra arguments go to the batch script
# (e.g. --iterations 300 --chains 6 for a quick run).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"
SCENE="${1:-corner}"
shift || true
bash "$ROOT/scripts/install_deps.sh"
BUILD_DIR="$BUILD_DIR" bash "$ROOT/scripts/build.sh"
"$BUILD_DIR/native/cli/sheetgen" check "$ROOT/sample_scenes/$SCENE/problem.json" --env
mkdir -p "$ROOT/out/$SCENE"
blender -b "$ROOT/sample_scenes/$SCENE/scene.blend" --python-exit-code 1 \
  --python "$ROOT/scripts/blender_batch.py" -- --out "$ROOT/out/$SCENE" --render --build-dir "$BUILD_DIR" "$@"
