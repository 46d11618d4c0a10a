"""Small geometry of the checks and pictures, in numpy: point-triangle and
point-box distances, sampling a tab, a load's box, both faces of a part's sheet."""
import math

import numpy as np

# The order the 8 corners of a box come in (x fastest, then y, then z) and its
# 6 faces as corner quads wound outward, two triangles each.
BOX_QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def point_triangle_distance(P, A, B, C):
    """Distances from points P (n by 3) to triangles A, B, C (m by 3 each): n by m.
    Ericson's Voronoi regions (Real-Time Collision Detection, 5.1.5), vectorised."""
    P = P[:, None, :]
    ab, ac, ap = B - A, C - A, P - A
    d1, d2 = (ab * ap).sum(-1), (ac * ap).sum(-1)
    bp = P - B
    d3, d4 = (ab * bp).sum(-1), (ac * bp).sum(-1)
    cp = P - C
    d5, d6 = (ab * cp).sum(-1), (ac * cp).sum(-1)
    va = d3 * d6 - d5 * d4
    vb = d5 * d2 - d1 * d6
    vc = d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        denom = va + vb + vc
        v = vb / denom
        w = vc / denom
        q = A + v[..., None] * ab + w[..., None] * ac  # interior
        t_ab = np.clip(d1 / (d1 - d3), 0, 1)
        t_ac = np.clip(d2 / (d2 - d6), 0, 1)
        t_bc = np.clip((d4 - d3) / ((d4 - d3) + (d5 - d6)), 0, 1)
    q = np.where(((vc <= 0) & (d1 >= 0) & (d3 <= 0))[..., None], A + t_ab[..., None] * ab, q)
    q = np.where(((vb <= 0) & (d2 >= 0) & (d6 <= 0))[..., None], A + t_ac[..., None] * ac, q)
    q = np.where(((va <= 0) & ((d4 - d3) >= 0) & ((d5 - d6) >= 0))[..., None], B + t_bc[..., None] * (C - B), q)
    q = np.where(((d1 <= 0) & (d2 <= 0))[..., None], A, q)
    q = np.where(((d3 >= 0) & (d4 <= d3))[..., None], B, q)
    q = np.where(((d6 >= 0) & (d5 <= d6))[..., None], C, q)
    return np.linalg.norm(P - q, axis=-1)


def load_rotation(load):
    """The load box's local -> world rotation matrix (3 by 3) from its (w, x, y, z) quaternion (normalised)."""
    w, x, y, z = load.get("rotation", [1, 0, 0, 0])
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    return R


def box_distance(P, load):
    """Signed distances (m) from points P (n by 3) to a load's box: negative inside."""
    R = load_rotation(load)
    local = (P - np.array(load["center"])) @ R
    q = np.abs(local) - 0.5 * np.array(load["size"])
    outside = np.linalg.norm(np.maximum(q, 0), axis=1)
    inside = np.minimum(q.max(axis=1), 0)
    return outside + inside


def box_corners(load, below=0.0):
    """The 8 corners (m, BOX_QUADS order) of a load's box with its bottom face
    lowered by `below` (m, along the box's own -z)."""
    R = load_rotation(load)
    h = 0.5 * (np.array(load["size"]) + np.array([0.0, 0.0, below]))
    c = np.array(load["center"]) - R @ np.array([0.0, 0.0, 0.5 * below])
    return [c + R @ (h * np.array([sx, sy, sz])) for sz in (-1, 1) for sy in (-1, 1) for sx in (-1, 1)]


def box_mesh(load, below=0.0):
    """A load's box as an inline problem mesh named "box:<load>", 12 triangles
    wound outward, its bottom lowered by `below` (m)."""
    vertices = [c.tolist() for c in box_corners(load, below)]
    triangles = [t for a, b, c, d in BOX_QUADS for t in ([a, b, c], [a, c, d])]
    return {"name": "box:" + load["name"], "vertices": vertices, "triangles": triangles}


def sample_polygon(corners, spacing):
    """Points (n by 3) covering a convex polygon: a fan of triangles, each sampled
    on a barycentric grid no coarser than `spacing` (m), row by row."""
    pts = []
    c = np.array(corners)
    for k in range(1, len(c) - 1):
        a, b, d = c[0], c[k], c[k + 1]
        n = max(2, int(math.ceil(max(np.linalg.norm(b - a), np.linalg.norm(d - a), np.linalg.norm(d - b)) / spacing)))
        # Grid points (i, j), i + j <= n, row i by row i; same arithmetic as point by point.
        i = np.concatenate([np.full(n + 1 - row, row) for row in range(n + 1)])
        j = np.concatenate([np.arange(n + 1 - row) for row in range(n + 1)])
        pts.append(a + (b - a) * i[:, None] / n + (d - a) * j[:, None] / n)
    return np.concatenate(pts)


def distance_to_segment(P, a, b):
    """Distances (m) from points P (n by 3) to the segment a-b."""
    ab = b - a
    t = np.clip(((P - a) @ ab) / max(ab @ ab, 1e-300), 0, 1)
    return np.linalg.norm(P - (a + t[:, None] * ab), axis=1)


def tab_plane(corners):
    """A tab's corners (k by 3) and its unit normal by Newell's method."""
    C = np.array(corners, float)
    n = np.zeros(3)
    for i in range(len(C)):
        n += np.cross(C[i], C[(i + 1) % len(C)])
    return C, n / np.linalg.norm(n)


def tab_normal(tab):
    """A tab's unit normal: result.json's "normal" when it has one, else the
    largest corner cross product (robust on slivers)."""
    if "normal" in tab:
        return np.asarray(tab["normal"], float)
    C = np.array(tab["corners"], float)
    n = np.cross(C[1] - C[0], C[2] - C[0])
    for k in range(3, len(C)):
        m = np.cross(C[k - 1] - C[0], C[k] - C[0])
        n = m if np.linalg.norm(m) > np.linalg.norm(n) else n
    return n / np.linalg.norm(n)


def part_faces(part, thickness):
    """A finished part as the parts after it must see it: both faces (mid-surface
    +- t/2, t = thickness in m) of every tab, fanned from its first corner.
    Returns (vertices #V by 3 m, triangles #F by 3)."""
    V, F = [], []
    for tab in part["tabs"]:
        C, n = np.array(tab["corners"], float), tab_normal(tab)
        for side in (-0.5, 0.5):
            base = len(V)
            V.extend(C + side * thickness * n)
            F.extend([base, base + k, base + k + 1] for k in range(1, len(C) - 1))
    return np.array(V), np.array(F, int)
