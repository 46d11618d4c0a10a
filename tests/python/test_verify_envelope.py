#!/usr/bin/python3
"""verify's CalculiX check over a load envelope (sheetgen_tools.ccx_check), with
CalculiX and gmsh (full tier).

* Closed forms on a clamped strip (100 x 10 x 1 mm, E = 70 GPa, nu = 0, S8R,
  rigid tip; seconds): the *BUCKLE steps ccx_check adds find the Euler load
  pi^2 E I / 4 L^2 of a case pushing with 100 x that load (factor 0.01), where
  ccx 2.20 at the case's own load reports the second mode; a pulling case has
  no positive factor; each static step's f^T u is P^2 L / (E b t) of its own
  load (OP=NEW between them); the first frequency is the cantilever's,
  1.8751^2 / (2 pi L^2) sqrt(E I / (rho A)).
* The corner scene with a 4 kg box under the FAR 25.561 preset (max_deflection
  3 mm), solved by the CLI at 4 x 200 and measured once by measure_calculix: the deck's loads and
  masses are the problem's, every case has a compliance, an MS and a buckling
  factor, and a part the solver calls ok passes; the same numbers judged
  against raised floors (min_frequency_hz or min_buckling_factor 1.5 x
  CalculiX's, max_deflection 1 um) fail the part on that check, and floors
  just below CalculiX's pass it; judged as a self-riveted part, ours more than
  5 % below the bonded solid or above the softer of it and S6 fails it, ours
  between them passes.

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_verify_envelope.py --sheetgen build/native/cli/sheetgen
"""
import copy
import dataclasses
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from sheetgen_tools import ccx_check, ccx_deck, runner, s8r_grid
from sheetgen_tools.findings import Findings

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_ccx_deck import corner_envelope_problem  # noqa: E402
import cli_tests  # noqa: E402  (tests/python/, the script's own folder)

SHEETGEN = None
L, B, T, E, RHO = 0.1, 0.01, 1e-3, 70e9, 2700.0
EULER = math.pi ** 2 * E * (B * T ** 3 / 12) / (4 * L * L)  # N, clamped-free


def strip_deck(cases, h=2.5e-3):
    """An S8R strip along x clamped at x = 0, its tip x = L a rigid body whose
    REF node carries each case's axial force (name, N) in a *STATIC step, after
    a *FREQUENCY step of 3 modes."""
    n, m = round(L / h), round(B / h)
    xs, ys = np.linspace(0, L, 2 * n + 1), np.linspace(0, B, 2 * m + 1)

    def node(i, j):
        return i * len(ys) + j + 1
    lines = ["*NODE, NSET=NALL"] + [f"{node(i, j)}, {x:.12g}, {y:.12g}, 0" for i, x in enumerate(xs)
                                    for j, y in enumerate(ys)]
    ref = len(xs) * len(ys) + 1
    lines += [f"{k}, {L:.12g}, {B / 2:.12g}, 0" for k in (ref, ref + 1)]
    lines += s8r_grid.s8r_elements(len(xs), len(ys), node)
    lines += ["*MATERIAL, NAME=SHEET", "*ELASTIC", f"{E:.12g}, 0", "*DENSITY", f"{RHO:.12g}",
              "*SHELL SECTION, ELSET=EALL, MATERIAL=SHEET", f"{T:.12g}", "*NSET, NSET=RIGID1"]
    lines += [f"{node(len(xs) - 1, j)}," for j in range(len(ys))]
    lines += [f"*RIGID BODY, NSET=RIGID1, REF NODE={ref}, ROT NODE={ref + 1}", "*BOUNDARY"]
    lines += [f"{node(0, j)}, 1, 6" for j in range(len(ys))]
    lines += ["** Natural frequencies", "*STEP", "*FREQUENCY", "3", "*END STEP"]
    for k, (name, px) in enumerate(cases):
        lines += [f"** Load case {k + 1} '{name}'", "*STEP", "*STATIC", "*CLOAD, OP=NEW" if k else "*CLOAD",
                  f"{ref}, 1, {px:.12g}", "*NODE PRINT, NSET=NALL", "U", "*END STEP"]
    return "\n".join(lines) + "\n"


def run_ccx(folder, job, text):
    with open(os.path.join(folder, job + ".inp"), "w") as f:
        f.write(text)
    subprocess.run(["ccx", "-i", job], cwd=folder, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                   env=dict(os.environ, OMP_NUM_THREADS="1"))
    with open(os.path.join(folder, job + ".dat")) as f:
        return ccx_deck.read_dat(f.read())


