"""A part's compliance and margin of safety re-computed by CalculiX (`ccx`).

* Compliance and load deflection on a solid model of the part
  (solid_reference.py: the tabs as t-thick plates fused and meshed in C3D10 by
  gmsh, with the supports, box link, loads and material of the S4 deck
  `sheetgen export-ccx` writes): within CCX_TOLERANCE of result.json, and within
  the limit (+ the same tolerance). CCX_TOLERANCE is 5 %, the check's acceptance bound. The solid
  and not CalculiX's shells: the shell decks are meshed from our own triangles,
  and their 20-node expansion (S8R) is 3-10 % softer than the solid on parts
  whose load passes a fold end, where ours is within 3 % of it (docs/fem.md
  "A solid reference"). S8R and S4 are reported beside it. A part the solid
  model cannot represent (self-riveted sheets apart) is checked against S8R
  instead, and the report says so.
* The margin of safety from CalculiX's stresses on the S4 deck
  (ccx_max_von_mises: surface von Mises per element, by the stress rule of
  docs/fem.md applied to CalculiX's own mesh): CalculiX's maximum may exceed
  the stress at which MS equals the requirement by at most STRESS_TOLERANCE.
"""
import math
import os
import re
import subprocess
import tempfile

import numpy as np

from . import solid_reference

CCX_TOLERANCE = 0.05  # see the module docstring
STRESS_TOLERANCE = 0.05  # CalculiX's maximum stress may exceed the allowed one by this share
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


def ccx_compliance(deck, dat):
    """C = sum of the deck's *CLOAD values times CalculiX's displacements (the
    rigid body's ROT node carries the rotations), and |u| of the load's REF node (m)."""
    cloads = [(int(a), int(b), float(c)) for a, b, c in re.findall(r"^\s*(\d+)\s*,\s*(\d+)\s*,\s*([-+0-9.eE]+)\s*$",
                                                                      deck.split("*CLOAD")[1].split("*")[0], re.M)]
    # The load's REF node carries the force (a self-rivet's rigid body comes first in the deck).
    ref = next((n for n, d, _ in cloads if d <= 3), None) or int(re.search(r"REF NODE=(\d+)", deck).group(1))
    disp = {}
    for line in dat.split("displacements (vx,vy,vz)")[-1].splitlines():
        p = line.split()
        if len(p) == 4 and p[0].isdigit():
            disp[int(p[0])] = [float(x) for x in p[1:]]
    return sum(v * disp[n][d - 1] for n, d, v in cloads), float(np.linalg.norm(disp[ref]))


def _s4_mesh(deck):
    """The S4 deck's nodes: (X #N by 3 m, {node id: row}), and its elements: (ids, quads #Q by 4 rows)."""
    ids, X = [], []
    for line in solid_reference.deck_section_lines(deck, "*NODE"):
        p = line.split(",")
        if len(p) == 4:
            ids.append(int(p[0]))
            X.append([float(v) for v in p[1:]])
    index = {n: i for i, n in enumerate(ids)}
    elem_ids, quads = [], []
    for line in solid_reference.deck_section_lines(deck, "*ELEMENT"):
        p = line.split(",")
        if len(p) == 5:
            elem_ids.append(int(p[0]))
            quads.append([index[int(v)] for v in p[1:]])
    return np.array(X), index, elem_ids, np.array(quads)


def _singular_points(deck, index, quads, X):
    """Rows of the clamped nodes, the rigid bodies' nodes and the re-entrant
    corners that carry an element, the longest incident edge per node (m),
    and the re-entrant corners alone."""
    singular = set()
    for line in solid_reference.deck_section_lines(deck, "*BOUNDARY"):
        if line.strip():
            singular.add(index[int(line.split(",")[0])])
    for m in re.finditer(r"^\*NSET, NSET=(RIGID\d+)\s*$", deck, re.M):
        body = deck[m.end():].split("\n*")[0]
        singular.update(index[int(v)] for v in re.findall(r"\d+", body))
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


