"""Generate in Blender: the operator's execute(), the results in the scene, cancel, errors, the batch command.

Small searches (chains 6, iterations 300, beam 2) on sample_scenes/corner: about 6 s each here.
(4 x 300 finds no valid part for seed 1 with the exact tab clearance.)
"""
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import bpy
import numpy as np

from test_addon_support import ROOT, clean_scene, enable_addon, mesh_object, make_box_load

CORNER = os.path.join(ROOT, "sample_scenes", "corner")


def import_corner(chains=6, iterations=300, seed=1, beam_width=2):
    clean_scene()
    assert bpy.ops.sheetgen.import_problem(filepath=os.path.join(CORNER, "problem.json")) == {'FINISHED'}
    s = bpy.context.scene.sheetgen
    s.chains, s.iterations, s.seed, s.beam_width = chains, iterations, seed, beam_width
    s.result_collection = None


def scene_state():
    return (sorted(o.name for o in bpy.data.objects), sorted(c.name for c in bpy.data.collections),
            len(bpy.data.meshes))


def polygon_areas(obj):
    return sum(p.area for p in obj.data.polygons)


class GenerateCorner(unittest.TestCase):
    """One generate run on the corner sample through execute(), shared by the tests of this class."""

    @classmethod
    def setUpClass(cls):
        enable_addon()
        import_corner()
        cls.env_before = [m["name"] for m in cls._problem()["environment"]["meshes"]]
        t0 = time.monotonic()
        cls.ret = bpy.ops.sheetgen.generate()          # background: execute(), synchronous
        cls.seconds = time.monotonic() - t0
        cls.col = bpy.context.scene.sheetgen.result_collection
        from sheetgen_blender import results
        cls.doc = results.run_document(cls.col)

    @staticmethod
    def _problem():
        from sheetgen_blender import operators
        return operators.build_problem(bpy.context)[0]

    def part(self):
        return self.doc["parts"][0]

    def test_run_collection(self):
        self.assertEqual(self.ret, {'FINISHED'})
        self.assertEqual(self.col.name, "sheetgen run 1")
        self.assertEqual(self.doc["format"], "sheetgen-result/1")
        self.assertEqual([p["load"] for p in self.doc["parts"]], ["avionics_box"])
        self.assertEqual(self.part()["status"], "ok")
        self.assertEqual(sorted(o.name for o in self.col.objects),
                         ["avionics_box flat", "avionics_box flat holes", "avionics_box part", "avionics_box rivets"])

    def test_bent_mesh_matches_the_tabs(self):
        part = self.part()
        obj = self.col.objects["avionics_box part"]
        triangles = sum(len(t["corners"]) - 2 for t in part["tabs"])
        self.assertEqual(len(obj.data.polygons), triangles)
        # the mesh's own polygon areas = the tab polygons' areas (float32 coordinates)
        from sheetgen_blender.core import result as core_result
        self.assertAlmostEqual(polygon_areas(obj), core_result.bent_mesh(part).area(), delta=1e-6)
        # one marked edge per bend, numbered like flat_pattern.bends, and seams on them
        bend = [d.value for d in obj.data.attributes["sheetgen_bend"].data]
        self.assertEqual(sorted(v for v in bend if v), sorted(b["number"] for b in part["flat_pattern"]["bends"]))
        self.assertEqual(sum(e.use_seam for e in obj.data.edges), part["bends"])
        mod = obj.modifiers["Thickness"]
        self.assertEqual(mod.type, 'SOLIDIFY')
        self.assertAlmostEqual(mod.thickness, part["thickness_m"], places=7)  # the part's own sheet
        self.assertEqual(mod.offset, 0.0)
        self.assertTrue(obj.material_slots[0].material.metallic > 0.5)

    def test_flat_mesh_is_the_outline_split_at_the_bends(self):
        part = self.part()
        fp = part["flat_pattern"]
        obj = self.col.objects["avionics_box flat"]
        # every bend line cuts the outline here: one face per outline polygon + one per bend
        self.assertEqual(len(obj.data.polygons), len(fp["outline"]) + len(fp["bends"]))
        self.assertAlmostEqual(polygon_areas(obj), fp["area_m2"], delta=fp["area_m2"] * 1e-6)
        self.assertTrue(all(abs(v.co.z) < 1e-12 for v in obj.data.vertices))
        bend = [d.value for d in obj.data.attributes["sheetgen_bend"].data]
        self.assertEqual(sorted(v for v in bend if v), sorted(b["number"] for b in fp["bends"]))
        # laid beside the scene: its world bounding box starts 0.1 m beyond the environment's largest x
        from mathutils import Vector
        xs = [(obj.matrix_world @ Vector(c)).x for c in obj.bound_box]
        env_max_x = max((o.matrix_world @ Vector(c)).x for o in bpy.data.objects
                        if o.name in ("floor", "wall") for c in o.bound_box)
        self.assertAlmostEqual(min(xs), env_max_x + 0.1, places=5)

    def test_rivet_markers(self):
        obj = self.col.objects["avionics_box rivets"]
        self.assertEqual(len(obj.data.vertices), 6 * len(self.part()["rivets"]))
        self.assertEqual(len(obj.data.polygons), 8 * len(self.part()["rivets"]))

    def test_flat_holes_sit_on_the_flat_pattern(self):
        # One 16-gon per hole of flat_pattern.holes (one per rivet here: the corner part has no
        # self-rivet), of the hole's area, on the flat's top face (flat mid-plane + t/2) and inside its outline.
        from mathutils import Vector
        holes = self.part()["flat_pattern"]["holes"]
        self.assertEqual(len(holes), len(self.part()["rivets"]))
        obj = self.col.objects["avionics_box flat holes"]
        self.assertEqual(len(obj.data.polygons), len(holes))
        n = 16
        for poly, h in zip(obj.data.polygons, holes):
            r = 0.5 * h["diameter"]
            self.assertAlmostEqual(poly.area, 0.5 * n * r * r * np.sin(2 * np.pi / n), places=9)
        flat = self.col.objects["avionics_box flat"]
        t = self.part()["thickness_m"]  # the sheet the part is made of, which may be a thicker gauge
        self.assertAlmostEqual(obj.location.z - flat.location.z, t / 2 + 1e-4, places=6)
        xs = [(flat.matrix_world @ Vector(c)).x for c in flat.bound_box]
        for v in obj.data.vertices:
            w = obj.matrix_world @ v.co
            self.assertTrue(min(xs) <= w.x <= max(xs))

    def test_results_panel_values_equal_result_json(self):
        from sheetgen_blender.core import result as core_result
        with tempfile.TemporaryDirectory() as tmp:
            self.assertEqual(bpy.ops.sheetgen.export_results(directory=tmp), {'FINISHED'})
            with open(os.path.join(tmp, "result.json")) as f:
                written = json.load(f)
            for name in ("problem.json", "avionics_box/flat.dxf", "avionics_box/flat.svg", "avionics_box/bends.csv",
                         "avionics_box/part.obj"):
                self.assertTrue(os.path.getsize(os.path.join(tmp, name)) > 0, name)
        p = written["parts"][0]
        v = core_result.report(self.part())       # what the Results panel shows
        self.assertEqual(v["area_m2"], p["area_m2"] * 1e4)
        self.assertEqual(v["mass_kg"], p["mass_kg"] * 1e3)
        self.assertEqual(v["bends"], p["bends"])
        self.assertEqual(v["compliance"], p["compliance"])
        self.assertEqual(v["compliance_limit"], p["compliance_limit"])
        self.assertEqual(v["deflection_m"], p["deflection_m"] * 1e3)
        self.assertEqual(v["deflection_along_force_m"], p["deflection_along_force_m"] * 1e3)
        self.assertEqual(v["margin_of_safety"], p["margin_of_safety"])
        self.assertEqual(v["time_s"], p["timing"]["total_s"])
        self.assertEqual(p["bends"], len(p["flat_pattern"]["bends"]))

    def test_export_step_and_drawing_of_the_run(self):
        from sheetgen_blender.core import jsonio
        # Export Drawing and Export STEP (Results panel) write the run's own files; a run without drawing.pdf
        # (made before sheetgen wrote one) gets it from the native write_drawing on its problem.json and
        # result.json: the same bytes (the sheet has no creation date, docs/drawing.md).
        from sheetgen_blender import results
        files = results.run_files(self.col)
        scene = bpy.context.scene
        with tempfile.TemporaryDirectory() as tmp:
            self.assertEqual(bpy.ops.sheetgen.export_drawing(load="avionics_box", filepath=os.path.join(tmp, "sheet")),
                             {'FINISHED'})
            with open(os.path.join(tmp, "sheet.pdf"), "rb") as f:
                pdf = f.read()
            self.assertTrue(pdf.startswith(b"%PDF-"))
            old = bpy.data.collections.new("sheetgen old run")
            old[results.KEY_RESULT] = self.col[results.KEY_RESULT]
            old[results.KEY_FILES] = {k: v for k, v in files.items() if not k.endswith("drawing.pdf")}
            scene.sheetgen.result_collection = old
            try:
                self.assertEqual(bpy.ops.sheetgen.export_drawing(load="avionics_box",
                                                                 filepath=os.path.join(tmp, "again.pdf")), {'FINISHED'})
            finally:
                scene.sheetgen.result_collection = self.col
                bpy.data.collections.remove(old)
            with open(os.path.join(tmp, "again.pdf"), "rb") as f:
                self.assertEqual(f.read(), pdf)
            if "avionics_box/drawing.pdf" in files:
                self.assertEqual(pdf, jsonio.text_to_file(files["avionics_box/drawing.pdf"]))
            for flat, name in ((False, "part.step"), (True, "flat.step")):
                target = os.path.join(tmp, "out_" + name)
                if "avionics_box/" + name in files:
                    self.assertEqual(bpy.ops.sheetgen.export_step(load="avionics_box", flat=flat, filepath=target),
                                     {'FINISHED'})
                    with open(target) as f:
                        text = f.read()
                    self.assertEqual(text, files["avionics_box/" + name])
                    self.assertTrue(text.startswith("ISO-10303-21;"))
                else:    # a native module without the STEP writer: one sentence, nothing written
                    with self.assertRaises(RuntimeError) as ctx:
                        bpy.ops.sheetgen.export_step(load="avionics_box", flat=flat, filepath=target)
                    self.assertIn("Re-run to make it", str(ctx.exception))
                    self.assertFalse(os.path.exists(target))

    def test_generated_objects_are_not_environment(self):
        after = [m["name"] for m in self._problem()["environment"]["meshes"]]
        self.assertEqual(after, self.env_before)
        self.assertEqual(after, ["wall", "floor"])    # the imported file's order
        self.assertTrue(all(o.sheetgen.exclude for o in self.col.objects))


