#!/usr/bin/python3
"""What the load envelope costs: one sheetgen binary solves a scene twice in one
run, as given (its FAR 25.561 envelope, buckling and frequency floors) and with
the one 9 g downward force the sample scenes had before their envelopes
(`sheetgen_tools.problem.single_force`), and prints per load and in total the
wall time, sheet, mass and bends of both, and the ratios (docs/benchmarks.md
"Envelope against one case").

Usage: PYTHONPATH=tools /usr/bin/python3 bench/envelope_bench.py [--scene avionics_bay]
           [--sheetgen build/native/cli/sheetgen] [--threads 2] [--out DIR]

The one-case problem is written to OUT/one_case/problem.json and each solve
keeps its output folder under OUT, so their parts can be checked. Exits 1
when a run fails.
"""
import argparse
import json
import os
import sys
import tempfile

from sheetgen_tools import paths, runner
from sheetgen_tools.problem import single_force


def totals(result):
    """(loads with a part, loads, cm^2, kg, bends) of a result.json."""
    ok = [p for p in result["parts"] if p["status"] == "ok"]
    return (len(ok), len(result["parts"]), sum(p["area_m2"] for p in ok) * 1e4, sum(p["mass_kg"] for p in ok),
            sum(p["bends"] for p in ok))


def per_load(run):
    """{load: (status, cm^2, total s)} of a run."""
    return {p["load"]: (p["status"], p.get("area_m2", 0.0) * 1e4, p["timing"]["total_s"]) for p in run.result["parts"]}


def solve(problem, out_dir, args):
    run = runner.solve(problem, out_dir, runner.SolveOptions(threads=args.threads, sheetgen=args.sheetgen))
    if run.result is None:
        sys.exit(f"{problem}: sheetgen exited {run.exit_code} without a result.json: {run.stderr.strip()[-300:]}")
    return run


def print_report(scene, one, env):
    print(f"Scene {scene}, binary {one.command[0]}, both runs one after the other\n")
    print("| load | one case: status, cm², s | envelope: status, cm², s |")
    print("| --- | --- | --- |")
    a, b = per_load(one), per_load(env)
    for load in b:
        print("| %s | %s, %.1f, %.1f | %s, %.1f, %.1f |" % ((load,) + a.get(load, ("-", 0, 0)) + b[load]))
    (n1, m1, area1, kg1, bends1), (n2, m2, area2, kg2, bends2) = totals(one.result), totals(env.result)
    print()
    print(f"One case: {n1}/{m1} parts, {area1:.1f} cm², {kg1:.3f} kg, {bends1} bends, wall {one.wall_s:.1f} s")
    print(f"Envelope: {n2}/{m2} parts, {area2:.1f} cm², {kg2:.3f} kg, {bends2} bends, wall {env.wall_s:.1f} s")
    print(f"Envelope over one case: wall {env.wall_s / one.wall_s:.2f}, sheet {area2 / area1:.3f}, mass {kg2 / kg1:.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scene", default="avionics_bay")
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--out", default=None, help="folder for the two outputs (default: a fresh temporary one)")
    args = ap.parse_args()
    out = args.out or tempfile.mkdtemp(prefix="envelope_bench_")
    problem = paths.scene_problem(args.scene)
    with open(problem) as f:
        doc = json.load(f)
    os.makedirs(os.path.join(out, "one_case"), exist_ok=True)
    one_problem = os.path.join(out, "one_case", "problem.json")
    with open(one_problem, "w") as f:
        json.dump(single_force(doc, os.path.dirname(problem)), f)
    one = solve(one_problem, os.path.join(out, "one_case", "out"), args)
    env = solve(problem, os.path.join(out, "envelope"), args)
    print_report(args.scene, one, env)


if __name__ == "__main__":
    main()
