#!/usr/bin/python3
"""Regenerates docs/results.md and docs/images/results/*.png from the outputs of
scripts/solve_all.py (out/<run>/result.json, run.json, verify.log, summary.json).

    /usr/bin/python3 scripts/make_report.py [--out out] [--doc docs/results.md]

Per run: the Blender presentation render out/<run>/render.png when it exists
and is newer than out/<run>/result.json (made by scripts/render_results.py,
docs/blender.md "Rendering an existing result"; copied to
docs/images/results/<run>_render.png), a 3-D view of the part(s) in the
environment (matplotlib, from result.json tabs and the scene's meshes, always,
from a fixed angle; environment translucent grey, rivet areas green, load
boxes orange, parts blue, drawn over the environment), the
flat pattern(s) (result.json flat_pattern outline, bend lines dashed: blue up,
red down, with bend number and angle), the convergence of the composition
(history: best area and C/Cmax against candidates evaluated) and the numbers.
Nothing here computes engineering values: every number is read from result.json.
"""
import argparse
import datetime
import json
import math
import os
import re
import shutil
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
from verify_result import load_problem, load_rotation  # noqa: E402
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from solve_all import RUNS  # noqa: E402

# Paper, Fig. 10 table (Barda et al. 2023): avionics bay, 10 loads.
PAPER = {"expert": (12.45, 5.169), "ours": (3.65, 4.467)}

# Camera per scene (elev, azim) for the 3-D views.
VIEWS = {"shelf": (25, -60), "corner": (22, -50), "wall_standoff": (15, -40), "corner_obstacle": (22, -50),
         "slanted": (18, -70), "sharp_angles": (22, 150), "boxed_in": (35, -35), "bulkhead_hole": (20, -35),
         "maze": (55, -75), "avionics_bay": (30, 112), "avionics_bay_right_angles": (30, 112)}
PART_COLOURS = ["#1f5fbf", "#7b3fbf", "#0f8f8f", "#bf3f7b", "#3f7fbf", "#5f5fff", "#2f9f4f", "#9f2fbf", "#1f9fdf", "#6f4f2f"]


def box_faces(load):
    R = load_rotation(load)
    h = 0.5 * np.array(load["size"])
    c = np.array(load["center"])
    corners = [c + R @ (h * np.array([sx, sy, sz])) for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)]
    quads = [(0, 1, 3, 2), (4, 5, 7, 6), (0, 1, 5, 4), (2, 3, 7, 6), (0, 2, 6, 4), (1, 3, 7, 5)]
    return [[corners[i] for i in q] for q in quads]


