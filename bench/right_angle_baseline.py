#!/usr/bin/python3
"""Free angles against `--right-angles` on every single-load scene of the
library, at each problem's own settings (10 chains x 1000 iterations, beam 8,
seed 1): the issue-6 comparison "on all sample problems", as a table.

The right-angle run is the stand-in for the expert's practice the paper
compares against (every bend 90 deg +- 0.5 deg, no skew). Material saved is
reported only where both runs have a valid part; the other rows say why the
run that failed failed (the reason line of `sheetgen solve`).

    /usr/bin/python3 bench/right_angle_baseline.py [--scenes a,b] [--out DIR]

Writes DIR/right_angle_baseline.md (default build/right_angle_baseline/) and
keeps each run's output folder next to it, so `tests/python/verify_result.py`
can check the parts. One solve at a time; about 10 minutes on 2 cores.
"""
import argparse
import json
import os
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = "shelf,corner,wall_standoff,corner_obstacle,slanted,sharp_angles,boxed_in,bulkhead_hole,maze"


def run(sheetgen, problem, out, extra, who="right_angle_baseline"):
    """`sheetgen solve PROBLEM --out OUT --threads 2 EXTRA`: (result.json, wall time s).
    Exits with the solver's output unless it exited 0 or 2 (a load without a part)."""
    start = time.monotonic()
    p = subprocess.run([sheetgen, "solve", problem, "--out", out, "--threads", "2"] + extra,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, stdin=subprocess.DEVNULL)
    wall = time.monotonic() - start
    if p.returncode not in (0, 2):
        raise SystemExit(f"{who}: {problem}: sheetgen exited {p.returncode}:\n{p.stdout[-2000:]}")
    with open(os.path.join(out, "result.json")) as f:
        return json.load(f), wall


def solve(sheetgen, problem, out, extra):
    result, wall = run(sheetgen, problem, out, extra)
    part = result["parts"][0]
    return {"ok": part.get("status") == "ok", "area_cm2": part.get("area_m2", 0.0) * 1e4,
            "bends": part.get("bends", 0), "reason": part.get("reason", ""), "wall_s": wall}


def cell(r):
    if r["ok"]:
        return "%.0f cm², %d bends, %.0f s" % (r["area_cm2"], r["bends"], r["wall_s"])
    return "no part (%.0f s)" % r["wall_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default=SCENES)
    ap.add_argument("--out", default=os.path.join(ROOT, "build", "right_angle_baseline"))
    ap.add_argument("--sheetgen", default=os.path.join(ROOT, "build", "native", "cli", "sheetgen"))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    rows, reasons = [], []
    both_free = both_ra = 0.0
    for scene in args.scenes.split(","):
        problem = os.path.join(ROOT, "sample_scenes", scene, "problem.json")
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
    main()
