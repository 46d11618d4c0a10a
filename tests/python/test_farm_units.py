#!/usr/bin/python3
"""The pieces of sheetgen-farm without a cluster or the solver (docs/farm.md):
output names, resume decisions, the output lock, staging sweeps, publishing
(a second attempt never duplicates a result), timeouts and crashes of a
stand-in solver, and the summary's worst check.

Run: PYTHONPATH=tools /usr/bin/python3 -m unittest discover -s tests/python -p test_farm_units.py
"""
import json
import os
import stat
import tempfile
import textwrap
import unittest

from sheetgen_tools import runner
from sheetgen_tools.farm import plan, summary, task


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return path


PROBLEM = json.dumps({"format": "sheetgen-problem/1", "environment": {"meshes": [{"name": "w", "file": "wall.obj"}]},
                      "loads": [{"name": "a"}, {"name": "b"}], "search": {"chains": 3, "iterations": 7}})


class Names(unittest.TestCase):
    def test_stem_or_scene_folder(self):
        self.assertEqual(plan.output_name("/x/bay/bracket_03.json"), "bracket_03")
        self.assertEqual(plan.output_name("/x/corner/problem.json"), "corner")


class FarmFolder(unittest.TestCase):
    """Each test gets a temporary folder `root` with an empty output folder `out` in it."""
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.root = self.tmp.name
        self.out = os.path.join(self.root, "out")
        os.makedirs(self.out)

    def tearDown(self):
        self.tmp.cleanup()


class Plan(FarmFolder):
    def setUp(self):
        super().setUp()
        self.problem = write(os.path.join(self.root, "p", "corner", "problem.json"), PROBLEM)
        self.mesh = write(os.path.join(self.root, "p", "corner", "wall.obj"), "v 0 0 0\n")
        self.solve = runner.SolveOptions(threads=1, chains=2)

    def finish(self, **changes):
        """A farm.json as a solved task of an earlier run leaves it."""
        [p] = plan.plan([self.problem], self.out, self.solve)
        record = task.TaskRecord(name="corner", problem=self.problem, status="solved", run_id="earlier",
                                 inputs_sha256=p.inputs_sha256, settings=plan.solve_settings(self.solve))
        for k, v in changes.items():
            setattr(record, k, v)
        write(os.path.join(self.out, "corner", task.RECORD_FILE), json.dumps(record.to_json()))
        write(os.path.join(self.out, "corner", "result.json"), "{}")

    def test_work_is_loads_chains_iterations(self):
        [p] = plan.plan([self.problem], self.out, self.solve)
        self.assertEqual(p.work, 2 * 2 * 7)   # --chains 2 overrides the file's 3; its 7 iterations stay

    def test_same_file_twice_is_one_problem_two_files_one_name_refused(self):
        self.assertEqual(len(plan.plan([self.problem, self.problem], self.out, self.solve)), 1)
        other = write(os.path.join(self.root, "q", "corner.json"), PROBLEM)
        with self.assertRaises(plan.PlanError):
            plan.plan([self.problem, other], self.out, self.solve)

    def test_unreadable_file_is_planned_as_failed(self):
        [p] = plan.plan([os.path.join(self.root, "nope.json")], self.out, self.solve)
        self.assertIn("No such file", p.unreadable)

    def test_resume_skips_only_an_unchanged_solved_problem(self):
        self.finish()
        self.assertIsNotNone(plan.plan([self.problem], self.out, self.solve)[0].done)
        self.assertIsNone(plan.plan([self.problem], self.out, self.solve, force=True)[0].done)
        other = runner.SolveOptions(threads=4, chains=2)          # threads do not change the answer
        self.assertIsNotNone(plan.plan([self.problem], self.out, other)[0].done)
        other = runner.SolveOptions(threads=1, chains=2, seed=5)  # a seed does
        self.assertIsNone(plan.plan([self.problem], self.out, other)[0].done)
        write(self.mesh, "v 0 0 1\n")                             # an edited mesh file does
        self.assertIsNone(plan.plan([self.problem], self.out, self.solve)[0].done)

    def test_resume_solves_a_failed_problem_again(self):
        self.finish(status="failed")
        self.assertIsNone(plan.plan([self.problem], self.out, self.solve)[0].done)

    def test_resume_solves_a_problem_whose_result_json_is_gone(self):
        self.finish()
        os.remove(os.path.join(self.out, "corner", "result.json"))
        self.assertIsNone(plan.plan([self.problem], self.out, self.solve)[0].done)

    def test_second_run_on_the_same_folder_is_refused(self):
        with plan.OutputLock(self.out):
            with self.assertRaises(plan.PlanError):
                plan.OutputLock(self.out).__enter__()
        with plan.OutputLock(self.out):
            pass  # released

    def test_sweep_removes_staging_of_one_run_or_all(self):
        for name in (".a.farm-run1-x", ".b.farm-run1-y", ".a.farm-run2-z"):
            os.makedirs(os.path.join(self.out, name))
        os.makedirs(os.path.join(self.out, "a"))
        self.assertEqual(plan.sweep_staging(self.out, "run1"), 2)
        self.assertEqual(plan.sweep_staging(self.out), 1)
        self.assertEqual(os.listdir(self.out), ["a"])


