#!/usr/bin/python3
"""Whole `sheetgen solve` per sample problem (issue 6 benchmark): wall time,
the stages from result.json, and the peak resident memory of the process
(os.wait4's ru_maxrss, the kernel's own count).

Usage: bench/solve_bench.py [--sheetgen build/native/cli/sheetgen] [--problems corner,corner_obstacle,slanted]
                            [--threads 2] [--chains 10] [--iterations 1000]
Prints a Markdown table (for docs/benchmarks.md). One solve at a time.
"""
import argparse
import json
import os
import platform
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run(sheetgen, problem, threads, chains, iterations):
    out = tempfile.mkdtemp(prefix="sheetgen_bench_")
    cmd = [sheetgen, "solve", problem, "--out", out, "--threads", str(threads),
           "--chains", str(chains), "--iterations", str(iterations)]
    t0 = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - t0
    code = os.waitstatus_to_exitcode(status)
    doc = json.load(open(os.path.join(out, "result.json")))
    parts = doc["parts"]
    stage = lambda k: sum(p["timing"][k] for p in parts)
    return {"wall": wall, "exit": code, "peak_mb": usage.ru_maxrss / 1024.0, "cpu": usage.ru_utime + usage.ru_stime,
            "discovery": stage("discovery_s"), "composition": stage("composition_s"), "loads": len(parts),
            "ok": sum(p["status"] == "ok" for p in parts)}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", default=os.path.join(ROOT, "build", "native", "cli", "sheetgen"))
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
        problem = os.path.join(ROOT, "sample_scenes", name, "problem.json")
        r = run(args.sheetgen, problem, args.threads, args.chains, args.iterations)
        print("| %s | %d/%d | %.1f | %.1f | %.1f | %.1f | %.0f |" % (name, r["ok"], r["loads"], r["wall"], r["discovery"],
                                                                 r["composition"], r["cpu"], r["peak_mb"]), flush=True)


if __name__ == "__main__":
    main()
