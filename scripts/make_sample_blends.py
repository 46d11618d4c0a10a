"""Writes sample_scenes/<scene>/scene.blend for every scene of the library (docs/scenes.md).

    blender -b --factory-startup --python-exit-code 1 --python scripts/make_sample_blends.py [-- SCENE ...]

Each scene is the problem JSON imported with the add-on's Import operator into
an empty file (rivet areas tagged and coloured, load boxes with their masses,
the envelope and the other settings), the viewport set to show the rivet-area colours. Open one, press
Generate in the Sheet Metal tab.
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Blender runs this file by path and no PYTHONPATH reaches its Python: the one
# bootstrap line that makes the tools package importable (tools/sheetgen_tools/__init__.py).
sys.path.insert(0, os.path.join(ROOT, "tools"))
from sheetgen_tools import addon_loader, paths  # noqa: E402
from sheetgen_tools.scenes import LIBRARY  # noqa: E402


def frame_views(scene):
    """3D views: rivet-area colours shown, looking at the scene from a 3/4 view, the sidebar open."""
    import bpy
    from mathutils import Euler, Vector
    from sheetgen_blender import tagging
    pts = [o.matrix_world @ Vector(c) for o in scene.objects if o.type == 'MESH' for c in o.bound_box]
    lo = Vector(map(min, *pts)) if len(pts) > 1 else Vector()
    hi = Vector(map(max, *pts)) if len(pts) > 1 else Vector((1, 1, 1))
    for screen in bpy.data.screens:
        tagging.show_in_viewports(screen)
        for area in screen.areas:
            if area.type != 'VIEW_3D':
                continue
            space = area.spaces.active
            space.show_region_ui = True
            r3d = space.region_3d
            r3d.view_perspective = 'PERSP'
            r3d.view_location = (lo + hi) / 2
            r3d.view_distance = (hi - lo).length * 1.6
            r3d.view_rotation = Euler((1.1, 0.0, 2.3)).to_quaternion()


def main(names):
    import bpy
    for name in names:
        bpy.ops.wm.read_homefile(use_empty=True)
        addon_loader.enable_addon()
        src = paths.scene_problem(name)
        res = bpy.ops.sheetgen.import_problem(filepath=src)
        if res != {'FINISHED'}:
            raise RuntimeError("import of %s failed" % src)
        scene = bpy.context.scene
        scene.name = name
        scene.sheetgen.filepath = "//problem.json"
        scene.unit_settings.system = 'METRIC'
        scene.unit_settings.scale_length = 1.0
        scene.render.resolution_x, scene.render.resolution_y = 640, 400
        frame_views(scene)
        out = os.path.join(paths.SAMPLE_SCENES, name, "scene.blend")
        bpy.ops.wm.save_as_mainfile(filepath=out, compress=True)
        print("wrote %s" % out)


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    main(argv or LIBRARY)
