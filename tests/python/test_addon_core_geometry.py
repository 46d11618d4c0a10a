"""The add-on core's geometry, number and file helpers, outside Blender.

Run: /usr/bin/python3 -m unittest discover -s tests/python -p 'test_addon_core_*.py'
"""
import json
import math
import os
import struct
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

from sheetgen_blender.core import geometry, jsonio  # noqa: E402


def read_text(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


class Geometry(unittest.TestCase):
    def test_triangle_area_closed_form(self):
        self.assertEqual(geometry.triangle_area((0, 0, 0), (2, 0, 0), (0, 3, 0)), 3.0)
        # Equilateral triangle of side 2 in a tilted plane: sqrt(3).
        a, b = (1, 0, 0), (0, 1, 0)
        self.assertAlmostEqual(geometry.triangle_area(a, b, (0, 0, 1)), math.sqrt(3) / 2, places=15)

    def test_rivet_area_areas_sums_per_id(self):
        v = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]
        t = [(0, 1, 2), (0, 2, 3)]
        self.assertEqual(geometry.rivet_area_areas(v, t, [2, 2]), {2: (1.0, 2)})
        self.assertEqual(geometry.rivet_area_areas(v, t, [0, 5]), {5: (0.5, 1)})

    def test_quaternion_rotation(self):
        s = math.sqrt(0.5)
        x = geometry.quat_rotate((s, 0, 0, s), (1, 0, 0))  # 90 degrees about z: x -> y
        self.assertAlmostEqual(x[0], 0, places=15)
        self.assertAlmostEqual(x[1], 1, places=15)
        self.assertEqual(geometry.quat_normalized((-2, 0, 0, 0)), (1.0, -0.0, -0.0, -0.0))
        with self.assertRaises(ValueError):
            geometry.quat_normalized((0, 0, 0, 0))
        # Unit to float32 precision: kept digit for digit (sign made w >= 0); otherwise normalised.
        q = (0.9238795, 0.0, 0.0, 0.3826834)     # |q| = 1 - 4e-8
        self.assertEqual(geometry.quat_unit(q), q)
        self.assertEqual(geometry.quat_unit(tuple(-x for x in q)), q)
        self.assertEqual(geometry.quat_unit((0.0, 0.0, 3.0, 4.0)), (0.0, 0.0, 0.6, 0.8))

    def test_shortest_float32(self):
        self.assertEqual(geometry.shortest_float32(f32(0.3)), 0.3)
        self.assertEqual(geometry.shortest_float32(f32(73.1)), 73.1)
        self.assertEqual(geometry.shortest_float32(f32(1.0 / 3.0)), 0.33333334)  # needs 8 digits
        self.assertEqual(geometry.shortest_float32(f32(-1.6e-3)), -1.6e-3)
        self.assertEqual(geometry.shortest_float32(0.0), 0.0)
        # Every result maps back to the same float32 (checked over 2000 spread values).
        for i in range(1, 2001):
            x = f32(math.sin(i) * 10 ** (i % 9 - 4))
            self.assertEqual(f32(geometry.shortest_float32(x)), x)


class JsonFiles(unittest.TestCase):
    def test_dumps_compact_arrays_round_trip(self):
        p = {"a": {"vertices": [[0.1, -2e-05, 3], [1, 2, 3]], "faces": [1, 2, 3]}, "name": "x [1, 2]"}
        text = jsonio.dumps(p)
        self.assertEqual(json.loads(text), p)
        self.assertIn("[0.1, -2e-05, 3]", text)
        self.assertIn('"faces": [1, 2, 3]', text)
        with self.assertRaises(ValueError):
            jsonio.dumps({"x": float("nan")})

    def test_write_atomic_replaces_and_leaves_no_temp(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "problem.json")
            jsonio.write_atomic(path, "old\n")
            jsonio.write_atomic(path, "new\n")
            self.assertEqual(read_text(path), "new\n")
            self.assertEqual(os.listdir(d), ["problem.json"])
            # A refused write keeps the previous file whole and leaves no temporary.
            with self.assertRaises(TypeError):
                jsonio.write_atomic(path, 12345)  # neither text nor bytes
            self.assertEqual(read_text(path), "new\n")
            self.assertEqual(os.listdir(d), ["problem.json"])

    def test_read_names_the_file(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "bad.json")
            with open(path, "w") as f:
                f.write("{oops")
            with self.assertRaises(ValueError) as ctx:
                jsonio.read(path)
            self.assertTrue(str(ctx.exception).startswith(path + ": is not valid JSON"))


if __name__ == "__main__":
    unittest.main()
