#!/usr/bin/python3
"""Self-riveting ablation (paper Fig. 9), written to docs/ablation_self_rivet.md (+ PNG).

The paper's setting: a light load close to a wall, far from the floor, where the
wall is the only near structure and a springboard from it is too compliant. Our
`wall_standoff` scene has a 250 mm tall wall rivet area, tall enough for a second
wall flange to close the triangle a gusset would (docs/ablation_composition.md,
"Reading"). Here its wall rivet area is cut to a strip (default z = 0.50-0.60 m,
100 mm: the flange of a frame or a doubler, spanning the box's bottom at 0.57 m),
the box made light (masses swept, default 0.5, 0.4, 0.35 and 0.3 kg at 9 g),
and the deflection limit swept. Per mass, limit and seed the problem is solved
with and without self-riveting
(`--no-self-rivet`); with --verify every self-riveted part is checked by
sheetgen_tools.verify (brute-force clearance, rivet flanges, CalculiX, DXF).

Usage: PYTHONPATH=tools /usr/bin/python3 bench/ablation_self_rivet.py [--build build] [--seeds 1,2,3]
       [--limits 4,3,2,1] [--strip 0.50,0.60] [--masses 0.5,0.4,0.35,0.3] [--quick] [--verify]
One solve at a time (the machine has 2 cores); --quick uses 6 chains x 400 iterations,
the default is the paper's 10 x 1000.
"""
import argparse
import json
import os
import sys
import tempfile
import time

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ablation_composition import solve  # noqa: E402  (bench/, this script's own folder)
from sheetgen_tools import paths, runner  # noqa: E402
from sheetgen_tools.pictures import box_faces  # noqa: E402
from sheetgen_tools.problem import problem_of_result, read_obj, with_absolute_files  # noqa: E402
from sheetgen_tools.scenes import G  # noqa: E402  (m/s^2, as the sample scenes' forces)
from sheetgen_tools.verify import VerifyOptions, verify_output  # noqa: E402

ROOT = paths.ROOT


def strip_problem(scene_dir, z_lo, z_hi, mass, limit, out_dir):
    """wall_standoff with its wall rivet area cut to the faces within z_lo..z_hi (m),
    a box of `mass` kg at 9 g and the deflection limit `limit` (m)."""
    doc = with_absolute_files(json.load(open(os.path.join(scene_dir, "problem.json"))), scene_dir)
    meshes = {m["name"]: m for m in doc["environment"]["meshes"]}
    wall = next(ra for ra in doc["rivet_areas"] if ra["name"] == "wall_rivets")
    V, F = read_obj(meshes[wall["mesh"]]["file"])
    wall["faces"] = [f for f in wall["faces"] if all(z_lo - 1e-9 <= V[i][2] <= z_hi + 1e-9 for i in F[f])]
    if not wall["faces"]:
        sys.exit(f"ablation_self_rivet: --strip {z_lo},{z_hi}: no wall rivet face lies within it")
    (load,) = doc["loads"]
    load["force"] = [0.0, 0.0, -mass * 9 * G]
    doc["requirements"]["max_deflection"] = limit
    doc["description"] = (f"wall_standoff, wall rivet area cut to z = {z_lo:.2f}-{z_hi:.2f} m, {mass:g} kg at 9 g, "
                          f"deflection limit {limit * 1e3:g} mm (bench/ablation_self_rivet.py)")
    path = os.path.join(out_dir, "problem.json")
    json.dump(doc, open(path, "w"), indent=1)
    return path, len(wall["faces"])


def verify(build, out):
    """sheetgen_tools.verify on one output: (passed, its compliance line, its FAIL lines)."""
    report = verify_output(out, VerifyOptions(sheetgen=paths.sheetgen_in(build)))
    lines = report.text().splitlines()
    comp = next((l.split(": ", 1)[1] for l in lines if "compliance ours" in l), "")
    return report.ok, comp, [l for l in lines if l.startswith("FAIL")]


