"""The add-on core's load cases (issue 33), outside Blender: a load's mass, centre of mass, inertia and explicit
cases, the problem's envelope (the FAR/CS 25.561 preset or a factor list), the buckling factor and frequency
floor, both ways between scene data and the problem dict, and their error sentences.

Run: /usr/bin/python3 -m unittest discover -s tests/python -p 'test_addon_core_*.py'
(the native cross-checks need the module built for the system Python 3.11; SHEETGEN_BUILD_DIR picks the build).
"""
import json
import math
import os
import re
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

from sheetgen_blender.core import geometry, jsonio, model  # noqa: E402
from sheetgen_blender.core.model import Envelope, FactorData, LoadCaseData, LoadData, MeshData, SceneData  # noqa: E402
from sheetgen_blender.core.problem import ProblemError, problem_to_scene, scene_to_problem  # noqa: E402
from sheetgen_tools.native_module import native_or_none  # noqa: E402


def issue_problem():
    """The issue's example (docs/problem-format.md "Load cases"): a box with a mass, explicit cases and the
    preset envelope, a buckling factor and a frequency floor; one wall with a rivet area."""
    return {
        "format": "sheetgen-problem/1", "name": "radio", "units": "m",
        "environment": {"meshes": [{"name": "wall", "vertices": [[0, -0.5, 0], [0, 0.5, 0], [0, 0.5, 1], [0, -0.5, 1]],
                                    "triangles": [[0, 1, 2], [0, 2, 3]]}]},
        "rivet_areas": [{"name": "w", "mesh": "wall", "faces": [0, 1]}],
        "loads": [{"name": "radio", "center": [0.3, 0.0, 0.3], "size": [0.16, 0.12, 0.08], "rotation": [1.0, 0.0, 0.0, 0.0],
                   "mass": 2.4,
                   "cases": [{"name": "connector pull", "force": [0.0, -200.0, 0.0]},
                             {"name": "handling", "force": [0.0, 0.0, -150.0], "moment": [0.0, 4.0, 0.0],
                              "max_deflection": 2e-3}]}],
        "load_cases": {"forward": [0.0, -1.0, 0.0], "up": [0.0, 0.0, 1.0], "factors": "far25.561"},
        "requirements": {"min_buckling_factor": 1.5, "min_frequency_hz": 25.0},
    }


def factor_list_problem():
    p = issue_problem()
    ld = p["loads"][0]
    del ld["cases"]
    ld.update({"center_of_mass": [0.31, 0.01, 0.29], "inertia": [[0.0068, 0.0001, 0.0], [0.0001, 0.0107, 0.0],
                                                                  [0.0, 0.0, 0.0133]]})
    p["load_cases"] = {"forward": [1.0, 0.0, 0.0], "up": [0.0, 0.0, 1.0],
                       "factors": [{"name": "forward 9 g", "g": [9.0, 0.0, 0.0]},
                                   {"name": "down 6 g", "g": [0.0, 0.0, -6.0], "max_deflection": 3e-3}]}
    del p["requirements"]["min_buckling_factor"]
    return p


def round_trip(problem):
    scene, warnings = problem_to_scene(problem)
    again, more = scene_to_problem(scene)
    return scene, again, warnings + more