def _surface_von_mises(dat, elem_ids, Q):
    """Per element (corners Q #E by 4 by 3): the larger surface von Mises stress (Pa)
    of its two faces, from the 2 x 2 x 2 integration points CalculiX prints."""
    block = dat.split("stresses (elem, integ.pnt.")[-1]
    S = {}
    for line in block.splitlines()[1:]:
        p = line.split()
        if len(p) >= 8 and p[0].isdigit():
            S.setdefault(int(p[0]), [None] * 8)[int(p[1]) - 1] = [float(v) for v in p[2:8]]
    sig = np.array([S[e] for e in elem_ids])  # E x 8 x 6 (xx, yy, zz, xy, xz, yz)
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


def ccx_max_von_mises(deck, dat, t, corner_clearance=0.0):
    """The largest surface von Mises stress (Pa) CalculiX finds away from the singular points.

    CalculiX expands each S4 shell into a brick with 2 x 2 x 2 integration points
    (1-4 on one side of the mid-surface, 5-8 on the other, at +-t/(2 sqrt 3)).
    Per element, each layer's points are averaged (the element centre), the
    in-plane part kept (P = I - n n^T; a surface carries no transverse shear or
    normal stress) and extrapolated linearly to the two surfaces. The rule is
    the one docs/fem.md states, applied to CalculiX's own mesh: elements whose
    centre is within 2 t + h_p of a clamped node, a rigid-body node or a
    re-entrant corner of the outline (corner angles > 190 deg) are left out.
    h_p is the longest triangle edge at p, as in sheetgen's rule: the deck
    splits every triangle at its edge midpoints into three quads, so it is
    twice the longest quad edge at p. At a re-entrant corner the radius is
    2 t + max(h_p, corner_clearance), the bend radius, as sheetgen's rule
    (docs/fem.md "Graded fold ends"). Returns (sigma_max, number of singular
    points, number of re-entrant corners).
    """
    X, index, elem_ids, quads = _s4_mesh(deck)
    pts, size, corners = _singular_points(deck, index, quads, X)
    Q = X[quads]
    vm = _surface_von_mises(dat, elem_ids, Q)
    excluded = _excluded_elements(Q.mean(axis=1), X, pts, size, corners, t, corner_clearance)
    kept = vm[~excluded] if (~excluded).any() else vm
    return float(kept.max()), len(pts), len(corners)


