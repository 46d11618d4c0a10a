#!/usr/bin/python3
"""sheetgen-farm against one solve after another (issue 36 benchmark), and a
model of larger farms (docs/farm.md "Speed").

1. serial: `sheetgen solve --threads 2` on each problem, one after another
   (the way one machine solves a batch without the farm);
2. farm: `sheetgen-farm` on all of them with its local cluster at its default
   size (cores / 1 thread per task), wall time of the whole command (Python
   start, cluster start, solves, summary);
3. the ratio serial / farm, and whether every farm result.json equals its
   serial one (timing fields aside, as tests/python/test_farm.py compares);
4. the model: each problem's one-thread solve time t_i from the farm's
   farm.json, N problems as copies of the measured ones, W workers of one
   core each; the farm's policy (largest loads x chains x iterations first,
   each task to the first free worker) simulated, beside the lower bound
   max(sum t / W, max t); plus the farm's own overhead measured in step 2.

Usage: PYTHONPATH=tools /usr/bin/python3 bench/farm_bench.py [--sheetgen build/native/cli/sheetgen]
           [--problems corner,shelf,...] [--out DIR] [--model-problems 300] [--model-workers 10,100]
Prints Markdown for docs/farm.md. Run it alone: both steps use every core.
"""
import argparse
import heapq
import json
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import time

from sheetgen_tools import paths, runner
from sheetgen_tools.farm import plan as farm_plan


def result_of(out_dir):
    with open(os.path.join(out_dir, "result.json")) as f:
        return runner.strip_timing(json.load(f), out_dir)


def folder_mb(path):
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(path) for f in files) / 1e6


def serial(problems, sheetgen, root):
    """{name: SolveRun} of `sheetgen solve --threads 2`, one after another."""
    runs = {}
    for name, problem in problems.items():
        runs[name] = runner.solve(problem, os.path.join(root, name),
                                  runner.SolveOptions(threads=2, sheetgen=sheetgen)).check()
        print(f"  serial {name}: {runs[name].wall_s:.1f} s", file=sys.stderr, flush=True)
    return runs


def farm(problems, farm_cmd, out):
    """(wall s of the whole command, its exit code, {name: farm.json})."""
    t0 = time.monotonic()
    run = subprocess.run([farm_cmd, *problems.values(), "--out", out], stdout=subprocess.PIPE, text=True)
    wall = time.monotonic() - t0
    print(run.stdout, file=sys.stderr, flush=True)
    records = {}
    for name in problems:
        with open(os.path.join(out, name, "farm.json")) as f:
            records[name] = json.load(f)
    return wall, run.returncode, records


def makespan(times, workers):
    """The farm's policy: tasks in the given order (largest work first), each to the first free worker."""
    free = [0.0] * workers
    for t in times:
        heapq.heapreplace(free, free[0] + t)
    return max(free)


