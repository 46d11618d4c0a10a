#!/usr/bin/python3
"""`sheetgen solve` sizes each valid answer (docs/pipeline.md "Sizing"), and
`--no-sizing` keeps the answer as the composition left it: the same search,
so the unsized run's part is exactly what the sized run started from.

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_sizing_cli.py --sheetgen build/native/cli/sheetgen
"""
import sys
import unittest

import cli_tests  # noqa: E402  (tests/python/, the script's own folder)
import test_solve_hard_cases as hard

SHEETGEN = None


class SizingCli(unittest.TestCase):
    def test_sized_answer_starts_from_the_unsized_one_and_costs_no_more(self):
        hard.SHEETGEN = SHEETGEN
        # A 100 N box over a floor, 2 mm allowed: a bracket of the widest
        # plates discovery could make has room to lose.
        p, sized, _ = hard.solve(hard.floor_and_wall())
        self.assertEqual(p.exit_code, 0, p.stdout + p.stderr)
        q, plain, _ = hard.solve(hard.floor_and_wall(), "--no-sizing")
        self.assertEqual(q.exit_code, 0, q.stdout + q.stderr)
        self.assertTrue(sized["search"]["sizing"])
        self.assertFalse(plain["search"]["sizing"])
        a, b = sized["parts"][0], plain["parts"][0]
        s = a["sizing"]
        # The record of where sizing started is the unsized run's answer.
        self.assertEqual(s["area_before_m2"], b["area_m2"])
        self.assertEqual(s["search_score_before_m2"], b["cost_m2"])
        self.assertEqual(a["segments"], b["segments"])
        self.assertFalse(s["final_check_failed"])
        self.assertGreater(s["trials"], 0)
        # Sizing only ever keeps a cheaper valid part, and it only cuts.
        self.assertLessEqual(a["cost_m2"], b["cost_m2"])
        self.assertLessEqual(a["area_m2"], b["area_m2"])
        if s["cuts"] > 0:
            self.assertLess(a["area_m2"], b["area_m2"])
        self.assertLessEqual(a["compliance"], a["compliance_limit"])
        self.assertGreaterEqual(a["margin_of_safety"], 0.0)
        self.assertNotIn("sizing", b)
        print("sizing: %d trials, %d cuts, area %.1f -> %.1f cm^2, C %.4g J (limit %.4g)" % (
            s["trials"], s["cuts"], b["area_m2"] * 1e4, a["area_m2"] * 1e4, a["compliance"], a["compliance_limit"]))


if __name__ == "__main__":
    result = cli_tests.run_with_sheetgen(sys.modules[__name__])
    sys.exit(0 if result.wasSuccessful() else 1)
