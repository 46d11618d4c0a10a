#!/usr/bin/python3
"""The expert stand-in on a multi-load problem, completed with the next gauge up.

Our stand-in for the expert's practice is the solver restricted to right angles
(`--right-angles`, docs/results.md). On the avionics bay under its envelope it
finds no part for six of the ten loads at the problem's sheet (0.063 in): a
right-angle bracket of that sheet is too soft for them (docs/gauge_baseline.md).
A designer would then take the next standard 2024-T3 gauge. This script does
the same, so the bay gets a whole-bay total to set against the free-angle run:

1. the problem is solved with free angles (`sheetgen solve`, or --free reuses
   an output of the same problem);
2. the expert stand-in solves the loads one by one in the problem's order, as
   sheetgen does: each load alone with `--right-angles`, at the problem's
   sheet first and then at each standard gauge up (GAUGES_IN) until it has a
   part, with every part before it (both faces of its sheet, at its own
   thickness) as an obstacle, as sheetgen makes earlier parts obstacles;
3. material is compared by area and by mass (the gauges differ).

With --verify each part at a thicker gauge is checked by sheetgen_tools.verify
(brute-force clearance, rivet flanges, CalculiX, DXF) on its one-load run,
whose environment holds the parts before it. One solve at a time.

    PYTHONPATH=tools /usr/bin/python3 bench/gauge_baseline.py [--problem P] [--out DIR] [--free DIR] [--reuse]
                                                               [--verify] [--doc docs/gauge_baseline.md]

The doc's "## Reading" section, written by hand, is kept when the table is remade.
"""
import argparse
import json
import os
import sys
import time

from sheetgen_tools import paths, runner
from sheetgen_tools.geometry import part_faces
from sheetgen_tools.pictures import scene_picture
from sheetgen_tools.problem import load_problem, one_load_problem
from sheetgen_tools.verify import VerifyOptions, verify_output

INCH = 0.0254
# Standard 2024-T3 sheet thicknesses above 0.063 in (AMS-QQ-A-250/4 sizes), in.
GAUGES_IN = [0.071, 0.080, 0.090, 0.100, 0.125, 0.160]


def solve(sheetgen, problem, out, flags):
    """Solves at the problem's own settings, 2 threads; returns the wall time, s."""
    return runner.solve(problem, out, runner.SolveOptions(flags=tuple(flags), sheetgen=sheetgen)).check().wall_s


def read_result(out):
    with open(os.path.join(out, "result.json")) as f:
        return json.load(f)


def sheet_faces(part, thickness):
    """Both faces of a part's sheet (thickness m) as one inline problem mesh "part:<load>"."""
    V, F = part_faces(part, thickness)
    return {"name": "part:" + part["load"], "vertices": V.tolist(), "triangles": F.tolist()}


def verify(sheetgen, out):
    """sheetgen_tools.verify on one output folder: (passed, its summary line, its FAIL lines)."""
    report = verify_output(out, VerifyOptions(sheetgen=sheetgen))
    lines = report.text().splitlines()
    return report.ok, lines[-1], [l for l in lines if l.startswith("FAIL")]


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--problem", default=paths.scene_problem("avionics_bay"))
    ap.add_argument("--out", default=os.path.join(paths.DEFAULT_BUILD, "gauge_baseline"))
    ap.add_argument("--free", help="reuse this free-angle output folder of the same problem")
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    ap.add_argument("--verify", action="store_true",
                    help="check the stand-in's parts at a thicker gauge with sheetgen_tools.verify (CalculiX)")
    ap.add_argument("--doc", default=os.path.join(paths.ROOT, "docs", "gauge_baseline.md"))
    ap.add_argument("--reuse", action="store_true",
                    help="read a run's result.json from --out where it exists instead of solving again (its wall "
                         "time is the solver's own total_s)")
    return ap.parse_args()


