"""Add-on inside blender -b: problem JSON import/export round trip, Check, error reports.

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
"""
import json
import os
import tempfile
import unittest

import bpy

from test_addon_support import (ROOT, clean_scene, edit_select_faces, enable_addon, face_attribute,
                                make_box_load, object_mode, triangle_grid)


def setUpModule():
    enable_addon()


# Decimal numbers that are not float32 values (0.3, 0.45, 73.1e9 ...) on purpose: Blender holds
# float32, and the add-on writes the shortest decimal with the same float32 back.
PROBLEM = {
    "format": "sheetgen-problem/1",
    "name": "bench",
    "description": "round trip",
    "units": "m",
    "environment": {"meshes": [
        {"name": "wall", "vertices": [[0.0, -0.3, 0.1], [0.0, 0.3, 0.1], [0.0, 0.3, 0.45], [0.0, -0.3, 0.45],
                                      [0.0, 0.0, 0.7]],
         "triangles": [[0, 1, 2], [0, 2, 3], [3, 2, 4]]},
        {"name": "floor", "vertices": [[0.0, -0.5, 0.0], [0.75, -0.5, 0.0], [0.75, 0.5, 0.0], [0.0, 0.5, 0.0]],
         "triangles": [[0, 1, 2], [0, 2, 3]]}]},
    "rivet_areas": [{"name": "wall_low", "mesh": "wall", "faces": [0, 1]},
                    {"name": "wall_top", "mesh": "wall", "faces": [2]},
                    {"name": "floor_all", "mesh": "floor", "faces": [0, 1]}],
    "loads": [{"name": "radio", "center": [0.3, 0.05, 0.3], "size": [0.16, 0.12, 0.08],
               "rotation": [0.9238795, 0.0, 0.0, 0.3826834], "force": [0.0, 12.5, -353.2],
               "moment": [0.1, 0.0, -2.5]}],
    "material": {"youngs_modulus": 70e9, "poisson_ratio": 0.3, "density": 2700.0, "yield_strength": 276e6,
                 "ultimate_strength": 310e6, "thickness": 2.0e-3},
    "requirements": {"max_compliance": 0.02, "min_margin_of_safety": 0.15, "safety_factor": 2.0, "clearance": 2.5e-3},
    "manufacturing": {"k_factor": 0.4, "kerf": 0.0003},
    "search": {"chains": 4, "iterations": 250, "beam_width": 3, "seed": 42, "threads": 2, "alpha": 1.5, "beta": 2.0,
               "scene_unit": 0.05},
}


def export(path):
    result = bpy.ops.sheetgen.export_problem(filepath=path)
    with open(path) as f:
        return result, json.load(f)


class SceneAndFolder(unittest.TestCase):
    """Each test starts from a clean scene and gets its own temporary folder."""
    def setUp(self):
        clean_scene()
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        object_mode()
        self.tmp.cleanup()

    def path(self, name):
        return os.path.join(self.tmp.name, name)


class ProblemRoundTrip(SceneAndFolder):
    def assertProblemsEqual(self, got, want):
        for mg, mw in zip(got["environment"]["meshes"], want["environment"]["meshes"]):
            self.assertEqual(mg["name"], mw["name"])
            self.assertEqual(mg["triangles"], mw["triangles"])
            self.assertEqual(len(mg["vertices"]), len(mw["vertices"]))
            for vg, vw in zip(mg["vertices"], mw["vertices"]):
                for a, b in zip(vg, vw):
                    self.assertAlmostEqual(a, b, delta=1e-9)
        self.assertEqual(len(got["environment"]["meshes"]), len(want["environment"]["meshes"]))
        rest = lambda p: {k: v for k, v in p.items() if k != "environment"}  # noqa: E731
        self.assertEqual(rest(got), rest(want))

    def test_import_then_export_gives_the_file_back(self):
        src = self.path("in.json")
        with open(src, "w") as f:
            json.dump(PROBLEM, f)
        self.assertEqual(bpy.ops.sheetgen.import_problem(filepath=src), {'FINISHED'})
        wall = bpy.data.objects["wall"]
        self.assertEqual(face_attribute(wall), [1, 1, 2])
        self.assertEqual([a.name for a in wall.sheetgen.rivet_areas], ["wall_low", "wall_top"])
        self.assertAlmostEqual(wall.sheetgen.rivet_areas[0].area_m2, 0.6 * 0.35, places=6)
        radio = bpy.data.objects["radio"]
        self.assertTrue(radio.sheetgen.is_load)
        self.assertEqual(bpy.context.scene.sheetgen.stiffness_limit, 'COMPLIANCE')
        result, out = export(self.path("out.json"))
        self.assertEqual(result, {'FINISHED'})
        # The file's order of meshes and rivet areas is kept (result.json refers to them by index), though
        # floor sorts before wall by name. Everything else is the input, exactly.
        self.assertProblemsEqual(out, json.loads(json.dumps(PROBLEM)))

    def test_scene_export_import_export(self):
        grid = triangle_grid("deck", 4, size=0.5, z=0.25)
        grid.location = (0.1, -0.2, 0.0)
        grid.rotation_euler = (0.3, 0.0, 0.0)
        edit_select_faces(grid, [0, 1, 9])
        bpy.ops.sheetgen.rivet_area_mark()
        object_mode()
        make_box_load(force=(5.0, 0.0, -40.0))
        bpy.context.scene.sheetgen.chains = 3
        bpy.context.scene.sheetgen.thickness_mm = 1.27
        _, first = export(self.path("a.json"))
        self.assertEqual(first["search"]["chains"], 3)
        self.assertEqual(first["material"]["thickness"], 0.00127)
        self.assertEqual(first["rivet_areas"], [{"name": "deck_rivets_1", "mesh": "deck", "faces": [0, 1, 9]}])
        # World space: vertex 0 (0, 0, 0.25) rotated 0.3 rad about x, then moved.
        import math
        v0 = first["environment"]["meshes"][0]["vertices"][0]
        for a, b in zip(v0, (0.1, -0.2 - 0.25 * math.sin(0.3), 0.25 * math.cos(0.3))):
            self.assertAlmostEqual(a, b, delta=1e-7)   # float32 object matrix
        clean_scene()
        self.assertEqual(bpy.ops.sheetgen.import_problem(filepath=self.path("a.json")), {'FINISHED'})
        _, second = export(self.path("b.json"))
        self.assertProblemsEqual(second, first)

    def test_sample_scene_with_mesh_files(self):
        """Meshes given by OBJ file are read by the native reader, so face indices mean the solver's faces."""
        src = os.path.join(ROOT, "sample_scenes", "corner", "problem.json")
        self.assertEqual(bpy.ops.sheetgen.import_problem(filepath=src), {'FINISHED'})
        wall, floor = bpy.data.objects["wall"], bpy.data.objects["floor"]
        self.assertEqual(len(wall.data.polygons) + len(floor.data.polygons), 576)
        # wall_rivets: 6 x 4 cells of 0.05 m = 0.06 m^2 (as tests/blender/test_native_module.py).
        self.assertAlmostEqual(wall.sheetgen.rivet_areas["wall_rivets"].area_m2, 0.06, places=6)
        self.assertEqual(bpy.ops.sheetgen.check_problem(), {'FINISHED'})
        _, out = export(self.path("corner.json"))
        with open(src) as f:
            original = json.load(f)
        self.assertEqual({ra["name"]: sorted(ra["faces"]) for ra in out["rivet_areas"]},
                         {ra["name"]: sorted(ra["faces"]) for ra in original["rivet_areas"]})