class RoundTrip(unittest.TestCase):
    def test_issue_example_comes_back_as_written(self):
        p = issue_problem()
        scene, again, warnings = round_trip(p)
        self.assertEqual(warnings, [])
        ld = scene.loads[0]
        self.assertEqual(ld.own, model.OWN_CASES)
        self.assertEqual(ld.mass, 2.4)
        self.assertIsNone(ld.center_of_mass)
        self.assertEqual(scene.settings.load_cases.preset, "far25.561")
        # loads[0], load_cases and the two new requirements exactly as in the file (a case without a moment
        # is written without one; the old force/moment are not written beside cases)
        self.assertEqual(again["loads"], p["loads"])
        self.assertEqual(again["load_cases"], p["load_cases"])
        self.assertEqual(again["requirements"]["min_buckling_factor"], 1.5)
        self.assertEqual(again["requirements"]["min_frequency_hz"], 25.0)

    def test_factor_list_with_mass_properties(self):
        p = factor_list_problem()
        scene, again, _ = round_trip(p)
        ld = scene.loads[0]
        self.assertEqual(ld.own, model.OWN_NONE)      # neither force nor cases: the envelope's cases only
        self.assertNotIn("force", again["loads"][0])
        self.assertEqual(again["loads"], p["loads"])
        self.assertEqual(again["load_cases"], p["load_cases"])
        self.assertEqual(scene.settings.load_cases.factors[1], FactorData("down 6 g", [0.0, 0.0, -6.0], 3e-3))
        # not named: not written (naming it would turn the eigen checks on for an old file)
        self.assertNotIn("min_buckling_factor", again["requirements"])

    def test_force_and_mass_under_the_envelope(self):
        p = issue_problem()
        ld = p["loads"][0]
        del ld["cases"]
        ld.update({"force": [0.0, 0.0, -100.0], "moment": [0.0, 0.0, 0.0]})
        scene, again, _ = round_trip(p)
        self.assertEqual(scene.loads[0].own, model.OWN_FORCE)
        self.assertEqual(again["loads"], p["loads"])

    def test_old_file_gets_no_new_field(self):
        p = issue_problem()
        ld = p["loads"][0]
        for key in ("mass", "cases"):
            del ld[key]
        ld["force"] = [0.0, 0.0, -353.0]
        del p["load_cases"]
        del p["requirements"]
        _, again, _ = round_trip(p)
        self.assertEqual(set(again["loads"][0]), {"name", "center", "size", "rotation", "force", "moment"})
        self.assertNotIn("load_cases", again)
        self.assertEqual(set(again["requirements"]),
                         {"max_deflection", "min_margin_of_safety", "safety_factor", "clearance"})

    def test_preset_table_is_the_documented_expansion(self):
        """model.PRESETS (what the Envelope panel lists) is docs/problem-format.md's table of the preset."""
        with open(os.path.join(ROOT, "docs", "problem-format.md"), encoding="utf-8") as f:
            rows = re.findall(r"^\| `([^`]+ g)` \| \(([^)]*)\) \|", f.read(), re.M)
        documented = [(name, tuple(float(x.replace("−", "-")) for x in g.split(","))) for name, g in rows]
        self.assertEqual(documented, [(n, tuple(g)) for n, g in model.PRESETS[model.PRESET_FAR25_561]])


class FileOrder(unittest.TestCase):
    def test_rivet_areas_keep_the_file_order(self):
        """result.json names rivet areas by index: an imported file keeps its order, even interleaved across
        meshes (the areas of one mesh are otherwise written together)."""
        p = issue_problem()
        p["environment"]["meshes"].append({"name": "floor", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0]],
                                           "triangles": [[0, 1, 2]]})
        p["rivet_areas"] = [{"name": "a", "mesh": "wall", "faces": [0]}, {"name": "b", "mesh": "floor", "faces": [0]},
                            {"name": "c", "mesh": "wall", "faces": [1]}]
        _, again, _ = round_trip(p)
        self.assertEqual(again["rivet_areas"], p["rivet_areas"])


