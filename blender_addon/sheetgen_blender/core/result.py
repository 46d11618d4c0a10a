"""``sheetgen-result/1`` -> plain mesh data and report numbers (no bpy, no numpy).

What the Blender layer builds per load (docs/pipeline.md "result.json"):

- the **bent part**: every tab's ``corners`` (a 3-D polygon on the sheet's
  mid-surface, m) fanned into ``n - 2`` triangles, coincident corners of
  neighbouring tabs welded; the bend of a child tab is its first edge
  (``corners[0]``-``corners[1]``, which lies on the parent's ``parent_edge``);
- the **flat pattern**: the ``outline`` polygons (m, base-tab frame, z = 0),
  with the bend lines' end points inserted on the outline and each polygon
  split along its bend lines, so a bend is a real edge between two faces (a
  bend line that does not cross its polygon stays a loose edge). The reliefs
  are notches of the outline already;
- **rivet markers**: a small octahedron around every rivet centre, and one
  around every self-rivet (between its two sheets' points);
- **hole discs**: the flat pattern's rivet and self-rivet holes
  (``flat_pattern.holes``) as filled circles in the flat frame (z = 0);
- the **report**: area, mass, bends, compliance and its limit, deflection,
  MS, run time, in the panel's units.
"""
import math
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple

RESULT_FORMAT = "sheetgen-result/1"
WELD_TOL = 1e-6          # m: corners of neighbouring tabs closer than this are one vertex
ON_EDGE_TOL = 1e-6       # m: points this close are the same outline point
SNAP_THICKNESSES = 2.0   # a bend end point within 2 t of the outline is moved onto it (relief corners)


class ResultError(ValueError):
    """A result document that cannot be turned into meshes (one sentence naming the field)."""


@dataclass
class MeshPlain:
    """A mesh as plain lists: vertices (m), faces (vertex index loops), marked edges."""
    vertices: List[Tuple[float, float, float]] = field(default_factory=list)
    faces: List[List[int]] = field(default_factory=list)
    bend_edges: List[Tuple[int, int, int]] = field(default_factory=list)   # (v0, v1, bend number)
    loose_edges: List[Tuple[int, int]] = field(default_factory=list)       # edges not on any face

    def face_area(self, f):
        """Area of face f (Newell's formula: planar polygons, any winding)."""
        n = [0.0, 0.0, 0.0]
        loop = self.faces[f]
        for i, a in enumerate(loop):
            p, q = self.vertices[a], self.vertices[loop[(i + 1) % len(loop)]]
            n[0] += (p[1] - q[1]) * (p[2] + q[2])
            n[1] += (p[2] - q[2]) * (p[0] + q[0])
            n[2] += (p[0] - q[0]) * (p[1] + q[1])
        return 0.5 * math.sqrt(n[0] ** 2 + n[1] ** 2 + n[2] ** 2)

    def area(self):
        return sum(self.face_area(f) for f in range(len(self.faces)))


@dataclass
class PartMeshes:
    load: str
    status: str
    reason: str = ""
    bent: Optional[MeshPlain] = None
    flat: Optional[MeshPlain] = None
    rivets: Optional[MeshPlain] = None
    self_rivets: Optional[MeshPlain] = None
    holes: Optional[MeshPlain] = None
    thickness: float = 0.0


# ---------------------------------------------------------------------------
# bent part

