"""Brute-force clearance of a part, independent of the solver's distance field:
every tab sampled every 1.5 mm, the exact point-triangle distance (numpy) to
every environment triangle and load box, except the documented allowed
contacts (a flange on its own rivet area, the base tab on its own load, and the
bend zone next to each: docs/grammar.md). Every rivet flange must lie on its
rivet area: its samples t/2 from the area's faces."""
import math

import numpy as np

from .geometry import box_distance, distance_to_segment, point_triangle_distance, sample_polygon
from .problem import rivet_area_mesh

SPACING = 1.5e-3         # m between samples; sampling misses at most half of it
TOLERANCE = 0.5 * 1.6e-3  # m; the tool guarantees required - h/4 (docs/environment.md)
FLUSH = 0.1e-3            # m, how far a rivet flange may sit off t/2 from its area
CHUNK = 256               # samples and triangles per distance matrix, to bound memory


class _Setting:
    """The numbers one part's check needs, read once from the problem."""

    def __init__(self, prob, part):
        self.t = prob.get("material", {}).get("thickness", 1.6e-3)
        clearance = prob.get("requirements", {}).get("clearance", 1.0e-3)
        bend_radius = prob.get("manufacturing", {}).get("bend_radius", 4 * self.t)
        self.required = 0.5 * self.t + clearance
        # The allowed-contact zone next to the bend into a contact (docs/grammar.md), generous.
        self.band = bend_radius + self.t + 0.5 * self.t + 1e-4
        self.load_index = [l["name"] for l in prob["loads"]].index(part["load"])
        self.ra_faces = {i: (rivet_area_mesh(prob, ra), set(ra["faces"])) for i, ra in enumerate(prob["rivet_areas"])}


def _bend_roots(tabs, ti, ra):
    """Corner arrays of the tabs whose first edge is a bend between tab ti and a
    flange on rivet area ra (a child flange, or ti itself when its parent is one)."""
    tab = tabs[ti]
    roots = [np.array(tb["corners"]) for tb in tabs if tb["parent"] == ti and tb.get("rivet_area", -1) == ra]
    if tab["parent"] >= 0 and tabs[tab["parent"]].get("rivet_area", -1) == ra:
        roots.append(np.array(tab["corners"]))
    return roots


def _lower_to_triangles(d_min, rows, P, V, F):
    """Lowers d_min[rows] to the distances from the samples P[rows] to the
    triangles F (#F by 3 into V) wherever that can lower the tab's smallest
    distance min(d_min). Per run of CHUNK samples (neighbours on the tab), the
    triangles go nearest first by the distance between their bounding box and
    the samples'; one farther than min(d_min) cannot lower it and is left out.
    So min(d_min) and the sample it is at come out as the brute force over
    every triangle gives them, in a fraction of the time (the other samples
    may keep larger values, which nothing reads)."""
    if not len(F) or not len(rows):
        return
    T = V[F]
    t_lo, t_hi = T.min(axis=1), T.max(axis=1)
    for j in range(0, len(rows), CHUNK):
        r = rows[j:j + CHUNK]
        Q = P[r]
        gap = np.maximum(0.0, np.maximum(t_lo - Q.max(axis=0), Q.min(axis=0) - t_hi))
        lower_bound = np.linalg.norm(gap, axis=1)
        near = np.nonzero(lower_bound <= d_min.min())[0]
        near = near[np.argsort(lower_bound[near], kind="stable")]
        for k in range(0, len(near), CHUNK):
            batch = near[k:k + CHUNK]
            batch = batch[lower_bound[batch] <= d_min.min()]
            if not len(batch):
                break  # sorted: every later triangle is farther still
            A, B, C = V[F[batch, 0]], V[F[batch, 1]], V[F[batch, 2]]
            d_min[r] = np.minimum(d_min[r], point_triangle_distance(Q, A, B, C).min(axis=1))