@unittest.skipUnless(shutil.which("ccx"), "CalculiX (calculix-ccx) is required")
class StripClosedForms(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()

    def tearDown(self):
        self.tmp.cleanup()

    def test_buckling_frequency_and_every_static_case(self):
        cases = [("push hard", -100 * EULER), ("pull", 50.0), ("push", -10.0)]
        # The step pushes with a tenth of the Euler load: factors near 10, as the check has them.
        text = ccx_deck.with_buckle_steps(strip_deck(cases), 1e-3, ccx_check.BUCKLE_CARD)
        steps = ccx_deck.deck_steps(text)
        self.assertEqual([s.kind for s in steps], ["BUCKLE", "BUCKLE", "FREQUENCY", "STATIC", "STATIC", "STATIC"])
        dat = run_ccx(self.tmp.name, "strip", text)
        factors = ccx_deck.buckling_factors(steps, dat)
        print(f"strip: factors {[round(factors[k][0], 6) for k in range(3)]}, Euler {EULER:.5f} N")
        self.assertAlmostEqual(factors[0][0] * 100, 1.0, delta=0.005)
        self.assertTrue(math.isinf(factors[1][0]))  # pulling compresses nothing
        self.assertAlmostEqual(factors[2][0] * 10 / EULER, 1.0, delta=0.005)
        # Each step's own load: P^2 L / (E b t) (ccx's expanded S8R with its rigid tip: +0.32 %).
        for step, u in zip([s for s in steps if s.kind == "STATIC"], dat.static_displacements()):
            P = next(v for (_, dof), v in step.loads.items())
            self.assertAlmostEqual(ccx_deck.compliance(step.loads, u) / (P * P * L / (E * B * T)), 1.0, delta=0.005)
        f1 = 1.8751 ** 2 / (2 * math.pi * L * L) * math.sqrt(E * B * T ** 3 / 12 / (RHO * B * T))
        print(f"strip: f1 CalculiX {dat.frequencies_hz[0][0]:.4f} Hz, cantilever {f1:.4f} Hz")
        self.assertAlmostEqual(dat.frequencies_hz[0][0] / f1, 1.0, delta=0.005)

    def test_ccx_at_the_cases_own_load_misses_the_lowest_factor(self):
        # Why the check scales its *BUCKLE loads (ccx_deck.buckling_factors): at
        # 100 x the Euler load ccx 2.20 reports a higher mode. Shown, not asserted:
        # a ccx that finds the lowest factor here would make the scaling moot, not wrong.
        text = ccx_deck.with_buckle_steps(strip_deck([("push hard", -100 * EULER)]), 1.0, ccx_check.BUCKLE_CARD)
        dat = run_ccx(self.tmp.name, "unscaled", text)
        print(f"strip at 100 x Euler, unscaled *BUCKLE: ccx reports {dat.buckling_factors[0]}, the lowest is 0.01")


@unittest.skipUnless(shutil.which("ccx"), "CalculiX (calculix-ccx) is required")
class CornerUnderFar25561(unittest.TestCase):
    """One measurement, judged against the problem and against variants of its requirements."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        path = corner_envelope_problem(cls.tmp.name)
        run = runner.solve(path, os.path.join(cls.tmp.name, "out"),
                           runner.SolveOptions(chains=4, iterations=200, sheetgen=SHEETGEN)).check()
        print(run.stdout.strip())
        with open(path) as f:
            cls.prob = json.load(f)
        cls.part = run.parts[0]
        cls.measure = None
        if cls.part["status"] == "ok":
            cls.measure = ccx_check.measure_calculix(run.out_dir, cls.prob, cls.part, SHEETGEN)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def setUp(self):
        self.assertEqual(self.part["status"], "ok", self.part.get("reason"))

    def judge(self, requirements=None):
        prob = copy.deepcopy(self.prob)
        prob.setdefault("requirements", {}).update(requirements or {})
        findings = Findings()
        ccx_check.judge_calculix(prob, self.part, self.measure, findings)
        return findings

    def test_the_part_passes_its_own_problem(self):
        m = self.measure
        self.assertEqual(m.mismatches, [])
        self.assertEqual([c.name for c in m.cases], ["forward 9 g", "rearward 1.5 g", "left 3 g", "right 3 g",
                                                     "down 6 g", "up 3 g"])
        self.assertTrue(all(c.buckling_factor is not None for c in m.cases))
        self.assertEqual(m.buckle_steps, 6)
        self.assertEqual(len(m.frequencies_hz), ccx_check.FREQUENCY_MODES)
        findings = self.judge()
        print("\n".join(findings.lines + ["FAIL: " + f for f in findings.failures]))
        self.assertEqual(findings.failures, [])

    def test_raised_floors_fail_and_floors_just_met_pass(self):
        f1 = self.measure.frequencies_hz[0]
        factor = min(c.buckling_factor for c in self.measure.cases)
        # The eigen floors have no tolerance: 0.5 % above CalculiX's own values fails.
        for requirements, failing in (({"min_frequency_hz": 1.005 * f1}, "first frequency"),
                                      ({"min_buckling_factor": 1.005 * factor}, "buckling factor"),
                                      ({"max_deflection": 1e-6}, "exceeds the limit")):
            failures = " ".join(self.judge(requirements).failures)
            self.assertIn(failing, failures, requirements)
        failures = " ".join(self.judge({"min_frequency_hz": 0.98 * f1, "min_buckling_factor": 0.98 * factor}).failures)
        self.assertNotIn("first frequency", failures)
        self.assertNotIn("buckling factor", failures)

    def test_a_self_riveted_part_lies_between_its_bonded_solid_and_the_softer_model(self):
        # The same numbers judged as if the part were self-riveted: ours may lie
        # from 5 % below the bonded solid to 5 % above the softer of it and S6.
        ours = [ccx_check.ours_of(self.part)[0][c.name]["compliance"] for c in self.measure.cases]

        def failures(bonded, softer):  # both as multiples of ours
            cases = [dataclasses.replace(c, bonded_solid=bonded * C, reference=softer * C)
                     for c, C in zip(self.measure.cases, ours)]
            findings = Findings()
            ccx_check.judge_calculix(self.prob, self.part, dataclasses.replace(
                self.measure, cases=cases, reference=ccx_check.BRACKET), findings)
            return " ".join(f for f in findings.failures if "compliance differs" in f)
        self.assertIn("differs from the solid with its laps bonded by -5.7 %", failures(1.06, 1.06))
        self.assertEqual(failures(1.04, 1.04), "")
        self.assertEqual(failures(0.80, 0.96), "")
        self.assertIn(f"differs from CalculiX ({ccx_check.BRACKET}) by 11.1 %", failures(0.80, 0.90))

if __name__ == "__main__":
    result = cli_tests.run_with_sheetgen(sys.modules[__name__])
    sys.exit(0 if result.wasSuccessful() else 1)
