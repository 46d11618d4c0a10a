"""Enable the sheetgen add-on from this checkout inside a running Blender (no install):
the add-on from blender_addon/ and the native module from BUILD_DIR/python.
Shared by scripts/blender_batch.py and scripts/render_results.py."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def enable_addon(build_dir):
    """Raises RuntimeError naming the add-on folder when it cannot be enabled."""
    import addon_utils
    import bpy
    if hasattr(bpy.types.Scene, "sheetgen"):
        return
    for p in (os.path.join(build_dir, "python"), os.path.join(ROOT, "blender_addon")):
        if p not in sys.path:
            sys.path.insert(0, p)
    mod = addon_utils.enable("sheetgen_blender", default_set=False, handle_error=None)
    if mod is None or not hasattr(bpy.types.Scene, "sheetgen"):
        raise RuntimeError("the sheetgen add-on could not be enabled from %s" % os.path.join(ROOT, "blender_addon"))