class Cancel(unittest.TestCase):
    def test_cancel_from_another_thread_within_a_second(self):
        enable_addon()
        import_corner(chains=10, iterations=1000)     # a long run: it is cancelled long before the end
        from sheetgen_blender import generate
        before = scene_state()
        box = {}

        def canceller():
            while generate.active_run() is None:
                time.sleep(0.01)
            run = generate.active_run()
            # Cancel in the search proper: the native environment stage does not poll the flag.
            while run.progress.stage not in ("discovery", "composition"):
                time.sleep(0.01)
            time.sleep(0.5)
            box["stage"] = run.progress.stage
            box["t0"] = time.monotonic()
            run.cancel()
        th = threading.Thread(target=canceller)
        th.start()
        ret = bpy.ops.sheetgen.generate()
        t_end = time.monotonic()
        th.join()
        self.assertEqual(ret, {'CANCELLED'})
        self.assertLess(t_end - box["t0"], 1.0, "cancelled in stage %s" % box["stage"])
        self.assertEqual(scene_state(), before)
        self.assertIsNone(generate.active_run())


class Errors(unittest.TestCase):
    def test_scene_without_rivet_areas_is_a_report(self):
        enable_addon()
        clean_scene()
        mesh_object("floor", [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2, 3)])
        make_box_load()
        before = scene_state()
        with self.assertRaises(RuntimeError) as ctx:   # an ERROR report, not a Python traceback
            bpy.ops.sheetgen.generate()
        msg = str(ctx.exception)
        self.assertTrue(msg.startswith("Error: "), msg)
        self.assertIn("no rivet areas", msg)
        self.assertNotIn("Traceback", msg)
        self.assertEqual(scene_state(), before)


