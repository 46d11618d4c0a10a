#!/usr/bin/python3
"""Whole `sheetgen solve` per sample problem (issue 6 benchmark): wall time,
the stages from result.json, and the peak resident memory of the process
(os.wait4's ru_maxrss, the kernel's own count).

Usage: PYTHONPATH=tools /usr/bin/python3 bench/solve_bench.py [--sheetgen build/native/cli/sheetgen]
           [--problems corner,corner_obstacle,slanted] [--threads 2] [--chains 10] [--iterations 1000]
Prints a Markdown table (for docs/benchmarks.md). One solve at a time.
"""
import argparse
import os
import platform
import sys

from sheetgen_tools import paths, runner


def run(sheetgen, problem, threads, chains, iterations):
    """One solve in a fresh folder: wall, CPU and stage times (s), the solver's peak memory (MiB)."""
    options = runner.SolveOptions(threads=threads, chains=chains, iterations=iterations, sheetgen=sheetgen)
    solved = runner.solve(problem, options=options).check()
    parts = solved.parts
    stage = lambda k: sum(p["timing"][k] for p in parts)  # noqa: E731
    return {"wall": solved.wall_s, "exit": solved.exit_code, "peak_mb": solved.peak_rss_mb, "cpu": solved.cpu_s,
            "discovery": stage("discovery_s"), "composition": stage("composition_s"), "loads": len(parts),
            "ok": sum(p["status"] == "ok" for p in parts)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    ap.add_argument("--problems", default="corner,corner_obstacle,slanted")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--chains", type=int, default=10)
    ap.add_argument("--iterations", type=int, default=1000)
    args = ap.parse_args()
    print("Machine: %s, %d cores, %s; load average before: %.2f" %
          (platform.processor() or platform.machine(), os.cpu_count(), platform.platform(), os.getloadavg()[0]))
    print()
    print("| problem | loads ok | wall time (s) | discovery (s) | composition (s) | CPU time (s) | peak memory (MB) |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for name in args.problems.split(","):
        problem = paths.scene_problem(name)
        r = run(args.sheetgen, problem, args.threads, args.chains, args.iterations)
        print("| %s | %d/%d | %.1f | %.1f | %.1f | %.1f | %.0f |" % (name, r["ok"], r["loads"], r["wall"], r["discovery"],
                                                                 r["composition"], r["cpu"], r["peak_mb"]), flush=True)


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"solve_bench: {e}")
