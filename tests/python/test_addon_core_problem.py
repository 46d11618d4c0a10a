"""The add-on's bpy-free core: scene data <-> sheetgen-problem/1, outside Blender.

Run: /usr/bin/python3 -m unittest discover -s tests/python -p 'test_addon_core_*.py'
(the system Python: the native cross-check needs the module built for 3.11).
"""
import copy
import json
import os
import re
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

from sheetgen_blender.core import jsonio, model  # noqa: E402
from sheetgen_blender.core.model import LoadData, MeshData, SceneData  # noqa: E402
from sheetgen_blender.core.problem import ProblemError, problem_to_scene, scene_to_problem  # noqa: E402
from sheetgen_tools.native_module import native_or_none  # noqa: E402


def two_meshes():
    """A 1 m x 1 m floor of 2 triangles and a 0.5 m x 0.5 m wall quad (2 triangles) in x = 0."""
    floor = MeshData("floor", [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2], [0, 2, 3]],
                     face_areas=[0, 3], area_names={3: "floor_left"})
    wall = MeshData("wall", [[0, 0, 0], [0, 0.5, 0], [0, 0.5, 0.5], [0, 0, 0.5]], [[0, 1, 2], [0, 2, 3]],
                    face_areas=[1, 1], area_names={1: "wall_rivets", 2: "unused"})
    box = LoadData("box", center=[0.3, 0.25, 0.3], size=[0.16, 0.12, 0.08], rotation=[2, 0, 0, 0],
                   force=[0, 0, -353], moment=[0, 0, 0])
    return SceneData(name="corner", meshes=[floor, wall], loads=[box])