def model_rows(jobs, overhead_s, serial_total, n_problems, worker_counts):
    """jobs: [(work, t one thread s)] of the measured problems; copies up to n_problems."""
    copies = [jobs[i % len(jobs)] for i in range(n_problems)]
    ordered = [t for _, t in sorted(copies, key=lambda j: -j[0])]  # stable: the farm's priority, ties as given
    total, longest = sum(ordered), max(ordered)
    serial_n = serial_total * n_problems / len(jobs)
    rows = []
    for w in worker_counts:
        span = makespan(ordered, w) + overhead_s
        bound = max(total / w, longest)
        rows.append((w, span, bound, serial_n / span, total / (w * span)))
    return rows, serial_n


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    ap.add_argument("--farm", help="default: sheetgen-farm beside --sheetgen")
    ap.add_argument("--problems", default=",".join(paths.sample_scene_names()))
    ap.add_argument("--out", help="keep the outputs here (default: a temporary folder, removed)")
    ap.add_argument("--model-problems", type=int, default=300)
    ap.add_argument("--model-workers", default="10,100")
    args = ap.parse_args()
    sheetgen = os.path.abspath(args.sheetgen)
    farm_cmd = os.path.abspath(args.farm or os.path.join(os.path.dirname(sheetgen), "sheetgen-farm"))
    problems = {n: paths.scene_problem(n) for n in args.problems.split(",")}
    root = args.out or tempfile.mkdtemp(prefix="farm_bench_")
    load_before = os.getloadavg()
    try:
        serial_runs = serial(problems, sheetgen, os.path.join(root, "serial"))
        serial_total = sum(r.wall_s for r in serial_runs.values())
        farm_wall, farm_exit, records = farm(problems, farm_cmd, os.path.join(root, "farm"))
        same = sum(result_of(os.path.join(root, "farm", n)) == result_of(serial_runs[n].out_dir) for n in problems)
        out_mb = {n: folder_mb(os.path.join(root, "farm", n)) for n in problems}
    finally:
        if not args.out:
            shutil.rmtree(root, ignore_errors=True)
    load_after = os.getloadavg()
    commit = subprocess.run(["git", "-C", paths.ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    busy = {}
    for r in records.values():
        busy[r["worker"]] = busy.get(r["worker"], 0.0) + r["wall_s"]
    overhead = farm_wall - max(busy.values())

    print(f"Machine: {platform.machine()}, {os.cpu_count()} cores, {platform.platform()}; commit {commit}; "
          f"load average {load_before[0]:.2f} before, {load_after[0]:.2f} after\n")
    print("| problem | loads | serial, 2 threads (s) | farm, 1 thread (s) | farm CPU (s) | worker | output (MB) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for n in problems:
        r = records[n]
        loads = len(serial_runs[n].parts)
        print(f"| {n} | {loads} | {serial_runs[n].wall_s:.1f} | {r['wall_s']:.1f} | {r['cpu_s']:.1f} | "
              f"{r['worker'].rsplit('/', 1)[-1]} | {out_mb[n]:.1f} |")
    print(f"\nserial total **{serial_total:.1f} s**; farm ({len(busy)} workers, exit {farm_exit}) **{farm_wall:.1f} s**; "
          f"ratio serial / farm **{serial_total / farm_wall:.2f}**; busiest worker {max(busy.values()):.1f} s, "
          f"farm overhead (start, scheduling, summary) {overhead:.1f} s; "
          f"same result.json as serial: {same}/{len(problems)}\n")

    jobs = []
    for n, problem in problems.items():
        [p] = farm_plan.plan([problem], root, runner.SolveOptions())
        jobs.append((p.work, records[n]["wall_s"]))
    measured_order = [t for _, t in sorted(jobs, key=lambda j: -j[0])]
    print(f"The policy simulated on the measured run: {makespan(measured_order, len(busy)):.1f} s of solving "
          f"(measured busiest worker {max(busy.values()):.1f} s)\n")
    workers = [int(w) for w in args.model_workers.split(",")]
    rows, serial_n = model_rows(jobs, overhead, serial_total, args.model_problems, [len(busy)] + workers)
    print(f"Model: {args.model_problems} problems ({args.model_problems / len(jobs):g} copies of each), "
          f"one solve per one-core worker at the one-thread times above, plus the measured overhead "
          f"{overhead:.1f} s; serial (2 threads, one 2-core machine) {serial_n / 3600:.2f} h\n")
    print("| workers | farm makespan (s) | lower bound max(Σt/W, max t) (s) | speed-up over serial | worker use |")
    print("| --- | --- | --- | --- | --- |")
    for w, span, bound, speedup, use in rows:
        print(f"| {w} | {span:.0f} | {bound:.0f} | {speedup:.1f} | {use:.0%} |")
    json.dump({"commit": commit, "serial_s": {n: r.wall_s for n, r in serial_runs.items()}, "farm_wall_s": farm_wall,
               "farm": records, "overhead_s": overhead, "same": same}, sys.stderr, indent=1)


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"farm_bench: {e}")
