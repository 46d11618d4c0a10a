"""Add-on inside blender -b: load boxes (size, centre, rotation, force arrow) in the exported problem.

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
"""
import json
import math
import os
import tempfile
import unittest

import bpy
from mathutils import Euler, Vector

from test_addon_support import (clean_scene, edit_select_faces, enable_addon, object_mode,
                                triangle_grid)


def setUpModule():
    enable_addon()


def qmul(a, b):
    """Hamilton product of quaternions (w, x, y, z)."""
    w1, x1, y1, z1 = a
    w2, x2, y2, z2 = b
    return (w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2, w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2,
            w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2, w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2)


class Loads(unittest.TestCase):
    def setUp(self):
        clean_scene()
        grid = triangle_grid("floor", 2)
        edit_select_faces(grid, [0, 1])
        bpy.ops.sheetgen.rivet_area_mark()
        object_mode()
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        object_mode()
        self.tmp.cleanup()

    def export(self):
        path = os.path.join(self.tmp.name, "p.json")
        self.assertEqual(bpy.ops.sheetgen.export_problem(filepath=path), {'FINISHED'})
        with open(path) as f:
            return json.load(f)

    def test_rotated_scaled_cube(self):
        # A cube of side 2 (local +-1), scaled (0.1, 0.2, 0.3), Euler XYZ (30, 0, 45) degrees, at (1, 2, 3).
        bpy.ops.mesh.primitive_cube_add(size=2.0, location=(1.0, 2.0, 3.0))
        box = bpy.context.active_object
        box.name = "radio"
        box.scale = (0.1, 0.2, 0.3)
        box.rotation_euler = Euler((math.radians(30), 0.0, math.radians(45)), 'XYZ')
        bpy.ops.sheetgen.load_make()
        box.sheetgen.force = (30.0, 0.0, -40.0)
        box.sheetgen.moment = (0.0, 1.5, 0.0)
        (load,) = self.export()["loads"]
        self.assertEqual(load["name"], "radio")
        for a, b in zip(load["size"], (0.2, 0.4, 0.6)):          # local size x scale
            self.assertAlmostEqual(a, b, delta=1e-7)
        self.assertEqual(load["center"], [1.0, 2.0, 3.0])
        self.assertEqual(load["force"], [30.0, 0.0, -40.0])
        self.assertEqual(load["moment"], [0.0, 1.5, 0.0])
        # Euler XYZ = Rz(45) Ry(0) Rx(30): q = qz * qx, half angles 22.5 and 15 degrees.
        c22, s22, c15, s15 = (math.cos(math.radians(22.5)), math.sin(math.radians(22.5)),
                              math.cos(math.radians(15)), math.sin(math.radians(15)))
        want = qmul((c22, 0, 0, s22), (c15, s15, 0, 0))
        self.assertAlmostEqual(want[0], c22 * c15, places=15)
        for a, b in zip(load["rotation"], want):
            self.assertAlmostEqual(a, b, delta=1e-7)
        # The exported box reproduces Blender's world corner: centre + R (size/2).
        from sheetgen_blender.core.geometry import quat_rotate
        corner_local = Vector((1.0, 1.0, 1.0))       # the cube's (+,+,+) vertex
        world = box.matrix_world @ corner_local
        half = [s / 2 for s in load["size"]]
        mine = [c + d for c, d in zip(load["center"], quat_rotate(load["rotation"], half))]
        for a, b in zip(mine, world):
            self.assertAlmostEqual(a, b, delta=1e-6)

    def test_parented_load_uses_world_transform(self):
        parent = bpy.data.objects.new("rack", None)
        bpy.context.scene.collection.objects.link(parent)
        parent.location = (0.5, 0.0, 0.0)
        parent.scale = (2.0, 2.0, 2.0)
        bpy.ops.mesh.primitive_cube_add(size=0.1, location=(0.0, 0.0, 0.25))
        box = bpy.context.active_object
        box.parent = parent
        bpy.ops.sheetgen.load_make()
        bpy.context.view_layer.update()
        (load,) = self.export()["loads"]
        self.assertEqual(load["center"], [0.5, 0.0, 0.5])      # parent translation + 2 x 0.25
        for a in load["size"]:
            self.assertAlmostEqual(a, 0.2, delta=1e-7)          # 0.1 x parent scale 2

    def test_force_arrow(self):
        bpy.ops.mesh.primitive_cube_add(size=0.2, location=(0.3, 0.3, 0.4))
        box = bpy.context.active_object
        bpy.ops.sheetgen.load_make()
        box.sheetgen.force = (30.0, 0.0, -40.0)
        arrow = box.sheetgen.arrow
        self.assertEqual((arrow.type, arrow.empty_display_type), ('EMPTY', 'SINGLE_ARROW'))
        self.assertTrue(arrow.sheetgen.is_arrow)
        box.rotation_euler = (0.0, 0.0, 1.0)   # the force is in world axes: turning the box does not turn it
        box.location = (0.0, 0.5, 0.4)
        bpy.context.view_layer.update()
        axis = arrow.matrix_world.to_3x3() @ Vector((0, 0, 1))
        for a, b in zip(axis.normalized(), (0.6, 0.0, -0.8)):
            self.assertAlmostEqual(a, b, places=6)
        for a, b in zip(arrow.matrix_world.translation, (0.0, 0.5, 0.4)):
            self.assertAlmostEqual(a, b, places=6)
        # Arrows are empties and loads are not environment: only the floor is a mesh of the problem.
        problem = self.export()
        self.assertEqual([m["name"] for m in problem["environment"]["meshes"]], ["floor"])
        arrow_name = arrow.name
        bpy.ops.sheetgen.load_clear()
        self.assertNotIn(arrow_name, bpy.data.objects)
        self.assertFalse(box.sheetgen.is_load)
        with self.assertRaises(RuntimeError) as ctx:
            bpy.ops.sheetgen.export_problem(filepath=os.path.join(self.tmp.name, "none.json"))
        self.assertIn("no loads: select a box object and press 'Make Load'", str(ctx.exception))

    def test_flat_object_is_refused(self):
        bpy.ops.mesh.primitive_plane_add(size=0.2)
        with self.assertRaises(RuntimeError) as ctx:
            bpy.ops.sheetgen.load_make()
        self.assertIn("is flat", str(ctx.exception))
        self.assertFalse(bpy.context.active_object.sheetgen.is_load)

    def test_zero_force_is_reported_by_name(self):
        bpy.ops.mesh.primitive_cube_add(size=0.2, location=(0.3, 0.3, 0.4))
        box = bpy.context.active_object
        box.name = "idle"
        bpy.ops.sheetgen.load_make()
        box.sheetgen.force = (0.0, 0.0, 0.0)
        with self.assertRaises(RuntimeError) as ctx:
            bpy.ops.sheetgen.check_problem()
        self.assertIn("load 'idle': force and moment are both zero", str(ctx.exception))


if __name__ == "__main__":
    unittest.main()