def scene_picture(run, prob, meshes, result, path):
    fig = plt.figure(figsize=(10, 8.5) if len(prob["loads"]) > 1 else (7.5, 6.2))
    ax = fig.add_subplot(111, projection="3d")
    ax.computed_zorder = False
    ra_faces = {}
    for ra in prob["rivet_areas"]:
        m = ra["mesh"] if isinstance(ra["mesh"], str) else prob["environment"]["meshes"][ra["mesh"]]["name"]
        ra_faces.setdefault(m, set()).update(ra["faces"])
    pts = []
    for name, (V, F) in meshes.items():
        ras = ra_faces.get(name, set())
        plain = [V[f] for k, f in enumerate(F) if k not in ras]
        riv = [V[f] for k, f in enumerate(F) if k in ras]
        if plain:
            ax.add_collection3d(Poly3DCollection(plain, facecolor=(0.6, 0.6, 0.62, 0.16), edgecolor=(0.4, 0.4, 0.4, 0.05),
                                                 linewidth=0.2, zorder=1))
        if riv:
            ax.add_collection3d(Poly3DCollection(riv, facecolor=(0.2, 0.75, 0.3, 0.35), edgecolor="none", zorder=2))
        pts.append(V)
    for load in prob["loads"]:
        ax.add_collection3d(Poly3DCollection(box_faces(load), facecolor=(1.0, 0.6, 0.15, 0.30),
                                             edgecolor=(0.7, 0.35, 0.0, 0.8), linewidth=0.6, zorder=3))
    n_ok = 0
    for k, part in enumerate(result["parts"]):
        ok = part["status"] == "ok"
        n_ok += ok
        polys = [np.array(t["corners"]) for t in part.get("tabs", [])]
        if not polys:
            continue
        colour = PART_COLOURS[k % len(PART_COLOURS)] if ok else "#d62728"
        ax.add_collection3d(Poly3DCollection(polys, facecolor=colour, alpha=0.92 if ok else (0.45 if len(result["parts"]) == 1 else 0.25),
                                             edgecolor="black" if ok else "#7f0000", linewidth=0.4, zorder=5))
        if ok and part.get("rivets"):
            r = np.array(part["rivets"])
            ax.scatter(r[:, 0], r[:, 1], r[:, 2], s=3, c="k", depthshade=False, zorder=6)
    P = np.vstack(pts)
    lo, hi = P.min(0), P.max(0)
    for load in prob["loads"]:
        c = np.array(load["center"])
        lo, hi = np.minimum(lo, c), np.maximum(hi, c)
    mid, half = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
    ax.set_xlim(mid[0] - half, mid[0] + half)
    ax.set_ylim(mid[1] - half, mid[1] + half)
    ax.set_zlim(mid[2] - half, mid[2] + half)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")
    elev, azim = VIEWS.get(run, (25, -60))
    ax.view_init(elev=elev, azim=azim)
    n = len(result["parts"])
    title = "%s: %d/%d loads with a part" % (run, n_ok, n)
    if n_ok < n:
        title += "\n(red, translucent: nearest candidate of a load without a valid part)"
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def draw_flat(ax, part):
    fp = part["flat_pattern"]
    for poly in fp["outline"]:
        p = np.array(poly + [poly[0]]) * 1e3
        ax.fill(p[:, 0], p[:, 1], color="#c9d6ea", zorder=1)
        ax.plot(p[:, 0], p[:, 1], color="k", linewidth=0.8, zorder=3)
    for b in fp["bends"]:
        a, c = np.array(b["a"]) * 1e3, np.array(b["b"]) * 1e3
        col = "#1f5fbf" if b["direction"] == "up" else "#d62728"
        ax.plot([a[0], c[0]], [a[1], c[1]], linestyle="--", color=col, linewidth=0.9, zorder=2)
        m = 0.5 * (a + c)
        ax.text(m[0], m[1], "%d: %.0f°" % (b["number"], math.degrees(b["angle"])), fontsize=6, color=col,
                ha="center", va="center", zorder=4, bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.7))
    ax.set_aspect("equal")
    ax.tick_params(labelsize=6)
    ax.set_xlabel("mm", fontsize=7)
    ax.set_title("%s: %.0f cm², %d bends" % (part["load"], part["area_m2"] * 1e4, part["bends"]), fontsize=8)


def grid_fig(n, w=4.0, h=3.4):
    cols = min(n, 3)
    rows = int(math.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(w * cols, h * rows), squeeze=False)
    for ax in axes.flat[n:]:
        ax.axis("off")
    return fig, list(axes.flat[:n])


