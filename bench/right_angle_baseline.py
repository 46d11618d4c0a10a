#!/usr/bin/python3
"""Free angles against `--right-angles` on the scene library, load by load,
at each problem's own settings: is the free search ever heavier than the
right-angle search, which explores a subset of its parts?

The right-angle run is the stand-in for the expert's practice the paper
compares against (every bend 90 deg +- 0.5 deg, no skew, plates widened by flat
extensions). The free grammar contains every such part only when flat
extensions are on, so `--modes` can add a free run with `--flat-extensions`.
A row says "heavier" when the free area exceeds the right-angle area by more
than 1 % (the noise allowance of the comparison). Each other row says why a run
without a part has none (the reason line of `sheetgen solve`).

    PYTHONPATH=tools /usr/bin/python3 bench/right_angle_baseline.py \
        [--scenes a,b] [--modes free,flat,right] [--threads N] [--seed N] [--out DIR]

Writes DIR/right_angle_baseline.md (default build/right_angle_baseline/) and
keeps each run's output folder next to it, so `python3 -m sheetgen_tools.verify`
can check the parts. One solve at a time; the nine single-load scenes take
about 10 minutes on 2 cores, the bay about 10 more per mode.
"""
import argparse
import csv
import json
import math
import os
import sys
import time

from sheetgen_tools import paths, runner
from sheetgen_tools.scenes import LIBRARY

MODES = {  # name: (column title, sheetgen solve flags)
    "free": ("free angles", ()),
    "flat": ("free angles + flat extensions", ("--flat-extensions",)),
    "right": ("right angles", ("--right-angles",)),
}
NOISE = 0.01  # the free area may exceed the right-angle area by this share before a row says "heavier"


def min_bend_angle_deg(problem):
    """The problem's manufacturing.min_bend_angle in degrees (the solver's default, 5 deg, when absent: docs/cost.md)."""
    with open(problem, encoding="utf-8") as f:
        return math.degrees(json.load(f).get("manufacturing", {}).get("min_bend_angle", math.radians(5.0)))


def bends_at_lower_limit(limit_deg, part_dir):
    """How many bends of a part's bend table (part_dir/bends.csv) lie within 0.5 deg of the lower limit
    limit_deg: the bends a free search uses where a flat extension would do."""
    with open(os.path.join(part_dir, "bends.csv"), newline="", encoding="utf-8") as f:
        return sum(1 for row in csv.DictReader(f) if abs(float(row["angle_deg"])) < limit_deg + 0.5)


def solve(args, problem, out, flags):
    """One run at the problem's own settings (seed: --seed when given): {load name: part summary};
    SolveError unless sheetgen finished."""
    solved = runner.solve(problem, out, runner.SolveOptions(threads=args.threads, seed=args.seed, flags=tuple(flags),
                                                            sheetgen=args.sheetgen)).check()
    limit_deg = min_bend_angle_deg(problem)
    parts = {}
    for part in solved.parts:
        load, ok = part.get("load", ""), part.get("status") == "ok"
        parts[load] = {"ok": ok, "area_cm2": part.get("area_m2", 0.0) * 1e4, "bends": part.get("bends", 0),
                       "at_limit": bends_at_lower_limit(limit_deg, os.path.join(out, load)) if ok else 0,
                       "reason": part.get("reason", "")}
    return parts, solved.wall_s


def cell(r):
    if r["ok"]:
        limit = " (%d at the lower limit)" % r["at_limit"] if r["at_limit"] else ""
        return "%.0f cm², %d bends%s" % (r["area_cm2"], r["bends"], limit)
    return "no part"


def verdict(row, mode):
    """One free run against the right-angle run of the same load: 'ok', 'heavier' or 'n/a'."""
    if not row["right"]["ok"]:
        return "n/a"
    if not row[mode]["ok"]:
        return "heavier (no part)"
    change = row[mode]["area_cm2"] / row["right"]["area_cm2"] - 1.0
    return "%s (%+.1f %%)" % ("heavier" if change > NOISE else "ok", 100.0 * change)


def run_scene(args, scene, modes):
    """Every mode on one scene: ({load: {mode: part}}, {mode: wall s})."""
    rows, walls = {}, {}
    for mode in modes:
        parts, walls[mode] = solve(args, paths.scene_problem(scene), os.path.join(args.out, scene, mode),
                                   MODES[mode][1])
        for load, part in parts.items():
            rows.setdefault(load, {})[mode] = part
    return rows, walls


def table(args, modes):
    """The markdown lines: one row per load, then the walls and the reasons."""
    compared = [m for m in modes if m != "right"] if "right" in modes else []
    head = ("| scene | load | " + " | ".join(MODES[m][0] for m in modes) + " |" +
            "".join(" %s vs right angles |" % MODES[m][0] for m in compared))
    lines = [head, "|" + " --- |" * (len(modes) + len(compared) + 2)]
    walls, reasons = [], []
    for scene in args.scenes.split(","):
        rows, wall = run_scene(args, scene, modes)
        walls.append("* %s: " % scene + ", ".join("%s %.0f s" % (MODES[m][0], wall[m]) for m in modes))
        for load, row in rows.items():
            lines.append(f"| {scene} | {load} | " + " | ".join(cell(row[m]) for m in modes) + " |" +
                         "".join(" %s |" % verdict(row, m) for m in compared))
            print(lines[-1], flush=True)
            reasons += [f"* {scene} / {load}, {MODES[m][0]}: {row[m]['reason']}" for m in modes if not row[m]["ok"]]
    lines += ["", "Wall time of each run:", ""] + walls
    if reasons:
        lines += ["", "Why the runs without a part have none:", ""] + reasons
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default=",".join(LIBRARY))
    ap.add_argument("--modes", default="free,right", help="comma-separated: " + ", ".join(MODES))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=None, help="search seed (default: each problem's own)")
    ap.add_argument("--out", default=os.path.join(paths.DEFAULT_BUILD, "right_angle_baseline"))
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    args = ap.parse_args()
    modes = args.modes.split(",")
    unknown = [m for m in modes if m not in MODES]
    if unknown:
        sys.exit("right_angle_baseline: --modes: unknown mode %s (known: %s)" % (unknown[0], ", ".join(MODES)))
    os.makedirs(args.out, exist_ok=True)
    md = ["# Free angles vs right angles on the scene library", "",
          f"`bench/right_angle_baseline.py --modes {args.modes}`, {time.strftime('%Y-%m-%d %H:%M')}, "
          f"each problem's own settings, seed {args.seed or 'of the problem'}, {args.threads} threads.", ""] + table(args, modes)
    path = os.path.join(args.out, "right_angle_baseline.md")
    with open(path, "w") as f:
        f.write("\n".join(md) + "\n")
    print("wrote " + path)


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"right_angle_baseline: {e}")