def parts_picture(row, path):
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    mass, limit, seed, a, b, _ = row
    fig = plt.figure(figsize=(11, 5))
    for k, (label, run) in enumerate([("with self-riveting", a), ("without", b)]):
        result = json.load(open(os.path.join(run["out"], "result.json")))
        prob = json.load(open(problem_of_result(run["out"], result)))
        (part,) = result["parts"]
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        ax.computed_zorder = False
        for ra in prob["rivet_areas"]:
            mesh = next(m for m in prob["environment"]["meshes"] if m["name"] == ra["mesh"])
            V, F = read_obj(mesh["file"])
            ax.add_collection3d(Poly3DCollection([[V[i] for i in F[f]] for f in ra["faces"]], facecolor=(0.2, 0.75, 0.3, 0.3),
                                                 edgecolor="none", zorder=1))
        ax.add_collection3d(Poly3DCollection(box_faces(prob["loads"][0]), facecolor=(1.0, 0.6, 0.15, 0.3),
                                             edgecolor=(0.7, 0.35, 0.0, 0.8), linewidth=0.5, zorder=2))
        polys = [t["corners"] for t in part["tabs"]]
        ax.add_collection3d(Poly3DCollection(polys, facecolor="#d4a017", alpha=0.95, edgecolor="black", linewidth=0.4, zorder=3))
        for pts, colour in ((part.get("rivets", []), "k"), ([t["points"][0] for t in part.get("self_rivets", [])], "r")):
            if pts:
                P = [list(q) for q in pts]
                ax.scatter([q[0] for q in P], [q[1] for q in P], [q[2] for q in P], s=8, c=colour, depthshade=False, zorder=4)
        P = [c for poly in polys for c in poly]
        lo = [min(c[i] for c in P) for i in range(3)]
        hi = [max(c[i] for c in P) for i in range(3)]
        mid = [0.5 * (lo[i] + hi[i]) for i in range(3)]
        half = 0.5 * max(hi[i] - lo[i] for i in range(3)) + 0.01
        ax.set_xlim(mid[0] - half, mid[0] + half)
        ax.set_ylim(mid[1] - half, mid[1] + half)
        ax.set_zlim(mid[2] - half, mid[2] + half)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=-20, azim=-55)  # from below: the gussets hang under the arm
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
        ax.set_title("%s: %.1f cm², %d bends, %d self-rivets" % (label, part["area_m2"] * 1e4, part["bends"],
                                                                  len(part.get("self_rivets", []))), fontsize=9)
    fig.suptitle("%g kg box, limit %g mm, seed %d" % (mass, limit, seed), fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def sweep(args, sheetgen, scene_dir, seeds, limits, masses, z_lo, z_hi):
    """Every mass, limit and seed with and without self-riveting: (rows
    (mass, limit, seed, with, without, check or None), wall faces kept)."""
    work = tempfile.mkdtemp(prefix="sheetgen_fig9_")
    rows, faces = [], 0
    for mass in masses:
        for limit in limits:
            d = os.path.join(work, "mass_%g_limit_%g" % (mass, limit))
            os.makedirs(d)
            problem, faces = strip_problem(scene_dir, z_lo, z_hi, mass, limit * 1e-3, d)
            for seed in seeds:
                a = solve(sheetgen, problem, seed, [], args.quick)
                b = solve(sheetgen, problem, seed, ["--no-self-rivet"], args.quick)
                check = verify(args.build, a["out"]) if args.verify and a["ok"] and a["self_rivets"] else None
                rows.append((mass, limit, seed, a, b, check))
                print(mass, limit, seed, a["ok"], a["area"] * 1e4, a["self_rivets"], b["ok"], b["area"] * 1e4, check, flush=True)
    return rows, faces


def table(args, rows, faces, limits, masses, z_lo, z_hi):
    """The markdown of the sweep: one row per run, then how often self-riveting is lighter."""
    settings = "6 chains x 400 iterations" if args.quick else "10 chains x 1000 iterations (the paper's)"
    md = ["# Self-riveting ablation (paper Fig. 9, issue 6)", "",
          "Made by `bench/ablation_self_rivet.py%s%s` on %s (2 cores, %s). One run at a time." %
          (" --quick" if args.quick else "", " --verify" if args.verify else "", time.strftime("%Y-%m-%d"), settings), "",
          "`wall_standoff` with its wall rivet area cut to the %d faces within z = %.2f-%.2f m (a %.0f mm strip across "
          "the box's bottom at 0.57 m, like the flange of a frame), a light box at 9 g 60 mm from the wall "
          "and 0.57 m above the floor, whose rivet area is unchanged; box masses %s kg. Per mass, deflection limit and "
          "seed: valid, flat area cm², self-rivets used, wall time s; *saved* is the area self-riveting saves." %
          (faces, z_lo, z_hi, (z_hi - z_lo) * 1e3, ", ".join("%g" % m for m in masses)), "",
          "| mass (kg) | force (N) | limit (mm) | seed | with self-riveting | without | saved |%s" %
          (" independent check of the self-riveted part |" if args.verify else ""),
          "| --- | --- | --- | --- | --- | --- | --- |%s" % (" --- |" if args.verify else "")]
    for mass, limit, seed, a, b, check in rows:
        saved = (1 - a["area"] / b["area"]) * 100 if a["ok"] and b["ok"] and b["area"] > 0 else float("nan")
        cell = "%.1f %%" % saved if saved == saved else ("only with self-riveting" if a["ok"] and not b["ok"] else "n/a")
        line = "| %g | %.1f | %g | %d | %s, %.1f, %d, %.0f | %s, %.1f, %.0f | %s |" % (
            mass, mass * 9 * G, limit, seed, "yes" if a["ok"] else "no", a["area"] * 1e4, a["self_rivets"], a["wall"],
            "yes" if b["ok"] else "no", b["area"] * 1e4, b["wall"], cell)
        if args.verify:
            line += " %s |" % ("—" if check is None else ("pass: " if check[0] else "FAIL: ") + (check[1] if check[0] else "; ".join(check[2])))
        md.append(line)
    md.append("")
    for mass in masses:
        for limit in limits:
            sub = [(a, b) for m, lim, _, a, b, _ in rows if m == mass and lim == limit]
            lighter = [(a, b) for a, b in sub if a["ok"] and (not b["ok"] or a["area"] < b["area"] - 1e-9)]
            md.append("* %g kg, %g mm: self-riveting lighter in %d of %d seeds." % (mass, limit, len(lighter), len(sub)))
    md.append("")

    return md


def plot(rows, limits, masses, path):
    """Flat area against the deflection limit, one panel per mass."""
    fig, axes = plt.subplots(1, len(masses), figsize=(3.2 * len(masses) + 0.5, 3.6), sharey=True, squeeze=False)
    for ax, mass in zip(axes[0], masses):
        for k, (label, key, marker) in enumerate([("with self-riveting", 3, "o"), ("without", 4, "s")]):
            sub = [r for r in rows if r[0] == mass and r[key]["ok"]]
            ax.scatter([r[1] + (k - 0.5) * 0.08 for r in sub], [r[key]["area"] * 1e4 for r in sub], marker=marker, label=label)
            means = []
            for limit in limits:
                v = [r[key]["area"] * 1e4 for r in sub if r[1] == limit]
                if v:
                    means.append((limit, sum(v) / len(v)))
            ax.plot([m[0] for m in means], [m[1] for m in means], alpha=0.6)
        ax.set_xlabel("deflection limit, mm")
        ax.set_title("%g kg box (%.1f N)" % (mass, mass * 9 * G), fontsize=9)
    axes[0][0].set_ylabel("flat area of the valid part, cm²")
    axes[0][0].legend(fontsize=8)
    fig.suptitle("Fig. 9: a light box near a wall strip, far from the floor", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--seeds", default="1,2,3")
    ap.add_argument("--limits", default="4,3,2,1", help="deflection limits, mm")
    ap.add_argument("--strip", default="0.50,0.60", help="z range of the wall rivet area kept, m")
    ap.add_argument("--masses", default="0.5,0.4,0.35,0.3", help="box masses, kg (at 9 g)")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--verify", action="store_true", help="check every self-riveted part with sheetgen_tools.verify")
    args = ap.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    limits = [float(x) for x in args.limits.split(",")]
    masses = [float(x) for x in args.masses.split(",")]
    z_lo, z_hi = (float(x) for x in args.strip.split(","))
    sheetgen = paths.sheetgen_in(args.build)
    scene_dir = os.path.join(paths.SAMPLE_SCENES, "wall_standoff")
    rows, faces = sweep(args, sheetgen, scene_dir, seeds, limits, masses, z_lo, z_hi)
    md = table(args, rows, faces, limits, masses, z_lo, z_hi)
    plot(rows, limits, masses, os.path.join(ROOT, "docs", "ablation_self_rivet.png"))
    md += ["![self-riveting ablation](ablation_self_rivet.png)", ""]
    # A row where self-riveting is lighter (else the first), with and without, side by side.
    shown = next((r for r in rows if r[3]["ok"] and r[4]["ok"] and r[3]["area"] < r[4]["area"] - 1e-9), rows[0])
    if shown[3]["ok"] and shown[4]["ok"]:
        parts_picture(shown, os.path.join(ROOT, "docs", "ablation_self_rivet_parts.png"))
        md += ["The parts at %g kg, %g mm, seed %d (gold: the part; red dots: self-rivets, black: rivets to the structure; "
               "orange: the box; green: the wall strip and the floor's rivet area):" % (shown[0], shown[1], shown[2]), "",
               "![parts with and without self-riveting](ablation_self_rivet_parts.png)", ""]
    path = os.path.join(ROOT, "docs", "ablation_self_rivet.md")
    # The hand-written reading below the generated part survives a re-run.
    reading = ""
    if os.path.exists(path):
        old = open(path).read()
        k = old.find("\n## Reading")
        reading = old[k:] if k >= 0 else ""
    open(path, "w").write("\n".join(md) + reading.rstrip("\n") + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"ablation_self_rivet: {e}")
