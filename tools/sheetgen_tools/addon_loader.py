"""Enables the sheetgen add-on of this checkout inside a running Blender (no
install): the add-on from blender_addon/ and the native module from
BUILD_DIR/python. Used by the scripts Blender runs (scripts/blender_batch.py,
render_results.py, make_sample_blends.py, make_screenshots.py)."""
import os
import sys

from . import paths


def enable_addon(build_dir=paths.DEFAULT_BUILD):
    """Raises RuntimeError naming the add-on folder when it cannot be enabled."""
    import addon_utils
    import bpy
    if hasattr(bpy.types.Scene, "sheetgen"):
        return
    addon_dir = os.path.join(paths.ROOT, "blender_addon")
    for p in (os.path.join(build_dir, "python"), addon_dir):
        if p not in sys.path:
            sys.path.insert(0, p)
    mod = addon_utils.enable("sheetgen_blender", default_set=False, handle_error=None)
    if mod is None or not hasattr(bpy.types.Scene, "sheetgen"):
        raise RuntimeError("the sheetgen add-on could not be enabled from %s" % addon_dir)
