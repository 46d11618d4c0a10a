"""Add-on inside blender -b: registration, rivet-area tagging, areas, colours.

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
"""
import json
import math
import os
import sys
import tempfile
import unittest

import addon_utils
import bpy
from mathutils import Euler

from test_addon_support import (ADDON, activate, clean_scene, edit_select_faces, enable_addon, face_attribute,
                                make_box_load, mesh_object, object_mode, triangle_grid)


def setUpModule():
    enable_addon()


class Registration(unittest.TestCase):
    def test_sidebar_tab_and_clean_unregister(self):
        panel = bpy.types.SHEETGEN_PT_main
        self.assertEqual((panel.bl_space_type, panel.bl_region_type, panel.bl_category),
                         ('VIEW_3D', 'UI', "Sheet Metal"))
        for op in ("rivet_area_mark", "rivet_area_unmark", "rivet_area_select", "load_make", "export_problem",
                   "import_problem", "check_problem"):
            self.assertTrue(hasattr(bpy.ops.sheetgen, op), op)
        addon_utils.disable(ADDON, default_set=True)
        try:
            self.assertFalse(hasattr(bpy.types.Scene, "sheetgen"))
            self.assertFalse(hasattr(bpy.types.Object, "sheetgen"))
            self.assertFalse(hasattr(bpy.types, "SHEETGEN_PT_main"))
        finally:
            enable_addon()
        self.assertTrue(hasattr(bpy.types, "SHEETGEN_PT_main"))

    def test_missing_native_module_is_one_sentence_not_a_failure(self):
        from sheetgen_blender import native
        saved = (native._HERE, dict(sys.modules), list(sys.path))
        with tempfile.TemporaryDirectory() as empty:
            try:
                native.reset()
                native._HERE = empty
                sys.modules.pop("_sheetgen_native", None)
                sys.path[:] = [p for p in sys.path if not any(f.startswith("_sheetgen_native") for f in
                                                              (os.listdir(p) if os.path.isdir(p) else []))]
                self.assertIsNone(native.get())
                msg = native.error()
                self.assertTrue(msg.startswith("sheetgen native module _sheetgen_native could not be loaded: "
                                               "not beside the add-on in %s" % empty), msg)
                self.assertIn("scripts/install_addon.sh", msg)
                # Check reports the sentence (bpy.ops turns an ERROR report into RuntimeError).
                clean_scene()
                with self.assertRaises(RuntimeError) as ctx:
                    bpy.ops.sheetgen.check_problem()
                self.assertIn("could not be loaded", str(ctx.exception))
                self.assertNotIn("Traceback", str(ctx.exception))
            finally:
                native._HERE = saved[0]
                sys.modules.update(saved[1])
                sys.path[:] = saved[2]
                native.reset()
        self.assertIsNotNone(native.get())


class StubLayout:
    """Stands in for UILayout headless (panels are not drawn under -b): checks every prop/operator name."""

    def __init__(self, test):
        self.test, self.props, self.ops, self.labels = test, [], [], []

    def prop(self, data, name, **kw):
        self.test.assertIn(name, data.bl_rna.properties.keys(), "%s has no property %s" % (data, name))
        self.props.append(name)

    def operator(self, idname, **kw):
        mod, op = idname.split(".")
        self.test.assertTrue(hasattr(getattr(bpy.ops, mod), op), idname)
        self.ops.append(idname)

    def label(self, text="", **kw):
        self.labels.append(text)

    def template_list(self, listtype, list_id, data, propname, active_data, active_propname, **kw):
        self.test.assertTrue(hasattr(bpy.types, listtype), listtype)
        self.test.assertIn(propname, data.bl_rna.properties.keys())
        self.test.assertIn(active_propname, active_data.bl_rna.properties.keys())

    def __getattr__(self, name):  # row(), column(), box(), separator(), alert, enabled ...
        return lambda *a, **kw: self

    def __setattr__(self, name, value):
        object.__setattr__(self, name, value)