class _Welder:
    def __init__(self, tol=WELD_TOL):
        self.tol2 = tol * tol
        self.vertices = []

    def index(self, p):
        p = (float(p[0]), float(p[1]), float(p[2]))
        for i, q in enumerate(self.vertices):  # parts have tens of corners: a linear scan is enough
            if (p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 + (p[2] - q[2]) ** 2 <= self.tol2:
                return i
        self.vertices.append(p)
        return len(self.vertices) - 1


def bent_mesh(part):
    """The bent part: one triangle fan per tab (n - 2 triangles), welded corners, bend edges."""
    w = _Welder()
    m = MeshPlain()
    bend_number = {}
    for b in (part.get("flat_pattern") or {}).get("bends", []):
        bend_number[b.get("tab")] = b.get("number", 0)
    for k, tab in enumerate(part.get("tabs", [])):
        corners = tab.get("corners") or []
        if len(corners) < 3:
            raise ResultError("parts['%s'].tabs[%d].corners: a tab needs at least 3 corners, got %d"
                              % (part.get("load"), k, len(corners)))
        idx = [w.index(c) for c in corners]
        for i in range(1, len(idx) - 1):
            m.faces.append([idx[0], idx[i], idx[i + 1]])
        flat = ((tab.get("parameters") or {}).get("theta3") == 0)  # a flat extension: no bend at its root
        if tab.get("parent", -1) >= 0 and not flat:
            m.bend_edges.append((idx[0], idx[1], bend_number.get(tab.get("index", k), 0)))
    m.vertices = w.vertices
    return m


def tab_triangle_count(part):
    return sum(max(len(t.get("corners") or []) - 2, 0) for t in part.get("tabs", []))


# ---------------------------------------------------------------------------
# flat pattern

def _inside(p, poly):
    """Even-odd point in polygon (2-D)."""
    x, y = p
    c = False
    for i in range(len(poly)):
        (x1, y1), (x2, y2) = poly[i], poly[i - 1]
        if (y1 > y) != (y2 > y) and x < (x2 - x1) * (y - y1) / (y2 - y1) + x1:
            c = not c
    return c


def _chord_crosses(loop, pts, i, j):
    """Whether the chord between loop positions i and j properly crosses another edge of the loop."""
    a, b = pts[loop[i]], pts[loop[j]]

    def orient(p, q, r):
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    n = len(loop)
    for k in range(n):
        if k in (i, j) or (k + 1) % n in (i, j):
            continue
        c, d = pts[loop[k]], pts[loop[(k + 1) % n]]
        d1, d2, d3, d4 = orient(a, b, c), orient(a, b, d), orient(c, d, a), orient(c, d, b)
        if d1 * d2 < 0 and d3 * d4 < 0:
            return True
    return False


def flat_mesh(part, snap=ON_EDGE_TOL):
    """The flat pattern in its base-tab frame (z = 0): outline faces split along the bend lines.

    A bend line ends at the relief, which may leave its end point a little off the traced outline:
    an end point within ``snap`` (m) of the outline moves onto it (the nearest edge).
    """
    fp = part.get("flat_pattern") or {}
    outline = fp.get("outline") or []
    pts = []
    rings = []
    for r, ring in enumerate(outline):
        if len(ring) < 3:
            raise ResultError("parts['%s'].flat_pattern.outline[%d]: a polygon needs at least 3 points"
                              % (part.get("load"), r))
        start = len(pts)
        pts.extend((float(x), float(y)) for x, y in ring)
        rings.append(list(range(start, len(pts))))

    def insert(p):
        """Index of p on the outline: an existing corner, or p's projection on the nearest edge inserted
        into its ring; None when no edge is within ``snap``."""
        best = None
        for ring in rings:
            for i in range(len(ring)):
                a, b = pts[ring[i]], pts[ring[(i + 1) % len(ring)]]
                dx, dy = b[0] - a[0], b[1] - a[1]
                L2 = dx * dx + dy * dy
                s = 0.0 if L2 == 0.0 else min(max(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / L2, 0.0), 1.0)
                q = (a[0] + s * dx, a[1] + s * dy)
                d2 = (q[0] - p[0]) ** 2 + (q[1] - p[1]) ** 2
                if best is None or d2 < best[0]:
                    best = (d2, ring, i, q)
        if best is None or best[0] > snap * snap:
            return None
        _d2, ring, i, q = best
        for v in (ring[i], ring[(i + 1) % len(ring)]):
            if (pts[v][0] - q[0]) ** 2 + (pts[v][1] - q[1]) ** 2 <= ON_EDGE_TOL ** 2:
                return v
        pts.append(q)
        ring.insert(i + 1, len(pts) - 1)
        return len(pts) - 1

    ends = []
    for b in fp.get("bends", []):
        ends.append((insert(b["a"]), insert(b["b"]), b.get("number", 0), b["a"], b["b"]))
    faces = [list(r) for r in rings]
    m = MeshPlain()
    loose = []
    for ia, ib, number, a, b in ends:
        split = False
        if ia is not None and ib is not None and ia != ib:
            for f, loop in enumerate(faces):
                if ia in loop and ib in loop:
                    i, j = sorted((loop.index(ia), loop.index(ib)))
                    mid = ((pts[ia][0] + pts[ib][0]) / 2, (pts[ia][1] + pts[ib][1]) / 2)
                    if j - i < 2 or len(loop) - (j - i) < 2 or not _inside(mid, [pts[v] for v in loop]) \
                            or _chord_crosses(loop, pts, i, j):
                        break
                    faces[f] = loop[i:j + 1]
                    faces.append(loop[j:] + loop[:i + 1])
                    split = True
                    break
        if split:
            m.bend_edges.append((ia, ib, number))
        else:
            # The bend line does not cut its polygon cleanly: draw it as a loose edge.
            if ia is None:
                pts.append((float(a[0]), float(a[1])))
                ia = len(pts) - 1
            if ib is None:
                pts.append((float(b[0]), float(b[1])))
                ib = len(pts) - 1
            loose.append((ia, ib, number))
    for ia, ib, number in loose:
        m.bend_edges.append((ia, ib, number))
        m.loose_edges.append((ia, ib))
    m.vertices = [(x, y, 0.0) for x, y in pts]
    m.faces = faces
    return m


def outline_area(part):
    """Shoelace area of the outline polygons (m²), the flat mesh's area."""
    total = 0.0
    for ring in (part.get("flat_pattern") or {}).get("outline") or []:
        s = 0.0
        for i in range(len(ring)):
            (x1, y1), (x2, y2) = ring[i - 1], ring[i]
            s += x1 * y2 - x2 * y1
        total += abs(s) / 2
    return total


# ---------------------------------------------------------------------------
# rivets

def rivet_markers(points, radius):
    """An octahedron of the given radius (m) around every point: 6 vertices, 8 faces each."""
    m = MeshPlain()
    for p in points:
        o = len(m.vertices)
        x, y, z = (float(c) for c in p)
        m.vertices += [(x + radius, y, z), (x - radius, y, z), (x, y + radius, z), (x, y - radius, z),
                       (x, y, z + radius), (x, y, z - radius)]
        for a, b in ((0, 2), (2, 1), (1, 3), (3, 0)):
            m.faces.append([o + a, o + b, o + 4])
            m.faces.append([o + b, o + a, o + 5])
    return m


def self_rivet_centres(part):
    """Per self-rivet the midpoint of its two sheets' points (m): where the rivet is."""
    out = []
    for k, s in enumerate(part.get("self_rivets") or []):
        pts = s.get("points") if isinstance(s, dict) else None
        if not isinstance(pts, list) or len(pts) != 2:
            raise ResultError("parts['%s'].self_rivets[%d].points: needs one point on each sheet"
                              % (part.get("load"), k))
        out.append(tuple(0.5 * (float(a) + float(b)) for a, b in zip(pts[0], pts[1])))
    return out


HOLE_SEGMENTS = 16


def hole_discs(part, segments=HOLE_SEGMENTS):
    """Every hole of ``flat_pattern.holes`` as an n-gon of its diameter in the flat frame (z = 0)."""
    m = MeshPlain()
    for k, h in enumerate((part.get("flat_pattern") or {}).get("holes") or []):
        try:
            cx, cy = (float(v) for v in h["centre"])
            r = 0.5 * float(h["diameter"])
        except (KeyError, TypeError, ValueError):
            raise ResultError("parts['%s'].flat_pattern.holes[%d]: needs centre [x, y] and diameter (m)"
                              % (part.get("load"), k))
        if not r > 0:
            raise ResultError("parts['%s'].flat_pattern.holes[%d].diameter: must be > 0" % (part.get("load"), k))
        o = len(m.vertices)
        m.vertices += [(cx + r * math.cos(2 * math.pi * i / segments), cy + r * math.sin(2 * math.pi * i / segments), 0.0)
                       for i in range(segments)]
        m.faces.append(list(range(o, o + segments)))
    return m


# ---------------------------------------------------------------------------
# the whole document

def check_document(doc):
    if not isinstance(doc, dict) or doc.get("format") != RESULT_FORMAT:
        raise ResultError("not a %s document (format is %r)" % (RESULT_FORMAT, doc.get("format") if
                                                               isinstance(doc, dict) else None))
    if not isinstance(doc.get("parts"), list):
        raise ResultError("parts: missing or not a list")


def part_sheet(part, thickness):
    """The sheet a part is made of, m: its thickness_m (a thicker gauge when the
    problem's sheet gave the load no part), else the problem's `thickness`."""
    t = part.get("thickness_m")
    return float(t) if isinstance(t, (int, float)) and t > 0 else thickness


def part_meshes(doc, thickness, rivet_radius=None):
    """PartMeshes per part of a result document, each in its own sheet
    (part_sheet; `thickness` is the problem's); parts without a valid part carry
    only status/reason."""
    check_document(doc)
    out = []
    for part in doc["parts"]:
        t = part_sheet(part, thickness)
        r = rivet_radius if rivet_radius is not None else max(1.5 * t, 0.002)
        pm = PartMeshes(load=part.get("load", "?"), status=part.get("status", "?"), reason=part.get("reason", ""),
                        thickness=t)
        if pm.status == "ok" and part.get("tabs"):
            pm.bent = bent_mesh(part)
            pm.flat = flat_mesh(part, snap=max(SNAP_THICKNESSES * t, ON_EDGE_TOL))
            pm.rivets = rivet_markers(part.get("rivets", []), r)
            pm.self_rivets = rivet_markers(self_rivet_centres(part), r)
            pm.holes = hole_discs(part)
        out.append(pm)
    return out


# Results panel rows: (key, label, factor from the result's SI value, format).
REPORT_FIELDS = [
    ("area_m2", "Area (cm²)", 1e4, "%.1f"),
    ("mass_kg", "Mass (g)", 1e3, "%.1f"),
    ("thickness_m", "Sheet (mm)", 1e3, "%.3g"),
    ("bends", "Bends", 1, "%d"),
    ("compliance", "Compliance (J)", 1, "%.4g"),
    ("compliance_limit", "Limit (J)", 1, "%.4g"),
    # Along F is what a max deflection bounds (C_max = |F| delta_max); |u| can
    # be larger when the box also swings sideways.
    ("deflection_along_force_m", "Deflection along F (mm)", 1e3, "%.3f"),
    ("deflection_m", "Displacement |u| (mm)", 1e3, "%.3f"),
    ("margin_of_safety", "MS", 1, "%.3f"),
]


def report(part):
    """The Results panel numbers of one part, in the panel's units: {key: value}; time in s."""
    values = {}
    for key, _label, factor, _fmt in REPORT_FIELDS:
        v = part.get(key)
        values[key] = None if v is None else (v * factor if key != "bends" else int(v))
    values["time_s"] = (part.get("timing") or {}).get("total_s")
    values["rivets"] = len(part.get("rivets") or [])
    values["self_rivets"] = len(part.get("self_rivets") or [])
    cost = part.get("cost")
    # A result.json written before the cost model has no cost.
    values["cost"] = cost.get("total") if isinstance(cost, dict) else None
    values["currency"] = cost.get("currency", "") if isinstance(cost, dict) else ""
    return values


def report_rows(part):
    """[(label, text)] for the Results panel: the numbers of ``report`` formatted."""
    values = report(part)
    rows = []
    for key, label, _factor, fmt in REPORT_FIELDS:
        v = values[key]
        rows.append((label, "—" if v is None else fmt % v))
    rows.append(("Rivets", "%d" % values["rivets"]))
    rows.append(("Self-rivets", "%d" % values["self_rivets"]))
    # Material, bends, rivets and the set-up share (docs/cost.md).
    c = values["cost"]
    rows.append(("Cost" + (" (%s)" % values["currency"] if values["currency"] else ""), "—" if c is None else "%.2f" % c))
    rows.append(("Press brake", press_brake_text(part)))
    t = values["time_s"]
    rows.append(("Run time (s)", "—" if t is None else "%.1f" % t))
    return rows


def press_brake_text(part):
    """Whether the problem's press-brake tools make every bend of the part (docs/manufacturing.md "Press
    brake"): "ok, N bends", the failing bend and why, or "—" for a result written before the check."""
    pb = part.get("press_brake")
    if not isinstance(pb, dict):
        return "—"
    if pb.get("ok"):
        return "ok, %d bends" % len(pb.get("tools") or [])
    return "no: " + (pb.get("message") or "no bend order found")


def status_line(part):
    if part.get("status") == "ok":
        line = "%s: %.1f cm², %d bends, MS %.2f" % (part.get("load"), part.get("area_m2", 0) * 1e4,
                                                 part.get("bends", 0), part.get("margin_of_safety", 0))
        if part.get("gauges_tried"):  # its own sheet gave no part: say which one it is made of
            line += ", %.3g mm sheet (thicker gauge)" % (part_sheet(part, 0.0) * 1e3)
        return line
    return "%s: no valid part (%s)" % (part.get("load"), part.get("reason") or part.get("status"))


# ---------------------------------------------------------------------------
# the envelope (result.json parts[i].envelope, docs/pipeline.md)

def _case(envelope, name):
    return next((c for c in envelope.get("cases") or [] if c.get("name") == name), None)


def envelope_rows(part):
    """[(label, text, alert)] of the Results panel for a part's envelope: the governing case of each check
    (rows "Stiffness": largest C/C_max; "Strength": lowest MS; "Buckling": lowest factor), the buckling factor
    and the natural frequencies. ``alert`` marks a number that misses the problem's requirement. [] without an envelope
    (a result.json written before load cases)."""
    env = part.get("envelope")
    if not isinstance(env, dict):
        return []
    gov = env.get("governing") or {}
    req = env.get("required") or {}
    checked = bool(req.get("checked"))
    rows = [("Cases", "%d" % len(env.get("cases") or []), False)]
    name = gov.get("stiffness")
    c = _case(env, name)
    if c is not None and c.get("compliance_limit"):
        ratio = c["compliance"] / c["compliance_limit"]
        rows.append(("Stiffness", "%s (C/C_max %.3f)" % (name, ratio), ratio > 1.0))
    else:
        rows.append(("Stiffness", name or "—", False))
    name = gov.get("strength")
    c = _case(env, name)
    if c is not None and c.get("margin_of_safety") is not None:
        rows.append(("Strength", "%s (MS %.3f)" % (name, c["margin_of_safety"]), False))
    else:
        rows.append(("Strength", name or "—", False))
    factor = env.get("buckling_factor")
    floor = req.get("min_buckling_factor")
    if factor is None:
        # null: nothing compresses the sheet, or the eigen checks were not run (a failed static case)
        text = "none (nothing buckles)" if env.get("eigen_checked") else "not computed"
        rows.append(("Buckling", gov.get("buckling") or "—", False))
        rows.append(("Buckling factor", text, False))
    else:
        rows.append(("Buckling", gov.get("buckling") or "—", False))
        low = checked and floor is not None and factor < floor
        rows.append(("Buckling factor", "%.3f" % factor + (" (min %.3g)" % floor if checked and floor else ""), low))
    freqs = env.get("frequencies_hz") or []
    fmin = req.get("min_frequency_hz")
    if freqs:
        low = checked and fmin is not None and freqs[0] < fmin
        rows.append(("1st frequency (Hz)", "%.1f" % freqs[0] + (" (floor %.3g)" % fmin if fmin else ""), low))
        if len(freqs) > 1:
            rows.append(("Frequencies (Hz)", ", ".join("%.1f" % f for f in freqs), False))
    else:
        rows.append(("1st frequency (Hz)", "not computed", False))
    return rows