class SceneToProblem(unittest.TestCase):
    def test_exact_problem_dict(self):
        problem, warnings = scene_to_problem(two_meshes())
        self.assertEqual(problem["format"], "sheetgen-problem/1")
        self.assertEqual(problem["units"], "m")
        self.assertEqual([m["name"] for m in problem["environment"]["meshes"]], ["floor", "wall"])
        self.assertEqual(problem["environment"]["meshes"][1]["vertices"][2], [0.0, 0.5, 0.5])
        self.assertEqual(problem["environment"]["meshes"][0]["triangles"], [[0, 1, 2], [0, 2, 3]])
        self.assertEqual(problem["rivet_areas"], [{"name": "floor_left", "mesh": "floor", "faces": [1]},
                                                  {"name": "wall_rivets", "mesh": "wall", "faces": [0, 1]}])
        # The quaternion is normalised: [2, 0, 0, 0] -> identity.
        self.assertEqual(problem["loads"], [{"name": "box", "center": [0.3, 0.25, 0.3], "size": [0.16, 0.12, 0.08],
                                             "rotation": [1.0, 0.0, 0.0, 0.0], "force": [0.0, 0.0, -353.0],
                                             "moment": [0.0, 0.0, 0.0]}])
        self.assertEqual(warnings, ["object 'wall': rivet area 'unused' has no faces and is left out"])
        # Settings: every field written with the defaults of docs/problem-format.md.
        self.assertEqual(problem["material"], {"youngs_modulus": 73.1e9, "poisson_ratio": 0.33, "density": 2780.0,
                                               "yield_strength": 345e6, "ultimate_strength": 483e6,
                                               "thickness": 1.6e-3})
        self.assertEqual(problem["requirements"], {"max_deflection": 1e-3, "min_margin_of_safety": 0.0,
                                                   "safety_factor": 1.5, "clearance": 1e-3})
        self.assertEqual(problem["search"], {"chains": 10, "iterations": 1000, "beam_width": 8, "seed": 1,
                                             "threads": 0, "alpha": 1.0, "beta": 3.0, "scene_unit": 0.1})
        self.assertEqual(problem["manufacturing"], {})

    def test_compliance_limit_replaces_deflection(self):
        s = two_meshes()
        s.settings.requirements.max_deflection, s.settings.requirements.max_compliance = None, 0.25
        problem, _ = scene_to_problem(s)
        self.assertEqual(problem["requirements"]["max_compliance"], 0.25)
        self.assertNotIn("max_deflection", problem["requirements"])

    def test_round_trip_through_problem(self):
        problem, _ = scene_to_problem(two_meshes())
        text = jsonio.dumps(problem)
        scene, warnings = problem_to_scene(json.loads(text))
        self.assertEqual(warnings, [])
        # Area ids are renumbered per mesh in file order: the wall's only area is 1, the floor's 1.
        self.assertEqual(scene.meshes[1].face_areas, [1, 1])
        self.assertEqual(scene.meshes[0].face_areas, [0, 1])
        self.assertEqual(scene.meshes[0].area_names, {1: "floor_left"})
        again, _ = scene_to_problem(scene)
        self.assertEqual(again, problem)

    def test_gauges_round_trip_and_bad_ones_name_the_field(self):
        from sheetgen_blender.core import problem as P
        s = two_meshes()
        problem, _ = scene_to_problem(s)
        self.assertNotIn("gauges", problem["material"])     # None: the format's default ladder
        s.settings.material.gauges = []
        self.assertEqual(scene_to_problem(s)[0]["material"]["gauges"], [])
        s.settings.material.gauges = [1.8034e-3, 2.032e-3]
        problem, _ = scene_to_problem(s)
        self.assertEqual(problem["material"]["gauges"], [1.8034e-3, 2.032e-3])
        scene, _ = problem_to_scene(json.loads(jsonio.dumps(problem)))
        self.assertEqual(scene.settings.material.gauges, [1.8034e-3, 2.032e-3])
        # The panel's text in mm, and back.
        self.assertEqual(P.gauges_to_mm_text([1.8034e-3, 2.032e-3]), (True, "1.8034, 2.032"))
        self.assertEqual(P.gauges_to_mm_text(None), (True, ""))
        self.assertEqual(P.gauges_to_mm_text([]), (False, ""))
        self.assertEqual(P.gauges_from_mm_text(True, "1.8034, 2.032"), [1.8034e-3, 2.032e-3])
        self.assertIsNone(P.gauges_from_mm_text(True, " "))
        self.assertEqual(P.gauges_from_mm_text(False, "3"), [])
        for gauges, message in [
                ([1.2e-3], "material.gauges[0]: 0.0012 m must be thicker than material.thickness (0.0016 m)"),
                ([2e-3, 1.8e-3], "material.gauges[1]: 0.0018 m must be thicker than the gauge before it (0.002 m)"),
                (P.gauges_from_mm_text(True, "2, two"), "material.gauges: expected a list of thicknesses (m), got '2, two'")]:
            s.settings.material.gauges = gauges
            with self.assertRaises(ProblemError) as ctx:
                scene_to_problem(s)
            self.assertTrue(any(e.startswith(message) for e in ctx.exception.errors), ctx.exception.errors)

    def test_defaults_match_problem_format_doc(self):
        with open(os.path.join(ROOT, "docs", "problem-format.md"), encoding="utf-8") as f:
            doc = f.read()
        row = lambda section: next(l for l in doc.splitlines() if l.startswith("| `%s`" % section))  # noqa: E731
        mat, search, req = row("material"), row("search"), row("requirements")
        m = model.Material()
        for key, _, _ in model.MATERIAL_FIELDS:
            value = float(re.search(r"`%s` ([0-9.e+-]+)" % key, mat).group(1))
            self.assertEqual(getattr(m, key), value, key)
        s = model.Search()
        for key in ("chains", "iterations", "beam_width", "seed", "alpha", "beta", "scene_unit", "threads"):
            value = float(re.search(r"`%s` ([0-9.e+-]+)" % key, search).group(1))
            self.assertEqual(getattr(s, key), value, key)
        r = model.Requirements()
        for key in ("max_deflection", "min_margin_of_safety", "safety_factor", "clearance"):
            value = float(re.search(r"`%s` ([0-9.e+-]+)" % key, req).group(1))
            self.assertEqual(getattr(r, key), value, key)