class PanelsDraw(unittest.TestCase):
    def test_panels_draw_with_known_names(self):
        clean_scene()
        box = make_box_load()
        grid = triangle_grid("floor", 2)
        edit_select_faces(grid, [0])
        bpy.ops.sheetgen.rivet_area_mark()
        ops = []
        for obj in (grid, box):
            if obj is box:
                object_mode()
                activate(box)
            for name in ("SHEETGEN_PT_main", "SHEETGEN_PT_rivet_areas", "SHEETGEN_PT_loads", "SHEETGEN_PT_material",
                         "SHEETGEN_PT_requirements", "SHEETGEN_PT_search"):
                stub = type("P", (), {"layout": StubLayout(self)})()
                getattr(bpy.types, name).draw(stub, bpy.context)
                ops += stub.layout.ops
            item = grid.sheetgen.rivet_areas[0]
            bpy.types.SHEETGEN_UL_rivet_areas.draw_item(None, bpy.context, StubLayout(self), grid.sheetgen, item,
                                                        0, grid.sheetgen, "rivet_area_index", 0)
        object_mode()
        self.assertIn("sheetgen.rivet_area_mark", ops)     # edit mode on the floor
        self.assertIn("sheetgen.load_clear", ops)          # the box is a load
        self.assertIn("sheetgen.check_problem", ops)


