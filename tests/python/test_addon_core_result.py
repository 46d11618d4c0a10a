"""The add-on core's result -> mesh data, outside Blender.

Run: /usr/bin/python3 -m unittest discover -s tests/python -p 'test_addon_core_*.py'

The document is a hand-made sheetgen-result/1 part: a 0.1 m x 0.1 m base tab
at z = 0.2 with one child tab bent 90 degrees down along its x = 0.1 edge
(0.08 m wide, 0.05 m long), the flat pattern with the child unfolded to
x in [0.1, 0.15] and two 1.6 mm relief notches at the bend's ends.
"""
import math
import os
import sys
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "blender_addon"))

from sheetgen_blender.core import result as R  # noqa: E402

T = 0.0016


def bracket(bend_b=(0.1008, 0.09), status="ok"):
    # base tab corners, then the child: its first edge lies on the base's edge 1 (x = 0.1), 1e-9 m off
    base = [[0.0, 0.0, 0.2], [0.1, 0.0, 0.2], [0.1, 0.1, 0.2], [0.0, 0.1, 0.2]]
    child = [[0.1 + 1e-9, 0.09, 0.2], [0.1, 0.01, 0.2], [0.1, 0.01, 0.15], [0.1, 0.09, 0.15]]
    outline = [[0.0, 0.0], [0.1, 0.0], [0.1, 0.01], [0.1016, 0.01], [0.15, 0.01], [0.15, 0.09],
               [0.1016, 0.09], [0.1, 0.09], [0.1, 0.1], [0.0, 0.1]]
    return {
        "load": "box", "status": status,
        "area_m2": 0.014, "mass_kg": 0.0623, "bends": 1, "compliance": 0.02, "compliance_limit": 0.1,
        "deflection_m": 0.0002, "deflection_along_force_m": 0.00015, "margin_of_safety": 1.25, "timing": {"total_s": 3.5},
        "tabs": [{"index": 0, "parent": -1, "corners": base},
                 {"index": 1, "parent": 0, "parent_edge": 1, "corners": child}],
        "rivets": [[0.05, 0.05, 0.2], [0.1, 0.05, 0.16]],
        "flat_pattern": {"outline": [outline], "area_m2": 0.014,
                         "bends": [{"tab": 1, "number": 1, "a": [0.1008, 0.01], "b": list(bend_b),
                                    "angle": -math.pi / 2, "direction": "down"}],
                         "reliefs": []},
    }


def doc(*parts):
    return {"format": "sheetgen-result/1", "parts": list(parts)}


class BentMesh(unittest.TestCase):
    def test_two_tabs_weld_and_mark_the_bend(self):
        m = R.bent_mesh(bracket())
        # 8 corners, the child's first two on the base's edge: (0.1+1e-9, 0.09) is not a base corner,
        # so nothing welds except what coincides within 1e-6 m: none of the base corners -> 8 vertices.
        self.assertEqual(len(m.vertices), 8)
        self.assertEqual(len(m.faces), 4)                         # 2 triangles per quad tab
        self.assertEqual(R.tab_triangle_count(bracket()), 4)
        self.assertEqual(m.bend_edges, [(4, 5, 1)])               # the child's corners 0-1, bend number 1
        self.assertAlmostEqual(m.area(), 0.1 * 0.1 + 0.08 * 0.05, places=12)

    def test_flat_extension_has_no_bend_edge(self):
        # A third tab continuing the child flat (theta3 = 0) is welded on but is no bend.
        part = bracket()
        part["tabs"][1]["parameters"] = {"theta3": -math.pi / 2}
        part["tabs"].append({"index": 2, "parent": 1, "parent_edge": 2, "parameters": {"theta3": 0.0},
                             "corners": [[0.1, 0.01, 0.15], [0.1, 0.09, 0.15], [0.1, 0.09, 0.12], [0.1, 0.01, 0.12]]})
        m = R.bent_mesh(part)
        self.assertEqual(m.bend_edges, [(4, 5, 1)])
        self.assertEqual(len(m.vertices), 10)                     # the extension shares the child's far corners
        self.assertAlmostEqual(m.area(), 0.1 * 0.1 + 0.08 * 0.05 + 0.08 * 0.03, places=12)

    def test_coincident_corners_are_one_vertex(self):
        part = bracket()
        part["tabs"][1]["corners"][0] = [0.1 + 4e-7, 0.1, 0.2]   # within WELD_TOL of the base corner 2
        m = R.bent_mesh(part)
        self.assertEqual(len(m.vertices), 7)
        self.assertEqual(m.bend_edges[0][0], 2)

    def test_tab_with_two_corners_is_an_error(self):
        part = bracket()
        part["tabs"][1]["corners"] = part["tabs"][1]["corners"][:2]
        with self.assertRaisesRegex(R.ResultError, r"parts\['box'\]\.tabs\[1\]\.corners"):
            R.bent_mesh(part)