class SceneValidation(unittest.TestCase):
    def errors(self, scene):
        with self.assertRaises(ProblemError) as ctx:
            scene_to_problem(scene)
        return ctx.exception.errors

    def test_no_rivet_area(self):
        s = two_meshes()
        for m in s.meshes:
            m.face_areas = [0] * len(m.triangles)
            m.area_names = {}
        errs = self.errors(s)
        self.assertEqual(len(errs), 1)
        self.assertTrue(errs[0].startswith("no rivet areas: select faces"), errs[0])

    def test_no_loads_and_no_meshes(self):
        errs = self.errors(SceneData(name="empty"))
        self.assertEqual(errs, ["no environment meshes: the scene has no visible mesh object other than the loads",
                                "no loads: select a box object and press 'Make Load' (Sheet Metal tab > Loads)"])

    def test_messages_name_object_and_field(self):
        s = two_meshes()
        s.meshes[0].name = "a/b"
        s.meshes[1].vertices[2] = [0, float("nan"), 0]
        s.meshes[1].name = "wall"
        s.loads[0].force = [0, 0, 0]
        s.loads[0].size = [0.1, 0.0, 0.1]
        s.settings.material.thickness = -1.0
        s.settings.search.chains = 0
        errs = self.errors(s)
        self.assertIn("object 'a/b': name 'a/b' must not contain '/' or '\\' or be '.' or '..' (rename the object)",
                      errs)
        self.assertIn("object 'wall': vertex 2 is not 3 finite numbers", errs)
        self.assertIn("load 'box': size must be positive on every axis, got [0.1, 0, 0.1] m "
                      "(a flat object cannot be a load box)", errs)
        self.assertIn("load 'box': force and moment are both zero (set Force in the Loads panel)", errs)
        self.assertIn("material.thickness (thickness (m)): must be positive, got -1", errs)
        self.assertIn("search.chains (chains): must be an integer in [1, 1024], got 0", errs)

    def test_area_name_used_twice(self):
        s = two_meshes()
        s.meshes[1].area_names[1] = "floor_left"
        errs = self.errors(s)
        self.assertEqual(errs, ["rivet area name 'floor_left' is used on object 'floor' and on object 'wall': "
                                "rename one"])

    def test_tag_without_name_gets_default_name(self):
        s = two_meshes()
        s.meshes[1].area_names = {}
        problem, warnings = scene_to_problem(s)
        self.assertEqual(problem["rivet_areas"][1]["name"], "wall_rivets_1")
        self.assertIn("object 'wall': faces tagged with rivet-area id 1 have no area name; named 'wall_rivets_1'",
                      warnings)


def corner_problem():
    return {
        "format": "sheetgen-problem/1", "name": "corner",
        "environment": {"meshes": [
            {"name": "wall", "vertices": [[0, 0, 0], [0, 1, 0], [0, 1, 1], [0, 0, 1]], "triangles": [[0, 1, 2], [0, 2, 3]]},
            {"name": "floor", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0]], "triangles": [[0, 1, 2]]}]},
        "rivet_areas": [{"name": "w", "mesh": "wall", "faces": [1, 0, 1]}, {"name": "f", "mesh": 1, "faces": [0]}],
        "loads": [{"name": "box", "center": [0.3, 0, 0.3], "size": [0.16, 0.12, 0.08], "force": [0, 0, -353]}],
        "material": {}, "requirements": {"max_compliance": 0.5}, "search": {"seed": 7}}