class Tagging(unittest.TestCase):
    def setUp(self):
        clean_scene()

    def tearDown(self):
        object_mode()

    def test_mark_export_import_round_trip(self):
        grid = triangle_grid("floor", 3)                       # 18 triangles, 1 m square
        edit_select_faces(grid, [1, 4, 5])
        self.assertEqual(bpy.ops.sheetgen.rivet_area_mark(), {'FINISHED'})
        bpy.ops.sheetgen.rivet_area_add(name="second")
        edit_select_faces(grid, [7, 16])
        bpy.ops.sheetgen.rivet_area_mark()
        edit_select_faces(grid, [5])
        bpy.ops.sheetgen.rivet_area_unmark()
        object_mode()
        expected = [0] * 18
        expected[1] = expected[4] = 1
        expected[7] = expected[16] = 2
        self.assertEqual(face_attribute(grid), expected)
        attr = grid.data.attributes["sheetgen_rivet_area"]
        self.assertEqual((attr.domain, attr.data_type), ('FACE', 'INT'))
        names = [(a.name, a.area_id, a.face_count) for a in grid.sheetgen.rivet_areas]
        self.assertEqual(names, [("floor_rivets_1", 1, 2), ("second", 2, 2)])
        # Each triangle is half a (1/3 m)^2 square: 2 triangles = 1/9 m^2.
        self.assertAlmostEqual(grid.sheetgen.rivet_areas[0].area_m2, 1 / 9, places=6)

        make_box_load()
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "tagged.json")
            self.assertEqual(bpy.ops.sheetgen.export_problem(filepath=path), {'FINISHED'})
            with open(path) as f:
                problem = json.load(f)
            self.assertEqual(problem["rivet_areas"], [{"name": "floor_rivets_1", "mesh": "floor", "faces": [1, 4]},
                                                      {"name": "second", "mesh": "floor", "faces": [7, 16]}])
            clean_scene()
            self.assertEqual(len(bpy.data.objects), 0)
            self.assertEqual(bpy.ops.sheetgen.import_problem(filepath=path), {'FINISHED'})
        floor = bpy.data.objects["floor"]
        self.assertEqual(face_attribute(floor), expected)
        self.assertEqual([(a.name, a.area_id, a.face_count) for a in floor.sheetgen.rivet_areas], names)
        self.assertAlmostEqual(floor.sheetgen.rivet_areas[1].area_m2, 1 / 9, places=6)
        self.assertTrue(bpy.data.objects["box"].sheetgen.is_load)

    def test_quads_export_their_loop_triangles(self):
        # 2 x 2 quads; polygon p becomes triangles 2p and 2p + 1.
        quads = mesh_object("quads", [(i, j, 0) for j in range(3) for i in range(3)],
                            [(0, 1, 4, 3), (1, 2, 5, 4), (3, 4, 7, 6), (4, 5, 8, 7)])
        edit_select_faces(quads, [2])
        bpy.ops.sheetgen.rivet_area_mark()
        object_mode()
        from sheetgen_blender import scene_io
        md = scene_io.read_mesh(quads)
        self.assertEqual(len(md.triangles), 8)
        self.assertEqual([f for f, k in enumerate(md.face_areas) if k], [4, 5])
        self.assertAlmostEqual(quads.sheetgen.rivet_areas[0].area_m2, 1.0, places=9)

    def test_area_of_scaled_rotated_plane(self):
        # A 2 m x 2 m plane scaled by (1.5, 0.5, 3) and rotated 30 degrees about x: 4 * 1.5 * 0.5 = 3 m^2.
        bpy.ops.mesh.primitive_plane_add(size=2.0)
        plane = bpy.context.active_object
        plane.scale = (1.5, 0.5, 3.0)
        plane.rotation_euler = Euler((math.radians(30), 0, 0))
        bpy.ops.object.mode_set(mode='EDIT')
        bpy.ops.mesh.subdivide(number_cuts=1)             # 4 quads of 1 m x 1 m locally
        bpy.ops.mesh.select_all(action='SELECT')
        bpy.ops.sheetgen.rivet_area_mark()
        item = plane.sheetgen.rivet_areas[0]
        self.assertEqual(item.face_count, 4)
        self.assertAlmostEqual(item.area_m2, 3.0, places=6)
        edit_select_faces(plane, [0])
        bpy.ops.sheetgen.rivet_area_unmark()
        self.assertAlmostEqual(item.area_m2, 2.25, places=6)   # one quarter untagged
        self.assertEqual(item.face_count, 3)
        # Scaling the object after tagging: Refresh recomputes in world space.
        object_mode()
        plane.scale = (3.0, 0.5, 1.0)
        bpy.ops.sheetgen.rivet_area_refresh()
        self.assertAlmostEqual(item.area_m2, 4.5, places=6)    # 3 quads of 3 x 0.5 m

    def test_select_by_area_and_remove(self):
        grid = triangle_grid("g", 2)                       # 8 triangles
        edit_select_faces(grid, [0, 3, 6])
        bpy.ops.sheetgen.rivet_area_mark()
        bpy.ops.mesh.select_all(action='DESELECT')
        bpy.ops.sheetgen.rivet_area_select()
        from sheetgen_blender import tagging
        self.assertEqual(tagging.selected_faces(grid), [0, 3, 6])
        edit_select_faces(grid, [1])
        bpy.ops.sheetgen.rivet_area_select(extend=True)
        self.assertEqual(tagging.selected_faces(grid), [0, 1, 3, 6])
        bpy.ops.sheetgen.rivet_area_remove()
        object_mode()
        self.assertEqual(face_attribute(grid), [0] * 8)
        self.assertEqual(len(grid.sheetgen.rivet_areas), 0)

    def test_tag_colours(self):
        grid = triangle_grid("c", 2)
        edit_select_faces(grid, [2])
        bpy.ops.sheetgen.rivet_area_mark()
        object_mode()
        col = grid.data.color_attributes.get("sheetgen_rivet_color")
        self.assertEqual((col.domain, col.data_type), ('CORNER', 'BYTE_COLOR'))
        self.assertEqual(grid.data.color_attributes.active_color.name, "sheetgen_rivet_color")
        want = tuple(grid.sheetgen.rivet_areas[0].color)
        for poly in grid.data.polygons:
            expect = want if poly.index == 2 else (0.8, 0.8, 0.8)
            for loop in range(poly.loop_start, poly.loop_start + poly.loop_total):
                c = col.data[loop].color_srgb
                for k in range(3):
                    # Byte colours (sRGB, like the COLOR_GAMMA swatch): 1/255 steps.
                    self.assertAlmostEqual(c[k], expect[k], delta=0.5 / 255 + 1e-6, msg="face %d" % poly.index)


if __name__ == "__main__":
    unittest.main()