class FlatMesh(unittest.TestCase):
    def test_bend_line_splits_the_outline(self):
        m = R.flat_mesh(bracket(), snap=2 * T)
        # the bend's end points are inserted on the relief edges: 10 + 2 vertices, 2 faces
        self.assertEqual(len(m.vertices), 12)
        self.assertEqual(len(m.faces), 2)
        self.assertEqual(m.loose_edges, [])
        (a, b, n), = m.bend_edges
        self.assertEqual(n, 1)
        self.assertEqual(m.vertices[a], (0.1008, 0.01, 0.0))
        self.assertEqual(m.vertices[b][2], 0.0)
        self.assertAlmostEqual(m.area(), R.outline_area(bracket()), places=15)
        self.assertAlmostEqual(R.outline_area(bracket()), 0.1 * 0.1 + 0.05 * 0.08, places=15)
        areas = sorted(m.face_area(f) for f in range(2))
        self.assertAlmostEqual(areas[0], 0.0492 * 0.08, places=12)   # the unfolded child, from the bend line
        self.assertAlmostEqual(areas[1], 0.01 + 0.0008 * 0.08, places=12)

    def test_end_point_off_the_outline_is_snapped(self):
        # b 0.5 mm beyond the outline: within 2 t, moved onto the nearest edge (y = 0.09)
        m = R.flat_mesh(bracket(bend_b=(0.1012, 0.0905)), snap=2 * T)
        self.assertEqual(len(m.faces), 2)
        b = m.vertices[m.bend_edges[0][1]]
        self.assertAlmostEqual(b[0], 0.1012, places=12)
        self.assertAlmostEqual(b[1], 0.09, places=12)

    def test_bend_far_from_the_outline_is_a_loose_edge(self):
        m = R.flat_mesh(bracket(bend_b=(0.1008, 0.2)), snap=2 * T)
        self.assertEqual(len(m.faces), 1)
        self.assertEqual(len(m.loose_edges), 1)
        self.assertEqual(len(m.bend_edges), 1)
        self.assertEqual(m.vertices[m.loose_edges[0][1]], (0.1008, 0.2, 0.0))