class ProblemToScene(unittest.TestCase):
    def errors(self, problem, reader=None):
        with self.assertRaises(ProblemError) as ctx:
            problem_to_scene(problem, reader)
        return ctx.exception.errors

    def test_reads_inline_problem_with_defaults(self):
        scene, warnings = problem_to_scene(corner_problem())
        self.assertEqual(warnings, [])
        self.assertEqual([m.name for m in scene.meshes], ["wall", "floor"])
        self.assertEqual(scene.meshes[0].face_areas, [1, 1])      # duplicate face 1 merged
        self.assertEqual(scene.meshes[1].face_areas, [1])         # mesh given by index
        self.assertEqual(scene.meshes[1].area_names, {1: "f"})
        ld = scene.loads[0]
        self.assertEqual(ld.rotation, [1.0, 0.0, 0.0, 0.0])      # default identity
        self.assertEqual(ld.moment, [0.0, 0.0, 0.0])             # default 0
        self.assertEqual(scene.settings.material, model.Material())
        self.assertEqual(scene.settings.requirements.max_compliance, 0.5)
        self.assertIsNone(scene.settings.requirements.max_deflection)
        self.assertEqual(scene.settings.search.seed, 7)
        self.assertEqual(scene.settings.search.chains, 10)

    def test_field_errors(self):
        p = corner_problem()
        p["requirments"] = {}
        self.assertEqual(self.errors(p)[0], "(top level): unknown field 'requirments' (expected one of: format, name, "
                         "description, units, environment, rivet_areas, loads, load_cases, material, requirements, manufacturing, "
                         "search)")
        p = corner_problem()
        p["rivet_areas"][1]["faces"] = [0, 9]
        self.assertEqual(self.errors(p), ["rivet_areas[1].faces[1]: face index 9 is out of range "
                                          "(mesh 'floor' has 1 faces)"])
        p = corner_problem()
        p["rivet_areas"][1]["mesh"] = "wall"
        self.assertEqual(self.errors(p), ["rivet_areas[1].faces[0]: face 0 of mesh 'wall' is already in rivet area "
                                          "'w'; in Blender a face belongs to one rivet area"])
        p = corner_problem()
        p["environment"]["meshes"][0]["triangles"][1] = [0, 2, 4]
        self.assertEqual(self.errors(p), ["environment.meshes[0].triangles[1]: expected 3 vertex indices in 0..3"])
        p = corner_problem()
        p["loads"][0]["size"] = [0.1, -1, 0.1]
        self.assertEqual(self.errors(p), ["loads[0].size: must be positive on every axis, got [0.1, -1, 0.1]"])

    def test_file_meshes_need_a_reader(self):
        p = corner_problem()
        p["environment"]["meshes"][1] = {"name": "floor", "file": "floor.obj"}
        self.assertEqual(self.errors(p), ["environment.meshes[1].file: mesh 'floor' is in file 'floor.obj': "
                                          "reading mesh files needs the native module"])
        seen = []

        def reader(index, mesh_json):
            seen.append((index, mesh_json["file"]))
            return [[0, 0, 0], [2, 0, 0], [0, 2, 0]], [[0, 1, 2]]
        scene, _ = problem_to_scene(p, reader)
        self.assertEqual(seen, [(1, "floor.obj")])
        self.assertEqual(scene.meshes[1].vertices[1], [2.0, 0.0, 0.0])
        self.assertEqual(scene.meshes[1].face_areas, [1])


@unittest.skipIf(native_or_none() is None, "native module not built (cmake --build build --target _sheetgen_native)")
class NativeAgrees(unittest.TestCase):
    def test_native_parser_accepts_core_output(self):
        sg = native_or_none()
        problem, _ = scene_to_problem(two_meshes())
        p = sg.parse_problem(jsonio.dumps(problem), "core.json", ".")
        self.assertEqual([ra.name for ra in p.rivet_areas], ["floor_left", "wall_rivets"])
        self.assertAlmostEqual(p.rivet_areas[0].area_m2, 0.5, places=12)    # half of the 1 m square
        self.assertAlmostEqual(p.rivet_areas[1].area_m2, 0.25, places=12)   # the 0.5 m square
        self.assertEqual(p.material.thickness, 1.6e-3)

    def test_native_defaults_equal_core_defaults(self):
        """A problem with empty settings sections, through the native parser, has the core's defaults."""
        sg = native_or_none()
        p = copy.deepcopy(corner_problem())
        p["requirements"] = {}
        parsed = sg.parse_problem(json.dumps(p), "c.json", ".")
        m = model.Material()
        for key, _, _ in model.MATERIAL_FIELDS:
            self.assertEqual(getattr(parsed.material, key), getattr(m, key), key)


if __name__ == "__main__":
    unittest.main()


class StoredExports(unittest.TestCase):
    """Exports kept in the .blend as text: text as it is, binary (convergence.png) base64, both back byte for byte."""

    def test_text_and_binary_round_trip(self):
        png = b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe"
        csv = "iteration,evaluated\n1,24\n"
        self.assertEqual(jsonio.file_to_text(csv.encode("utf-8")), csv)
        stored = jsonio.file_to_text(png)
        self.assertTrue(stored.startswith("base64:"))
        self.assertEqual(jsonio.text_to_file(stored), png)
        self.assertEqual(jsonio.text_to_file(jsonio.file_to_text(csv.encode())), csv)
        # A text file that happens to start with the marker is stored as base64 too, and comes back unchanged.
        odd = "base64:not really".encode()
        self.assertEqual(jsonio.text_to_file(jsonio.file_to_text(odd)), odd)

    def test_write_atomic_writes_bytes_exactly(self):
        import tempfile
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "sub", "convergence.png")
            data = bytes(range(256))
            jsonio.write_atomic(path, data)
            with open(path, "rb") as f:
                self.assertEqual(f.read(), data)
            jsonio.write_atomic(path, "é\n")
            with open(path, "rb") as f:
                self.assertEqual(f.read(), "é\n".encode("utf-8"))
