"""scripts/render_results.py (a finished run folder -> render.png) as a subprocess of this Blender.

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR

The run folder is hand-made (no solve): the corner problem (by a relative
path, as solve writes it) and a result.json with one valid two-tab part under
the load box (a 160 x 80 mm seat at the box's bottom, a 100 mm leg bent down
along its x = 0.34 m edge) and one load without a valid part whose nearest
candidate is a 100 x 200 mm tab beside the wall.
"""
import json
import math
import os
import subprocess
import tempfile
import unittest

import bpy

from test_addon_support import ROOT, enable_addon

SCRIPT = os.path.join(ROOT, "scripts", "render_results.py")
PROBLEM = os.path.join(ROOT, "sample_scenes", "corner", "problem.json")
SIZE = (160, 100)


def seat_part():
    z = 0.2992          # the load box's bottom (z = 0.30) minus half the 1.6 mm sheet
    seat = [[0.18, -0.04, z], [0.34, -0.04, z], [0.34, 0.04, z], [0.18, 0.04, z]]
    leg = [[0.34, 0.04, z], [0.34, -0.04, z], [0.34, -0.04, z - 0.1], [0.34, 0.04, z - 0.1]]
    outline = [[0.0, 0.0], [0.16, 0.0], [0.26, 0.0], [0.26, 0.08], [0.16, 0.08], [0.0, 0.08]]
    return {"load": "avionics_box", "status": "ok", "area_m2": 0.0208, "mass_kg": 0.09, "bends": 1,
            "compliance": 0.1, "compliance_limit": 0.35, "deflection_m": 3e-4, "margin_of_safety": 1.0,
            "tabs": [{"index": 0, "parent": -1, "corners": seat},
                     {"index": 1, "parent": 0, "parent_edge": 1, "corners": leg}],
            "rivets": [[0.34, 0.0, z - 0.09]],
            "flat_pattern": {"outline": [outline], "area_m2": 0.0208, "reliefs": [],
                             "bends": [{"tab": 1, "number": 1, "a": [0.16, 0.0], "b": [0.16, 0.08],
                                        "angle": -math.pi / 2, "direction": "down"}]}}


def candidate_part():
    tab = [[0.05, -0.2, 0.1], [0.15, -0.2, 0.1], [0.15, -0.2, 0.3], [0.05, -0.2, 0.3]]
    return {"load": "ghost", "status": "no_valid_part", "reason": "compliance over the limit",
            "tabs": [{"index": 0, "parent": -1, "corners": tab}]}


def run_script(out, *extra):
    import sheetgen_blender.native as native
    build_dir = os.path.dirname(os.path.dirname(native.get().__file__))
    cmd = [bpy.app.binary_path, "-b", "--factory-startup", "--python-exit-code", "1", "--python", SCRIPT, "--",
           out, "--build-dir", build_dir] + list(extra)
    return subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=300)


def png_pixels(path):
    """((w, h), [(r, g, b)]) of a PNG, linear floats as Blender loads them."""
    img = bpy.data.images.load(path, check_existing=False)
    try:
        w, h = img.size
        px = list(img.pixels[:])
        return (w, h), [tuple(px[i:i + 3]) for i in range(0, len(px), 4)]
    finally:
        bpy.data.images.remove(img)


class RenderResults(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        enable_addon()

    def test_renders_a_finished_run_folder(self):
        with tempfile.TemporaryDirectory() as out:
            doc = {"format": "sheetgen-result/1", "problem": os.path.relpath(PROBLEM, out),
                   "parts": [seat_part(), candidate_part()]}
            with open(os.path.join(out, "result.json"), "w") as f:
                json.dump(doc, f)
            p = run_script(out, "--samples", "4", "--resolution", str(SIZE[0]), str(SIZE[1]))
            self.assertEqual(p.returncode, 0, p.stdout[-2000:] + p.stderr[-2000:])
            self.assertIn("1/2 loads with a part; nearest candidate in translucent magenta: ghost", p.stdout)
            size, px = png_pixels(os.path.join(out, "render.png"))
            self.assertEqual(size, SIZE)
            # The part is the only gold in the picture: r > g > b with g well above b (grey, the blue box and
            # the translucent magenta candidate has g << r, b) and g not far below r (a red rivet area).
            gold = sum(1 for r, g, b in px if r > g > b + 0.08 and g > 0.55 * r)
            self.assertGreater(gold, 0.002 * len(px), "no gold (part) pixels")
            self.assertGreater(len(set(px)), 100)                           # not one flat colour
            self.assertTrue(os.path.getsize(os.path.join(out, "render_avionics_box_flat.png")) > 0)
            self.assertFalse(os.path.exists(os.path.join(out, "render_ghost_flat.png")))

    def test_bad_folder_is_one_sentence_and_exit_1(self):
        with tempfile.TemporaryDirectory() as out:
            p = run_script(out)
            self.assertEqual(p.returncode, 1)
            self.assertNotIn("Traceback", p.stderr)
            self.assertIn("render_results: %s has no result.json" % out, p.stderr)
            self.assertFalse(os.path.exists(os.path.join(out, "render.png")))


if __name__ == "__main__":
    unittest.main()