class Document(unittest.TestCase):
    def test_part_meshes_and_rivets(self):
        failed = bracket(status="no_valid_part")
        failed["load"] = "other"
        pms = R.part_meshes(doc(bracket(), failed), T)
        self.assertEqual([p.load for p in pms], ["box", "other"])
        self.assertIsNone(pms[1].bent)
        self.assertEqual(len(pms[0].rivets.vertices), 12)          # 6 per octahedron
        self.assertEqual(len(pms[0].rivets.faces), 16)             # 8 per octahedron
        r = max(1.5 * T, 0.002)
        self.assertEqual(pms[0].rivets.vertices[0], (0.05 + r, 0.05, 0.2))

    def test_a_part_in_a_thicker_gauge_is_drawn_in_its_own_sheet(self):
        thick = bracket()
        thick["thickness_m"], thick["gauges_tried"] = 2.032e-3, 2
        plain = bracket()
        plain["load"] = "plain"
        pms = R.part_meshes(doc(thick, plain), T)
        self.assertEqual([p.thickness for p in pms], [2.032e-3, T])  # the other keeps the problem's sheet
        r = max(1.5 * 2.032e-3, 0.002)
        self.assertEqual(pms[0].rivets.vertices[0], (0.05 + r, 0.05, 0.2))
        self.assertEqual(dict(R.report_rows(thick))["Sheet (mm)"], "2.03")
        self.assertEqual(R.status_line(thick), "box: 140.0 cm², 1 bends, MS 1.25, 2.03 mm sheet (thicker gauge)")
        self.assertEqual(R.status_line(plain), "plain: 140.0 cm², 1 bends, MS 1.25")

    def test_self_rivets_and_holes(self):
        part = bracket()
        # One self-rivet whose two sheet points are 1.6 mm apart; its holes and a flange rivet's in the flat.
        part["self_rivets"] = [{"tabs": [0, 1], "points": [[0.09, 0.05, 0.2], [0.09, 0.05, 0.2016]]}]
        part["flat_pattern"]["holes"] = [
            {"label": "R1", "kind": "flange", "centre": [0.14, 0.05], "diameter": 0.004},
            {"label": "S1", "kind": "self", "centre": [0.09, 0.05], "diameter": 0.004}]
        pm = R.part_meshes(doc(part), T)[0]
        self.assertEqual(len(pm.self_rivets.vertices), 6)
        r = max(1.5 * T, 0.002)
        self.assertAlmostEqual(pm.self_rivets.vertices[4][2], 0.2008 + r)   # the octahedron's top, about the midpoint
        self.assertEqual(len(pm.holes.faces), 2)
        self.assertEqual(len(pm.holes.faces[0]), R.HOLE_SEGMENTS)
        # A regular 16-gon of radius 2 mm: (n/2) r^2 sin(2 pi / n).
        n = R.HOLE_SEGMENTS
        self.assertAlmostEqual(pm.holes.face_area(1), 0.5 * n * 0.002 ** 2 * math.sin(2 * math.pi / n), places=15)
        self.assertEqual(pm.holes.vertices[0], (0.14 + 0.002, 0.05, 0.0))
        rows = dict(R.report_rows(part))
        self.assertEqual((rows["Rivets"], rows["Self-rivets"]), ("2", "1"))

    def test_bad_hole_is_one_sentence(self):
        part = bracket()
        part["flat_pattern"]["holes"] = [{"centre": [0.1, 0.05], "diameter": 0.0}]
        with self.assertRaisesRegex(R.ResultError, r"^parts\['box'\]\.flat_pattern\.holes\[0\]\.diameter: must be > 0$"):
            R.part_meshes(doc(part), T)
        part["flat_pattern"]["holes"] = [{"centre": [0.1], "diameter": 0.004}]
        with self.assertRaisesRegex(R.ResultError, r"holes\[0\]: needs centre \[x, y\] and diameter"):
            R.part_meshes(doc(part), T)

    def test_wrong_format(self):
        with self.assertRaisesRegex(R.ResultError, "sheetgen-result/1"):
            R.part_meshes({"format": "sheetgen-problem/1", "parts": []}, T)

    def test_report_in_panel_units(self):
        v = R.report(bracket())
        self.assertAlmostEqual(v["area_m2"], 140.0)          # cm²
        self.assertAlmostEqual(v["mass_kg"], 62.3)           # g
        self.assertEqual(v["bends"], 1)
        self.assertEqual(v["compliance"], 0.02)
        self.assertEqual(v["compliance_limit"], 0.1)
        self.assertAlmostEqual(v["deflection_m"], 0.2)       # mm
        self.assertAlmostEqual(v["deflection_along_force_m"], 0.15)  # mm
        self.assertEqual(v["margin_of_safety"], 1.25)
        self.assertEqual(v["time_s"], 3.5)
        rows = dict(R.report_rows(bracket()))
        self.assertEqual(rows["Area (cm²)"], "140.0")
        self.assertEqual(rows["Displacement |u| (mm)"], "0.200")
        self.assertEqual(rows["Deflection along F (mm)"], "0.150")
        self.assertEqual(rows["Run time (s)"], "3.5")
        self.assertEqual(rows["Cost"], "—")                  # a result written before the cost model
        self.assertEqual(R.status_line(bracket()), "box: 140.0 cm², 1 bends, MS 1.25")
        part = bracket()
        part["cost"] = {"currency": "EUR", "material": 0.934, "bends": 1.0, "rivets": 2.0, "setup": 6.0, "total": 9.934}
        self.assertEqual(dict(R.report_rows(part))["Cost (EUR)"], "9.93")

    def test_press_brake_row(self):
        part = bracket()
        self.assertEqual(dict(R.report_rows(part))["Press brake"], "—")   # a result written before the check
        part["press_brake"] = {"ok": True, "message": "", "tools": [{"tab": 1, "punch": "straight 30 deg",
                                                                     "die": "V12.8 85 deg", "turned_over": False}]}
        self.assertEqual(dict(R.report_rows(part))["Press brake"], "ok, 1 bends")
        part["press_brake"] = {"ok": False, "message": "bend of tab 1: tab 2 hits the ram above the punch at 4 deg",
                               "tools": []}
        self.assertEqual(dict(R.report_rows(part))["Press brake"],
                         "no: bend of tab 1: tab 2 hits the ram above the punch at 4 deg")


if __name__ == "__main__":
    unittest.main()
