"""CalculiX on a solid model of a part: the compliance reference of verify.py (ccx_check.py).

The shell decks `sheetgen export-ccx` writes are meshed from our own triangles;
this model is not. Every tab becomes a plate of thickness t about its
midsurface (the tab's polygon moved -t/2 along its normal and extruded by t),
the plates are fused by OpenCASCADE (gmsh; fuzzy unions, FUSE_TOLERANCES, and
the mesh checked to hold every tab, uncovered_tabs), meshed in quadratic tetrahedra
(C3D10) of size h_solid (default 1.25 t, see DEFAULT_SIZE) and solved by CalculiX. Supports, the
box link, the loads and the material come from the shell deck, so both models
carry the same problem:

* rivets: every solid node of the rivet flange within the rivet's footprint
  radius of its centre (in the flange's plane, through the thickness) is fixed,
  the radius read off the deck as the farthest clamped shell node of that rivet;
* the box: the solid nodes of the base plate inside the footprint (the convex
  hull of the box link's shell nodes), through the thickness, form the rigid
  body whose REF node carries the deck's *CLOAD;
* the cases: every *STATIC step of the shell deck is one. They all load the
  box's REF and ROT nodes, so the solid deck solves a linearly independent few
  of them (the FAR 25.561 six are three directions) and the others are their
  exact combinations (ccx_deck.independent_cases); ccx factors once per step.
  The deck's MASSk rigid bodies (the box's mass for *FREQUENCY, docs/fem.md
  "Rigid masses in CalculiX") play no part in a static solve and are left out.

Why a solid model (docs/fem.md "A solid reference"): on corner_obstacle and the
right-angle battery CalculiX's S8R (shells expanded to 20-node bricks) is
+3 % and +10 % softer than this model, while our shells are within 3 % of it;
on a plain fold, a fold end and a 30 deg fold S8R and C3D10 agree within 1.4 %
(tests/python/test_solid_reference.py checks the fold). At a sharp fold the
two plates meet along the fold line, each ending square to its own
mid-surface; a prism along the fold joins their end faces (_fold_fillers), so
the sheet is whole through its thickness there, the idealisation the shell
models share (neither has the bend radius).

Self-rivets (two sheets riveted face to face, paper Sec. 5.2): where the two
sheets touch or overlap (their tie points at most t apart), the fused plates
bond the lap over its whole overlap. That joint is stiffer than rivets, while
our shells tie each rivet's footprint (a disc of radius d), a softer one:
the two bracket the riveted part, and where the lap is much larger than the
footprints the bracket is wide (slanted: a 6.6 cm² lap for one rivet, 9-10 %),
so ccx_check takes a self-riveted part's solid as a lower bound only. The deck's rigid bodies
other than the box link are those ties; the bonded lap replaces them. Sheets
farther apart would not touch in the solid and leave the tie out; `SolidNotApplicable` says so and the caller falls back
to the shell deck, as it does for a result without the tie points.
"""
import concurrent.futures
import multiprocessing
import os
import subprocess

import numpy as np

from . import ccx_deck, geometry

# gmsh's 10-node tetrahedron numbers its edge nodes (0,1) (1,2) (2,0) (3,0) (3,2) (3,1);
# CalculiX's C3D10 (as Abaqus) wants (1,2) (2,3) (3,1) (1,4) (2,4) (3,4).
GMSH_TO_CCX_TET10 = [0, 1, 2, 3, 4, 5, 6, 7, 9, 8]

# Element size in sheet thicknesses. With one tetrahedron through the thickness
# the answer depends on the mesh by up to 2 % near h = 1.5 t (shelf: 0.25049 /
# 0.24419 J at h = 2.5 / 2.4 mm) and settles at 1.25 t (0.24618 J at 2.0 mm,
# 0.24602 J at 1.6 mm). Cost at 1.25 t: about 1.5 x the time of 1.5 t.
DEFAULT_SIZE = 1.25


class SolidNotApplicable(Exception):
    """The part has a feature the solid model does not represent."""


