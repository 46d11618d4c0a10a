"""Load cases in Blender (issue 33): a load's mass, cases and mass properties, the envelope (preset or factor
list, the aircraft's axes), the buckling factor and frequency floor; problem files with them imported and
written back. No solve here (test_addon_envelope_solve.py solves).

Run: blender -b --factory-startup --python-exit-code 1 --python tests/blender/run.py -- BUILD_DIR
"""
import json
import os
import tempfile
import unittest

import bpy

from test_addon_support import clean_scene, enable_addon, make_box_load, mesh_object, write_envelope_problems

G0 = 9.80665   # m/s^2, the g of the load factors


def build_problem():
    from sheetgen_blender import operators
    return operators.build_problem(bpy.context)[0]


def native_load(problem):
    from sheetgen_blender import native
    from sheetgen_blender.core import jsonio
    return native.get().parse_problem(jsonio.dumps(problem), "scene", ".").loads[0]


def cases_of(ld):
    return [(c.name, list(c.force), list(c.moment), c.max_deflection) for c in ld.cases]


def floats(x):
    """JSON numbers as floats, nested (a file's 1 and Blender's 1.0 are the same number)."""
    if isinstance(x, list):
        return [floats(v) for v in x]
    if isinstance(x, dict):
        return {k: floats(v) for k, v in x.items()}
    return float(x) if isinstance(x, (int, float)) and not isinstance(x, bool) else x


class ProblemFiles(unittest.TestCase):
    """The three files of the acceptance, imported and written back: every new field comes back as written."""

    @classmethod
    def setUpClass(cls):
        enable_addon()
        cls.tmp = tempfile.TemporaryDirectory(prefix="sheetgen-load-cases-")
        cls.paths = write_envelope_problems(cls.tmp.name)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def imported(self, name):
        clean_scene()
        self.assertEqual(bpy.ops.sheetgen.import_problem(filepath=self.paths[name]), {'FINISHED'})
        with open(self.paths[name], encoding="utf-8") as f:
            return json.load(f), build_problem()

    def test_new_fields_come_back_as_written(self):
        for name in self.paths:
            with self.subTest(name):
                src, got = self.imported(name)
                for key in ("mass", "center_of_mass", "inertia", "cases"):
                    self.assertEqual(floats(got["loads"][0].get(key)), floats(src["loads"][0].get(key)), key)
                self.assertEqual(floats(got.get("load_cases")), floats(src.get("load_cases")))
                for key in ("min_buckling_factor", "min_frequency_hz", "max_deflection"):
                    self.assertEqual(got["requirements"].get(key), floats(src["requirements"].get(key)), key)
                # the file's order of meshes, rivet areas and loads (result.json refers to them by index)
                for key in ("rivet_areas", "loads"):
                    self.assertEqual([x["name"] for x in got[key]], [x["name"] for x in src[key]])
                self.assertEqual([m["name"] for m in got["environment"]["meshes"]],
                                 [m["name"] for m in src["environment"]["meshes"]])
                # the native reader sees the same cases, digit for digit
                from sheetgen_blender import native
                want = native.get().load_problem(self.paths[name]).loads[0]
                self.assertEqual(cases_of(native_load(got)), cases_of(want))

    def test_export_and_import_again_is_stable(self):
        for name in self.paths:
            with self.subTest(name):
                _, first = self.imported(name)
                out = os.path.join(self.tmp.name, "again_" + name + ".json")
                self.assertEqual(bpy.ops.sheetgen.export_problem(filepath=out), {'FINISHED'})
                clean_scene()
                self.assertEqual(bpy.ops.sheetgen.import_problem(filepath=out), {'FINISHED'})
                self.assertEqual(build_problem(), first)

    def test_thicker_gauges_from_the_material_panel(self):
        """Thicker gauges (docs/pipeline.md): off writes [], a list in mm writes it in m, empty writes nothing
        (the format's default); the native reader reads what was written, and an import sets the panel back."""
        from sheetgen_blender import native
        from sheetgen_blender.core import jsonio
        self.imported("preset")
        p = bpy.context.scene.sheetgen
        self.assertTrue(p.thicker_gauges)
        self.assertEqual(p.gauges_mm, "")
        self.assertNotIn("gauges", build_problem()["material"])
        inch = 0.0254
        parse = lambda pr: list(native.get().parse_problem(jsonio.dumps(pr), "scene", ".").material.gauges)  # noqa: E731
        self.assertEqual(len(parse(build_problem())), 6)                    # 0.071 ... 0.160 in above 0.063 in
        self.assertAlmostEqual(parse(build_problem())[0], 0.071 * inch, places=12)
        p.thicker_gauges = False
        self.assertEqual(build_problem()["material"]["gauges"], [])
        self.assertEqual(parse(build_problem()), [])
        p.thicker_gauges, p.gauges_mm = True, "1.8034, 2.032"
        written = build_problem()
        self.assertEqual(written["material"]["gauges"], [1.8034e-3, 2.032e-3])
        self.assertEqual(parse(written), [1.8034e-3, 2.032e-3])
        out = os.path.join(self.tmp.name, "gauges.json")
        self.assertEqual(bpy.ops.sheetgen.export_problem(filepath=out), {'FINISHED'})
        clean_scene()
        self.assertEqual(bpy.ops.sheetgen.import_problem(filepath=out), {'FINISHED'})
        p = bpy.context.scene.sheetgen
        self.assertEqual((p.thicker_gauges, p.gauges_mm), (True, "1.8034, 2.032"))

    def test_panel_properties_after_import(self):
        self.imported("factors")
        p = bpy.context.scene.sheetgen
        self.assertTrue(p.use_envelope)
        self.assertEqual(p.envelope_kind, 'LIST')
        self.assertEqual(tuple(p.envelope_forward), (0.0, -1.0, 0.0))
        self.assertEqual([(f.name, tuple(f.g), f.use_max_deflection) for f in p.envelope_factors],
                         [("forward 9 g", (9.0, 0.0, 0.0), False), ("down 6 g", (0.0, 0.0, -6.0), True),
                          ("side 3 g", (0.0, 3.0, 1.0), False)])
        self.assertAlmostEqual(p.envelope_factors[1].max_deflection_mm, 3.0, places=6)
        box = bpy.data.objects["avionics_box"].sheetgen
        self.assertEqual(box.own_cases, 'NONE')
        self.assertTrue(box.use_mass)
        self.assertEqual(box.mass, 4.0)
        self.assertTrue(box.arrow.hide_viewport)   # no single force to draw
        self.imported("cases")
        box = bpy.data.objects["avionics_box"].sheetgen
        self.assertEqual(box.own_cases, 'CASES')
        self.assertEqual([c.name for c in box.cases], ["connector pull", "handling"])
        self.assertTrue(box.use_center_of_mass and box.use_inertia)
        self.assertFalse(bpy.context.scene.sheetgen.use_envelope)
        self.assertTrue(bpy.context.scene.sheetgen.use_min_frequency)
        self.assertFalse(bpy.context.scene.sheetgen.use_min_buckling_factor)


