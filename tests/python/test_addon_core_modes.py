"""The Results panel's envelope rows and the modes shown as shape keys, outside Blender; the native
``part_modes`` binding on a hand-made part.

Run: /usr/bin/python3 -m unittest discover -s tests/python -p 'test_addon_core_*.py'
(SHEETGEN_BUILD_DIR picks the build with the native module; its tests skip without one).

The hand-made part holds the corner sample's box (0.16 x 0.12 x 0.08 m, 4 kg, bottom at z = 0.30 m): a seat
tab 0.34 m long and 0.08 m wide at the box's bottom (mid-surface t/2 below it) reaching the wall x = 0, and a
0.08 m flange bent 90 degrees up along the wall and riveted to its rivet area.
"""
import json
import math
import os
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

from sheetgen_blender.core import modes as M  # noqa: E402
from sheetgen_blender.core import result as R  # noqa: E402
from sheetgen_tools.native_module import native_or_none  # noqa: E402

CORNER = os.path.join(ROOT, "sample_scenes", "corner")


def envelope_part(buckling=2.1, freqs=(31.0, 48.5, 90.2), required=(True, 1.5, 25.0)):
    cases = [{"name": "forward 9 g", "compliance": 0.2, "compliance_limit": 0.25, "margin_of_safety": 0.8,
              "buckling_factor": buckling},
             {"name": "down 6 g", "compliance": 0.1, "compliance_limit": 0.2, "margin_of_safety": 0.3,
              "buckling_factor": None}]
    return {"load": "box", "status": "ok",
            "envelope": {"cases": cases, "governing": {"stiffness": "forward 9 g", "strength": "down 6 g",
                                                       "buckling": "forward 9 g" if buckling else None},
                         "eigen_checked": True, "buckling_factor": buckling, "frequencies_hz": list(freqs),
                         "box_mass_kg": 4.0,
                         "required": {"checked": required[0], "min_buckling_factor": required[1],
                                      "min_frequency_hz": required[2]}}}


class EnvelopeRows(unittest.TestCase):
    def test_governing_cases_factor_and_frequencies(self):
        rows = R.envelope_rows(envelope_part())
        self.assertEqual(rows, [("Cases", "2", False),
                                ("Stiffness", "forward 9 g (C/C_max 0.800)", False),
                                ("Strength", "down 6 g (MS 0.300)", False),
                                ("Buckling", "forward 9 g", False),
                                ("Buckling factor", "2.100 (min 1.5)", False),
                                ("1st frequency (Hz)", "31.0 (floor 25)", False),
                                ("Frequencies (Hz)", "31.0, 48.5, 90.2", False)])

    def test_alerts_below_the_requirements(self):
        rows = dict((label, alert) for label, _text, alert in R.envelope_rows(envelope_part(1.2, (20.0,))))
        self.assertTrue(rows["Buckling factor"])
        self.assertTrue(rows["1st frequency (Hz)"])
        # not required (an old one-force file): reported, never red
        rows = dict((label, alert) for label, _t, alert in
                    R.envelope_rows(envelope_part(1.2, (20.0,), required=(False, 1.5, None))))
        self.assertFalse(rows["Buckling factor"])
        self.assertFalse(rows["1st frequency (Hz)"])

    def test_nothing_buckles_and_no_envelope(self):
        rows = dict((label, text) for label, text, _a in R.envelope_rows(envelope_part(None)))
        self.assertEqual(rows["Buckling factor"], "none (nothing buckles)")
        self.assertEqual(rows["Buckling"], "—")
        self.assertEqual(R.envelope_rows({"load": "box", "status": "ok"}), [])   # a result before load cases


def square_modes():
    """Two triangles on the unit square at z = 0, an extra unused node (the box's master node), the buckling
    mode lifting corner 2 by 1 and the vibration mode moving every node by 0.5 along x."""
    return {"vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0.3]],
            "triangles": [[0, 1, 2], [0, 2, 3]],
            "buckling_mode": [[0, 0, 0], [0, 0, 0], [0, 0, 1], [0, 0, 0], [0, 0, 0]],
            "vibration_mode": [[0.5, 0, 0]] * 4 + [[1, 0, 0]],
            "buckling_factor": 3.25, "buckling_case": "down 6 g", "frequencies_hz": [42.0, 60.0, 99.0]}


