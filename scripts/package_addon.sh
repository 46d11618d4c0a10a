#!/usr/bin/env bash
# Write the installable add-on: OUT/sheetgen_blender-<version>.zip, <version> from bl_info in
# blender_addon/sheetgen_blender/__init__.py. The zip holds one folder, sheetgen_blender/, with
#   the add-on's .py files (blender_addon/sheetgen_blender, no __pycache__),
#   the native module _sheetgen_native.<EXT_SUFFIX> beside them (where native.py looks first),
#   blender_manifest.toml (blender_addon/sheetgen_blender/: the extension platform of Blender 4.2
#                         and later; 3.4 ignores it),
#   LICENSE.
# Blender 3.4: Edit > Preferences > Add-ons > Install... takes the zip as it is; 4.2 and later
# install it from disk as an extension (docs/blender.md "Install").
#
# Usage: scripts/package_addon.sh [--build-dir DIR] [--out DIR]
#   --build-dir DIR  where the native module was built (default: build/; it must hold exactly one
#                    python/_sheetgen_native.*.so: cmake --build build --target _sheetgen_native)
#   --out DIR        where the zip goes (default: the build dir)
# Prints the zip's path on the last line. The module must fit the Python of the Blender that
# loads it: Debian's Blender 3.4 runs the system Python 3.11 (docs/platform.md).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="$ROOT/build"
OUT=""
while [ $# -gt 0 ]; do
  case "$1" in
    --build-dir) BUILD_DIR="$2"; shift ;;
    --out) OUT="$2"; shift ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "package_addon.sh: unknown argument '$1' (see --help)" >&2; exit 1 ;;
  esac
  shift
done
OUT="${OUT:-$BUILD_DIR}"

shopt -s nullglob
MODULES=("$BUILD_DIR"/python/_sheetgen_native*.so)
shopt -u nullglob
if [ ${#MODULES[@]} -ne 1 ]; then
  echo "package_addon.sh: expected one $BUILD_DIR/python/_sheetgen_native*.so, found ${#MODULES[@]}:" \
       "build it with: cmake --build $BUILD_DIR --target _sheetgen_native" >&2
  exit 1
fi
mkdir -p "$OUT"
# The zip is written by the system Python (zipfile, no zip package needed); the version comes from
# bl_info, read without importing the add-on (no bpy), and must be the manifest's.
/usr/bin/python3 - "$ROOT" "${MODULES[0]}" "$(cd "$OUT" && pwd)" <<'EOF'
import ast
import os
import sys
import tempfile
import tomllib
import zipfile

root, module, out = sys.argv[1:4]
src = os.path.join(root, "blender_addon", "sheetgen_blender")
with open(os.path.join(src, "__init__.py"), encoding="utf-8") as f:
    tree = ast.parse(f.read())
bl_info = next(ast.literal_eval(n.value) for n in tree.body
               if isinstance(n, ast.Assign) and any(getattr(t, "id", None) == "bl_info" for t in n.targets))
version = ".".join(str(v) for v in bl_info["version"])
with open(os.path.join(root, "LICENSE"), encoding="utf-8") as f:
    head = f.read(200)
# The README's "License" section: GPL-3.0-or-later (CGAL's 2-D triangulation requires 3 or later).
if "GNU GENERAL PUBLIC LICENSE" not in head or "Version 3" not in head:
    raise SystemExit("package_addon.sh: LICENSE is not the GPL version 3; update the manifest's license")
with open(os.path.join(src, "blender_manifest.toml"), "rb") as f:
    manifest = tomllib.load(f)
# One version and one name: bl_info's (Blender 3.4) and the manifest's (4.2 and later).
if manifest["version"] != version or manifest["name"] != bl_info["name"]:
    raise SystemExit("package_addon.sh: blender_manifest.toml says %s %s, bl_info says %s %s: make them agree"
                     % (manifest["name"], manifest["version"], bl_info["name"], version))
if manifest["license"] != ["SPDX:GPL-3.0-or-later"]:
    raise SystemExit("package_addon.sh: blender_manifest.toml's license is not the README's GPL-3.0-or-later")

name = "sheetgen_blender-%s.zip" % version
fd, tmp = tempfile.mkstemp(prefix=".sheetgen_blender-", suffix=".zip", dir=out)
os.close(fd)
try:
    with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
        for d, dirs, files in os.walk(src):
            dirs[:] = sorted(x for x in dirs if x != "__pycache__")
            for f in sorted(files):
                if f.endswith(".py") or f == "blender_manifest.toml":
                    full = os.path.join(d, f)
                    z.write(full, os.path.join("sheetgen_blender", os.path.relpath(full, src)))
        z.write(module, "sheetgen_blender/" + os.path.basename(module))
        z.write(os.path.join(root, "LICENSE"), "sheetgen_blender/LICENSE")
    os.chmod(tmp, 0o644)
    os.replace(tmp, os.path.join(out, name))   # never a half-written zip under the final name
finally:
    if os.path.exists(tmp):
        os.remove(tmp)
print("wrote %s (add-on %s, native module %s)" % (os.path.join(out, name), version, os.path.basename(module)))
print(os.path.join(out, name))
EOF
