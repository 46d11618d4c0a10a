"""A part's flat.dxf read by ezdxf, against result.json:

* the CUT outline is one simple closed polygon (shapely) whose area equals the
  flat-pattern area;
* the rivet holes (check_holes): one per rivet and two per self-rivet, sized
  for the rivet, their centres the rivet edge distance from every cut edge and
  from every bend zone (flat sheet only), keeping per tab the distances of
  their rivets on the bent part, and a self-rivet's two holes meeting when bent.
"""
import csv
import math
import os

import ezdxf
import numpy as np
from shapely.geometry import Point, Polygon

from .geometry import tab_plane

HOLE_PLAY = 0.2  # mm a hole may exceed the rivet's diameter
EDGE_SLACK = 0.01  # mm, rounding of the DXF's coordinates on the edge distance


def rivet_shank_diameter(prob, t):
    """The rivet diameter d the problem asks for (m): manufacturing.rivet_diameter, else
    2 t rounded up to 1/32 in and at least 1/8 in (the default of docs/problem-format.md)."""
    d = prob.get("manufacturing", {}).get("rivet_diameter", 0.0) or 0.0
    if d > 0:
        return d
    step = 0.0254 / 32
    return max(math.ceil(2 * t / step - 1e-9) * step, 0.0254 / 8)


def check_outline(out_dir, part, findings):
    """The CUT outline of <out_dir>/<load>/flat.dxf; returns the ezdxf document for check_holes."""
    name = part["load"]
    doc = ezdxf.readfile(os.path.join(out_dir, name, "flat.dxf"))
    outlines = [e for e in doc.modelspace() if e.dxf.layer == "CUT" and e.dxftype() in ("POLYLINE", "LWPOLYLINE")]
    if len(outlines) != 1:
        findings.fail(f"{name}: {len(outlines)} outlines on CUT, want 1")
        return doc
    pts = [(v.dxf.location.x, v.dxf.location.y) for v in outlines[0].vertices]
    closed = outlines[0].is_closed
    poly = Polygon(pts)
    area_mm2 = part["area_m2"] * 1e6
    findings.note(f"{name}: DXF outline {len(pts)} vertices, closed {closed}, simple {poly.is_valid}, "
                  f"area {poly.area:.3f} mm^2 vs result {area_mm2:.3f} mm^2")
    if not closed or not poly.is_valid:
        findings.fail(f"{name}: DXF outline is not a simple closed polygon")
    if abs(poly.area - area_mm2) > 1e-6 * area_mm2:
        findings.fail(f"{name}: DXF area {poly.area:.3f} mm^2 differs from result.json {area_mm2:.3f} mm^2")
    return doc


def _bend_zones(part):
    """(bend number, the band of width BA about its centre line as a shapely
    polygon in the DXF's mm frame) per bend of the flat pattern."""
    fp = part["flat_pattern"]
    lo = np.min(np.array(fp["outline"][0], float), axis=0)
    zones = []
    for b in fp["bends"]:
        A, B = 1e3 * (np.array(b["a"]) - lo), 1e3 * (np.array(b["b"]) - lo)
        u = (B - A) / np.linalg.norm(B - A)
        h = 0.5e3 * b["allowance"] * np.array([-u[1], u[0]])
        zones.append((b["number"], Polygon([A - h, B - h, B + h, A + h])))
    return zones


def _check_hole_places(name, circles, poly, zones, d, e_req, findings):
    """Every hole sized for a d mm rivet and at least e_req mm from a cut edge
    and from a bend zone; returns the smallest of both margins (mm)."""
    edge_margin, zone_margin = math.inf, math.inf
    for layer, cs in circles.items():
        for c in cs:
            dia = 2 * c.dxf.radius
            if not (d - 1e-6 <= dia <= d + HOLE_PLAY):
                findings.fail(f"{name}: a hole on {layer} is {dia:.3f} mm across for a {d:.3f} mm rivet")
            centre = Point(c.dxf.center.x, c.dxf.center.y)
            where = f"the hole at ({centre.x:.3f}, {centre.y:.3f}) mm on {layer}"
            to_edge = poly.exterior.distance(centre) if poly.contains(centre) else -math.inf
            edge_margin = min(edge_margin, to_edge)
            if to_edge < e_req - EDGE_SLACK:
                findings.fail(f"{name}: {where} is {to_edge:.3f} mm from a cut edge (edge distance {e_req:.3f} mm)")
            for number, zone in zones:
                to_zone = zone.distance(centre)
                zone_margin = min(zone_margin, to_zone)
                if to_zone < e_req - EDGE_SLACK:
                    findings.fail(f"{name}: {where} is {to_zone:.3f} mm from bend B{number}'s zone "
                                  f"(edge distance {e_req:.3f} mm)")
    return edge_margin, zone_margin


def _holes_by_tab(part, rows, circles, findings):
    """rivets.csv's holes per tab: {tab: [(flat centre mm, the rivet projected on the bent tab m, label)]};
    every row must have a hole drawn in flat.dxf."""
    name = part["load"]
    drawn = [(c.dxf.center.x, c.dxf.center.y) for cs in circles.values() for c in cs]
    by_tab = {}
    for row in rows:
        q = (float(row["x_mm"]), float(row["y_mm"]))
        if not any(math.dist(q, p) < 1e-3 for p in drawn):
            findings.fail(f"{name}: rivets.csv {row['label']} at {q} mm has no hole in flat.dxf")
        C, n = tab_plane(part["tabs"][int(row["tab"])]["corners"])
        w = np.array([float(row[k]) for k in ("world_x_m", "world_y_m", "world_z_m")])
        by_tab.setdefault(int(row["tab"]), []).append((np.array(q), w - (w - C[0]).dot(n) * n, row["label"]))
    return by_tab


