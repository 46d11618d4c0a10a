"""The matplotlib figures of the reports (scripts/make_report.py, the bench
scripts): a run's parts in their environment, the flat patterns, the
convergence of the composition. Every number drawn is read from result.json."""
import math

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

from .geometry import BOX_QUADS, box_corners  # noqa: E402
from .problem import rivet_area_mesh  # noqa: E402

# Camera per scene (elev, azim) for the 3-D views.
VIEWS = {"shelf": (25, -60), "corner": (22, -50), "wall_standoff": (15, -40), "corner_obstacle": (22, -50),
         "slanted": (18, -70), "sharp_angles": (22, 150), "boxed_in": (35, -35), "bulkhead_hole": (20, -35),
         "maze": (55, -75), "avionics_bay": (30, 112), "avionics_bay_right_angles": (30, 112)}
PART_COLOURS = ["#1f5fbf", "#7b3fbf", "#0f8f8f", "#bf3f7b", "#3f7fbf", "#5f5fff", "#2f9f4f", "#9f2fbf", "#1f9fdf", "#6f4f2f"]


def box_faces(load):
    """A load's box as 6 quads (4 corners by 3, m) for Poly3DCollection."""
    corners = box_corners(load)
    return [[corners[i] for i in q] for q in BOX_QUADS]


def scene_picture(run, prob, meshes, result, path):
    """A run's parts (result.json's, or {"parts": [...]}) in the problem's
    environment (load_problem's meshes), from the camera of VIEWS[run], to path (PNG)."""
    fig = plt.figure(figsize=(10, 8.5) if len(prob["loads"]) > 1 else (7.5, 6.2))
    ax = fig.add_subplot(111, projection="3d")
    ax.computed_zorder = False
    ra_faces = {}
    for ra in prob["rivet_areas"]:
        ra_faces.setdefault(rivet_area_mesh(prob, ra), set()).update(ra["faces"])
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
    n = max(len(result["parts"]), len(prob["loads"]))  # a load with no entry has no part either
    title = "%s: %d/%d loads with a part" % (run, n_ok, n)
    if n_ok < len(result["parts"]):  # some entry is a nearest candidate, drawn in red
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


def parts_fig(n, cell, single):
    """(fig, one axes per part): grid_fig's grid of `cell` (w, h) in cells for
    several parts, one axes of `single` (w, h) in for one part (or none)."""
    if n > 1:
        return grid_fig(n, *cell)
    fig, ax = plt.subplots(1, 1, figsize=single)
    return fig, [ax]


def flat_picture(result, path):
    parts = [p for p in result["parts"] if p["status"] == "ok"]
    if not parts:
        return False
    fig, axes = parts_fig(len(parts), (4.2, 3.6), (6, 4.6))
    for ax, p in zip(axes, parts):
        draw_flat(ax, p)
    fig.suptitle("flat patterns (cut outline; bend lines dashed: blue up, red down; number: order)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return True


def convergence_picture(result, path):
    parts = result["parts"]
    fig, axes = parts_fig(len(parts), (3.8, 2.8), (5.5, 3.4))
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
