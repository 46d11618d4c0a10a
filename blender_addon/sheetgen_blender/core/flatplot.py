"""The flat pattern of one part as a PNG, drawn with matplotlib from result.json (no bpy).

Outline filled light grey, reliefs outlined, rivet holes as circles
(magenta; self-rivet holes cyan), bend lines dashed (red: down, blue: up) with
their number and angle, a 50 mm scale bar. matplotlib is
imported lazily (Agg backend): ``available()`` says whether it is there.
"""
import math


def available():
    try:
        import matplotlib  # noqa: F401
        return True
    except ImportError:
        return False


def build_figure(part, width_px=800, height_px=500, dpi=100):
    """The flat pattern's matplotlib figure and its bend labels (annotations), not saved."""
    import matplotlib
    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.patches import Polygon

    fp = part["flat_pattern"]
    mm = 1e3
    fig = Figure(figsize=(width_px / dpi, height_px / dpi), dpi=dpi)
    canvas = FigureCanvasAgg(fig)
    ax = fig.add_axes([0.02, 0.02, 0.96, 0.88])
    ax.set_aspect("equal")
    ax.axis("off")
    xs, ys = [], []
    for ring in fp.get("outline", []):
        pts = [(x * mm, y * mm) for x, y in ring]
        xs += [p[0] for p in pts]
        ys += [p[1] for p in pts]
        ax.add_patch(Polygon(pts, closed=True, facecolor="#d9dde3", edgecolor="#222222", linewidth=1.2))
    for rl in fp.get("reliefs", []):
        pts = [(x * mm, y * mm) for x, y in rl.get("polygon", [])]
        if pts:
            ax.add_patch(Polygon(pts, closed=True, facecolor="none", edgecolor="#8a5a00", linewidth=0.8))
    from matplotlib.patches import Circle
    for h in fp.get("holes", []):
        # Rivet holes magenta, self-rivet holes cyan, as in flat.dxf / flat.svg.
        colour = "#0a8f9f" if h.get("kind") == "self" else "#b0209f"
        cx, cy = h["centre"]
        ax.add_patch(Circle((cx * mm, cy * mm), 0.5 * h["diameter"] * mm, facecolor="none", edgecolor=colour,
                            linewidth=1.0, zorder=5))  # over a bend label that lands on it
    if xs:
        span = max(max(xs) - min(xs), max(ys) - min(ys))
        pad = 0.06 * span
        ax.set_xlim(min(xs) - pad, max(xs) + pad)
        ax.set_ylim(min(ys) - pad, max(ys) + pad)
        x0, y0 = min(xs), min(ys) - pad * 0.6
        ax.plot([x0, x0 + 50], [y0, y0], color="black", linewidth=2)
        ax.annotate("50 mm", (x0 + 25, y0), xytext=(0, 3), textcoords="offset points", ha="center", fontsize=8)
    # Fix the axes' final place (equal aspect) before measuring label boxes.
    ax.apply_aspect()
    renderer = canvas.get_renderer()
    labels, boxes = [], []
    for b in fp.get("bends", []):
        (ax_, ay), (bx, by) = b["a"], b["b"]
        colour = "#c62828" if b.get("direction", "down") == "down" else "#1565c0"
        ax.plot([ax_ * mm, bx * mm], [ay * mm, by * mm], linestyle=(0, (6, 3)), color=colour, linewidth=1.4)
        mx, my = (ax_ + bx) / 2 * mm, (ay + by) / 2 * mm
        L = math.hypot(bx - ax_, by - ay) or 1.0
        nx, ny = -(by - ay) / L, (bx - ax_) / L   # label beside the line, not on it
        tx, ty = (bx - ax_) / L, (by - ay) / L
        text = "%d: %.0f° %s" % (b.get("number", 0), math.degrees(abs(b.get("angle", 0))), b.get("direction", ""))
        # Bends close together (the two folds of a leg and its flange) would
        # print their labels over each other: try beside the line on either
        # side, then further out, then slid along the line, and keep the first
        # place that is clear of the labels already placed.
        tries = [(14, 0), (-14, 0), (28, 0), (-28, 0), (14, 30), (14, -30), (-14, 30), (-14, -30), (42, 0), (-42, 0)]
        chosen = None
        for k, (off_n, off_t) in enumerate(tries):
            ann = ax.annotate(text, (mx, my), xytext=(off_n * nx + off_t * tx, off_n * ny + off_t * ty),
                              textcoords="offset points", fontsize=8, color=colour, ha="center", va="center",
                              bbox=dict(boxstyle="round,pad=0.15", facecolor="white", edgecolor="none", alpha=0.8))
            box = ann.get_window_extent(renderer).expanded(1.08, 1.25)  # the white box around the text
            if not any(box.overlaps(other) for other in boxes) or k == len(tries) - 1:
                chosen = (ann, box)
                break
            ann.remove()
        labels.append(chosen[0])
        boxes.append(chosen[1])
    fig.suptitle("%s — flat pattern: %.1f cm², %d bends (red down, blue up)"
                 % (part.get("load", "?"), fp.get("area_m2", part.get("area_m2", 0)) * 1e4,
                    len(fp.get("bends", []))), fontsize=10)
    return fig, labels


def draw(part, path, width_px=800, height_px=500, dpi=100):
    """Write the flat pattern of ``part`` (a result.json part with status ok) to ``path`` (PNG)."""
    fig, _ = build_figure(part, width_px, height_px, dpi)
    fig.savefig(path, dpi=dpi, facecolor="white")
    return path
