"""The stress rule of docs/fem.md on CalculiX's own S4 mesh: the largest
surface von Mises stress away from the singular points, per static step of a
deck (ccx_check.py's margin of safety)."""
import math

import numpy as np

from . import ccx_deck

REENTRANT_ANGLE = math.radians(190.0)  # a boundary node whose corner angles add up to more is a re-entrant corner


def _quad_reentrant_corners(quads, X, min_angle):
    """Boundary nodes of a quad mesh (quads #Q by 4 into X #N by 3) whose corner
    angles add up to more than min_angle (rad)."""
    angle_sum = np.zeros(len(X))
    for k in range(4):
        a, b, c = quads[:, k], quads[:, (k + 1) % 4], quads[:, (k + 3) % 4]
        u, v = X[b] - X[a], X[c] - X[a]
        ang = np.arctan2(np.linalg.norm(np.cross(u, v), axis=1), np.einsum("ij,ij->i", u, v))
        np.add.at(angle_sum, a, ang)
    edges = np.sort(np.concatenate([quads[:, [k, (k + 1) % 4]] for k in range(4)]), axis=1)
    uniq, uses = np.unique(edges, axis=0, return_counts=True)
    on_boundary = np.zeros(len(X), bool)
    on_boundary[uniq[uses == 1].ravel()] = True
    return np.nonzero(on_boundary & (angle_sum > min_angle))[0]


def _s4_mesh(deck):
    """The S4 deck's nodes: (X #N by 3 m, {node id: row}), and its elements: (ids, quads #Q by 4 rows)."""
    ids, X = [], []
    for n, x in ccx_deck.nodes(deck).items():
        ids.append(n)
        X.append(x)
    index = {n: i for i, n in enumerate(ids)}
    elem_ids, quads = [], []
    for line in ccx_deck.section_lines(deck, "ELEMENT"):
        p = line.split(",")
        if len(p) == 5:
            elem_ids.append(int(p[0]))
            quads.append([index[int(v)] for v in p[1:]])
    return np.array(X), index, elem_ids, np.array(quads)


def _singular_points(deck, index, quads, X):
    """Rows of the clamped nodes, the rigid links' nodes and the re-entrant
    corners that carry an element, the longest incident edge per node (m),
    and the re-entrant corners alone."""
    singular = set()
    for line in ccx_deck.section_lines(deck, "BOUNDARY"):
        singular.add(index[int(line.split(",")[0])])
    for _, _, _, members in ccx_deck.links(deck):
        singular.update(index[n] for n in members)
    corners = _quad_reentrant_corners(quads, X, REENTRANT_ANGLE)
    singular.update(corners.tolist())
    # Longest incident edge per node; points that carry no element do not count.
    size = np.zeros(len(X))
    for k in range(4):
        a, b = quads[:, k], quads[:, (k + 1) % 4]
        L = np.linalg.norm(X[b] - X[a], axis=1)
        np.maximum.at(size, a, L)
        np.maximum.at(size, b, L)
    pts = np.array(sorted(i for i in singular if size[i] > 0), dtype=int)
    return pts, size, corners


def _stress_tensors(v):
    """Symmetric 3 x 3 tensors from CalculiX's (xx, yy, zz, xy, xz, yz) rows (... by 6)."""
    T = np.empty(v.shape[:-1] + (3, 3))
    T[..., 0, 0], T[..., 1, 1], T[..., 2, 2] = v[..., 0], v[..., 1], v[..., 2]
    T[..., 0, 1] = T[..., 1, 0] = v[..., 3]
    T[..., 0, 2] = T[..., 2, 0] = v[..., 4]
    T[..., 1, 2] = T[..., 2, 1] = v[..., 5]
    return T