class ModesMesh(unittest.TestCase):
    def test_keys_scaled_to_a_tenth_of_the_part(self):
        m = M.modes_mesh(square_modes())
        self.assertEqual(len(m.vertices), 4)                 # the master node is not sheet
        self.assertEqual(m.triangles, [(0, 1, 2), (0, 2, 3)])
        self.assertEqual([k.name for k in m.keys], ["buckling down 6 g (factor 3.25)", "vibration 1 (42 Hz)"])
        buckling, vibration = m.keys
        # largest sheet displacement = 0.1 x the largest extent (1 m): 0.1 m
        self.assertAlmostEqual(buckling.positions[2][2], 0.1, places=15)
        self.assertEqual(buckling.positions[0], (0.0, 0.0, 0.0))
        # the vibration mode's peak over the sheet is 0.5 (the master node's 1 does not count): x + 0.1
        self.assertAlmostEqual(vibration.scale, 0.2, places=15)
        for base, moved in zip(m.vertices, vibration.positions):
            self.assertAlmostEqual(moved[0] - base[0], 0.1, places=15)
        self.assertEqual(m.summary, "buckling factor 3.25 (down 6 g), frequencies 42, 60, 99 Hz")

    def test_no_buckling_gives_one_key(self):
        d = square_modes()
        d["buckling_mode"], d["buckling_factor"], d["buckling_case"] = None, None, None
        m = M.modes_mesh(d)
        self.assertEqual([k.name for k in m.keys], ["vibration 1 (42 Hz)"])
        self.assertEqual(m.summary, "no buckling (nothing compresses the sheet), frequencies 42, 60, 99 Hz")

    def test_bad_input_is_one_sentence(self):
        d = square_modes()
        d["vibration_mode"] = d["vibration_mode"][:3]
        with self.assertRaisesRegex(M.ModesError, r"^mode 'vibration 1 \(42 Hz\)' has 3 nodes, the mesh 5$"):
            M.modes_mesh(d)
        with self.assertRaisesRegex(M.ModesError, "no mesh"):
            M.modes_mesh({})


def corner_problem(sg, mass=4.0, scale=1.0):
    with open(os.path.join(CORNER, "problem.json"), encoding="utf-8") as f:
        p = json.load(f)
    p.pop("load_cases", None)  # the box's two own cases only, not the corner's envelope
    p["requirements"].pop("min_frequency_hz", None)
    ld = p["loads"][0]
    for key in ("force", "moment"):
        ld.pop(key, None)
    ld["mass"] = mass
    ld["cases"] = [{"name": "down", "force": [0.0, 0.0, -353.0 * scale]},
                   {"name": "pull", "force": [300.0 * scale, 0.0, 0.0]}]
    return sg.parse_problem(json.dumps(p), "corner.json", CORNER)


def seat_and_flange():
    z, x0 = 0.2992, 0.0008     # the box bottom minus t/2; the wall x = 0 plus t/2
    seat = [[x0, -0.04, z], [0.34, -0.04, z], [0.34, 0.04, z], [x0, 0.04, z]]
    flange = [[x0, 0.04, z], [x0, -0.04, z], [x0, -0.04, z + 0.08], [x0, 0.04, z + 0.08]]
    return {"load": "avionics_box", "status": "ok",
            "tabs": [{"index": 0, "parent": -1, "rivet_area": -1, "corners": seat},
                     {"index": 1, "parent": 0, "parent_edge": 3, "rivet_area": 0, "corners": flange,
                      "parameters": {"theta3": math.pi / 2}}]}


@unittest.skipIf(native_or_none("part_modes") is None,
                 "native module with part_modes not built (target _sheetgen_native)")
