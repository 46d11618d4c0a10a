#!/usr/bin/python3
"""`sheetgen solve` on hard cases (issue 6): each ends with the documented exit
code and a per-load reason a user can act on, and Ctrl-C ends a run within a
second leaving nothing that looks finished.

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_solve_hard_cases.py --sheetgen build/native/cli/sheetgen
"""
import json
import math
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

from sheetgen_tools import runner
import cli_tests  # noqa: E402  (tests/python/, the script's own folder)

SHEETGEN = None
QUICK = {"chains": 4, "iterations": 150, "threads": 2}


def floor_and_wall(extra_meshes=(), ras=None, loads=None, requirements=None):
    """A floor z = 0 and a wall x = 0, 0.6 m squares, 2 triangles each."""
    meshes = [
        {"name": "floor", "vertices": [[0, -0.3, 0], [0.6, -0.3, 0], [0.6, 0.3, 0], [0, 0.3, 0]], "triangles": [[0, 1, 2], [0, 2, 3]]},
        {"name": "wall", "vertices": [[0, -0.3, 0], [0, 0.3, 0], [0, 0.3, 0.6], [0, -0.3, 0.6]], "triangles": [[0, 1, 2], [0, 2, 3]]},
    ] + list(extra_meshes)
    return {
        "format": "sheetgen-problem/1",
        "environment": {"meshes": meshes},
        "rivet_areas": ras or [{"name": "floor_all", "mesh": "floor", "faces": [0, 1]}],
        "loads": loads or [{"name": "box", "center": [0.3, 0, 0.25], "size": [0.12, 0.1, 0.08], "force": [0, 0, -100]}],
        "requirements": requirements or {"max_deflection": 2e-3},
    }