def _fold_fillers(occ, tabs, t):
    """One prism per fold, along the child's root edge (its corners 0 -> 1 on
    the parent's edge): the cross-section is the quadrilateral of the four
    points t/2 either side of the fold line along each plate's normal. Two
    plates extruded about their mid-surfaces and ending at the fold line leave
    a V-notch on the outer side of the bend, t/2 deep and as wide open as the
    bend angle: at a 5 deg bend a crack through half the thickness, which
    makes the solid soft where the shells (and the part) are whole. The prism
    closes it with a chamfer from one plate's outer face to the other's."""
    out = []
    for tab in tabs:
        parent = tab.get("parent", -1)
        if parent is None or parent < 0:
            continue
        na = np.asarray(tabs[parent]["normal"], float)
        nb = np.asarray(tab["normal"], float)
        na, nb = na / np.linalg.norm(na), nb / np.linalg.norm(nb)
        if np.linalg.norm(np.cross(na, nb)) < 1e-6:  # a flat extension: no notch
            continue
        c0, c1 = (np.asarray(c, float) for c in tab["corners"][:2])
        ring = [c0 + 0.5 * t * na, c0 + 0.5 * t * nb, c0 - 0.5 * t * na, c0 - 0.5 * t * nb]
        points = [occ.addPoint(*p) for p in ring]
        lines = [occ.addLine(points[k], points[(k + 1) % 4]) for k in range(4)]
        face = occ.addPlaneSurface([occ.addCurveLoop(lines)])
        out += [e for e in occ.extrude([(2, face)], *(c1 - c0)) if e[0] == 3]
    return out


# OpenCASCADE's fuzzy tolerances for the boolean union, in sheet thicknesses.
# The tabs' corners come out of the solver's floating point: folds of 89.94 deg,
# faces of neighbouring plates micrometres from coincident, the case booleans
# handle worst, and no one tolerance unites every part. Measured on two
# right-angle parts of the expert stand-in (tests/python/data):
#   battery, 0.071 in:       exact and 1e-4 t: 2 and 3 solids, two riveted
#                            flanges lost; 1e-3 and 1e-2 t: one solid, 292 119 mm^3;
#   power_supply, 0.125 in:  exact, 1e-4 and 1e-2 t: one solid, 431 610 mm^3;
#                            1e-3 t: 2 solids, a flange cut off and 27 000 mm^3 lost.
# Each lost piece was silent: the battery's solid came out 37 times too soft.
# A union that drops material only loses volume, so of the unions that are one
# solid the largest is meshed, and the next when gmsh cannot mesh it or the
# mesh misses a tab (uncovered_tabs).
FUSE_TOLERANCES = (0.0, 1e-4, 1e-3, 1e-2)


def _plates(occ, tabs, t):
    """One OCC volume per tab: its polygon moved -t/2 along its normal and extruded by t."""
    volumes = []
    for tab in tabs:
        n = np.asarray(tab["normal"], float)
        n /= np.linalg.norm(n)
        points = [occ.addPoint(*(np.asarray(c, float) - 0.5 * t * n)) for c in tab["corners"]]
        lines = [occ.addLine(points[k], points[(k + 1) % len(points)]) for k in range(len(points))]
        face = occ.addPlaneSurface([occ.addCurveLoop(lines)])
        volumes += [e for e in occ.extrude([(2, face)], *(t * n)) if e[0] == 3]
    return volumes


def _union(gmsh, tabs, t, tolerance):
    """Replaces gmsh's model by the union of the plates and fold prisms at the
    fuzzy tolerance (in t); returns (number of solids, their volume m^3)."""
    gmsh.clear()
    gmsh.option.setNumber("Geometry.ToleranceBoolean", tolerance * t)
    gmsh.model.add("part")
    occ = gmsh.model.occ
    volumes = _plates(occ, tabs, t) + _fold_fillers(occ, tabs, t)
    if len(volumes) > 1:
        volumes, _ = occ.fuse(volumes[:1], volumes[1:])
    occ.synchronize()
    return len(volumes), sum(occ.getMass(3, tag) for _, tag in volumes)


