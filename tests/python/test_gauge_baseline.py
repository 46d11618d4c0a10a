"""The obstacles of bench/gauge_baseline.py (sheetgen_tools.geometry's box_mesh
and part_faces, sheetgen_tools.problem's one_load_problem): what the expert
stand-in's one-load runs must avoid is what sheetgen's own run of the bay
avoids (every load box and both faces of every earlier part). Closed forms: a
box's volume and corner distances, the sheet's thickness between its faces."""
import json
import math
import os
import tempfile
import unittest

import numpy as np

from sheetgen_tools.geometry import box_mesh, part_faces
from sheetgen_tools.paths import SAMPLE_SCENES
from sheetgen_tools.problem import one_load_problem


def closed_mesh_volume(mesh):
    V = np.array(mesh["vertices"])
    return sum(np.dot(V[a], np.cross(V[b], V[c])) for a, b, c in mesh["triangles"]) / 6.0


class BoxMesh(unittest.TestCase):
    def test_rotated_box_is_closed_outward_and_has_its_size(self):
        # 30 deg about z, then the box 0.3 x 0.2 x 0.1 m at (1, 2, 3).
        half = math.radians(30) / 2
        load = {"name": "b", "center": [1.0, 2.0, 3.0], "size": [0.3, 0.2, 0.1],
                "rotation": [math.cos(half), 0.0, 0.0, math.sin(half)]}
        m = box_mesh(load)
        self.assertEqual(len(m["triangles"]), 12)
        # Divergence theorem: a closed, outward-wound mesh encloses + the box volume.
        self.assertAlmostEqual(closed_mesh_volume(m), 0.3 * 0.2 * 0.1, places=12)
        d = np.linalg.norm(np.array(m["vertices"]) - np.array(load["center"]), axis=1)
        np.testing.assert_allclose(d, 0.5 * math.sqrt(0.3 ** 2 + 0.2 ** 2 + 0.1 ** 2), rtol=1e-12)
        # The long side turned 30 deg: a corner's offset in x-y is R (+-0.15, +-0.1).
        v0 = np.array(m["vertices"][0]) - np.array(load["center"])
        c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
        np.testing.assert_allclose(v0[:2], [c * -0.15 - s * -0.1, s * -0.15 + c * -0.1], atol=1e-12)

    def test_lowered_box_keeps_its_top_and_gains_the_base_room(self):
        # Tilted 90 deg about x: the box's -z (its bottom) points along world +y.
        load = {"name": "b", "center": [0.0, 0.0, 0.0], "size": [0.3, 0.2, 0.1],
                "rotation": [math.cos(math.pi / 4), math.sin(math.pi / 4), 0.0, 0.0]}
        m = box_mesh(load, below=0.004)
        self.assertAlmostEqual(closed_mesh_volume(m), 0.3 * 0.2 * 0.104, places=12)
        V = np.array(m["vertices"])
        np.testing.assert_allclose(sorted(set(np.round(V[:, 1], 9))), [-0.05, 0.054], atol=1e-12)
        np.testing.assert_allclose(sorted(set(np.round(V[:, 2], 9))), [-0.1, 0.1], atol=1e-12)


class SheetFaces(unittest.TestCase):
    def test_both_faces_are_the_thickness_apart(self):
        part = {"load": "p", "tabs": [
            {"corners": [[0, 0, 0], [0.1, 0, 0], [0.1, 0.05, 0], [0, 0.05, 0]], "normal": [0, 0, 1]},
            {"corners": [[0.1, 0, 0], [0.1, 0.05, 0], [0.1, 0.05, -0.03], [0.1, 0, -0.03]], "normal": [1, 0, 0]}]}
        V, F = part_faces(part, 2.0e-3)
        self.assertEqual(len(V), 16)
        self.assertEqual(len(F), 8)  # two per quad face
        for k in (0, 8):  # each tab: its 4 corners at -t/2, then at +t/2
            np.testing.assert_allclose(np.linalg.norm(V[k + 4:k + 8] - V[k:k + 4], axis=1), 2.0e-3, rtol=1e-12)
        np.testing.assert_allclose(V[0], [0, 0, -1.0e-3])
        np.testing.assert_allclose(V[12], [0.101, 0, 0])


class OneLoadProblem(unittest.TestCase):
    def test_one_load_with_the_other_boxes_and_the_parts_before_it(self):
        doc = json.load(open(os.path.join(SAMPLE_SCENES, "avionics_bay", "problem.json")))
        obstacle = {"name": "part:x", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]]}
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "problem.json")
            one_load_problem(doc, os.path.join(SAMPLE_SCENES, "avionics_bay"), doc["loads"][3],
                             2.032e-3, [obstacle], path, base_room=1.6e-3)
            q = json.load(open(path))
        self.assertEqual([l["name"] for l in q["loads"]], [doc["loads"][3]["name"]])
        self.assertEqual(q["material"]["thickness"], 2.032e-3)
        names = [m["name"] for m in q["environment"]["meshes"]]
        self.assertEqual(names[:len(doc["environment"]["meshes"])], [m["name"] for m in doc["environment"]["meshes"]])
        self.assertEqual(names.count("part:x"), 1)
        self.assertEqual(sorted(n for n in names if n.startswith("box:")),
                         sorted("box:" + l["name"] for i, l in enumerate(doc["loads"]) if i != 3))
        for m in q["environment"]["meshes"]:
            if "file" in m:
                self.assertTrue(os.path.isfile(m["file"]), m["file"])
        self.assertEqual(q["rivet_areas"], doc["rivet_areas"])
        # Each other box reaches base_room below its bottom (the bay's boxes are upright).
        for m in q["environment"]["meshes"]:
            if m["name"].startswith("box:"):
                load = next(l for l in doc["loads"] if "box:" + l["name"] == m["name"])
                bottom = load["center"][2] - 0.5 * load["size"][2]
                self.assertAlmostEqual(min(v[2] for v in m["vertices"]), bottom - 1.6e-3, places=12)


if __name__ == "__main__":
    unittest.main()
