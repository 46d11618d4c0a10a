#!/usr/bin/python3
"""The CalculiX stress check (sheetgen_tools.ccx_stress) against a closed form.

A clamped strip (100 x 20 mm, 1.6 mm aluminium) carries 1 N at its tip. Beam
theory gives the surface stress sigma(x) = 6 P (L - x) / (b t^2); the rule
leaves out the elements whose centre is within 2 t + h_p of a clamped node, so
the kept maximum is sigma at the first kept column of elements. A T of quads
(a leg folded up from the middle of an edge) has exactly two re-entrant
corners, the ends of the fold.

Run: PYTHONPATH=tools /usr/bin/python3 -m unittest tests/python/test_verify_stress.py (needs ccx).
"""
import math
import os
import shutil
import subprocess
import tempfile
import unittest

import numpy as np

from sheetgen_tools import ccx_stress


def grid(origin, du, dv, nu, nv, ids):
    """Nodes of an (nu+1) x (nv+1) grid, reusing ids of points already in `ids` (dict rounded point -> id)."""
    out = np.empty((nu + 1, nv + 1), dtype=int)
    for i in range(nu + 1):
        for j in range(nv + 1):
            p = tuple(np.round(np.asarray(origin) + i * np.asarray(du) + j * np.asarray(dv), 9))
            out[i, j] = ids.setdefault(p, len(ids))
    return out


def quads_of(g):
    return [[g[i, j], g[i + 1, j], g[i + 1, j + 1], g[i, j + 1]]
            for i in range(g.shape[0] - 1) for j in range(g.shape[1] - 1)]


class CalculixStressRule(unittest.TestCase):
    @unittest.skipUnless(shutil.which("ccx"), "CalculiX (calculix-ccx) is required")
    def test_cantilever_strip_matches_beam_theory(self):
        L, b, t, h, P = 0.1, 0.02, 1.6e-3, 2.5e-3, 1.0
        ids = {}
        g = grid((0, 0, 0), (h, 0, 0), (0, h, 0), 40, 8, ids)
        X = np.array(sorted(ids, key=ids.get))
        quads = quads_of(g)
        tip = g[-1, :]
        lines = ["*NODE, NSET=NALL"] + ["%d, %.9g, %.9g, %.9g" % (k + 1, *x) for k, x in enumerate(X)]
        lines += ["*ELEMENT, TYPE=S4, ELSET=EALL"] + ["%d, %d, %d, %d, %d" % (e + 1, *[n + 1 for n in q])
                                                      for e, q in enumerate(quads)]
        lines += ["*MATERIAL, NAME=SHEET", "*ELASTIC", "70e9, 0.0", "*SHELL SECTION, ELSET=EALL, MATERIAL=SHEET",
                  str(t), "*STEP", "*STATIC", "*BOUNDARY"]
        lines += ["%d, 1, 6" % (n + 1) for n in g[0, :]]
        lines += ["*CLOAD"] + ["%d, 3, %.9g" % (n + 1, P / 8 * (0.5 if j in (0, 8) else 1.0))
                               for j, n in enumerate(tip)]
        lines += ["*NODE PRINT, NSET=NALL", "U", "*EL PRINT, ELSET=EALL", "S", "*END STEP", ""]
        deck = "\n".join(lines)
        with tempfile.TemporaryDirectory() as tmp:
            with open(os.path.join(tmp, "strip.inp"), "w") as f:
                f.write(deck)
            subprocess.run(["ccx", "-i", "strip"], cwd=tmp, check=True, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
            with open(os.path.join(tmp, "strip.dat")) as f:
                dat = f.read()
        sigma, n_singular, n_corners = ccx_stress.ccx_max_von_mises(deck, dat, t)
        # Clamped nodes: the 9 of x = 0; h_p = 2 x 2.5 mm, so the radius is
        # 3.2 + 5 = 8.2 mm and the first kept centres are at x = 8.75 mm.
        self.assertEqual(n_singular, 9)
        self.assertEqual(n_corners, 0)
        beam = 6 * P * (L - 8.75e-3) / (b * t * t)
        print("strip: CalculiX by the rule %.4g MPa, beam theory at x = 8.75 mm %.4g MPa" % (sigma * 1e-6, beam * 1e-6))
        self.assertAlmostEqual(sigma / beam, 1.0, delta=0.02)

    def test_fold_ends_inside_an_edge_are_the_only_reentrant_corners(self):
        ids = {}
        h = 5e-3
        base = grid((0, 0, 0), (h, 0, 0), (0, h, 0), 8, 8, ids)       # 40 x 40 mm in z = 0
        leg = grid((0.04, 0.01, 0), (0, h, 0), (0, 0, h), 4, 6, ids)  # y 10..30 mm, folded up at x = 40 mm
        X = np.array(sorted(ids, key=ids.get))
        quads = np.array(quads_of(base) + quads_of(leg))
        corners = ccx_stress._quad_reentrant_corners(quads, X, math.radians(190.0))
        got = sorted(tuple(np.round(X[c] * 1e3, 6)) for c in corners)
        self.assertEqual(got, [(40.0, 10.0, 0.0), (40.0, 30.0, 0.0)])
        # Over the whole edge (y 0..40 mm) the fold's ends are 90 + 90 deg: none.
        ids = {}
        base = grid((0, 0, 0), (h, 0, 0), (0, h, 0), 8, 8, ids)
        leg = grid((0.04, 0.0, 0), (0, h, 0), (0, 0, h), 8, 6, ids)
        X = np.array(sorted(ids, key=ids.get))
        quads = np.array(quads_of(base) + quads_of(leg))
        self.assertEqual(len(ccx_stress._quad_reentrant_corners(quads, X, math.radians(190.0))), 0)


if __name__ == "__main__":
    unittest.main()