def _mesh(gmsh, h):
    """C3D10 mesh of gmsh's model at size h: (X (n x 3) m, tets (k x 10), CalculiX's order)."""
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.3 * h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 1)  # mid-edge nodes on the straight edges: faces stay flat
    gmsh.model.mesh.generate(3)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    types, _, nodes = gmsh.model.mesh.getElements(3)
    tet_nodes = [nd for ty, nd in zip(types, nodes) if ty == 11]  # 11: 10-node tetrahedron
    if len(tet_nodes) != 1:
        raise RuntimeError("gmsh made no 10-node tetrahedra of the fused plates")
    index = np.zeros(int(tags.max()) + 1, dtype=np.int64)
    index[tags.astype(np.int64)] = np.arange(len(tags))
    return coords.reshape(-1, 3), index[tet_nodes[0].astype(np.int64).reshape(-1, 10)][:, GMSH_TO_CCX_TET10]


def _mesh_union(tabs, t, h, tolerance):
    """The union at `tolerance` meshed by _mesh, in a fresh gmsh session (run in
    a child process by mesh_plates)."""
    import gmsh  # Debian python3-gmsh; imported here so the checks without CalculiX run without it
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        _union(gmsh, tabs, t, tolerance)
        return _mesh(gmsh, h)
    finally:
        gmsh.finalize()


def run_in_child(fn, *args):
    """fn(*args) in a child process (forked): its result, its exception, or a
    RuntimeError when the child dies. gmsh's 3-D mesher aborts the whole
    process on some unions (an exception thrown where nothing catches it:
    "terminate called after throwing an instance of std::string", measured on
    boxed_in's part at c720526 with the 1e-2 t union; the other three meshed).
    In a child that is one failed attempt, and mesh_plates tries the next union."""
    context = multiprocessing.get_context("fork")
    with concurrent.futures.ProcessPoolExecutor(max_workers=1, mp_context=context) as pool:
        try:
            return pool.submit(fn, *args).result()
        except concurrent.futures.process.BrokenProcessPool:
            raise RuntimeError(f"{getattr(fn, '__name__', fn)} died in its child process") from None


def mesh_plates(tabs, t, h):
    """Fuse one t-thick plate per tab (dicts with 'corners' and 'normal', m) and
    mesh the solid in C3D10 of size h (m). Returns (X (n x 3) m, tets (k x 10)
    0-based indices into X, in CalculiX's node order). Raises RuntimeError,
    naming what each tolerance gave, when no union is one solid whose mesh
    holds every tab (FUSE_TOLERANCES)."""
    import gmsh  # Debian python3-gmsh; imported here so the checks without CalculiX run without it
    gmsh.initialize(readConfigFiles=False)
    try:
        gmsh.option.setNumber("General.Terminal", 0)
        unions = {tol: _union(gmsh, tabs, t, tol) for tol in FUSE_TOLERANCES}
    finally:
        gmsh.finalize()
    tried = [f"{tol:g} t: {n} solids" for tol, (n, _) in unions.items() if n != 1]
    for tol in sorted((tol for tol, (n, _) in unions.items() if n == 1), key=lambda k: -unions[k][1]):
        try:
            X, tets = run_in_child(_mesh_union, tabs, t, h, tol)
        except Exception as e:  # gmsh refuses some unions ("overlapping facets") or aborts on them
            tried.append(f"{tol:g} t: gmsh: {e}")
            continue
        missing = uncovered_tabs(tabs, t, X, tets)
        if not missing:
            return X, tets
        tried.append(f"{tol:g} t: the mesh leaves out tab(s) {missing}")
    raise RuntimeError("no union of the plates is one solid holding every tab (" + "; ".join(tried) + ")")


def _interior_samples(tab, t, per_side=5):
    """Points of the tab's mid-surface on a per_side x per_side grid over its
    polygon, kept where they are inside it and at least t from its edges (so a
    point is in the plate, not on its boundary)."""
    C = np.asarray(tab["corners"], float)
    n = np.asarray(tab["normal"], float)
    n /= np.linalg.norm(n)
    a = C[1] - C[0]
    a /= np.linalg.norm(a)
    b = np.cross(n, a)
    Q = np.c_[(C - C[0]) @ a, (C - C[0]) @ b]
    lo, hi = Q.min(axis=0), Q.max(axis=0)
    grid = np.stack(np.meshgrid(*(np.linspace(lo[k], hi[k], per_side + 2)[1:-1] for k in (0, 1))), -1).reshape(-1, 2)
    P = C[0] + np.outer(grid[:, 0], a) + np.outer(grid[:, 1], b)
    inside = np.zeros(len(grid), bool)
    clear = np.ones(len(grid), bool)
    for k in range(len(Q)):
        p, q = Q[k], Q[(k + 1) % len(Q)]
        crosses = (p[1] > grid[:, 1]) != (q[1] > grid[:, 1])  # even-odd rule along +u
        x_at = p[0] + (grid[:, 1] - p[1]) * (q[0] - p[0]) / np.where(q[1] != p[1], q[1] - p[1], 1.0)
        inside ^= crosses & (grid[:, 0] < x_at)
        clear &= geometry.distance_to_segment(P, C[k], C[(k + 1) % len(C)]) >= t
    return P[inside & clear]