def png_stats(path):
    img = bpy.data.images.load(path)
    try:
        w, h = img.size
        px = np.empty(w * h * 4, dtype=np.float32)
        img.pixels.foreach_get(px)
        rgb = px.reshape(-1, 4)[:, :3]
        return (w, h), float(rgb.var())
    finally:
        bpy.data.images.remove(img)


class Batch(unittest.TestCase):
    def test_batch_on_the_shelf_blend(self):
        # shelf: its part at 6 x 300, beam 2 takes 3.5 s, corner's 14 s (the batch script is the same)
        enable_addon()
        import sheetgen_blender.native as native
        build_dir = os.path.dirname(os.path.dirname(native.get().__file__))
        with tempfile.TemporaryDirectory() as out:
            cmd = [bpy.app.binary_path, "-b", os.path.join(ROOT, "sample_scenes", "shelf", "scene.blend"), "--python-exit-code", "1",
                   "--python", os.path.join(ROOT, "scripts", "blender_batch.py"), "--",
                   "--out", out, "--render", "--chains", "6", "--iterations", "300", "--beam", "2", "--samples", "8",
                   "--build-dir", build_dir]
            p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
            self.assertEqual(p.returncode, 0, p.stdout[-3000:])
            self.assertIn("sheetgen: load 1/1", p.stdout)                     # progress lines
            self.assertIn("every load has a part", p.stdout)
            with open(os.path.join(out, "result.json")) as f:
                doc = json.load(f)
            self.assertEqual(doc["problem"], "problem.json")
            self.assertEqual([(q["load"], q["status"]) for q in doc["parts"]], [("avionics_box", "ok")])
            self.assertEqual(doc["search"]["chains"], 6)
            self.assertEqual(doc["search"]["iterations"], 300)
            self.assertEqual(doc["search"]["beam_width"], 2)
            for name in ("problem.json", "avionics_box/flat.dxf", "avionics_box/bends.csv", "scene.blend"):
                self.assertTrue(os.path.getsize(os.path.join(out, name)) > 0, name)
            size, var = png_stats(os.path.join(out, "render.png"))
            self.assertEqual(size, (640, 400))
            self.assertGreater(var, 1e-3)                                     # not a blank image
            size, var = png_stats(os.path.join(out, "render_avionics_box_flat.png"))
            self.assertGreater(var, 1e-3)
            with bpy.data.libraries.load(os.path.join(out, "scene.blend")) as (src, _dst):
                self.assertIn("sheetgen run 1", src.collections)
                self.assertIn("avionics_box part", src.objects)


if __name__ == "__main__":
    unittest.main()