def expert_stand_in(doc, problem_dir, base_t, args):
    """The expert stand-in, load by load in the problem's order (as sheetgen
    solves them): right angles at the problem's sheet, else the first gauge up
    that has a part; the parts before it are its obstacles. Every other load's
    box is lowered by the thickest gauge tried: its base tab may need that
    sheet, and an earlier part that passed just under the box at the
    problem's sheet would leave it no room (inertial_unit under the envelope,
    docs/gauge_baseline.md "Reading"). Returns
    ({load: {"part", "thickness" m, "dir"}}, every try as (load, thickness m, part, wall s))."""
    expert, obstacles, tries = {}, [], []
    for li, load in enumerate(doc["loads"]):
        name = load["name"]
        for t in [base_t] + [g * INCH for g in GAUGES_IN if g * INCH > base_t + 1e-9]:
            run_dir = os.path.join(args.out, "expert", f"{li:02d}_{name}_{t / INCH:.3f}in")
            os.makedirs(run_dir, exist_ok=True)
            path = os.path.join(run_dir, "problem.json")
            one_load_problem(doc, problem_dir, load, t, obstacles, path, base_room=max(GAUGES_IN) * INCH)
            if args.reuse and os.path.exists(os.path.join(run_dir, "out", "result.json")):
                wall = read_result(os.path.join(run_dir, "out"))["timing"]["total_s"]
            else:
                wall = solve(args.sheetgen, path, os.path.join(run_dir, "out"), ["--right-angles"])
            part = read_result(os.path.join(run_dir, "out"))["parts"][0]
            tries.append((name, t, part, wall))
            print(f"{name} at {t / INCH:.3f} in: {part['status']} "
                  f"{part.get('area_m2', 0) * 1e4:.1f} cm^2 {part.get('reason', '')[:120]} ({wall:.0f} s)", flush=True)
            if part["status"] == "ok":
                expert[name] = {"part": part, "thickness": t, "dir": os.path.join(run_dir, "out")}
                obstacles.append(sheet_faces(part, t))
                break
    return expert, tries


def comparison_table(doc, base_t, free, expert):
    """Per load and in total: free angles against the stand-in, by area and by mass."""
    md = ["| load | free angles, %.3f in | expert stand-in: right angles | gauge (in) | free vs stand-in, mass |" % (base_t / INCH),
          "| --- | --- | --- | --- | --- |"]
    tot = {"free_a": 0.0, "free_m": 0.0, "ex_a": 0.0, "ex_m": 0.0}
    complete = True
    for load in doc["loads"]:
        name = load["name"]
        f = free.get(name)
        f = f if f and f["status"] == "ok" else None
        e = expert.get(name)
        fcell = "%.0f cm², %.3f kg, %d bends" % (f["area_m2"] * 1e4, f["mass_kg"], f["bends"]) if f else "no part"
        if e:
            p = e["part"]
            ecell = "%.0f cm², %.3f kg, %d bends" % (p["area_m2"] * 1e4, p["mass_kg"], p["bends"])
            gauge = "%.3f" % (e["thickness"] / INCH)
        else:
            ecell, gauge = "no part at any gauge tried", "–"
        change = "%+.1f %%" % (100.0 * (f["mass_kg"] / e["part"]["mass_kg"] - 1.0)) if (e and f) else "–"
        md.append(f"| {name} | {fcell} | {ecell} | {gauge} | {change} |")
        # Totals over the loads both have a part for, so that they compare like with like.
        complete = complete and bool(e and f)
        if e and f:
            tot["free_a"] += f["area_m2"]
            tot["free_m"] += f["mass_kg"]
            tot["ex_a"] += e["part"]["area_m2"]
            tot["ex_m"] += e["part"]["mass_kg"]
    md += ["", "| total | free angles | expert stand-in | change |", "| --- | --- | --- | --- |",
           "| material (m²) | %.4f | %.4f | %+.1f %% |" % (tot["free_a"], tot["ex_a"], 100.0 * (tot["free_a"] / tot["ex_a"] - 1.0)),
           "| mass (kg) | %.3f | %.3f | %+.1f %% |" % (tot["free_m"], tot["ex_m"], 100.0 * (tot["free_m"] / tot["ex_m"] - 1.0))]
    if not complete:
        md += ["", "**Incomplete:** some load has no part on one side (for the stand-in: at no gauge tried); "
               "the totals leave that load out on both sides."]
    return md