def uncovered_tabs(tabs, t, X, tets):
    """Indices of the tabs with a mid-surface point (_interior_samples) in no
    tetrahedron of the mesh (X, tets): a plate the fuse or the mesher dropped."""
    V = X[tets[:, :4]]  # the corner nodes; the mid-edge ones are on straight edges
    lo, hi = V.min(axis=1), V.max(axis=1)
    tol = 1e-9 * max(1.0, float(np.abs(X).max()))
    missing = []
    for i, tab in enumerate(tabs):
        for p in _interior_samples(tab, t):
            near = np.nonzero(np.all(lo - tol <= p, axis=1) & np.all(hi + tol >= p, axis=1))[0]
            if not any(_in_tet(V[k], p, tol) for k in near):
                missing.append(i)
                break
    return missing


def _in_tet(v, p, tol):
    """Whether p lies in the tetrahedron with corners v (4 x 3), within tol (m)."""
    M = (v[1:] - v[0]).T
    try:
        lam = np.linalg.solve(M, p - v[0])
    except np.linalg.LinAlgError:
        return False
    scale = tol / max(np.abs(M).max(), 1e-300)
    return lam.min() >= -scale and lam.sum() <= 1 + scale


def write_deck(path, X, tets, E, nu, fixed, rigid, ref_point, cloads, further_steps=()):
    """A CalculiX deck: C3D10 solid, `fixed` node indices with u = 0, `rigid`
    node indices tied to a REF node at ref_point carrying `cloads` [(dof 1-6, value)]
    (forces N on 1-3, moments N m on 4-6) in a *STATIC step, then one more
    *STATIC step per entry of `further_steps` (each such a list, OP=NEW).
    Returns the REF node's id (the ROT node is the next)."""
    ref, rot = len(X) + 1, len(X) + 2
    with open(path, "w") as f:
        f.write("*HEADING\nsheetgen solid reference (tools/sheetgen_tools/solid_reference.py)\n*NODE, NSET=NALL\n")
        f.writelines(f"{k + 1}, {x[0]:.12g}, {x[1]:.12g}, {x[2]:.12g}\n" for k, x in enumerate(X))
        for node in (ref, rot):
            f.write(f"{node}, {ref_point[0]:.12g}, {ref_point[1]:.12g}, {ref_point[2]:.12g}\n")
        f.write("*ELEMENT, TYPE=C3D10, ELSET=EALL\n")
        f.writelines(f"{e + 1}, " + ", ".join(str(i + 1) for i in tet) + "\n" for e, tet in enumerate(tets))
        f.write(f"*MATERIAL, NAME=SHEET\n*ELASTIC\n{E:.12g}, {nu:.12g}\n*SOLID SECTION, ELSET=EALL, MATERIAL=SHEET\n")
        f.write("*NSET, NSET=RIGID1\n")
        f.writelines(f"{k + 1},\n" for k in rigid)
        f.write(f"*RIGID BODY, NSET=RIGID1, REF NODE={ref}, ROT NODE={rot}\n*BOUNDARY\n")
        f.writelines(f"{k + 1}, 1, 3\n" for k in fixed)
        for k, step in enumerate([cloads, *further_steps]):
            f.write("*STEP\n*STATIC\n" + ("*CLOAD\n" if k == 0 else "*CLOAD, OP=NEW\n"))
            for dof, value in step:
                f.write(f"{ref if dof <= 3 else rot}, {dof if dof <= 3 else dof - 3}, {value:.12g}\n")
            f.write("*NODE PRINT, NSET=NALL\nU\n*END STEP\n")
    return ref


