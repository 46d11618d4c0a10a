#!/usr/bin/python3
"""The solid model of sheetgen_tools.solid_reference against a closed form and
against CalculiX's own shells where those are reliable.

* A bar (120 x 20 mm, 1.6 mm aluminium) clamped at one end, pulled by 100 N
  through a rigid end: C = P^2 L / (E b t).
* A strip folded 90 deg (100 mm, then 80 mm down, 60 mm wide), clamped at the
  flat end and pushed along the first leg through a rigid tip: the solid agrees
  with a structured S8R mesh of the same strip (1.5 % asserted; 0.3 % measured
  at h = 1.2 mm) and lies between the beam formulas with E I (narrow) and
  D b (plane strain).

Both run at the size sheetgen_tools.verify uses (solid_reference.DEFAULT_SIZE). Needs ccx and gmsh.
Run: PYTHONPATH=tools /usr/bin/python3 -m unittest tests/python/test_solid_reference.py
"""
import os
import tempfile
import unittest

import numpy as np

from sheetgen_tools import s8r_grid, solid_reference

T, E, NU = 1.6e-3, 73.1e9, 0.33
H = solid_reference.DEFAULT_SIZE * T


def rectangle(origin, du, dv, normal):
    o, du, dv = (np.asarray(x, float) for x in (origin, du, dv))
    return {"corners": [o, o + du, o + du + dv, o + dv], "normal": normal}


def s8r_folded_strip(path, L1, L2, b, h, P):
    """A structured S8R deck of the folded strip; returns the REF node id."""
    n1, n2, m = round(L1 / h), round(L2 / h), round(b / h)
    s = np.r_[np.linspace(0, L1, 2 * n1 + 1), np.linspace(L1, L1 + L2, 2 * n2 + 1)[1:]]
    y = np.linspace(0, b, 2 * m + 1)
    node = lambda i, j: i * len(y) + j + 1  # noqa: E731
    lines = ["*NODE, NSET=NALL"]
    for i, si in enumerate(s):
        for j, yj in enumerate(y):
            p = (si, yj, 0.0) if si <= L1 else (L1, yj, -(si - L1))
            lines.append("%d, %.12g, %.12g, %.12g" % ((node(i, j),) + p))
    ref = len(s) * len(y) + 1
    lines += ["%d, %.12g, %.12g, %.12g" % (k, L1, b / 2, -L2) for k in (ref, ref + 1)]
    lines += s8r_grid.s8r_elements(len(s), len(y), node)
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", "%.12g, %.12g" % (E, NU), "*SHELL SECTION, ELSET=EALL, MATERIAL=M",
              "%.12g" % T, "*NSET, NSET=TIP"] + ["%d," % node(len(s) - 1, j) for j in range(len(y))]
    lines += ["*RIGID BODY, NSET=TIP, REF NODE=%d, ROT NODE=%d" % (ref, ref + 1), "*STEP", "*STATIC", "*BOUNDARY"]
    lines += ["%d, 1, 6" % node(0, j) for j in range(len(y))]
    lines += ["*CLOAD", "%d, 1, %.12g" % (ref, P), "*NODE PRINT, NSET=NALL", "U", "*END STEP"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return ref


class SolidReference(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def solve(self, tabs, fixed_of, rigid_of, ref_point, cloads):
        X, tets = solid_reference.mesh_plates(tabs, T, H)
        fixed, rigid = np.nonzero(fixed_of(X))[0], np.nonzero(rigid_of(X))[0]
        self.assertGreater(len(fixed), 10)
        self.assertGreater(len(rigid), 10)
        deck = os.path.join(self.tmp.name, "solid.inp")
        ref = solid_reference.write_deck(deck, X, tets, E, NU, fixed, rigid, ref_point, cloads)
        u = solid_reference.run_ccx(deck)
        return sum(v * u[ref][d - 1] for d, v in cloads), len(tets)

    def test_bar_in_tension_matches_the_closed_form(self):
        L, b, P = 0.12, 0.02, 100.0
        C, n = self.solve([rectangle((0, 0, 0), (L, 0, 0), (0, b, 0), (0, 0, 1))],
                          lambda X: np.abs(X[:, 0]) < 1e-9, lambda X: np.abs(X[:, 0] - L) < 1e-9,
                          (L, b / 2, 0), [(1, P)])
        exact = P * P * L / (E * b * T)
        print(f"bar: C3D10 {C:.6e} J ({n} tets), P^2 L / (E b t) {exact:.6e} J, {(C / exact - 1) * 100:+.3f} %")
        # The clamped end face also stops the Poisson contraction there: a little stiffer, never softer.
        self.assertLess(C, exact * 1.002)
        self.assertGreater(C, exact * 0.99)

    def test_folded_strip_agrees_with_structured_s8r(self):
        L1, L2, b, P = 0.10, 0.08, 0.06, 100.0
        # The leg is the base's child along the fold (its first two corners), so
        # its fold is filled as on a part (solid_reference._fold_fillers).
        tabs = [rectangle((0, 0, 0), (L1, 0, 0), (0, b, 0), (0, 0, 1)),
                dict(rectangle((L1, 0, 0), (0, b, 0), (0, 0, -L2), (1, 0, 0)), parent=0)]
        C, n = self.solve(tabs, lambda X: np.abs(X[:, 0]) < 1e-9, lambda X: np.abs(X[:, 2] + L2) < 1e-9,
                          (L1, b / 2, -L2), [(1, P)])
        shell = os.path.join(self.tmp.name, "s8r.inp")
        ref = s8r_folded_strip(shell, L1, L2, b, 2e-3, P)
        C8 = P * solid_reference.run_ccx(shell)[ref][0]
        I = b * T ** 3 / 12
        beam_EI = P * P * (L2 ** 3 / 3 + L2 ** 2 * L1) / (E * I) + P * P * L1 / (E * b * T)
        beam_D = beam_EI * (1 - NU ** 2)  # bending with D = E t^3 / 12 (1 - nu^2) per width
        print(f"folded strip: C3D10 {C:.5f} J ({n} tets), S8R {C8:.5f} J ({(C8 / C - 1) * 100:+.2f} %), "
              f"beam D b {beam_D:.5f} J, beam E I {beam_EI:.5f} J")
        self.assertLess(abs(C8 / C - 1), 0.015)
        self.assertTrue(beam_D < C < beam_EI)

    def test_self_riveted_sheets_apart_are_refused(self):
        # Sheets more than t apart would not touch in the fused solid (the tie would be
        # lost), and a result without the tie points cannot be placed: the check
        # falls back to S8R for both.
        deck = "*SHELL SECTION, ELSET=EALL, MATERIAL=M\n0.0016\n"
        apart = {"tabs": [], "rivets": [], "self_rivets": [{"tabs": [1, 2], "points": [[0, 0, 0], [0, 0, 0.0025]]}]}
        with self.assertRaisesRegex(solid_reference.SolidNotApplicable, "2.50 mm apart"):
            solid_reference.solid_compliance(apart, deck, self.tmp.name)
        old = {"tabs": [], "rivets": [], "self_rivets": [{"tabs": [1, 2], "point": [0, 0, 0]}]}
        with self.assertRaisesRegex(solid_reference.SolidNotApplicable, "older sheetgen"):
            solid_reference.solid_compliance(old, deck, self.tmp.name)


if __name__ == "__main__":
    unittest.main()
