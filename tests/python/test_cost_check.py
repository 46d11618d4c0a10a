#!/usr/bin/python3
"""The cost of a solved part (docs/cost.md) through the real CLI: result.json's
cost equals the one sheetgen_tools.cost_check rebuilds from the problem's
prices, flat.dxf and bends.csv; prices given in the problem file are the ones
used; the search's cost_m2 is that cost in square metres of sheet; and the
check fails a result whose cost was altered.

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_cost_check.py --sheetgen build/native/cli/sheetgen
"""
import argparse
import json
import os
import sys
import tempfile
import unittest

import ezdxf

from sheetgen_tools import paths, runner
from sheetgen_tools.cost_check import check_cost, expected_cost
from sheetgen_tools.findings import Findings
from sheetgen_tools.problem import load_problem, problem_of_result, with_absolute_files

SHEETGEN = paths.DEFAULT_SHEETGEN
# A small search of the shelf scene: a part in a few seconds.
SMALL = {"chains": 4, "iterations": 200, "beam": 4}
PRICES = {"currency": "EUR", "material_per_kg": 40.0, "per_bend": 2.5, "per_rivet": 0.25, "setup": 90.0,
          "batch_size": 4, "objective": "area"}


def solve(problem_path, out_dir):
    run = runner.solve(problem_path, out_dir, runner.SolveOptions(sheetgen=SHEETGEN, **SMALL))
    if run.exit_code != 0:
        raise AssertionError(f"sheetgen solve exited {run.exit_code}: {run.stderr[-2000:]}")
    return run


class CostOfASolvedPart(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="sheetgen_cost_")
        scene = paths.scene_problem("shelf")
        with open(scene) as f:
            doc = with_absolute_files(json.load(f), os.path.dirname(scene))
        doc["cost"] = PRICES
        cls.priced = os.path.join(cls.tmp.name, "priced.json")
        with open(cls.priced, "w") as f:
            json.dump(doc, f)
        cls.default_out = os.path.join(cls.tmp.name, "default")
        cls.priced_out = os.path.join(cls.tmp.name, "priced")
        solve(scene, cls.default_out)
        solve(cls.priced, cls.priced_out)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def part_of(self, out_dir):
        with open(os.path.join(out_dir, "result.json")) as f:
            result = json.load(f)
        self.assertEqual(result["parts"][0]["status"], "ok")
        return result["parts"][0]

    def check(self, out_dir, part):
        with open(os.path.join(out_dir, "result.json")) as f:
            prob, _ = load_problem(problem_of_result(out_dir, json.load(f)))
        doc = ezdxf.readfile(os.path.join(out_dir, part["load"], "flat.dxf"))
        findings = Findings()
        check_cost(out_dir, prob, part, findings, doc)
        return prob, findings

    def test_default_prices(self):
        part = self.part_of(self.default_out)
        _, findings = self.check(self.default_out, part)
        self.assertEqual(findings.failures, [], findings.lines)
        cost = part["cost"]
        self.assertEqual(cost["currency"], "USD")
        # 1.6 mm 2024-T3 at 15 USD/kg: 66.72 USD per square metre; the set-up 60 USD over 10 parts.
        self.assertAlmostEqual(cost["material"], 66.72 * part["area_m2"], places=9)
        self.assertAlmostEqual(cost["setup"], 6.0, places=12)
        self.assertEqual(cost["rivet_count"], len(part["rivets"]) + len(part["self_rivets"]))
        # The search's score (the default objective) is the cost without the set-up share in m^2 of sheet.
        self.assertAlmostEqual(part["cost_m2"], (cost["total"] - cost["setup"]) / 66.72, places=9)

    def test_prices_from_the_problem_file(self):
        part = self.part_of(self.priced_out)
        _, findings = self.check(self.priced_out, part)
        self.assertEqual(findings.failures, [], findings.lines)
        cost = part["cost"]
        self.assertEqual(cost["currency"], "EUR")
        self.assertAlmostEqual(cost["bends"], 2.5 * part["bends"], places=12)
        self.assertAlmostEqual(cost["rivets"], 0.25 * cost["rivet_count"], places=12)
        self.assertAlmostEqual(cost["setup"], 22.5, places=12)
        per_m2 = 40.0 * 2780.0 * 1.6e-3
        self.assertAlmostEqual(cost["material"], per_m2 * part["area_m2"], places=9)
        # "objective": "area": the score is area + 2e-3 m^2 per bend; the cost is reported all the same.
        self.assertAlmostEqual(part["cost_m2"], part["area_m2"] + 2e-3 * part["bends"], places=12)

    def test_an_altered_cost_fails(self):
        part = self.part_of(self.default_out)
        part["cost"] = dict(part["cost"], total=part["cost"]["total"] * 0.9)
        _, findings = self.check(self.default_out, part)
        self.assertTrue(any("cost.total" in f for f in findings.failures), findings.failures)
        part = self.part_of(self.default_out)
        part["cost"] = dict(part["cost"], rivets=part["cost"]["rivets"] + 1.0)
        _, findings = self.check(self.default_out, part)
        self.assertTrue(any("cost.rivets" in f for f in findings.failures), findings.failures)

    def test_expected_cost_closed_form(self):
        c = expected_cost({"cost": {"per_bend": 3.0}}, 0.1, 4, 6)
        self.assertAlmostEqual(c["material"], 6.672, places=12)
        self.assertEqual((c["bends"], c["rivets"], c["setup"]), (12.0, 6.0, 6.0))
        self.assertAlmostEqual(c["total"], 30.672, places=12)


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", default=SHEETGEN)
    args, rest = ap.parse_known_args()
    SHEETGEN = os.path.abspath(args.sheetgen)
    unittest.main(argv=[sys.argv[0]] + rest)