def _surface_von_mises(block, elem_ids, Q):
    """Per element (corners Q #E by 4 by 3): the larger surface von Mises stress (Pa)
    of its two faces, from the 2 x 2 x 2 integration points CalculiX prints
    (block: {element: {point 1-8: 6 values}}, one stress block of ccx_deck.read_dat)."""
    sig = np.array([[block[e][p] for p in range(1, 9)] for e in elem_ids])  # E x 8 x 6 (xx, yy, zz, xy, xz, yz)
    lower, upper = _stress_tensors(sig[:, :4].mean(axis=1)), _stress_tensors(sig[:, 4:].mean(axis=1))
    n = np.cross(Q[:, 2] - Q[:, 0], Q[:, 3] - Q[:, 1])
    n /= np.linalg.norm(n, axis=1)[:, None]
    P = np.eye(3)[None] - n[:, :, None] * n[:, None, :]
    mid, half = 0.5 * (upper + lower), 0.5 * (upper - lower)
    vm = np.zeros(len(Q))
    for side in (1.0, -1.0):  # the layers sit at +-t/(2 sqrt 3): sqrt 3 extrapolates to the surfaces
        T = P @ (mid + side * math.sqrt(3.0) * half) @ P
        d = T[:, [0, 1, 2], [0, 1, 2]]
        v = np.sqrt(0.5 * ((d[:, 0] - d[:, 1]) ** 2 + (d[:, 1] - d[:, 2]) ** 2 + (d[:, 2] - d[:, 0]) ** 2)
                    + 3 * (T[:, 0, 1] ** 2 + T[:, 0, 2] ** 2 + T[:, 1, 2] ** 2))
        vm = np.maximum(vm, v)
    return vm


def _excluded_elements(centre, X, pts, size, corners, t, corner_clearance):
    """Elements whose centre (#E by 3) lies within 2 t + h_p of a singular point
    (2 t + max(h_p, corner_clearance) at a re-entrant corner)."""
    excluded = np.zeros(len(centre), bool)
    if not len(pts):
        return excluded
    reach = 2 * size[pts]
    at_corner = np.isin(pts, corners)
    reach[at_corner] = np.maximum(reach[at_corner], corner_clearance)
    Y, r2 = X[pts], (2 * t + reach) ** 2
    step = max(1, int(4e6 // len(pts)))  # a step x #points distance matrix, ~32 MB
    for k in range(0, len(centre), step):
        c = centre[k:k + step]
        d2 = (c * c).sum(axis=1)[:, None] + (Y * Y).sum(axis=1)[None, :] - 2 * c @ Y.T
        excluded[k:k + step] = (d2 < r2[None, :]).any(axis=1)
    return excluded


def max_von_mises_per_block(deck, stress_blocks, t, corner_clearance=0.0):
    """ccx_max_von_mises for each stress block (ccx_deck.read_dat(...).stresses,
    one per static step): ([sigma_max Pa per block], number of singular points,
    number of re-entrant corners). The excluded elements are the same for all."""
    X, index, elem_ids, quads = _s4_mesh(deck)
    pts, size, corners = _singular_points(deck, index, quads, X)
    Q = X[quads]
    excluded = _excluded_elements(Q.mean(axis=1), X, pts, size, corners, t, corner_clearance)
    out = []
    for block in stress_blocks:
        vm = _surface_von_mises(block, elem_ids, Q)
        out.append(float((vm[~excluded] if (~excluded).any() else vm).max()))
    return out, len(pts), len(corners)


def ccx_max_von_mises(deck, dat, t, corner_clearance=0.0):
    """The largest surface von Mises stress (Pa) CalculiX finds away from the
    singular points, in the .dat's (text) last stress block.

    CalculiX expands each S4 shell into a brick with 2 x 2 x 2 integration points
    (1-4 on one side of the mid-surface, 5-8 on the other, at +-t/(2 sqrt 3)).
    Per element, each layer's points are averaged (the element centre), the
    in-plane part kept (P = I - n n^T; a surface carries no transverse shear or
    normal stress) and extrapolated linearly to the two surfaces. The rule is
    the one docs/fem.md states, applied to CalculiX's own mesh: elements whose
    centre is within 2 t + h_p of a clamped node, a rigid-link node or a
    re-entrant corner of the outline (corner angles > 190 deg) are left out.
    h_p is the longest triangle edge at p, as in sheetgen's rule: the deck
    splits every triangle at its edge midpoints into three quads, so it is
    twice the longest quad edge at p. At a re-entrant corner the radius is
    2 t + max(h_p, corner_clearance), the bend radius, as sheetgen's rule
    (docs/fem.md "Graded fold ends"). Returns (sigma_max, number of singular
    points, number of re-entrant corners).
    """
    sigmas, n_singular, n_corners = max_von_mises_per_block(deck, ccx_deck.read_dat(dat).stresses[-1:], t,
                                                            corner_clearance)
    return sigmas[0], n_singular, n_corners