def _lower_to_mesh(d_min, P, tabs, ti, name, V, F, s):
    """Lowers d_min, the smallest distances (m) from tab ti's samples P, to one
    mesh, its allowed contacts left out."""
    every = np.arange(len(P))
    keep = np.ones(len(F), bool)
    for ra, (rm, faces) in s.ra_faces.items():
        if rm != name:
            continue
        roots = _bend_roots(tabs, ti, ra)
        if ra == tabs[ti].get("rivet_area", -1):
            keep[list(faces)] = False  # a flange on its own rivet area
        elif roots:
            # A tab may come near the rivet area of a flange across a bend from
            # it (its parent or a child) inside that bend's zone; elsewhere the area counts.
            zone = np.zeros(len(P), bool)
            for c in roots:
                zone |= distance_to_segment(P, c[0], c[1]) < s.band
            _lower_to_triangles(d_min, every[~zone], P, V, F[list(faces)])
            keep[list(faces)] = False
    _lower_to_triangles(d_min, every, P, V, F[keep])


def _box_distances(P, prob, tabs, ti, s):
    """Distances (m) from a tab's samples P to every load box, the base tab's
    own load and the bend zone of its children next to it left out."""
    d_min = np.full(len(P), np.inf)
    for li, load in enumerate(prob["loads"]):
        if li == s.load_index and ti == 0:
            continue  # the base tab carries its own load
        d = box_distance(P, load)
        if li == s.load_index and tabs[ti]["parent"] == 0:
            c = np.array(tabs[ti]["corners"])
            d = np.where(distance_to_segment(P, c[0], c[1]) < s.band, np.inf, d)
        d_min = np.minimum(d_min, d)
    return d_min


def _check_flush(P, prob, meshes, part, ti, s, findings):
    """A rivet flange's samples lie t/2 from its rivet area's faces."""
    ra = part["tabs"][ti]["rivet_area"]
    mname, faces = s.ra_faces[ra]
    V, F = meshes[mname]
    Fr = F[sorted(faces)]
    d = point_triangle_distance(P, V[Fr[:, 0]], V[Fr[:, 1]], V[Fr[:, 2]]).min(axis=1)
    off = np.abs(d - 0.5 * s.t).max()
    name = part["load"]
    findings.note(f"{name}: flange tab {ti} on rivet area {prob['rivet_areas'][ra]['name']}: "
                  f"max |distance - t/2| = {off * 1e3:.4f} mm")
    if off > FLUSH:
        findings.fail(f"{name}: flange tab {ti} is not flush on its rivet area (off by {off * 1e3:.3f} mm)")


def check_clearance(prob, meshes, part, findings):
    """The clearance of every tab of `part` (a result.json part) to `meshes`
    ({name: (#V by 3, #F by 3)}: the environment, and the earlier parts' faces
    for a multi-load problem) and to every load box; rivet flanges flush."""
    s = _Setting(prob, part)
    name, tabs = part["load"], part["tabs"]
    worst = (math.inf, None)
    for ti, tab in enumerate(tabs):
        P = sample_polygon(tab["corners"], SPACING)
        d_min = _box_distances(P, prob, tabs, ti, s)  # first: cheap, and a bound for the meshes
        for mname, (V, F) in meshes.items():
            _lower_to_mesh(d_min, P, tabs, ti, mname, V, F, s)
        i = int(np.argmin(d_min))
        if d_min[i] < worst[0]:
            worst = (float(d_min[i]), ti)
        if d_min[i] < s.required - TOLERANCE:
            findings.fail(f"{name}: tab {ti} is {d_min[i] * 1e3:.3f} mm from an obstacle at {np.round(P[i], 4).tolist()} "
                          f"(required {s.required * 1e3:.2f} mm)")
        if tab.get("rivet_area", -1) >= 0:
            _check_flush(P, prob, meshes, part, ti, s, findings)
    findings.note(f"{name}: min clearance {worst[0] * 1e3:.3f} mm (required {s.required * 1e3:.2f} mm) at tab {worst[1]}")