def runs_and_checks(tries, checks, walls):
    """Every run of the stand-in, the independent checks, the wall times."""
    md = ["", "Every run of the stand-in (each load alone, the parts before it as obstacles):", ""]
    for name, t, part, wall in tries:
        what = ("ok, %.0f cm², C %.4g of %.4g J, MS %.2f" % (part["area_m2"] * 1e4, part["compliance"], part["compliance_limit"],
                                                            part["margin_of_safety"])
                if part["status"] == "ok" else part.get("reason", ""))
        md.append(f"* {name}, {t / INCH:.3f} in ({wall:.0f} s): {what}")
    if checks:
        md += ["", "Independent checks of the stand-in's thicker parts (`sheetgen_tools.verify`, "
               "the one-load problem with the other parts as obstacles):", ""]
        for name, (ok, last, fails) in checks.items():
            md.append(f"* {name}: {'passed' if ok else 'FAILED'}: `{last}`" + ("".join(f"; `{x}`" for x in fails[:3])))
    md += ["", "Wall time: " + ", ".join(f"{k} {v:.0f} s" for k, v in walls.items()) + "."]
    return md


def picture(args, doc, expert):
    """The stand-in's parts in the environment, drawn as docs/results.md draws a run; its markdown line."""
    prob, meshes = load_problem(args.problem)
    doc_dir = os.path.dirname(os.path.abspath(args.doc))
    path = os.path.join(doc_dir, "images", "gauge_baseline_scene.png")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    parts = [expert[l["name"]]["part"] for l in doc["loads"] if l["name"] in expert]
    scene_picture("expert stand-in (right angles, next gauge up)", prob, meshes, {"parts": parts}, path)
    return ["", "![the expert stand-in's parts](%s)" % os.path.relpath(path, doc_dir)]


def main():
    args = parse_args()
    os.makedirs(args.out, exist_ok=True)
    with open(args.problem) as f:
        doc = json.load(f)
    problem_dir = os.path.dirname(os.path.abspath(args.problem))
    base_t = doc.get("material", {}).get("thickness", 1.6e-3)

    walls = {}
    free_dir = args.free or os.path.join(args.out, "free")
    if not args.free:
        walls["free"] = solve(args.sheetgen, args.problem, free_dir, [])
    free = {p["load"]: p for p in read_result(free_dir)["parts"]}
    expert, tries = expert_stand_in(doc, problem_dir, base_t, args)
    walls["expert stand-in (its one-load runs)"] = sum(w for _, _, _, w in tries)

    checks = {}
    if args.verify:
        for name, e in expert.items():
            if e["thickness"] > base_t + 1e-9:  # the parts only this script makes
                checks[name] = verify(args.sheetgen, e["dir"])
                print(f"verify {name}: {checks[name][1]}", flush=True)

    md = ["# The expert stand-in with the next gauge up (avionics bay)", "",
          f"Made by `bench/gauge_baseline.py` on {time.strftime('%Y-%m-%d')} (2 cores, one solve at a time), "
          f"problem `{os.path.relpath(args.problem, paths.ROOT)}` at its own settings "
          f"({doc.get('search', {}).get('chains', 10)} chains x {doc.get('search', {}).get('iterations', 1000)} iterations).", ""]
    md += comparison_table(doc, base_t, free, expert) + runs_and_checks(tries, checks, walls) + picture(args, doc, expert)
    # A "## Reading" section written by hand below the generated part is kept.
    reading = ""
    if os.path.exists(args.doc):
        old = open(args.doc).read()
        if "\n## Reading" in old:
            reading = old[old.index("\n## Reading"):]
    with open(args.doc, "w") as f:
        f.write("\n".join(md) + "\n" + reading)
    print("wrote " + args.doc)


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"gauge_baseline: {e}")