def box_mesh(name, lo, hi):
    v = [[hi[0] if k & 1 else lo[0], hi[1] if k & 2 else lo[1], hi[2] if k & 4 else lo[2]] for k in range(8)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    t = []
    for q in quads:
        t += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    return {"name": name, "vertices": v, "triangles": t}


def write_problem(problem, prefix):
    """problem.json in a fresh temporary folder; returns (its path, the folder's out/)."""
    d = tempfile.mkdtemp(prefix=prefix)
    path = os.path.join(d, "problem.json")
    json.dump(problem, open(path, "w"))
    return path, os.path.join(d, "out")


def solve(problem, *flags, env=None, out=None):
    """A quick solve of `problem` (a dict): (runner.SolveRun, result.json or None, the output folder)."""
    path, default_out = write_problem(problem, "sheetgen_hard_")
    p = runner.solve(path, out or default_out, runner.SolveOptions(**QUICK, flags=flags, env=env, sheetgen=SHEETGEN))
    return p, p.result, p.out_dir


class HardCases(unittest.TestCase):
    def test_unreachable_rivet_area_is_exit_2_with_reason(self):
        # The only rivet area is on the floor, sealed under a closed box (a cabinet) the part cannot enter.
        prob = floor_and_wall(extra_meshes=[box_mesh("cabinet", [0.35, -0.25, -0.01], [0.55, -0.05, 0.1])],
                              ras=[{"name": "under_cabinet", "mesh": "floor", "faces": [0, 1]}])
        # Restrict the rivet area to faces fully inside the cabinet: re-mesh the floor so one quad lies under it.
        prob["environment"]["meshes"][0] = {"name": "floor", "vertices": [
            [0, -0.3, 0], [0.6, -0.3, 0], [0.6, 0.3, 0], [0, 0.3, 0], [0.4, -0.2, 0], [0.5, -0.2, 0], [0.5, -0.1, 0], [0.4, -0.1, 0]],
            "triangles": [[4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]]}
        prob["rivet_areas"] = [{"name": "under_cabinet", "mesh": "floor", "faces": [0, 1]}]
        p, result, _ = solve(prob)
        self.assertEqual(p.exit_code, 2, p.stdout + p.stderr)
        part = result["parts"][0]
        self.assertEqual(part["status"], "no_valid_part")
        self.assertIn("no segment reached a rivet area", part["reason"])

    def test_load_inside_an_obstacle_is_exit_2_with_reason(self):
        prob = floor_and_wall(extra_meshes=[box_mesh("crate", [0.2, -0.1, 0.1], [0.4, 0.1, 0.4])])
        p, result, _ = solve(prob)
        self.assertEqual(p.exit_code, 2, p.stdout + p.stderr)
        reason = result["parts"][0]["reason"]
        self.assertIn("load 'box' lies inside a closed obstacle", reason)

    def test_load_touching_an_obstacle_is_exit_2_with_reason(self):
        # The box rests on a crate: its base tab would have to pass through the crate's top.
        prob = floor_and_wall(extra_meshes=[box_mesh("crate", [0.2, -0.1, 0.0], [0.4, 0.1, 0.21])])
        p, result, _ = solve(prob)
        self.assertEqual(p.exit_code, 2, p.stdout + p.stderr)
        reason = result["parts"][0]["reason"]
        self.assertIn("base tab under load 'box' is not clear", reason)
        self.assertIn("overlaps or touches an obstacle", reason)

    def test_impossible_compliance_is_exit_2_naming_the_miss(self):
        # A 1 micrometre deflection under 100 N: no 1.6 mm aluminium bracket is that stiff.
        # Press brake "require": the passes below, without the press-brake fallback's second
        # round of them (42 s of this test's 56; test_press_brake_use.py checks that round).
        prob = floor_and_wall(requirements={"max_deflection": 1e-6})
        prob["manufacturing"] = {"press_brake": "require"}
        p, result, _ = solve(prob)
        self.assertEqual(p.exit_code, 2, p.stdout + p.stderr)
        reason = result["parts"][0]["reason"]
        self.assertIn("compliance", reason)
        self.assertIn("over the limit", reason)
        # Every fallback ran before giving up: web roots, flat extensions, then the two retries.
        part = result["parts"][0]
        self.assertTrue(part["web_pass_tried"] and part["flat_pass_tried"], part)
        self.assertEqual(part["seed_retries_tried"], 2)
        self.assertIn(part["seed_retry"], (0, 1, 2))  # the pass whose candidate came nearest to valid
        self.assertTrue(result["search"]["flat_fallback"])
        self.assertEqual(result["search"]["seed_retries"], 2)
        self.check_stage_times(part["timing"])
        # Flat extensions already on: no third search (it would repeat the first); retries off.
        p, result, _ = solve(prob, "--flat-extensions", "--seed-retries", "0")
        self.assertEqual(p.exit_code, 2, p.stdout + p.stderr)
        self.assertFalse(result["parts"][0]["flat_pass_tried"])
        self.assertEqual(result["parts"][0]["seed_retries_tried"], 0)
        self.assertFalse(result["search"]["flat_fallback"])

    def test_right_angle_pass_replaces_the_answer_only_by_a_cheaper_right_angle_part(self):
        # A box between a floor and a wall, both rivet areas: the free search's
        # part scores 0.255 m^2 before sizing, the right-angle pass finds one of
        # 0.206 m^2 (measured; docs/pipeline.md "Right-angle pass").
        prob = floor_and_wall(ras=[{"name": "wall_all", "mesh": "wall", "faces": [0, 1]},
                                   {"name": "floor_all", "mesh": "floor", "faces": [0, 1]}])
        p, with_pass, _ = solve(prob)
        q, without, _ = solve(prob, "--no-right-angle-pass")
        self.assertEqual((p.exit_code, q.exit_code), (0, 0), p.stdout + p.stderr + q.stdout + q.stderr)
        a, b = with_pass["parts"][0], without["parts"][0]
        self.assertTrue(with_pass["search"]["right_angle_pass"] and a["right_angle_pass_tried"], a)
        self.assertFalse(without["search"]["right_angle_pass"] or b["right_angle_pass_tried"], b)
        self.assertTrue(a["right_angle_pass"], a)
        self.assertLess(a["sizing"]["search_score_before_m2"], b["sizing"]["search_score_before_m2"])
        # The answer is in the right-angle grammar: every bend 90 deg (+-0.5) or a
        # flat extension, no skew.
        for tab in a["tabs"]:
            q3 = tab["parameters"] and tab["parameters"]["theta3"]
            if not tab["parameters"]:
                continue
            self.assertTrue(q3 == 0.0 or abs(abs(q3) - math.pi / 2) <= math.radians(0.5) + 1e-9, tab)
            self.assertLessEqual(max(abs(tab["parameters"]["theta1"]), abs(tab["parameters"]["theta2"])), 1e-3 + 1e-9, tab)
        # A right-angle run has no second right-angle search.
        r, square, _ = solve(prob, "--right-angles")
        self.assertFalse(square["search"]["right_angle_pass"] or square["parts"][0]["right_angle_pass_tried"])

    def check_stage_times(self, timing):
        # Wall and CPU per stage, summed over the load's passes: each stage took
        # some of both, and together they fit in the load's total (planning and
        # the bookkeeping between stages are the rest).
        for clock in ("", "cpu_"):
            stages = [timing[f"{s}_{clock}s"] for s in ("environment", "discovery", "composition", "sizing")]
            self.assertTrue(all(t >= 0 for t in stages), timing)
            self.assertGreater(timing[f"discovery_{clock}s"], 0, timing)
            self.assertGreater(timing[f"composition_{clock}s"], 0, timing)
            self.assertLessEqual(sum(stages), timing[f"total_{clock}s"] + 1e-3, timing)

    def test_ctrl_c_ends_within_a_second_and_writes_nothing(self):
        path, out = write_problem(floor_and_wall(), "sheetgen_sigint_")
        # 20 x the default iterations: the default run ends in about 2 s on
        # two threads, and this test must interrupt it while it is going.
        proc = subprocess.Popen([SHEETGEN, "solve", path, "--out", out, "--threads", "2", "--iterations", "20000"],
                                stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        time.sleep(2.0)
        self.assertIsNone(proc.poll(), "the run should still be going after 2 s")
        t0 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=10)
        waited = time.monotonic() - t0
        self.assertEqual(proc.returncode, 130)
        self.assertLess(waited, 1.0)
        self.assertIn("interrupted", err)
        self.assertFalse(os.path.exists(os.path.join(out, "result.json")))
        leftovers = [f for f in os.listdir(out)] if os.path.isdir(out) else []
        self.assertEqual([f for f in leftovers if not f.startswith(".sheetgen-staging")], [])

    def test_ten_thousand_loads_progress_and_cancel_within_a_second(self):
        # 100 x 100 small boxes over a 6 m floor: check is fast, solve starts on
        # load 1, and Ctrl-C ends it within a second, writing nothing.
        loads = [{"name": "box%05d" % (i * 100 + j), "center": [0.03 + 0.06 * i, -2.97 + 0.06 * j, 0.2],
                  "size": [0.03, 0.03, 0.02], "force": [0, 0, -10]} for i in range(100) for j in range(100)]
        prob = floor_and_wall(loads=loads)
        prob["environment"]["meshes"][0]["vertices"] = [[0, -3, 0], [6, -3, 0], [6, 3, 0], [0, 3, 0]]
        path, out = write_problem(prob, "sheetgen_10k_")
        t0 = time.monotonic()
        chk = subprocess.run([SHEETGEN, "check", path], capture_output=True, text=True)
        self.assertEqual(chk.returncode, 0, chk.stderr)
        self.assertIn("loads: 10000", chk.stdout)
        print("check of 10 000 loads: %.2f s" % (time.monotonic() - t0))
        # 20 x the default iterations: the default run ends in about 2 s on
        # two threads, and this test must interrupt it while it is going.
        proc = subprocess.Popen([SHEETGEN, "solve", path, "--out", out, "--threads", "2", "--iterations", "20000"],
                                stdout=subprocess.PIPE,
                                stderr=subprocess.PIPE, text=True)
        time.sleep(4.0)
        self.assertIsNone(proc.poll())
        t1 = time.monotonic()
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=30)
        waited = time.monotonic() - t1
        print("cancel of a 10 000-load solve: %.3f s" % waited)
        self.assertEqual(proc.returncode, 130, err)
        # Issue 9 asks that such a run "progresses and cancels"; the one-second
        # rule is asserted on an ordinary problem (test_ctrl_c_...). Here the
        # signal arrives while the clearance field of the 6 m x 6 m floor is
        # built, and OpenVDB polls its interrupter only between stages:
        # measured 0.61 s alone, 1.31 s and 3.1-3.6 s with other jobs on the
        # 2 cores (docs/reliability.md). The bound says it cancels, not hangs.
        self.assertLess(waited, 10.0)
        self.assertFalse(os.path.exists(os.path.join(out, "result.json")))

    def test_exception_in_a_worker_thread_reaches_the_caller(self):
        # SHEETGEN_INJECT_FAULT=composition throws inside a TBB composition task.
        p, _, out = solve(floor_and_wall(), env={"SHEETGEN_INJECT_FAULT": "composition"})
        self.assertEqual(p.exit_code, 3, p.stderr)
        self.assertEqual(p.stderr.strip(), "sheetgen: internal error: injected fault in a composition worker")
        self.assertFalse(os.path.exists(os.path.join(out, "result.json")))

    def test_unwritable_output_is_an_error_not_a_half_written_folder(self):
        # --out names an existing regular file: the folder cannot be made (this works as root too,
        # where permission bits would not stop a write).
        out = os.path.join(tempfile.mkdtemp(prefix="sheetgen_ro_"), "not_a_folder")
        open(out, "w").write("keep me")
        p, _, _ = solve(floor_and_wall(), out=out)
        self.assertEqual(p.exit_code, 1, p.stderr)
        self.assertIn("cannot create the output folder", p.stderr)
        self.assertEqual(len(p.stderr.strip().splitlines()), 1, p.stderr)
        self.assertEqual(open(out).read(), "keep me")


if __name__ == "__main__":
    result = cli_tests.run_with_sheetgen(sys.modules[__name__])
    print("hard cases: %d passed, %d failed" % (result.testsRun - len(result.failures) - len(result.errors) - len(result.skipped),
                                               len(result.failures) + len(result.errors)))
    sys.exit(0 if result.wasSuccessful() else 1)