def run_ccx_steps(deck_path):
    """Runs ccx on deck_path; returns each static step's displacements [{node id: (ux, uy, uz)} m]."""
    work, name = os.path.split(os.path.abspath(deck_path))
    job = name[:-4] if name.endswith(".inp") else name
    subprocess.run(["ccx", "-i", job], cwd=work, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    with open(os.path.join(work, job + ".dat")) as f:
        return ccx_deck.read_dat(f.read()).static_displacements()


def run_ccx(deck_path):
    """Runs ccx on deck_path; returns the last step's displacements {node id: (ux, uy, uz)} m."""
    return run_ccx_steps(deck_path)[-1]


def _convex_hull(P):
    """Counter-clockwise convex hull of 2D points (monotone chain)."""
    P = sorted(set(map(tuple, np.round(P, 12))))
    if len(P) < 3:
        return np.array(P)

    def half(points):
        h = []
        for p in points:
            while len(h) >= 2 and np.cross(np.subtract(h[-1], h[-2]), np.subtract(p, h[-2])) <= 0:
                h.pop()
            h.append(p)
        return h
    lower, upper = half(P), half(reversed(P))
    return np.array(lower[:-1] + upper[:-1])


def _inside_convex(Q, hull, tol):
    """Which 2D points Q lie inside the CCW convex polygon hull (within tol)."""
    inside = np.ones(len(Q), bool)
    for k in range(len(hull)):
        a, b = hull[k], hull[(k + 1) % len(hull)]
        e = b - a
        cross = e[0] * (Q[:, 1] - a[1]) - e[1] * (Q[:, 0] - a[0])
        inside &= cross >= -tol * np.linalg.norm(e)
    return inside


def _box_link(part, shell_deck, t):
    """(REF node, ROT node, member node ids) of the deck's box link, and the
    static cases' loads as [(dof 1-6, value)] on it; SolidNotApplicable when
    the deck is not the box link plus one rigid body per self-rivet (the mass
    stand-ins, MASSk, are the box's inertia for *FREQUENCY and play no part here)."""
    for tie in part.get("self_rivets") or []:
        points = tie.get("points")
        if not points or len(points) != 2:
            raise SolidNotApplicable("a self-rivet without its two points (a result from an older sheetgen)")
        gap = float(np.linalg.norm(np.subtract(points[0], points[1])))
        if gap > t * (1 + 1e-6):
            raise SolidNotApplicable(f"self-riveted sheets {gap * 1e3:.2f} mm apart would not touch in the fused solid")
    # The box link is the rigid body whose nodes carry the loads; any other is a
    # self-rivet's footprint tie, which the fused solid replaces by its bonded lap.
    bodies = ccx_deck.links(shell_deck)
    statics = ccx_deck.static_steps(shell_deck)
    if not statics:
        raise ValueError("shell deck: no *STATIC step")
    load_nodes = {n for s in statics for n, _ in s.loads}
    box = [b for b in bodies if b[1] in load_nodes or b[2] in load_nodes]
    if len(box) != 1 or len(bodies) - 1 > len(part.get("self_rivets") or []):
        raise SolidNotApplicable(f"the deck has {len(bodies)} rigid bodies, not the box link and one per self-rivet")
    _, ref_id, rot_id, members = box[0]
    cases = []
    for s in statics:
        loads = []
        for (n, dof), value in sorted(s.loads.items()):
            if n not in (ref_id, rot_id):
                raise SolidNotApplicable(f"a load on node {n}, not on the box's reference node")
            loads.append((dof + (3 if n == rot_id and n != ref_id else 0), value))
        cases.append(loads)
    return ref_id, members, cases


def _fixed_nodes(part, X, t, nodes, clamped):
    """Solid nodes within each rivet's footprint radius (its farthest clamped
    shell node) of its centre, in the flange's plane, through the thickness."""
    tabs = part["tabs"]
    eps = 1e-3 * t
    centres = np.asarray(part["rivets"], float).reshape(-1, 3)
    C = np.array([nodes[n] for n in clamped])
    owner = np.argmin(np.linalg.norm(C[:, None, :] - centres[None], axis=2), axis=1)
    flanges = [tb for tb in tabs if tb.get("rivet_area", -1) >= 0]
    fixed = np.zeros(len(X), bool)
    for i, c in enumerate(centres):
        mine = C[owner == i]
        if not len(mine):
            raise ValueError(f"shell deck: rivet {i} at {np.round(c, 4).tolist()} has no clamped node")
        radius = np.linalg.norm(mine - c, axis=1).max()
        flange = min(flanges, key=lambda tb: abs(np.dot(np.asarray(tb["corners"][0]) - c, tb["normal"])))
        n = np.asarray(flange["normal"], float)
        rel = X - c
        off = rel @ n
        inplane = np.linalg.norm(rel - np.outer(off, n), axis=1)
        mine = (np.abs(off) <= 0.5 * t + eps) & (inplane <= radius + eps)
        if not mine.any():
            raise RuntimeError(f"rivet {i} at {np.round(c, 4).tolist()} m has no solid node within its footprint")
        fixed |= mine
    return fixed


def _rigid_nodes(part, X, t, R, fixed):
    """Base-plate solid nodes inside the box footprint (the convex hull of the
    link's shell nodes R, #R by 3), through the thickness, not fixed."""
    eps = 1e-3 * t
    n0 = np.asarray(part["tabs"][0]["normal"], float)
    o = R.mean(axis=0)
    u = np.cross(n0, [1.0, 0, 0] if abs(n0[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    v = np.cross(n0, u)
    hull = _convex_hull(np.c_[(R - o) @ u, (R - o) @ v])
    rel = X - o
    return (np.abs(rel @ n0) <= 0.5 * t + eps) & _inside_convex(np.c_[rel @ u, rel @ v], hull, eps) & ~fixed


def solid_compliance(part, shell_deck, work_dir, h=None):
    """Compliance (J) and |u| of the load point (m) of every static case of
    `shell_deck` (the text of an S4 deck by `sheetgen export-ccx`) on the solid
    model of `part` (a result.json part), with the deck's supports, box link,
    loads and material. The cases are solved as a linearly independent few of
    them (the FAR 25.561 six are three directions) and the others superposed:
    the loads all act on the box's REF and ROT nodes, so each case's u there is
    the same combination of the solved ones' (exact, linear elasticity). Writes
    solid.inp into work_dir. Returns a dict with "cases" ([{"C", "deflection"}]
    per static step of the deck, in order), C and deflection of the first case,
    nodes, elements, h, fixed, rigid and solved (the cases ccx solved)."""
    t = float(ccx_deck.section_lines(shell_deck, "SHELL SECTION")[0].split(",")[0])
    ref_id, members, cases = _box_link(part, shell_deck, t)
    E, nu = (float(x) for x in ccx_deck.section_lines(shell_deck, "ELASTIC")[0].split(",")[:2])
    h = DEFAULT_SIZE * t if h is None else h
    nodes = ccx_deck.nodes(shell_deck)
    clamped = sorted({int(line.split(",")[0]) for line in ccx_deck.section_lines(shell_deck, "BOUNDARY")})

    X, tets = mesh_plates(part["tabs"], t, h)
    fixed = _fixed_nodes(part, X, t, nodes, clamped)
    rigid = _rigid_nodes(part, X, t, np.array([nodes[n] for n in members]), fixed)

    basis, A = ccx_deck.independent_cases([dict(c) for c in cases])
    deck = os.path.join(work_dir, "solid.inp")
    solved = [cases[j] for j in basis]
    ref = write_deck(deck, X, tets, E, nu, np.nonzero(fixed)[0], np.nonzero(rigid)[0], nodes[ref_id],
                     solved[0], solved[1:])
    blocks = run_ccx_steps(deck)
    # u of the REF node (translations) and the ROT node (rotations) per solved case.
    U = [{1: b[ref], 4: b[ref + 1]} for b in blocks]
    out = []
    for k, loads in enumerate(cases):
        u = ccx_deck.superpose(A[k], U)
        C = sum(value * (u[1][dof - 1] if dof <= 3 else u[4][dof - 4]) for dof, value in loads)
        out.append({"C": float(C), "deflection": float(np.linalg.norm(u[1]))})
    return {"cases": out, "C": out[0]["C"], "deflection": out[0]["deflection"], "nodes": len(X),
            "elements": len(tets), "h": h, "fixed": int(fixed.sum()), "rigid": int(rigid.sum()), "solved": len(basis)}
