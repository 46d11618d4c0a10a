#!/usr/bin/python3
"""Thicker gauges (docs/pipeline.md "Thicker gauges"): a load that the
problem's sheet gives no valid part is searched again in each of
material.gauges. The part found is the one the same problem written at that
thickness gives, and it is made of that sheet everywhere it is written:
result.json (thickness_m, mass), the flat pattern's rivet holes, the cost and
the CalculiX deck, each checked against the problem file by
sheetgen_tools.verify and by the deck's own *SHELL SECTION.

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_gauges_cli.py --sheetgen build/native/cli/sheetgen
"""
import os
import subprocess
import sys
import tempfile
import unittest

import cli_tests  # noqa: E402  (tests/python/, the script's own folder)
import test_solve_hard_cases as hard
from sheetgen_tools.verify import VerifyOptions, verify_output

SHEETGEN = None
INCH = 0.0254
# One search per sheet: no web, flat, seed-retry or right-angle passes, and no second round
# without the press-brake check, so the test pays for two searches.
ONE_PASS = ("--seed-retries", "0", "--no-web-roots", "--no-flat-fallback", "--no-right-angle-pass")


def stiff_problem(gauges):
    """A 100 N box over a floor with 0.2 mm of deflection allowed: at 4 x 150
    no 1.6 mm part found is that stiff (the nearest is several times over),
    while a 0.125 in part has room to spare (0.08 mm measured)."""
    prob = hard.floor_and_wall(requirements={"max_deflection": 2e-4})
    prob["material"] = {"gauges": gauges}
    prob["manufacturing"] = {"press_brake": "require"}
    return prob


class Gauges(unittest.TestCase):
    def setUp(self):
        hard.SHEETGEN = SHEETGEN

    def test_a_load_too_soft_in_its_sheet_gets_a_part_in_a_thicker_gauge(self):
        t = 0.125 * INCH
        p, result, out = hard.solve(stiff_problem([t]), *ONE_PASS)
        self.assertEqual(p.exit_code, 0, p.stdout + p.stderr)
        part = result["parts"][0]
        self.assertEqual(part["status"], "ok")
        self.assertEqual(part["gauges_tried"], 1)
        self.assertAlmostEqual(part["thickness_m"], t, delta=1e-12)
        self.assertAlmostEqual(part["mass_kg"], part["area_m2"] * t * 2780.0, delta=1e-9)
        self.assertLessEqual(part["deflection_along_force_m"], 2e-4)
        self.assertIn("sheet 3.17 mm (thicker gauge 1)", p.stdout)
        # The same problem written at that thickness gives the same part.
        at_t = stiff_problem([])
        at_t["material"]["thickness"] = t
        q, alone, _ = hard.solve(at_t, *ONE_PASS)
        self.assertEqual(q.exit_code, 0, q.stdout + q.stderr)
        self.assertEqual(alone["parts"][0]["tabs"], part["tabs"])
        self.assertEqual(alone["parts"][0]["gauges_tried"], 0)
        # The independent checks in that sheet: clearance t/2 + 1 mm, the rivet
        # holes of a 6.35 mm rivet (2 t) in flat.dxf, the cost of its mass.
        report = verify_output(out, VerifyOptions(calculix=False))
        self.assertTrue(report.ok, report.text())
        # The CalculiX deck is that sheet's.
        with tempfile.TemporaryDirectory() as tmp:
            deck = os.path.join(tmp, "box.inp")
            subprocess.run([SHEETGEN, "export-ccx", os.path.join(out, "result.json"), "--load", "box", "--out", deck],
                           check=True, capture_output=True)
            lines = open(deck).read().splitlines()
        section = lines.index(next(ln for ln in lines if ln.startswith("*SHELL SECTION")))
        self.assertAlmostEqual(float(lines[section + 1]), t, delta=1e-12)

    def test_without_gauges_the_load_has_no_part_and_says_why(self):
        p, result, _ = hard.solve(stiff_problem([]), *ONE_PASS)
        self.assertEqual(p.exit_code, 2, p.stdout + p.stderr)
        part = result["parts"][0]
        self.assertEqual(part["gauges_tried"], 0)
        self.assertAlmostEqual(part["thickness_m"], 1.6e-3, delta=1e-15)
        self.assertIn("over the limit", part["reason"])
        self.assertNotIn("thicker gauges", part["reason"])

    def test_a_part_in_a_sheet_the_problem_does_not_allow_fails_verify(self):
        p, result, out = hard.solve(stiff_problem([0.125 * INCH]), *ONE_PASS)
        self.assertEqual(p.exit_code, 0, p.stdout + p.stderr)
        path = os.path.join(out, "result.json")
        import json
        doc = json.load(open(path))
        doc["parts"][0]["thickness_m"] = 0.1 * INCH  # not in material.gauges
        json.dump(doc, open(path, "w"))
        report = verify_output(out, VerifyOptions(calculix=False))
        self.assertFalse(report.ok)
        self.assertIn("is neither material.thickness nor one of its gauges", report.text())


if __name__ == "__main__":
    result = cli_tests.run_with_sheetgen(sys.modules[__name__])
    sys.exit(0 if result.wasSuccessful() else 1)
