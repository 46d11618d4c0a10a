#!/usr/bin/env bash
# Install the sheetgen Blender add-on into a Blender user scripts folder:
#   <scripts>/addons/sheetgen_blender/            the add-on (blender_addon/sheetgen_blender)
#   <scripts>/addons/sheetgen_blender/_sheetgen_native.<EXT_SUFFIX>   the native module, beside it
#
# Usage: scripts/install_addon.sh [--link] [--enable] [--build-dir DIR] [--scripts-dir DIR]
#   --scripts-dir DIR  default: $BLENDER_USER_SCRIPTS, else ~/.config/blender/<version>/scripts
#                      (<version> from `blender --version`, else 3.4)
#   --build-dir DIR    where the native module was built (default: build/; it must hold
#                      python/_sheetgen_native.*.so: cmake --build build --target _sheetgen_native)
#   --link             symlink the files instead of copying (for add-on development; rerun
#                      after adding files to the package)
#   --enable           enable the add-on in Blender's preferences and save them
#                      (with BLENDER_USER_SCRIPTS=DIR when --scripts-dir is not the default)
# A module must be built for the Python of the Blender that loads it: Debian's Blender 3.4
# runs the system Python 3.11; blender.org builds of 3.4 ship Python 3.10 (see docs/platform.md).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="$ROOT/build"
SCRIPTS_DIR="${BLENDER_USER_SCRIPTS:-}"
LINK=0
ENABLE=0
while [ $# -gt 0 ]; do
  case "$1" in
    --link) LINK=1 ;;
    --enable) ENABLE=1 ;;
    --build-dir) BUILD_DIR="$2"; shift ;;
    --scripts-dir) SCRIPTS_DIR="$2"; shift ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "install_addon.sh: unknown argument '$1' (see --help)" >&2; exit 1 ;;
  esac
  shift
done

BLENDER="$(command -v blender || true)"
if [ -z "$SCRIPTS_DIR" ]; then
  VERSION=3.4
  if [ -n "$BLENDER" ]; then
    VERSION="$("$BLENDER" --version 2>/dev/null | sed -n 's/^Blender \([0-9]*\.[0-9]*\).*/\1/p' | head -n1)"
    VERSION="${VERSION:-3.4}"
  fi
  SCRIPTS_DIR="$HOME/.config/blender/$VERSION/scripts"
fi

SRC="$ROOT/blender_addon/sheetgen_blender"
shopt -s nullglob
MODULES=("$BUILD_DIR"/python/_sheetgen_native*.so)
shopt -u nullglob
if [ ${#MODULES[@]} -ne 1 ]; then
  echo "install_addon.sh: expected one $BUILD_DIR/python/_sheetgen_native*.so, found ${#MODULES[@]}:" \
       "build it with: cmake --build $BUILD_DIR --target _sheetgen_native" >&2
  exit 1
fi
MODULE="${MODULES[0]}"

# Warn when the module does not fit this Blender's Python (it would not import).
if [ -n "$BLENDER" ]; then
  EXT="$("$BLENDER" -b --factory-startup --python-expr \
        "import sysconfig; print('EXT_SUFFIX=' + sysconfig.get_config_var('EXT_SUFFIX'))" 2>/dev/null \
        | sed -n 's/^EXT_SUFFIX=//p')"
  if [ -n "$EXT" ] && [ "$(basename "$MODULE")" != "_sheetgen_native$EXT" ]; then
    echo "install_addon.sh: warning: $(basename "$MODULE") does not match this Blender's Python" \
         "(needs _sheetgen_native$EXT); the add-on will show 'native module not loaded'" >&2
  fi
fi

DEST="$SCRIPTS_DIR/addons/sheetgen_blender"
rm -rf "$DEST"
mkdir -p "$DEST"
if [ "$LINK" = 1 ]; then
  for f in "$SRC"/*; do
    case "$(basename "$f")" in __pycache__) continue ;; esac
    ln -s "$f" "$DEST/$(basename "$f")"
  done
  ln -s "$(readlink -f "$MODULE")" "$DEST/$(basename "$MODULE")"
else
  (cd "$SRC" && find . -name __pycache__ -prune -o -type f -name '*.py' -print | while read -r f; do
     mkdir -p "$DEST/$(dirname "$f")"; cp "$f" "$DEST/$f"; done)
  cp "$MODULE" "$DEST/"
fi
echo "installed the sheetgen add-on in $DEST (native module $(basename "$MODULE"))"

if [ "$ENABLE" = 1 ]; then
  [ -n "$BLENDER" ] || { echo "install_addon.sh: --enable needs blender on PATH" >&2; exit 1; }
  BLENDER_USER_SCRIPTS="$SCRIPTS_DIR" "$BLENDER" -b --python-exit-code 1 --python-expr \
    "import addon_utils, bpy; assert addon_utils.enable('sheetgen_blender', default_set=True); bpy.ops.wm.save_userpref()" \
    >/dev/null
  echo "enabled sheetgen_blender in Blender's preferences"
fi