class SceneErrors(unittest.TestCase):
    """What a Blender user can get wrong, one sentence each, naming the object (or the envelope) and the field."""

    def scene(self, **load):
        wall = MeshData("wall", [[0, -0.5, 0], [0, 0.5, 0], [0, 0.5, 1], [0, -0.5, 1]], [[0, 1, 2], [0, 2, 3]],
                        face_areas=[1, 1], area_names={1: "w"})
        ld = LoadData("box", center=[0.3, 0.0, 0.3], size=[0.16, 0.12, 0.08], force=[0, 0, -100])
        for k, v in load.items():
            setattr(ld, k, v)
        return SceneData(name="s", meshes=[wall], loads=[ld])

    def errors(self, scene):
        with self.assertRaises(ProblemError) as ctx:
            scene_to_problem(scene)
        return ctx.exception.errors

    def test_mass_not_positive(self):
        self.assertEqual(self.errors(self.scene(mass=0.0)), ["load 'box': mass (kg): must be positive, got 0"])

    def test_envelope_needs_a_massed_load(self):
        s = self.scene()
        s.settings.load_cases = Envelope()
        self.assertEqual(self.errors(s), ["envelope: no load has a mass, so no load gets its cases (set a load's Mass "
                                          "in the Loads panel, or turn the envelope off)"])

    def test_envelope_only_load_needs_mass_and_envelope(self):
        self.assertEqual(self.errors(self.scene(own=model.OWN_NONE)),
                         ["load 'box': it has no force and no cases of its own, so it needs a Mass and the envelope "
                          "(Loads panel)"])

    def test_axes_not_orthogonal(self):
        s = self.scene(mass=2.0)
        s.settings.load_cases = Envelope(forward=[1, 0, 0], up=[0.01, 0, 1])
        errs = self.errors(s)
        self.assertEqual(len(errs), 1)
        self.assertTrue(errs[0].startswith("envelope: forward and up are not orthogonal (89.427"), errs[0])

    def test_empty_and_zero_cases(self):
        s = self.scene(own=model.OWN_CASES, cases=[LoadCaseData("a", [0, 0, 0], [0, 0, 0]),
                                                   LoadCaseData("a", [0, 0, 1])])
        self.assertEqual(self.errors(s), ["load 'box', case 1 'a': force and moment are both zero",
                                          "load 'box', case 2: duplicate case name 'a'"])
        self.assertEqual(self.errors(self.scene(own=model.OWN_CASES, cases=[])),
                         ["load 'box': the case list is empty (add a case in the Loads panel, or use Force)"])

    def test_case_named_like_a_factor(self):
        s = self.scene(mass=2.0, own=model.OWN_CASES, cases=[LoadCaseData("down 6 g", [0, 0, -1])])
        s.settings.load_cases = Envelope()
        self.assertEqual(self.errors(s), ["load 'box': its case 'down 6 g' has the name of an envelope factor; names "
                                          "must be unique per load (rename one)"])

    def test_inertia_and_centre_of_mass(self):
        errs = self.errors(self.scene(mass=2.0, inertia=[[1, 0, 0], [0, 1, 0], [0, 0, 3]],
                                      center_of_mass=[0.3, 0.0, 0.35]))
        self.assertEqual(errs, ["load 'box': centre of mass [0.3, 0, 0.35] m lies 10 mm outside the load box",
                                "load 'box': inertia is not that of a rigid body (principal moments 1, 1, 3 kg·m²: "
                                "the largest exceeds the sum of the other two)"])
        errs = self.errors(self.scene(mass=2.0, inertia=[[1, 0.5, 0], [0.4, 1, 0], [0, 0, 1]]))
        self.assertEqual(errs, ["load 'box': inertia is not symmetric: [0][1] = 0.5 but [1][0] = 0.4"])
        errs = self.errors(self.scene(inertia=[[1, 0, 0], [0, 1, 0], [0, 0, 1]]))
        self.assertEqual(errs, ["load 'box': a centre of mass or inertia is given without a mass (set Mass in the "
                                "Loads panel)"])

    def test_factor_list(self):
        s = self.scene(mass=2.0)
        s.settings.load_cases = Envelope(preset=None, factors=[FactorData("x", [0, 0, 0]), FactorData("x", [1, 0, 0])])
        self.assertEqual(self.errors(s), ["envelope, factor 1 'x': g is [0, 0, 0]: a case with no force",
                                          "envelope, factor 2: duplicate factor name 'x'"])
        s.settings.load_cases = Envelope(preset="far25.562")
        self.assertEqual(self.errors(s), ["envelope: unknown preset 'far25.562' (the one preset is 'far25.561')"])

    def test_requirement_floors_must_be_positive(self):
        s = self.scene()
        s.settings.requirements.min_frequency_hz = -5.0
        self.assertEqual(self.errors(s), ["requirements.min_frequency_hz (frequency floor (Hz)): must be positive, "
                                          "got -5"])


