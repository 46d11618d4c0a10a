"""Shared set-up for the add-on tests inside Blender (no test cases here).

Enables the add-on from the source tree (blender_addon/ on sys.path); the
native module comes from BUILD_DIR/python, which tests/blender/run.py puts on
sys.path.
"""
import os
import sys

import addon_utils
import bmesh
import bpy

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
ADDON_DIR = os.path.join(ROOT, "blender_addon")
ADDON = "sheetgen_blender"


def enable_addon():
    if ADDON_DIR not in sys.path:
        sys.path.insert(0, ADDON_DIR)
    mod = addon_utils.enable(ADDON, default_set=True, handle_error=None)
    assert mod is not None and hasattr(bpy.types.Scene, "sheetgen"), "sheetgen add-on did not register"
    return mod


def clean_scene():
    """An empty scene in object mode with default sheetgen settings."""
    if bpy.context.object is not None and bpy.context.object.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')
    for obj in list(bpy.data.objects):
        bpy.data.objects.remove(obj, do_unlink=True)
    for me in list(bpy.data.meshes):
        bpy.data.meshes.remove(me)
    for col in list(bpy.data.collections):
        bpy.data.collections.remove(col)
    scene = bpy.context.scene
    if "sheetgen" in scene:
        del scene["sheetgen"]  # back to the property defaults
    return scene


def mesh_object(name, vertices, faces, location=(0, 0, 0)):
    me = bpy.data.meshes.new(name)
    me.from_pydata(vertices, [], faces)
    me.update()
    obj = bpy.data.objects.new(name, me)
    obj.location = location
    bpy.context.scene.collection.objects.link(obj)
    return obj


def triangle_grid(name, n, size=1.0, z=0.0):
    """An n x n grid of squares in the plane z, each split into 2 triangles: 2 n^2 faces, face 2k+1 shares square k."""
    h = size / n
    verts = [(i * h, j * h, z) for j in range(n + 1) for i in range(n + 1)]
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            faces += [(a, a + 1, a + n + 2), (a, a + n + 2, a + n + 1)]
    return mesh_object(name, verts, faces)


def activate(obj):
    for o in bpy.context.view_layer.objects:
        o.select_set(False)
    bpy.context.view_layer.objects.active = obj
    obj.select_set(True)


def edit_select_faces(obj, indices):
    """Enter edit mode on obj and select exactly the faces ``indices``."""
    activate(obj)
    if obj.mode != 'EDIT':
        bpy.ops.object.mode_set(mode='EDIT')
    bpy.ops.mesh.select_mode(type='FACE')
    bm = bmesh.from_edit_mesh(obj.data)
    bm.faces.ensure_lookup_table()
    for f in bm.faces:
        f.select_set(False)
    for i in indices:
        bm.faces[i].select_set(True)
    bm.select_flush_mode()
    bmesh.update_edit_mesh(obj.data)


def object_mode():
    if bpy.context.object is not None and bpy.context.object.mode != 'OBJECT':
        bpy.ops.object.mode_set(mode='OBJECT')


def face_attribute(obj, name="sheetgen_rivet_area"):
    attr = obj.data.attributes.get(name)
    return None if attr is None else [d.value for d in attr.data]


def make_box_load(name="box", location=(0.5, 0.5, 0.3), force=(0, 0, -100)):
    bpy.ops.mesh.primitive_cube_add(size=0.2, location=location)
    box = bpy.context.active_object
    box.name = name
    bpy.ops.sheetgen.load_make()
    box.sheetgen.force = force
    return box


def build_dir():
    """The BUILD_DIR tests/blender/run.py was given: where the native module was loaded from."""
    import sheetgen_blender.native as native
    return os.path.dirname(os.path.dirname(native.get().__file__))


CORNER = os.path.join(ROOT, "sample_scenes", "corner")


def write_envelope_problems(folder):
    """Three problem files in the format of issue 33 (docs/problem-format.md "Load cases"), made from the corner
    sample (its own envelope and frequency floor taken out) with a box of 4.0 kg: {"preset": the far25.561 envelope with a buckling
    factor and a frequency floor, "factors": an explicit factor list (one with its own max_deflection),
    "cases": explicit cases of the box (one with its own max_deflection) with its centre of mass and inertia}.
    The limits (4 mm, 4 mm and 3 mm of deflection; a 15 Hz floor) are ones a small search (2 chains, 100
    iterations, beam 2) meets, so each comparison covers a whole valid part; at the sample's 1 mm and a 25 Hz
    floor the first two end without one (9 g forward bends that corner 2.9 mm; its first mode is 16.7 Hz). The
    OBJ meshes are copied beside them. Returns {name: path}."""
    import copy
    import json
    import shutil
    with open(os.path.join(CORNER, "problem.json"), encoding="utf-8") as f:
        base = json.load(f)
    for m in base["environment"]["meshes"]:
        shutil.copy(os.path.join(CORNER, m["file"]), os.path.join(folder, m["file"]))
    # The corner's own envelope and frequency floor give way to each file's below.
    base.pop("load_cases", None)
    base["requirements"].pop("min_frequency_hz", None)
    ld = base["loads"][0]
    for key in ("force", "moment"):
        ld.pop(key, None)
    ld["mass"] = 4.0
    problems = {}
    p = copy.deepcopy(base)
    p["load_cases"] = {"forward": [1, 0, 0], "up": [0, 0, 1], "factors": "far25.561"}
    p["requirements"].update({"max_deflection": 4e-3, "min_buckling_factor": 1.5, "min_frequency_hz": 15})
    problems["preset"] = p
    p = copy.deepcopy(base)
    p["load_cases"] = {"forward": [0, -1, 0], "up": [0, 0, 1],
                       "factors": [{"name": "forward 9 g", "g": [9, 0, 0]},
                                   {"name": "down 6 g", "g": [0, 0, -6], "max_deflection": 3e-3},
                                   {"name": "side 3 g", "g": [0, 3, 1]}]}
    p["requirements"]["max_deflection"] = 4e-3
    problems["factors"] = p
    p = copy.deepcopy(base)
    p["loads"][0].update({"center_of_mass": [0.27, 0.01, 0.33],
                          "inertia": [[0.0068, 0, 0], [0, 0.0107, 0], [0, 0, 0.0133]],
                          "cases": [{"name": "connector pull", "force": [0, -200, 0]},
                                    {"name": "handling", "force": [0, 0, -150], "moment": [0, 4, 0],
                                     "max_deflection": 2e-3}]})
    p["requirements"].update({"max_deflection": 3e-3, "min_frequency_hz": 15})
    problems["cases"] = p
    paths = {}
    for name, p in problems.items():
        paths[name] = os.path.join(folder, name + ".json")
        with open(paths[name], "w", encoding="utf-8") as f:
            json.dump(p, f, indent=1)
    return paths