def _run_deck(sheetgen, out_dir, load, tmp, job, element_type, extra=""):
    """`sheetgen export-ccx` of one load into tmp/job.inp (`extra` added to its
    step), solved by ccx: (deck text, .dat text, (C J, |u| m))."""
    deck = os.path.join(tmp, job + ".inp")
    subprocess.run([sheetgen, "export-ccx", os.path.join(out_dir, "result.json"), "--load", load,
                    "--out", deck, "--element-type", element_type], check=True, stdout=subprocess.DEVNULL)
    text = open(deck).read()
    if extra:
        open(deck, "w").write(text.replace("*END STEP", extra + "*END STEP"))
    subprocess.run(["ccx", "-i", job], cwd=tmp, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    dat = open(os.path.join(tmp, job + ".dat")).read()
    return text, dat, ccx_compliance(text, dat)


def _solid_or_s8r(part, deck, tmp, s8r, findings):
    """(C J, |u| m, the reference's name): the solid model's, else S8R's with the reason."""
    name = part["load"]
    try:
        solid = solid_reference.solid_compliance(part, deck, tmp)
        findings.note(f"{name}: solid model h = {solid['h'] * 1e3:.2f} mm, {solid['nodes']} nodes, "
                      f"{solid['elements']} C3D10, {solid['fixed']} fixed, {solid['rigid']} in the box link")
        return solid["C"], solid["deflection"], "solid C3D10"
    except solid_reference.SolidNotApplicable as e:
        findings.note(f"{name}: no solid model ({e}); compliance checked against S8R")
    except Exception as e:  # gmsh or ccx failed on this part: a failed check, not a crash
        findings.fail(f"{name}: the solid model could not be built or solved ({type(e).__name__}: {e})")
    return s8r[0], s8r[1], "S8R"


def _check_compliance(part, C, deflection, reference, C8, C4, findings):
    name = part["load"]
    c_ours, d_ours, limit = part["compliance"], part["deflection_m"], part["compliance_limit"]
    findings.note(f"{name}: compliance ours {c_ours:.5g} J, CalculiX {reference} {C:.5g} J ({(c_ours / C - 1) * 100:+.2f} %), "
                  f"S8R {C8:.5g} J ({(c_ours / C8 - 1) * 100:+.2f} %), S4 {C4:.5g} J ({(c_ours / C4 - 1) * 100:+.2f} %); "
                  f"deflection ours {d_ours * 1e3:.4f} mm, CalculiX {deflection * 1e3:.4f} mm; limit {limit:.4g} J")
    if abs(c_ours / C - 1) > CCX_TOLERANCE:
        findings.fail(f"{name}: compliance differs from CalculiX ({reference}) by {(c_ours / C - 1) * 100:.1f} %")
    if C > (1 + CCX_TOLERANCE) * limit:
        findings.fail(f"{name}: CalculiX ({reference}) compliance {C:.4g} J exceeds the limit {limit:.4g} J")


def _check_margin(prob, part, s_ccx, n_singular, n_corners, findings):
    # MS from CalculiX's stress: MS = Fty / (SF sigma) - 1, so Fty / SF = (1 + MS) sigma_ours.
    name = part["load"]
    s_ours, ms_ours = part["max_von_mises_pa"], part["margin_of_safety"]
    ms_required = prob.get("requirements", {}).get("min_margin_of_safety", 0.0)
    ms_ccx = (1 + ms_ours) * s_ours / s_ccx - 1
    findings.note(f"{name}: max von Mises ours {s_ours * 1e-6:.2f} MPa, CalculiX {s_ccx * 1e-6:.2f} MPa "
                  f"({(s_ours / s_ccx - 1) * 100:+.2f} %; {n_singular} singular points, {n_corners} re-entrant "
                  f"corners); MS ours {ms_ours:.3f}, CalculiX {ms_ccx:.3f}, required {ms_required:.3g}")
    allowed = (1 + ms_ours) * s_ours / (1 + ms_required)  # Pa, the stress at which MS = required
    if s_ccx > (1 + STRESS_TOLERANCE) * allowed:
        findings.fail(f"{name}: CalculiX stress {s_ccx * 1e-6:.1f} MPa gives MS {ms_ccx:.3f} below the required "
                      f"{ms_required:.3g} by more than {STRESS_TOLERANCE * 100:.0f} % of the stress")


def check_calculix(out_dir, prob, part, sheetgen, findings):
    """Compliance (the solid model, S8R and S4 beside it) and MS (the S4 deck's
    stresses) of one part of out_dir/result.json by CalculiX."""
    t = prob.get("material", {}).get("thickness", 1.6e-3)
    bend_radius = prob.get("manufacturing", {}).get("bend_radius", 4 * t)
    name = part["load"]
    with tempfile.TemporaryDirectory() as tmp:
        # Ask CalculiX for the stresses at its integration points as well.
        text, dat, (C4, _) = _run_deck(sheetgen, out_dir, name, tmp, "part", "S4", "*EL PRINT, ELSET=EALL\nS\n")
        s_ccx, n_singular, n_corners = ccx_max_von_mises(text, dat, t, bend_radius)
        _, _, s8r = _run_deck(sheetgen, out_dir, name, tmp, "part8", "S8R")
        C, deflection, reference = _solid_or_s8r(part, text, tmp, s8r, findings)
    _check_compliance(part, C, deflection, reference, s8r[0], C4, findings)
    _check_margin(prob, part, s_ccx, n_singular, n_corners, findings)