# Bad files: (change to the issue's example, the field the sentence names). The native reader rejects each too.
BAD_FILES = [
    (lambda p: p["loads"][0].update(mass=-1.0), "loads[0].mass: must be positive, got -1"),
    (lambda p: p["load_cases"].update(up=[0.0, 0.1, 1.0]), "load_cases.up: forward and up are not orthogonal"),
    (lambda p: p["load_cases"].update(factors="far25"), "load_cases.factors: unknown preset 'far25'"),
    (lambda p: p["loads"][0]["cases"][0].update(force=[0.0, 0.0, 0.0]),
     "loads[0].cases[0]: case 'connector pull' has no force and no moment"),
    (lambda p: p["loads"][0].update(inertia=[[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]),
     "loads[0].inertia: inertia is not positive definite"),
    (lambda p: p["loads"][0].update(force=[0.0, 0.0, -1.0]),
     "loads[0].force: give either 'cases' or 'force'/'moment', not both"),
    (lambda p: p["loads"][0].pop("mass"), "load_cases: no load has a 'mass'"),
]


class FileErrors(unittest.TestCase):
    def test_each_bad_file_is_one_sentence_naming_the_field(self):
        for change, expected in BAD_FILES:
            p = issue_problem()
            change(p)
            with self.assertRaises(ProblemError) as ctx:
                problem_to_scene(p)
            self.assertEqual(len(ctx.exception.errors), 1, ctx.exception.errors)
            self.assertTrue(ctx.exception.errors[0].startswith(expected), ctx.exception.errors[0])


class Geometry(unittest.TestCase):
    def test_symmetric_eigenvalues(self):
        # [[2, 1, 0], [1, 2, 0], [0, 0, 5]]: 2 +- 1 and 5
        for got, want in zip(geometry.symmetric_eigenvalues([[2, 1, 0], [1, 2, 0], [0, 0, 5]]), (1.0, 3.0, 5.0)):
            self.assertAlmostEqual(got, want, places=12)
        # a rotated diag(1, 2, 3): R diag R^T about z by 30 degrees keeps the eigenvalues
        c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
        m = [[c * c * 1 + s * s * 2, c * s * (1 - 2), 0], [c * s * (1 - 2), s * s * 1 + c * c * 2, 0], [0, 0, 3]]
        for got, want in zip(geometry.symmetric_eigenvalues(m), (1.0, 2.0, 3.0)):
            self.assertAlmostEqual(got, want, places=12)

    def test_left_is_up_cross_forward(self):
        self.assertEqual(geometry.left_axis([1, 0, 0], [0, 0, 1]), (0.0, 1.0, 0.0))
        self.assertEqual(geometry.left_axis([0, -1, 0], [0, 0, 1]), (1.0, 0.0, 0.0))


@unittest.skipIf(native_or_none("part_modes") is None,
                 "native module with part_modes not built (target _sheetgen_native)")
class NativeAgrees(unittest.TestCase):
    """The core's output is what the native reader reads, with the cases the format defines."""

    def test_preset_cases_are_mass_g0_factor_in_the_aircraft_axes(self):
        sg = native_or_none("part_modes")
        problem, _ = scene_to_problem(problem_to_scene(issue_problem())[0])
        ld = sg.parse_problem(jsonio.dumps(problem), "core.json", ".").loads[0]
        names = [c.name for c in ld.cases]
        self.assertEqual(names, ["connector pull", "handling"] + [n for n, _ in model.PRESETS["far25.561"]])
        fwd, up = (0.0, -1.0, 0.0), (0.0, 0.0, 1.0)
        left = geometry.left_axis(fwd, up)
        for case, (_, g) in zip(ld.cases[2:], model.PRESETS["far25.561"]):
            want = [2.4 * model.STANDARD_GRAVITY * (g[0] * fwd[i] + g[1] * left[i] + g[2] * up[i]) for i in range(3)]
            for got, w in zip(case.force, want):
                self.assertAlmostEqual(got, w, delta=1e-12 * 300)
        self.assertEqual(ld.cases[1].max_deflection, 2e-3)
        self.assertEqual(ld.mass, 2.4)

    def test_mass_properties_reach_the_native_load(self):
        sg = native_or_none("part_modes")
        problem, _ = scene_to_problem(problem_to_scene(factor_list_problem())[0])
        ld = sg.parse_problem(jsonio.dumps(problem), "core.json", ".").loads[0]
        self.assertEqual(list(ld.center_of_mass), [0.31, 0.01, 0.29])
        self.assertEqual(ld.inertia.tolist(), factor_list_problem()["loads"][0]["inertia"])
        self.assertEqual([c.name for c in ld.cases], ["forward 9 g", "down 6 g"])
        self.assertEqual(ld.cases[1].max_deflection, 3e-3)

    def test_native_rejects_the_bad_files_too(self):
        sg = native_or_none("part_modes")
        for change, expected in BAD_FILES:
            p = issue_problem()
            change(p)
            with self.assertRaises(ValueError, msg=expected):
                sg.parse_problem(json.dumps(p), "bad.json", ".")


if __name__ == "__main__":
    unittest.main()