# A stand-in for sheetgen: `FAKE solve PROBLEM --out DIR --threads T`, behaving as $FAKE_MODE says.
FAKE_SHEETGEN = textwrap.dedent("""\
    #!/bin/sh
    out="$4"
    case "$(cat "$2")" in
      ok) mkdir -p "$out/load" && echo '{"parts": []}' > "$out/result.json" && exit 0 ;;
      bad) echo "sheetgen: $2: loads: expected an array." >&2; exit 1 ;;
      hang) exec sleep 60 ;;
      crash) kill -SEGV $$ ;;
    esac
    """)


class Tasks(FarmFolder):
    def setUp(self):
        super().setUp()
        self.sheetgen = write(os.path.join(self.root, "sheetgen"), FAKE_SHEETGEN)
        os.chmod(self.sheetgen, stat.S_IRWXU)

    def task(self, mode, run_id="run1", timeout_s=None):
        problem = write(os.path.join(self.root, mode + ".json"), mode)
        return task.SolveTask(problem=problem, name=mode, out_root=self.out, timeout_s=timeout_s, run_id=run_id,
                              options=runner.SolveOptions(threads=1, sheetgen=self.sheetgen), settings={},
                              inputs_sha256="h")

    def test_solved_folder_is_published_with_its_record(self):
        record = task.solve_task(self.task("ok"))
        self.assertEqual(record.status, "solved")
        self.assertEqual(sorted(os.listdir(self.out)), ["ok"])
        self.assertEqual(task.read_record(os.path.join(self.out, "ok")).run_id, "run1")
        self.assertTrue(os.path.isfile(os.path.join(self.out, "ok", "result.json")))

    def test_second_attempt_of_a_run_is_dropped_an_earlier_runs_folder_replaced(self):
        first = task.solve_task(self.task("ok"))
        again = task.solve_task(self.task("ok"))           # e.g. its worker was declared dead but finished
        self.assertEqual(again.wall_s, first.wall_s)             # the first attempt's record
        self.assertEqual(sorted(os.listdir(self.out)), ["ok"])
        newer = task.solve_task(self.task("ok", run_id="run2"))
        self.assertEqual(task.read_record(os.path.join(self.out, "ok")).run_id, "run2")
        self.assertEqual(newer.run_id, "run2")
        self.assertEqual(sorted(os.listdir(self.out)), ["ok"])

    def test_bad_input_fails_with_sheetgens_line_and_keeps_the_log(self):
        record = task.solve_task(self.task("bad"))
        self.assertEqual(record.status, "failed")
        self.assertEqual(record.exit_code, 1)
        self.assertTrue(record.reason.endswith("loads: expected an array."), record.reason)
        self.assertEqual(os.listdir(self.out), ["bad" + task.FAILED_LOG])

    def test_timeout_ends_the_solver_and_leaves_no_folder(self):
        record = task.solve_task(self.task("hang", timeout_s=0.5))
        self.assertEqual(record.reason, "timed out after 0.5 s")
        self.assertLess(record.wall_s, 5.0)   # SIGTERM ended `sleep` at once; SIGKILL would come after TERM_GRACE_S
        self.assertEqual(os.listdir(self.out), ["hang" + task.FAILED_LOG])

    def test_crash_raises_for_dasks_retries(self):
        with self.assertRaisesRegex(task.SolverCrashed, "SIGSEGV"):
            task.solve_task(self.task("crash"))
        self.assertEqual(os.listdir(self.out), [])


def part(compliance, limit, ms, buckling=None, frequency=None, required=None):
    return {"load": "box", "status": "ok", "mass_kg": 0.25, "compliance": compliance, "compliance_limit": limit,
            "margin_of_safety": ms, "envelope": {"buckling_factor": buckling, "frequencies_hz": [frequency],
                                                 "required": required or {"checked": False}}}


class Summary(unittest.TestCase):
    def test_utilisations(self):
        checks = dict(summary.part_checks(part(0.3, 0.4, 1.0)))
        self.assertAlmostEqual(checks["stiffness"], 0.75)
        self.assertAlmostEqual(checks["strength"], 0.5)          # stress x safety factor / allowable = 1 / (1 + MS)
        self.assertAlmostEqual(dict(summary.part_checks(part(0.3, 0.4, 1.0), min_margin=0.2))["strength"], 0.6)
        self.assertNotIn("buckling", checks)                     # not asked for
        required = {"checked": True, "min_buckling_factor": 1.5, "min_frequency_hz": 25.0}
        checks = dict(summary.part_checks(part(0.3, 0.4, 1.0, buckling=2.0, frequency=20.0, required=required)))
        self.assertAlmostEqual(checks["buckling"], 0.75)
        self.assertAlmostEqual(checks["frequency"], 1.25)

    def test_worst_check_and_exit_codes(self):
        row = summary.Row(problem="p", status="")
        summary._fill_from_result(row, {"parts": [part(0.3, 0.4, 1.0), dict(part(0.1, 0.4, 0.1), load="tray")]}, 0.0)
        self.assertEqual((row.status, row.worst_check, row.worst_load), ("ok", "strength", "tray"))
        self.assertAlmostEqual(row.worst_utilisation, 1 / 1.1)
        self.assertAlmostEqual(row.mass_kg, 0.5)
        ok, none, failed = (summary.Row(problem=s, status=s) for s in ("ok", "no part", "failed"))
        self.assertEqual(summary.exit_code([ok], False), 0)
        self.assertEqual(summary.exit_code([ok, none], False), 2)
        self.assertEqual(summary.exit_code([ok, none, failed], False), 3)
        self.assertEqual(summary.exit_code([ok], True), 130)


if __name__ == "__main__":
    unittest.main()
