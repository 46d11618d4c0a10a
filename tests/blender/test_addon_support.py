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