class LoadsPanel(unittest.TestCase):
    """What the Loads, Envelope and Requirements panels set, through their operators and properties."""

    def setUp(self):
        enable_addon()
        clean_scene()
        floor = mesh_object("floor", [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2, 3)])
        floor.data.attributes.new("sheetgen_rivet_area", 'INT', 'FACE').data[0].value = 1
        item = floor.sheetgen.rivet_areas.add()
        item.area_id, item.name = 1, "floor_rivets"
        self.box = make_box_load("box", location=(0.5, 0.5, 0.3))

    def test_cases_mass_and_preset_factors(self):
        s = self.box.sheetgen
        for _ in range(2):
            self.assertEqual(bpy.ops.sheetgen.load_case_add(), {'FINISHED'})
        self.assertEqual(s.own_cases, 'CASES')
        self.assertEqual([c.name for c in s.cases], ["case 1", "case 2"])
        s.cases[0].force = (0, 0, -50)
        s.cases[1].force = (10, 0, 0)
        s.cases[1].moment = (0, 2, 0)
        s.cases[1].use_max_deflection, s.cases[1].max_deflection_mm = True, 2.5
        s.use_mass, s.mass = True, 4.0
        p = bpy.context.scene.sheetgen
        p.use_envelope = True
        p.envelope_forward, p.envelope_up = (0, 1, 0), (0, 0, 1)
        self.assertEqual(bpy.ops.sheetgen.envelope_factors_from_preset(), {'FINISHED'})
        self.assertEqual(p.envelope_kind, 'LIST')
        problem = build_problem()
        self.assertEqual(problem["loads"][0]["cases"],
                         [{"name": "case 1", "force": [0.0, 0.0, -50.0]},
                          {"name": "case 2", "force": [10.0, 0.0, 0.0], "moment": [0.0, 2.0, 0.0],
                           "max_deflection": 0.0025}])
        self.assertNotIn("force", problem["loads"][0])
        self.assertEqual(problem["load_cases"]["forward"], [0.0, 1.0, 0.0])
        self.assertEqual([(f["name"], f["g"]) for f in problem["load_cases"]["factors"]],
                         [("forward 9 g", [9.0, 0.0, 0.0]), ("rearward 1.5 g", [-1.5, 0.0, 0.0]),
                          ("left 3 g", [0.0, 3.0, 0.0]), ("right 3 g", [0.0, -3.0, 0.0]),
                          ("down 6 g", [0.0, 0.0, -6.0]), ("up 3 g", [0.0, 0.0, 3.0])])
        ld = native_load(problem)
        self.assertEqual(len(ld.cases), 8)
        # forward +y and up +z: left = up x forward = -x, so "left 3 g" pushes the 4 kg box along -x
        left = next(c for c in ld.cases if c.name == "left 3 g")
        for got, want in zip(left.force, (-4.0 * G0 * 3.0, 0.0, 0.0)):
            self.assertAlmostEqual(got, want, delta=1e-9)
        self.assertEqual(bpy.ops.sheetgen.load_case_remove(), {'FINISHED'})
        self.assertEqual([c.name for c in s.cases], ["case 1"])

    def test_envelope_only_and_preset(self):
        s = self.box.sheetgen
        s.own_cases = 'NONE'
        s.use_mass, s.mass = True, 2.5
        p = bpy.context.scene.sheetgen
        p.use_envelope = True
        problem = build_problem()
        self.assertEqual(problem["load_cases"], {"forward": [1.0, 0.0, 0.0], "up": [0.0, 0.0, 1.0],
                                                 "factors": "far25.561"})
        self.assertEqual(problem["loads"][0]["mass"], 2.5)
        down = next(c for c in native_load(problem).cases if c.name == "down 6 g")
        self.assertAlmostEqual(down.force[2], -2.5 * G0 * 6.0, delta=1e-9)

    def test_requirement_floors_written_only_when_set(self):
        p = bpy.context.scene.sheetgen
        self.assertNotIn("min_buckling_factor", build_problem()["requirements"])
        self.assertNotIn("min_frequency_hz", build_problem()["requirements"])
        p.use_min_buckling_factor, p.min_buckling_factor = True, 2.0
        p.use_min_frequency, p.min_frequency_hz = True, 30.0
        req = build_problem()["requirements"]
        self.assertEqual((req["min_buckling_factor"], req["min_frequency_hz"]), (2.0, 30.0))

    def test_arrow_only_for_a_single_force(self):
        s = self.box.sheetgen
        self.assertFalse(s.arrow.hide_viewport)
        s.own_cases = 'CASES'
        self.assertTrue(s.arrow.hide_viewport)
        s.own_cases = 'FORCE'
        self.assertFalse(s.arrow.hide_viewport)

    def test_mistakes_are_sentences_not_tracebacks(self):
        from sheetgen_blender.core.problem import ProblemError
        p = bpy.context.scene.sheetgen
        p.use_envelope = True           # and no load has a mass
        with self.assertRaises(ProblemError) as ctx:
            build_problem()
        self.assertEqual(ctx.exception.errors, ["envelope: no load has a mass, so no load gets its cases (set a "
                                                "load's Mass in the Loads panel, or turn the envelope off)"])
        # the operator reports it (an ERROR report, which bpy.ops raises as RuntimeError in a script)
        with self.assertRaisesRegex(RuntimeError, r"^Error: envelope: no load has a mass"):
            bpy.ops.sheetgen.check_problem()
        self.box.sheetgen.use_mass = True
        p.envelope_up = (0.1, 0, 1)
        with self.assertRaises(ProblemError) as ctx:
            build_problem()
        self.assertTrue(ctx.exception.errors[0].startswith("envelope: forward and up are not orthogonal"))
        with self.assertRaisesRegex(RuntimeError, r"^Error: envelope: forward and up are not orthogonal"):
            bpy.ops.sheetgen.generate()


if __name__ == "__main__":
    unittest.main()
