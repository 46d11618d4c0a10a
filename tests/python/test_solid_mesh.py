#!/usr/bin/python3
"""The solid model's geometry (sheetgen_tools.solid_reference.mesh_plates)
without CalculiX: the plates fuse into one solid that contains every tab.

* Two parts that OpenCASCADE's union split at one fuzzy tolerance or another
  (the right-angle battery at 0.071 in and power_supply at 0.125 in, data/)
  mesh with every tab in the solid, and the mesh's volume lies between the
  plates' sum less their overlap at the folds and the plates' sum plus the
  fold prisms.
* The coverage check names a tab the mesh leaves out.
* Plates that do not touch are refused as separate solids.

Needs gmsh (Debian python3-gmsh). Run:
PYTHONPATH=tools /usr/bin/python3 -m unittest tests/python/test_solid_mesh.py
"""
import json
import os
import unittest

import numpy as np

from sheetgen_tools import solid_reference

HERE = os.path.dirname(os.path.abspath(__file__))


def rectangle(origin, du, dv, normal):
    o, du, dv = (np.asarray(x, float) for x in (origin, du, dv))
    return {"corners": [o, o + du, o + du + dv, o + dv], "normal": normal}


def tet_volume(X, tets):
    V = X[tets[:, :4]]
    return float(np.abs(np.einsum("ij,ij->i", np.cross(V[:, 1] - V[:, 0], V[:, 2] - V[:, 0]),
                                  V[:, 3] - V[:, 0])).sum() / 6)


def polygon_area(corners, normal):
    C = np.asarray(corners, float)
    return 0.5 * abs(sum(np.cross(C[k], C[(k + 1) % len(C)]) for k in range(len(C))) @ np.asarray(normal, float))


class SolidMesh(unittest.TestCase):
    def check_part(self, name):
        with open(os.path.join(HERE, "data", name)) as f:
            doc = json.load(f)
        t, tabs = doc["thickness_m"], doc["tabs"]
        # The union does not depend on the mesh size; a coarse one keeps the test short.
        X, tets = solid_reference.mesh_plates(tabs, t, 3 * t)
        self.assertEqual(solid_reference.uncovered_tabs(tabs, t, X, tets), [])
        plates = sum(polygon_area(tb["corners"], tb["normal"]) * t for tb in tabs)
        # At a fold two plates ending on the fold line overlap in at most a
        # t/2 x t/2 square along it (right angles here: every fold is 90 +- 0.3
        # deg or flat), and the prism adds at most t x t along it.
        folds = [np.linalg.norm(np.subtract(tb["corners"][1], tb["corners"][0]))
                 for tb in tabs if tb["parent"] >= 0
                 and np.linalg.norm(np.cross(tb["normal"], tabs[tb["parent"]]["normal"])) > 1e-6]
        volume = tet_volume(X, tets)
        print(f"{name}: {len(tabs)} tabs, {len(folds)} folds, mesh {volume * 1e9:.0f} mm^3, "
              f"plates {plates * 1e9:.0f} mm^3, {len(tets)} C3D10")
        self.assertGreater(volume, plates - sum(folds) * t * t / 4)
        self.assertLess(volume, plates + sum(folds) * t * t)

    def test_right_angle_battery_keeps_every_tab(self):
        self.check_part("battery_right_angles_0071.json")

    def test_right_angle_power_supply_keeps_every_tab(self):
        self.check_part("power_supply_right_angles_0125.json")

    def test_a_tab_outside_the_mesh_is_named(self):
        t = 1.6e-3
        a = rectangle((0, 0, 0), (0.04, 0, 0), (0, 0.02, 0), (0, 0, 1))
        b = rectangle((0.1, 0, 0), (0.04, 0, 0), (0, 0.02, 0), (0, 0, 1))
        X, tets = solid_reference.mesh_plates([a], t, 2 * t)
        self.assertEqual(solid_reference.uncovered_tabs([a], t, X, tets), [])
        self.assertEqual(solid_reference.uncovered_tabs([a, b], t, X, tets), [1])

    def test_plates_apart_are_refused(self):
        t = 1.6e-3
        a = rectangle((0, 0, 0), (0.04, 0, 0), (0, 0.02, 0), (0, 0, 1))
        b = rectangle((0.1, 0, 0), (0.04, 0, 0), (0, 0.02, 0), (0, 0, 1))
        with self.assertRaisesRegex(RuntimeError, "no union .* is one solid .*0 t: 2 solids"):
            solid_reference.mesh_plates([a, b], t, 2 * t)

    def test_a_child_that_dies_is_an_exception_not_a_crash(self):
        # gmsh's mesher aborts its process on some unions (solid_reference.run_in_child);
        # os.abort stands for it: the same SIGABRT, here on purpose.
        self.assertEqual(solid_reference.run_in_child(divmod, 7, 2), (3, 1))
        with self.assertRaisesRegex(RuntimeError, "abort died in its child process"):
            solid_reference.run_in_child(os.abort)
        with self.assertRaises(ZeroDivisionError):  # an exception of the child is raised as itself
            solid_reference.run_in_child(divmod, 1, 0)


if __name__ == "__main__":
    unittest.main()
