#!/usr/bin/python3
"""`manufacturing.press_brake` through the real CLI (docs/manufacturing.md
"Press brake"), on the shelf scene with a press brake that can bend nothing:
its one die keeps only flanges 50 V = 640 mm long, longer than any tab. Then

* "prefer" (the default) finds no part the tools bend, searches again without
  the check, and answers that search's part, marked `press_fallback`, with
  the failing bend in `press_brake.message`;
* that part is the one "report" answers (the same search, the same seed);
* "require" answers no valid part, and says the press brake is why: its
  discovery dropped every connection (docs/discovery.md "Press-brake filter"),
  and the reason names the flange too short for the die;
* with the standard tools, "prefer" needs no fallback: the shelf's part bends;
* `press_rejected_segments` counts the segments discovery's filter dropped and
  `press_rejected` the candidates the composition's check dropped: both none
  under "report" (the search never checks); under "require", on the press brake
  that bends nothing, the filter drops every segment, so no candidate is left
  for the composition to drop; "prefer" counts the same (its checked passes
  are the "require" search; the fallback checks nothing).

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_press_brake_use.py --sheetgen build/native/cli/sheetgen
"""
import argparse
import json
import os
import sys
import tempfile
import unittest

from sheetgen_tools import paths, runner
from sheetgen_tools.problem import with_absolute_files

SHEETGEN = paths.DEFAULT_SHEETGEN
SMALL = {"chains": 4, "iterations": 200, "beam": 4}  # a part of the shelf in a few seconds
NO_DIE_FITS = {"dies": [{"v_per_thickness": 8, "min_flange_ratio": 50}]}


class PressBrakeUse(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="sheetgen_press_use_")
        scene = paths.scene_problem("shelf")
        with open(scene) as f:
            cls.doc = with_absolute_files(json.load(f), os.path.dirname(scene))
        cls.runs = {}
        for use, tools in (("prefer", NO_DIE_FITS), ("report", NO_DIE_FITS), ("require", NO_DIE_FITS),
                           ("standard", None)):
            cls.runs[use] = cls.solve(use, tools)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    @classmethod
    def solve(cls, name, tools):
        doc = json.loads(json.dumps(cls.doc))
        manufacturing = doc.setdefault("manufacturing", {})
        if name != "standard":  # the standard run leaves press_brake at its default
            manufacturing["press_brake"] = name
        if tools is not None:
            manufacturing["press_brake_tools"] = tools
        path = os.path.join(cls.tmp.name, name + ".json")
        with open(path, "w") as f:
            json.dump(doc, f)
        run = runner.solve(path, os.path.join(cls.tmp.name, name), runner.SolveOptions(sheetgen=SHEETGEN, **SMALL))
        run.check()
        return run.result["parts"][0]

    def test_prefer_falls_back_and_names_the_bend(self):
        part = self.runs["prefer"]
        self.assertEqual(part["status"], "ok")
        self.assertTrue(part["press_fallback"])
        self.assertFalse(part["press_brake"]["ok"])
        self.assertIn("the flange of tab", part["press_brake"]["message"])
        self.assertIn("50.0 x V = 640.0 mm", part["press_brake"]["message"])

    def test_the_fallback_is_the_report_search(self):
        prefer, report = self.runs["prefer"], self.runs["report"]
        self.assertFalse(report["press_fallback"])
        self.assertEqual(report["press_brake"]["message"], prefer["press_brake"]["message"])
        self.assertEqual(report["area_m2"], prefer["area_m2"])
        self.assertEqual([t["corners"] for t in report["tabs"]], [t["corners"] for t in prefer["tabs"]])

    def test_require_has_no_part_and_says_why(self):
        part = self.runs["require"]
        self.assertNotEqual(part["status"], "ok")
        self.assertFalse(part["press_fallback"])
        self.assertIn("press brake", part["reason"])
        self.assertIn("flange", part["reason"])

    def test_standard_tools_need_no_fallback(self):
        part = self.runs["standard"]
        self.assertEqual(part["status"], "ok")
        self.assertFalse(part["press_fallback"])
        self.assertTrue(part["press_brake"]["ok"], part["press_brake"]["message"])

    def test_press_rejected_counts_the_checked_passes_alone(self):
        for counter in ("press_rejected", "press_rejected_segments"):
            self.assertEqual(self.runs["report"][counter], 0, counter)
            self.assertEqual(self.runs["prefer"][counter], self.runs["require"][counter], counter)
        self.assertGreater(self.runs["require"]["press_rejected_segments"], 0)
        self.assertEqual(self.runs["require"]["press_rejected"], 0)


if __name__ == "__main__":
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", default=SHEETGEN)
    args, rest = ap.parse_known_args()
    SHEETGEN = args.sheetgen
    unittest.main(argv=[sys.argv[0]] + rest)