class NativePartModes(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.sg = native_or_none("part_modes")
        cls.part = json.dumps(seat_and_flange())
        cls.modes = cls.sg.part_modes(corner_problem(cls.sg), 0, cls.part, "hand-made")

    def test_mesh_is_the_part(self):
        d = self.modes
        self.assertEqual(d["vertices"].shape[1], 3)
        self.assertEqual(d["triangles"].shape[1], 3)
        self.assertEqual(d["load_node"], d["vertices"].shape[0] - 1)    # the master node comes last
        used = sorted({int(i) for t in d["triangles"] for i in t})
        for i in used:   # every sheet node lies on the seat (z) or the flange (x) mid-surface
            x, _y, z = d["vertices"][i]
            self.assertTrue(abs(z - 0.2992) < 1e-9 or abs(x - 0.0008) < 1e-9, (x, z))

    def test_modes_are_normalised_to_a_largest_translation_of_one(self):
        for key in ("buckling_mode", "vibration_mode"):
            u = self.modes[key]
            self.assertEqual(u.shape, self.modes["vertices"].shape)
            self.assertAlmostEqual(max(math.sqrt(sum(x * x for x in row)) for row in u), 1.0, places=12)
        self.assertIn(self.modes["buckling_case"], ("down", "pull"))
        f = self.modes["frequencies_hz"]
        self.assertEqual(len(f), 3)
        self.assertTrue(0 < f[0] <= f[1] <= f[2], f)

    def test_buckling_factor_is_inverse_in_the_load(self):
        # Linear buckling: K + lambda K_G(F) is singular; K_G is linear in F, so twice the forces halve lambda.
        twice = self.sg.part_modes(corner_problem(self.sg, scale=2.0), 0, self.part)
        self.assertAlmostEqual(twice["buckling_factor"] * 2.0 / self.modes["buckling_factor"], 1.0, places=6)
        self.assertEqual(twice["buckling_case"], self.modes["buckling_case"])

    def test_first_frequency_of_a_mass_dominated_bracket(self):
        # The box (4 kg, its inertia scaling with it) dwarfs the sheet (about 0.15 kg): four times the mass,
        # half the frequency, to the sheet's share of the mass (within 2 %).
        heavy = self.sg.part_modes(corner_problem(self.sg, mass=16.0), 0, self.part)
        ratio = self.modes["frequencies_hz"][0] / heavy["frequencies_hz"][0]
        self.assertAlmostEqual(ratio, 2.0, delta=0.04)

    def test_errors_are_exceptions_with_one_sentence(self):
        problem = corner_problem(self.sg)
        with self.assertRaises(ValueError) as ctx:
            self.sg.part_modes(problem, 3, self.part, "r.json")
        self.assertIn("load_index", str(ctx.exception))
        with self.assertRaises(ValueError) as ctx:   # sg.InputError: a malformed part
            self.sg.part_modes(problem, 0, json.dumps({"load": "x", "tabs": [{"corners": [[0, 0]]}]}), "r.json")
        self.assertIn("r.json", str(ctx.exception))
        no_rivets = seat_and_flange()
        no_rivets["tabs"][1]["rivet_area"] = -1
        with self.assertRaises(RuntimeError) as ctx:  # sg.FemError: nothing holds the part
            self.sg.part_modes(problem, 0, json.dumps(no_rivets), "r.json")
        self.assertIsInstance(ctx.exception, self.sg.FemError)
        for e in (ctx.exception,):
            self.assertNotIn("\n", str(e))

    def test_glue_finds_problem_and_part(self):
        from sheetgen_blender import modes
        doc = {"format": "sheetgen-result/1", "parts": [seat_and_flange()]}
        d = modes.part_modes(corner_problem(self.sg), doc, "avionics_box", self.sg)
        self.assertEqual(d["frequencies_hz"], self.modes["frequencies_hz"])
        with self.assertRaisesRegex(M.ModesError, "^the result has no part for load 'ghost'$"):
            modes.part_modes(corner_problem(self.sg), doc, "ghost", self.sg)
        doc["parts"][0]["status"] = "no_valid_part"
        with self.assertRaisesRegex(M.ModesError, "has no valid part"):
            modes.part_modes(corner_problem(self.sg), doc, "avionics_box", self.sg)


if __name__ == "__main__":
    unittest.main()
