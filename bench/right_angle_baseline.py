#!/usr/bin/python3
"""Free angles against `--right-angles` on every single-load scene of the
library, at each problem's own settings (10 chains x 1000 iterations, beam 8,
seed 1): the issue-6 comparison "on all sample problems", as a table.

The right-angle run is the stand-in for the expert's practice the paper
compares against (every bend 90 deg +- 0.5 deg, no skew). Material saved is
reported only where both runs have a valid part; the other rows say why the
run that failed failed (the reason line of `sheetgen solve`).

    PYTHONPATH=tools /usr/bin/python3 bench/right_angle_baseline.py [--scenes a,b] [--out DIR]

Writes DIR/right_angle_baseline.md (default build/right_angle_baseline/) and
keeps each run's output folder next to it, so `python3 -m sheetgen_tools.verify`
can check the parts. One solve at a time; about 10 minutes on 2 cores.
"""
import argparse
import os
import sys
import time

from sheetgen_tools import paths, runner
from sheetgen_tools.scenes import LIBRARY

# Every single-load scene of the library (the bay has its own baseline, bench/gauge_baseline.py).
SCENES = ",".join(s for s in LIBRARY if s != "avionics_bay")


def solve(sheetgen, problem, out, flags):
    """One run at the problem's own settings, 2 threads; SolveError unless sheetgen finished."""
    solved = runner.solve(problem, out, runner.SolveOptions(flags=tuple(flags), sheetgen=sheetgen)).check()
    part = solved.parts[0]
    return {"ok": part.get("status") == "ok", "area_cm2": part.get("area_m2", 0.0) * 1e4,
            "bends": part.get("bends", 0), "reason": part.get("reason", ""), "wall_s": solved.wall_s}


def cell(r):
    if r["ok"]:
        return "%.0f cm², %d bends, %.0f s" % (r["area_cm2"], r["bends"], r["wall_s"])
    return "no part (%.0f s)" % r["wall_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default=SCENES)
    ap.add_argument("--out", default=os.path.join(paths.DEFAULT_BUILD, "right_angle_baseline"))
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows, reasons = [], []
    both_free = both_ra = 0.0
    for scene in args.scenes.split(","):
        problem = paths.scene_problem(scene)
        free = solve(args.sheetgen, problem, os.path.join(args.out, scene, "free"), [])
        ra = solve(args.sheetgen, problem, os.path.join(args.out, scene, "right_angles"), ["--right-angles"])
        saved = "n/a"
        if free["ok"] and ra["ok"]:
            saved = "%.1f %%" % (100.0 * (free["area_cm2"] / ra["area_cm2"] - 1.0))
            both_free += free["area_cm2"]
            both_ra += ra["area_cm2"]
        rows.append(f"| {scene} | {cell(free)} | {cell(ra)} | {saved} |")
        for label, r in (("free", free), ("right angles", ra)):
            if not r["ok"]:
                reasons.append(f"* {scene}, {label}: {r['reason']}")
        print(rows[-1], flush=True)
    md = ["# Free angles vs right angles on the scene library", "",
          f"`bench/right_angle_baseline.py`, {time.strftime('%Y-%m-%d %H:%M')}, each problem's own settings, 2 threads.", "",
          "| scene | free angles | right angles | material (free vs right angles) |", "| --- | --- | --- | --- |"]
    md += rows
    if both_ra > 0:
        md += ["", "Over the scenes both runs solve: free %.0f cm², right angles %.0f cm² (%.1f %%)."
               % (both_free, both_ra, 100.0 * (both_free / both_ra - 1.0))]
    md += ["", "Why the runs without a part have none:", ""] + reasons
    path = os.path.join(args.out, "right_angle_baseline.md")
    with open(path, "w") as f:
        f.write("\n".join(md) + "\n")
    print("wrote " + path)


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"right_angle_baseline: {e}")