class Reports(SceneAndFolder):
    def test_no_rivet_area_is_a_report_and_writes_nothing(self):
        triangle_grid("floor", 2)
        make_box_load()
        path = os.path.join(self.tmp.name, "p.json")
        with open(path, "w") as f:
            f.write("previous\n")
        for op in (lambda: bpy.ops.sheetgen.export_problem(filepath=path), bpy.ops.sheetgen.check_problem):
            # An ERROR report makes bpy.ops raise RuntimeError("Error: <the report>"): no Python traceback.
            with self.assertRaises(RuntimeError) as ctx:
                op()
            msg = str(ctx.exception)
            self.assertTrue(msg.startswith("Error: no rivet areas: select faces of an environment mesh in Edit Mode"),
                            msg)
            self.assertNotIn("Traceback", msg)
        with open(path) as f:
            self.assertEqual(f.read(), "previous\n")
        self.assertEqual(os.listdir(self.tmp.name), ["p.json"])

    def test_check_reports_the_native_input_error(self):
        grid = triangle_grid("floor", 2)
        edit_select_faces(grid, [0])
        bpy.ops.sheetgen.rivet_area_mark()
        object_mode()
        make_box_load()
        self.assertEqual(bpy.ops.sheetgen.check_problem(), {'FINISHED'})
        # A misspelt manufacturing field passes the core (kept verbatim) and is caught by the native parser.
        bpy.context.scene.sheetgen.manufacturing_json = '{"kfactor": 0.4}'
        with self.assertRaises(RuntimeError) as ctx:
            bpy.ops.sheetgen.check_problem()
        msg = str(ctx.exception)
        self.assertIn("scene 'Scene': manufacturing: unknown field 'kfactor'", msg)
        self.assertNotIn("Traceback", msg)

    def test_hidden_objects_and_loads_are_not_environment(self):
        grid = triangle_grid("floor", 2)
        edit_select_faces(grid, [0])
        bpy.ops.sheetgen.rivet_area_mark()
        object_mode()
        hidden = triangle_grid("hidden", 1)
        hidden.hide_set(True)
        make_box_load()
        _, out = export(os.path.join(self.tmp.name, "p.json"))
        self.assertEqual([m["name"] for m in out["environment"]["meshes"]], ["floor"])
        self.assertEqual([ld["name"] for ld in out["loads"]], ["box"])

    def test_bad_problem_file_is_a_report(self):
        path = os.path.join(self.tmp.name, "bad.json")
        with open(path, "w") as f:
            json.dump({"format": "sheetgen-problem/1", "environment": {"meshes": []}, "rivet_areas": [], "loads": []}, f)
        with self.assertRaises(RuntimeError) as ctx:
            bpy.ops.sheetgen.import_problem(filepath=path)
        self.assertIn("Error: environment.meshes: there are no meshes", str(ctx.exception))
        self.assertEqual(len(bpy.data.objects), 0)


if __name__ == "__main__":
    unittest.main()