def _check_bent_distances(part, rows, by_tab, t, findings):
    """rivets.csv lists result.json's rivets in order; bending keeps each tab's
    hole distances (rigid per tab); a self-rivet's two holes meet when bent
    (within 1.5 t, the stacking offset of two sheets). Returns (worst distance
    error mm, widest self-rivet gap mm)."""
    name = part["load"]
    world = [tuple(r) for r in part.get("rivets", [])] + [tuple(p) for s in part.get("self_rivets", []) for p in s["points"]]
    listed = [tuple(float(r[k]) for k in ("world_x_m", "world_y_m", "world_z_m")) for r in rows]
    if len(listed) != len(world) or any(math.dist(a, b) > 1e-8 for a, b in zip(listed, world)):
        findings.fail(f"{name}: rivets.csv does not list result.json's rivets and self-rivet points in order")
    worst = 0.0
    for holes in by_tab.values():
        for i in range(len(holes)):
            for j in range(i + 1, len(holes)):
                worst = max(worst, abs(np.linalg.norm(holes[i][0] - holes[j][0]) - 1e3 * np.linalg.norm(holes[i][1] - holes[j][1])))
    if worst > 1e-3:
        findings.fail(f"{name}: holes of one tab are {worst:.4f} mm off the distances of their rivets on the bent part")
    apart = 0.0
    for s_i in range(len(part.get("self_rivets", []))):
        label = f"S{s_i + 1}"
        ends = [h for holes in by_tab.values() for h in holes if h[2] == label]
        if len(ends) != 2:
            findings.fail(f"{name}: rivets.csv has {len(ends)} holes for {label}, want 2")
            continue
        apart = max(apart, 1e3 * float(np.linalg.norm(ends[0][1] - ends[1][1])))
    if apart > 1.5 * t * 1e3 + 1e-6:
        findings.fail(f"{name}: the two holes of a self-rivet are {apart:.3f} mm apart when bent (limit 1.5 t)")
    return worst, apart


def check_holes(out_dir, prob, part, findings, doc=None):
    """The rivet and self-rivet holes of flat.dxf (ezdxf; `doc` when already read) against result.json's
    rivets: one CIRCLE per rivet on RIVET_HOLES and two per self-rivet on
    SELF_RIVET_HOLES, a rivet of diameter d fits with at most HOLE_PLAY mm play, each
    hole lies inside the outline by at least the edge distance. rivets.csv names each
    hole's tab; with it, the holes of one tab must keep in the flat the
    distances their rivets have on the bent tab, and the two holes of a
    self-rivet must meet when bent."""
    name = part["load"]
    t = prob.get("material", {}).get("thickness", 1.6e-3)
    d = rivet_shank_diameter(prob, t) * 1e3  # mm
    if doc is None:
        doc = ezdxf.readfile(os.path.join(out_dir, name, "flat.dxf"))
    msp = doc.modelspace()
    outline = [e for e in msp if e.dxf.layer == "CUT" and e.dxftype() == "POLYLINE"]
    if len(outline) != 1:
        return  # check_outline reports it
    poly = Polygon([(v.dxf.location.x, v.dxf.location.y) for v in outline[0].vertices])
    circles = {layer: [e for e in msp if e.dxftype() == "CIRCLE" and e.dxf.layer == layer]
               for layer in ("RIVET_HOLES", "SELF_RIVET_HOLES")}
    n_rivets, n_self = len(part.get("rivets", [])), len(part.get("self_rivets", []))
    if len(circles["RIVET_HOLES"]) != n_rivets:
        findings.fail(f"{name}: {len(circles['RIVET_HOLES'])} circles on RIVET_HOLES for {n_rivets} rivets")
    if len(circles["SELF_RIVET_HOLES"]) != 2 * n_self:
        findings.fail(f"{name}: {len(circles['SELF_RIVET_HOLES'])} circles on SELF_RIVET_HOLES for {n_self} self-rivets")
    # Edge distance: from every cut edge, and from every bend zone (the band of
    # width BA about the bend's centre line, where the sheet is curved): a
    # rivet seats on flat sheet only.
    e_req = (prob.get("manufacturing", {}).get("rivet_edge_distance", 0.0) or 0.0) * 1e3 or 2 * d  # mm
    edge_margin, zone_margin = _check_hole_places(name, circles, poly, _bend_zones(part), d, e_req, findings)
    csv_path = os.path.join(out_dir, name, "rivets.csv")
    if not os.path.exists(csv_path):
        findings.fail(f"{name}: {csv_path} is missing")
        return
    with open(csv_path) as f:
        rows = list(csv.DictReader(f))
    worst, apart = _check_bent_distances(part, rows, _holes_by_tab(part, rows, circles, findings), t, findings)
    findings.note(f"{name}: holes {n_rivets} rivet + {2 * n_self} self-rivet, d {d:.3f} mm; centres at least "
                  f"{edge_margin:.3f} mm from a cut edge and {zone_margin:.3f} mm from a bend zone (edge distance "
                  f"{e_req:.3f} mm); per-tab distances within {worst:.2e} mm; "
                  f"self-rivet holes {apart:.3f} mm apart when bent")
