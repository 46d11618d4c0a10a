"""The brute-force clearance check (sheetgen_tools.clearance) on hand-made parts with known
distances: a tab next to a rivet flange may come within t/2 of that flange's
rivet area inside the bend zone between them, whichever of the two is the
parent (check_validity's rule, docs/grammar.md); anywhere else it may not. And
the parts of a multi-load problem keep the clearance from each other's faces."""
import unittest

import numpy as np

from sheetgen_tools.clearance import check_clearance
from sheetgen_tools.findings import Findings
from sheetgen_tools.geometry import part_faces

T = 1.6e-3


def problem():
    # A wall x = 0 (y, z in -1..1) whose two faces are one rivet area; a box far away.
    return {"material": {"thickness": T}, "requirements": {"clearance": 1.0e-3}, "manufacturing": {"bend_radius": 4 * T},
            "rivet_areas": [{"name": "wall", "mesh": "wall", "faces": [0, 1]}],
            "environment": {"meshes": [{"name": "wall"}]},
            "loads": [{"name": "box", "center": [0.5, 0.0, 0.5], "size": [0.1, 0.1, 0.1], "rotation": [1, 0, 0, 0]}]}


def meshes():
    V = np.array([[0, -1, -1], [0, 1, -1], [0, 1, 1], [0, -1, 1]], float)
    return {"wall": (V, np.array([[0, 1, 2], [0, 2, 3]]))}


def flange_and_gusset(gusset_parent_is_flange):
    """A flange flush on the wall (x = t/2) and a tab square to it leaving along
    its edge z = 0.05 into +x: it starts t/2 from the wall, at the bend line."""
    flange = {"parent": 0, "rivet_area": 0, "corners": [[T / 2, -0.05, 0.05], [T / 2, 0.05, 0.05], [T / 2, 0.05, 0.0], [T / 2, -0.05, 0.0]]}
    tab = {"parent": 1 if gusset_parent_is_flange else 0, "rivet_area": -1,
           "corners": [[T / 2, 0.05, 0.05], [T / 2, -0.05, 0.05], [0.04, -0.05, 0.05], [0.04, 0.05, 0.05]]}
    if gusset_parent_is_flange:  # base, then the flange, then the tab on the flange
        base = {"parent": -1, "rivet_area": -1, "corners": [[0.3, -0.05, 0.3], [0.4, -0.05, 0.3], [0.4, 0.05, 0.3], [0.3, 0.05, 0.3]]}
        return [base, flange, tab]
    tab["parent"] = -1  # the tab is the base and the flange its child
    flange["parent"] = 0
    return [tab, flange]


def run(tabs):
    findings = Findings()
    check_clearance(problem(), meshes(), {"load": "box", "tabs": tabs}, findings)
    assert any("min clearance" in r for r in findings.lines), findings.lines
    return findings.lines, findings.failures


class FlangeBendZone(unittest.TestCase):
    def test_child_of_a_flange_may_touch_its_rivet_area_at_the_bend(self):
        report, bad = run(flange_and_gusset(True))
        self.assertEqual([b for b in bad if "obstacle" in b], [], report)

    def test_parent_of_a_flange_may_touch_its_rivet_area_at_the_bend(self):
        report, bad = run(flange_and_gusset(False))
        self.assertEqual([b for b in bad if "obstacle" in b], [], report)

    def test_a_tab_not_next_to_the_flange_may_not(self):
        tabs = flange_and_gusset(True)
        tabs[2]["parent"] = 0  # the same tab, hung from the base: no bend joins it to the flange
        report, bad = run(tabs)
        self.assertTrue(any("tab 2 is 0.800 mm from an obstacle" in b for b in bad), bad)


class PartsAvoidEachOther(unittest.TestCase):
    """A later part's clearance counts both faces of every earlier part's tabs."""

    def plate(self, z):
        return {"parent": -1, "rivet_area": -1, "corners": [[0.3, -0.05, z], [0.4, -0.05, z], [0.4, 0.05, z], [0.3, 0.05, z]]}

    def check(self, gap):
        earlier = {"load": "first", "tabs": [self.plate(0.3)]}
        later = {"load": "box", "tabs": [self.plate(0.3 + gap)]}
        findings = Findings()
        check_clearance(problem(), {**meshes(), "part:first": part_faces(earlier, T)}, later, findings)
        return findings.lines, findings.failures

    def test_faces_not_mid_surfaces(self):
        # Mid-surfaces 2.6 mm apart: the sheets' facing surfaces are 1.0 mm apart,
        # 1.8 mm from the later mid-surface to the earlier part's top face = required.
        report, bad = self.check(2.6e-3)
        self.assertEqual(bad, [], report)
        self.assertTrue(any("min clearance 1.800 mm" in r for r in report), report)

    def test_too_close(self):
        report, bad = self.check(1.5e-3)  # 0.7 mm to the face, below 1.8 - 0.8 mm tolerance
        self.assertTrue(any("tab 0 is 0.700 mm from an obstacle" in b for b in bad), bad)


if __name__ == "__main__":
    unittest.main()
