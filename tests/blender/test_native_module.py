"""The native module inside Blender: import, problem loading, environment queries.

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
(tests/blender/run.py runs every tests/blender/test_*.py with unittest).
"""
import math
import os
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))


def native():
    import _sheetgen_native  # put on sys.path by run.py (BUILD_DIR/python)
    return _sheetgen_native


class NativeModuleInBlender(unittest.TestCase):
    def test_runs_inside_blender(self):
        import bpy  # noqa: F401  (proves we are inside Blender's Python)
        self.assertEqual(sys.version_info[:2], (3, 11))

    def test_load_sample_problem(self):
        sg = native()
        p = sg.load_problem(os.path.join(ROOT, "sample_scenes", "corner", "problem.json"))
        self.assertEqual([m.name for m in p.meshes], ["wall", "floor"])
        self.assertEqual(p.triangle_count, 576)
        # wall_rivets: 6 x 4 cells of 0.05 m = 0.3 m x 0.2 m.
        self.assertAlmostEqual(p.rivet_areas[0].area_m2, 0.06, places=12)
        self.assertEqual(p.meshes[0].vertices.shape, (169, 3))
        self.assertAlmostEqual(p.material.thickness, 1.6e-3)

    def test_bad_input_raises_input_error_with_field(self):
        sg = native()
        with self.assertRaises(sg.InputError) as ctx:
            sg.parse_problem('{"format": "sheetgen-problem/1", "environment": {"meshes": []}}', "inline.json", ".")
        self.assertIn("inline.json: environment.meshes", str(ctx.exception))
        self.assertTrue(issubclass(sg.InputError, ValueError))

    def test_environment_queries_match_closed_form(self):
        import numpy as np
        sg = native()
        p = sg.load_problem(os.path.join(ROOT, "sample_scenes", "corner", "problem.json"))
        env = sg.Environment(p)
        # Points 3 cm in front of the plain wall (x = 0) and 2 cm above the plain floor (z = 0),
        # away from rivet areas and the load: distance is the plane distance.
        pts = np.array([[0.03, 0.25, 0.55], [0.55, 0.25, 0.02]])
        d = env.clearance(pts)
        self.assertAlmostEqual(d[0], 0.03, places=9)
        self.assertAlmostEqual(d[1], 0.02, places=9)
        hit = env.cast_ray([0.3, 0.0, 0.3], [-1.0, 0.0, 0.0], 10.0)
        self.assertIsNotNone(hit)
        self.assertAlmostEqual(hit.distance, 0.3, places=9)
        self.assertEqual(hit.rivet_area, 0)  # wall_rivets spans z in [0.2, 0.4], y in [-0.15, 0.15]
        self.assertIsNone(env.cast_ray([0.3, 0.0, 0.2], [1.0, 0.0, 0.0], 10.0))
        ra = env.rivet_area_distance(0, np.array([[0.1, 0.0, 0.3]]))
        self.assertAlmostEqual(ra[0], 0.1, places=9)


if __name__ == "__main__":
    unittest.main()


class GenerateInBlender(unittest.TestCase):
    """generate() inside Blender: releases the GIL, reports progress, cancels within a second."""

    def test_generate_reports_progress_and_result(self):
        import json
        import threading
        import time
        sg = native()
        # shelf: about 2.5 s at this size (corner, which finds no part there and runs every fallback, 13 s)
        p = sg.load_problem(os.path.join(ROOT, "sample_scenes", "shelf", "problem.json"))
        progress = sg.GenerateProgress()
        box = {}
        worker = threading.Thread(target=lambda: box.setdefault("r", sg.generate(p, progress, seed=3, chains=2, iterations=100, beam_width=2)))
        worker.start()
        ticks = 0
        while worker.is_alive():  # the GIL is free: this loop runs while the solver works
            ticks += 1
            time.sleep(0.05)
        worker.join()
        self.assertGreater(ticks, 5)
        self.assertEqual(progress.stage, "done")
        self.assertEqual(progress.total_iterations, 2 * 100)
        doc = json.loads(sg.result_json(p, box["r"], "problem.json"))
        self.assertEqual(doc["format"], "sheetgen-result/1")
        self.assertEqual([part["load"] for part in doc["parts"]], ["avionics_box"])
        self.assertIn(doc["parts"][0]["status"], ("ok", "no_valid_part"))

    def test_cancel_returns_within_a_second(self):
        import threading
        import time
        sg = native()
        # shelf: about 2.5 s at this size (corner, which finds no part there and runs every fallback, 13 s)
        p = sg.load_problem(os.path.join(ROOT, "sample_scenes", "shelf", "problem.json"))
        progress = sg.GenerateProgress()
        box = {}
        worker = threading.Thread(target=lambda: box.setdefault("r", sg.generate(p, progress)))
        worker.start()
        time.sleep(1.5)
        self.assertTrue(worker.is_alive())
        t0 = time.monotonic()
        progress.cancel()
        worker.join(timeout=5)
        waited = time.monotonic() - t0
        self.assertFalse(worker.is_alive())
        self.assertLess(waited, 1.0)
        self.assertTrue(box["r"].cancelled)
        self.assertFalse(box["r"].all_ok)