def flat_picture(result, path):
    parts = [p for p in result["parts"] if p["status"] == "ok"]
    if not parts:
        return False
    if len(parts) > 1:
        fig, axes = grid_fig(len(parts), 4.2, 3.6)
    else:
        fig, ax = plt.subplots(1, 1, figsize=(6, 4.6))
        axes = [ax]
    for ax, p in zip(axes, parts):
        draw_flat(ax, p)
    fig.suptitle("flat patterns (cut outline; bend lines dashed: blue up, red down; number: order)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return True


def convergence_picture(result, path):
    parts = result["parts"]
    if len(parts) > 1:
        fig, axes = grid_fig(len(parts), 3.8, 2.8)
    else:
        fig, ax = plt.subplots(1, 1, figsize=(5.5, 3.4))
        axes = [ax]
    for ax, p in zip(axes, parts):
        hist = p.get("history", [])
        ev = [h["evaluated"] for h in hist if h["found"]]
        area = [h["best_area_m2"] * 1e4 for h in hist if h["found"]]
        cr = [h["compliance"] / p["compliance_limit"] for h in hist if h["found"]]
        ax.set_title("%s (%s)" % (p["load"], p["status"]), fontsize=8)
        ax.tick_params(labelsize=6)
        ax.set_xlabel("candidates evaluated", fontsize=7)
        if not ev:
            ax.text(0.5, 0.5, "no valid candidate\nat any level", ha="center", va="center", transform=ax.transAxes, fontsize=8)
            continue
        ax.step(ev, area, where="post", color="#1f5fbf", marker="o", markersize=3)
        ax.set_ylabel("best area (cm²)", fontsize=7, color="#1f5fbf")
        ax2 = ax.twinx()
        ax2.step(ev, cr, where="post", color="#d62728", marker="s", markersize=2.5)
        ax2.axhline(1.0, color="#2ca02c", linewidth=0.8)
        ax2.set_ylim(0, max(1.15, max(cr) * 1.1))
        ax2.set_ylabel("C / C_max", fontsize=7, color="#d62728")
        ax2.tick_params(labelsize=6)
    fig.suptitle("composition: best valid part per beam-search level (green line: compliance limit)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def fmt(v, spec, scale=1.0):
    return "–" if v is None else format(v * scale, spec)


def part_rows(result):
    lines = ["| load | status | area (cm²) | mass (g) | bends | C (J) | C_max (J) | deflection (mm) | σ_vm max (MPa) | MS | segments (library) | FEM calls | time (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in result["parts"]:
        ok = p["status"] == "ok"
        t = p.get("timing", {})
        lines.append("| %s | %s | %s | %s | %s | %s | %s | %s | %s | %s | %s (%s) | %s | %s |" % (
            p["load"], p["status"], fmt(p.get("area_m2") if ok else None, ".1f", 1e4),
            fmt(p.get("mass_kg") if ok else None, ".0f", 1e3), p["bends"] if ok else "–",
            fmt(p.get("compliance") if ok else None, ".4f"), fmt(p.get("compliance_limit"), ".4f"),
            fmt(p.get("deflection_m") if ok else None, ".3f", 1e3), fmt(p.get("max_von_mises_pa") if ok else None, ".0f", 1e-6),
            fmt(p.get("margin_of_safety") if ok else None, ".2f"), len(p.get("segments", [])) if ok else "–",
            p.get("library_segments", "–"), p.get("fem_calls", "–"), fmt(t.get("total_s"), ".1f")))
    return lines


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(ROOT, "out"))
    ap.add_argument("--doc", default=os.path.join(ROOT, "docs", "results.md"))
    ap.add_argument("--note", action="append", default=[], help="a paragraph to print under the title (repeatable)")
    args = ap.parse_args()
    img_dir = os.path.join(ROOT, "docs", "images", "results")
    os.makedirs(img_dir, exist_ok=True)
    summary = {r["run"]: r for r in json.load(open(os.path.join(args.out, "summary.json")))["rows"]}
    doc_dir = os.path.dirname(args.doc)
    rel = lambda p: os.path.relpath(p, doc_dir)  # noqa: E731

    md = ["# Results: the scene library", "",
          "Generated by `scripts/make_report.py` from the outputs of `scripts/solve_all.py` "
          "(%s). The scenes are described in [scenes.md](scenes.md); the discovery ablation on the maze "
          "scene is in [ablation_discovery.md](ablation_discovery.md). Every number below is read from "
          "`out/<scene>/result.json`; the verify column is `tests/python/verify_result.py` (brute-force "
          "clearance, flanges on their rivet areas, CalculiX compliance and margin of safety, DXF outline) on the same output."
          % datetime.date.today().isoformat(), "",
          "Pictures are matplotlib views (environment translucent grey, rivet areas green, load boxes orange, "
          "parts opaque and drawn over the environment so they stay visible, black dots: rivets). "
          "Where `out/<scene>/render.png` is newer than its result.json, the scene also shows the Blender "
          "presentation render of that result (`scripts/render_results.py`, docs/blender.md: part gold, "
          "environment grey with the rivet areas in their tag colours, load boxes translucent blue, nearest "
          "candidate of a load without a valid part translucent magenta).", "",
          ] + [n + "\n" for n in args.note] + [
          "## Summary", "",
          "| scene | loads ok | area (cm²) | mass (kg) | bends | worst C/C_max | lowest MS | wall time (s) | settings | verify |",
          "|---|---|---|---|---|---|---|---|---|---|"]
    order = [r[0] for r in RUNS if r[0] in summary]
    for run in order:
        r = summary[run]
        s = r.get("settings") or {}
        ok = r["ok"] > 0
        md.append("| [%s](#%s) | %d/%d | %s | %s | %s | %s | %s | %s | %s × %s | %s |" % (
            run, run, r["ok"], r["loads"], fmt(r["area_m2"] if ok else None, ".0f", 1e4),
            fmt(r["mass_kg"] if ok else None, ".3f"), r["bends"] if ok else "–", fmt(r["worst_c_ratio"], ".3f"),
            fmt(r["min_ms"], ".2f"), fmt(r["wall_s"], ".0f"), s.get("chains", "?"), s.get("iterations", "?"), r["verify"]))
    md += ["", "Area, mass and bends are sums over the loads that have a part; C/C_max is the worst load, MS the "
           "lowest. Wall time is the whole `sheetgen solve` run on the shared 2-core machine (`--threads 2`, one "
           "solve at a time, other engineers' jobs running).", ""]

    fails = [(run, f) for run in order for f in summary[run]["failures"]]
    md += ["## Loads without a valid part", ""]
    if fails:
        md += ["| scene | load | reason (result.json) | nearest candidate: rivet areas reached; tab widths w (mm, flanges excluded) |",
               "|---|---|---|---|"]
        for run, f in fails:
            res = json.load(open(os.path.join(os.path.realpath(os.path.join(args.out, run)), "result.json")))
            prob = json.load(open(os.path.normpath(os.path.join(os.path.realpath(os.path.join(args.out, run)), res["problem"]))))
            part = next(p for p in res["parts"] if p["load"] == f["load"])
            tabs = part.get("tabs", [])
            reached = sorted({prob["rivet_areas"][t["rivet_area"]]["name"] for t in tabs if t.get("rivet_area", -1) >= 0})
            widths = [t["parameters"]["w"] * 1e3 for t in tabs if t.get("parameters") and t.get("rivet_area", -1) < 0]
            md.append("| %s | %s | %s | %s; %s |" % (run, f["load"], f["reason"], ", ".join(reached) or "none",
                                                  " ".join("%.0f" % w for w in widths) or "–"))
        md += ["", "The tab widths show how far the nearest candidate was widened (docs/discovery.md, "
               "\"Widening\"): 16 mm is the feeler width `min_tab_width` = 10t, i.e. a tab that was not widened at all."]
    else:
        md.append("None: every load of every scene has a valid part.")
    md.append("")

    # What the independent checker measured (verify.log of each run).
    md += ["## Independent check (tests/python/verify_result.py)", "",
           "Per part: the smallest brute-force clearance (required t/2 + 1 mm = 1.80 mm, tolerance 0.8 mm), the "
           "compliance re-computed by CalculiX on a solid model of the part (tabs as t-thick plates in C3D10, "
           "tests/python/solid_reference.py, with the supports and loads of the deck `sheetgen export-ccx` writes; "
           "docs/fem.md \"A solid reference\"; the check requires agreement within 5 % and C_CalculiX ≤ 1.05 C_max; "
           "the shell decks' differences, S8R and S4, are shown for comparison), and the margin of safety from CalculiX's stresses on the S4 deck "
           "by the same stress rule (docs/fem.md; CalculiX's maximum may exceed the stress at MS = 0 by at most 5 %). "
           "FAIL lines are quoted as the checker printed them.", "",
           "| scene | load | min clearance (mm) | C ours (J) | C CalculiX (J) | difference | vs S8R | vs S4 "
           "| C_CalculiX / C_max | MS ours | MS CalculiX | checker failures |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for run in order:
        vlog = os.path.join(os.path.realpath(os.path.join(args.out, run)), "verify.log")
        if not os.path.exists(vlog):
            continue
        text = open(vlog).read().splitlines()
        loads = {}
        for line in text:
            m = re.match(r"(\S+): min clearance ([0-9.]+) mm", line)
            if m:
                loads.setdefault(m.group(1), {})["clear"] = m.group(2)
            m = re.match(r"(\S+): compliance ours ([0-9.eE+-]+) J, CalculiX (?:solid C3D10 |S8R )?([0-9.eE+-]+) J "
                         r"\(([-+0-9.]+) %\)(?:, S8R ([0-9.eE+-]+) J \(([-+0-9.]+) %\))?"
                         r"(?:, S4 ([0-9.eE+-]+) J \(([-+0-9.]+) %\))?.*limit ([0-9.eE+-]+) J", line)
            if m:
                d = loads.setdefault(m.group(1), {})
                d.update(ours=m.group(2), ccx=m.group(3), diff=m.group(4), ratio=float(m.group(3)) / float(m.group(9)),
                         s8_diff=m.group(6) or "–", s4_diff=m.group(8) or "–")
            m = re.match(r"(\S+): max von Mises .*; MS ours ([-0-9.einf]+), CalculiX ([-0-9.einf]+), required", line)
            if m:
                loads.setdefault(m.group(1), {}).update(ms=m.group(2), ms_ccx=m.group(3))
        for name, d in loads.items():
            fails = [l[len("FAIL: "):].split(": ", 1)[1] for l in text if l.startswith("FAIL: %s:" % name)]
            md.append("| %s | %s | %s | %s | %s | %s %% | %s %% | %s %% | %s | %s | %s | %s |" % (
                run, name, d.get("clear", "–"), d.get("ours", "–"), d.get("ccx", "–"), d.get("diff", "–"),
                d.get("s8_diff", "–"), d.get("s4_diff", "–"),
                "%.3f" % d["ratio"] if "ratio" in d else "–", d.get("ms", "–"), d.get("ms_ccx", "–"),
                "; ".join(fails) or "none"))
    md.append("")

    # Avionics bay against the paper.
    if "avionics_bay" in summary:
        a = summary["avionics_bay"]
        b = summary.get("avionics_bay_right_angles")
        md += ["## Avionics bay against the paper (Fig. 10)", "",
               "The paper compares one domain expert (CAD, right-angle bends) with its system on its own bay "
               "(10 loads). We have neither the expert nor the paper's bay, so our stand-in for the expert's practice "
               "is the same solver restricted to ±90° bends without skew (`--right-angles`, the practice the paper "
               "attributes to the expert, Fig. 11), on our bay (`sample_scenes/avionics_bay`, docs/scenes.md). "
               "Times are wall-clock hours of the whole run; material is the summed flat-pattern area.", "",
               "| | time (h) | material (m²) | loads with a part | bends |", "|---|---|---|---|---|",
               "| paper: expert | %.2f | %.3f | 10/10 | – |" % PAPER["expert"],
               "| paper: their system | %.2f | %.3f | 10/10 | – |" % PAPER["ours"],
               "| paper: change | %+.1f %% | %+.1f %% | | |" % ((PAPER["ours"][0] / PAPER["expert"][0] - 1) * 100,
                                                        (PAPER["ours"][1] / PAPER["expert"][1] - 1) * 100)]
        if b:
            md.append("| sheetgen `--right-angles` (expert stand-in) | %.3f | %.4f | %d/%d | %d |" % (
                b["wall_s"] / 3600, b["area_m2"], b["ok"], b["loads"], b["bends"]))
        md.append("| sheetgen, free angles | %.3f | %.4f | %d/%d | %d |" % (a["wall_s"] / 3600, a["area_m2"], a["ok"], a["loads"], a["bends"]))
        if b:
            res_a = json.load(open(os.path.join(args.out, "avionics_bay", "result.json")))
            res_b = json.load(open(os.path.join(args.out, "avionics_bay_right_angles", "result.json")))
            both = [(pa, pb) for pa, pb in zip(res_a["parts"], res_b["parts"]) if pa["status"] == "ok" and pb["status"] == "ok"]
            if both:
                sa = sum(p["area_m2"] for p, _ in both)
                sb = sum(p["area_m2"] for _, p in both)
                # Time over the same loads too: each load's own total_s.
                ta = sum(p.get("timing", {}).get("total_s", 0) for p, _ in both)
                tb = sum(p.get("timing", {}).get("total_s", 0) for _, p in both)
                md.append("| change, on the %d loads both runs solved | %s | %+.1f %% | | |" % (
                    len(both), "%+.1f %%" % ((ta / tb - 1) * 100) if tb > 0 else "–", (sa / sb - 1) * 100))
            else:
                md += ["", "**No load has a part in both runs**, so the material saved by free angles cannot be "
                       "measured on this bay: the totals above are over different loads and are not comparable. "
                       "What the runs do show: the free-angle run finds valid parts for %d loads, the right-angle "
                       "run for %d." % (a["ok"], b["ok"])]
            md += ["", "Per load (area in cm², bends):", "", "| load | free angles | right angles |", "|---|---|---|"]
            for pa, pb in zip(res_a["parts"], res_b["parts"]):
                f = lambda p: ("%.0f cm², %d bends" % (p["area_m2"] * 1e4, p["bends"])) if p["status"] == "ok" else "no valid part"  # noqa: E731
                md.append("| %s | %s | %s |" % (pa["load"], f(pa), f(pb)))
        md += ["", "Our bay's boxes are smaller and closer to their rivet areas than the paper's (its parts average "
               "0.45 m² each, ours %.0f cm² over the free-angle parts), so only the ratios are comparable, not the "
               "absolute numbers." % (a["area_m2"] / max(a["ok"], 1) * 1e4), ""]

    # Per scene.
    md += ["## Scenes", ""]
    for run in order:
        out_dir = os.path.realpath(os.path.join(args.out, run))
        res_path = os.path.join(out_dir, "result.json")
        if not os.path.exists(res_path):
            md += ["### %s" % run, "", "No result.json.", ""]
            continue
        result = json.load(open(res_path))
        prob_path = os.path.normpath(os.path.join(out_dir, result["problem"]))
        prob, meshes = load_problem(prob_path)
        r = summary[run]
        scene_png = os.path.join(img_dir, run + "_scene.png")
        flat_png = os.path.join(img_dir, run + "_flat.png")
        conv_png = os.path.join(img_dir, run + "_convergence.png")
        scene_picture(run, prob, meshes, result, scene_png)
        # The presentation render of scripts/render_results.py, if it was made from this result.json.
        render_src = os.path.join(out_dir, "render.png")
        render_png = None
        if os.path.exists(render_src) and os.path.getmtime(render_src) > os.path.getmtime(res_path):
            render_png = os.path.join(img_dir, run + "_render.png")
            shutil.copyfile(render_src, render_png)
        has_flat = flat_picture(result, flat_png)
        convergence_picture(result, conv_png)
        s = result.get("search", {})
        md += ["### %s" % run, "",
               "%s. Problem `%s`; run with %s chains × %s iterations, beam %s, seed %s%s; wall time %s s; verify: %s." % (
                   prob.get("description", ""), os.path.relpath(prob_path, ROOT), s.get("chains"), s.get("iterations"),
                   s.get("beam_width"), s.get("seed"), ", `--right-angles`" if "right_angles" in run else "",
                   fmt(r["wall_s"], ".0f"), r["verify"]), ""]
        md += part_rows(result) + [""]
        for p in result["parts"]:
            if p["status"] != "ok":
                md.append("*%s*: no valid part: %s" % (p["load"], p.get("reason", "")))
                md.append("")
        if render_png:
            md.append("![%s: presentation render (Blender)](%s)" % (run, rel(render_png)))
            md.append("")
        md.append("![%s in its environment](%s)" % (run, rel(scene_png)))
        md.append("")
        if has_flat:
            md.append("![%s flat patterns](%s)" % (run, rel(flat_png)))
            md.append("")
        md.append("![%s convergence](%s)" % (run, rel(conv_png)))
        md.append("")
        print("drew", run, flush=True)

    md += ["## Reading the numbers", "",
           "* C is the compliance fᵀu (J) of the design load case; C_max = |F| · 1 mm bounds the displacement "
           "*along the force*, so the reported deflection (the norm of the load point's displacement, sideways "
           "components included) can exceed 1 mm on a valid part.",
           "* MS = F_ty / (1.5 · σ_vm,max) − 1 with F_ty = 345 MPa (2024-T3); peak stresses at rivets are excluded "
           "by the solver's documented rule (docs/fem.md).",
           "* Convergence plots show the composition's beam search (one point per level: candidates evaluated so far, "
           "area and C/C_max of the best valid part); the discovery phase itself is summarised by the library size.",
           "* The discovery ablation (paper Sec. 6.4.1, Fig. 13) is in [ablation_discovery.md](ablation_discovery.md).", "",
           "## Ablations", "",
           "Tables, settings and readings: [ablation_discovery.md](ablation_discovery.md) (edge and segment policies on "
           "the maze, paper Fig. 13) and [ablation_composition.md](ablation_composition.md) (composition vs the best "
           "single chain, Fig. 14; self-riveting, Fig. 9; free vs right angles).", "",
           "![discovery ablation](ablation_discovery.png)", "",
           "![composition ablations](ablation_composition.png)", ""]
    open(args.doc, "w").write("\n".join(md))
    print("wrote", args.doc)


if __name__ == "__main__":
    main()
