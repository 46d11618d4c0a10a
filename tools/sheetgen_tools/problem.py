"""Reading a problem (sheetgen-problem/1) with its meshes, its load cases,
limits and eigen requirements, for the checks and the pictures (independent of
the solver's own reader), and the problem variants the benchmarks solve."""
import copy
import dataclasses
import json
import os
from typing import Optional

import numpy as np

from .geometry import box_mesh, load_rotation


def read_obj(path):
    """An OBJ file's vertices (#V by 3, m) and triangles (#F by 3, 0-based;
    polygons fanned from their first corner, so a quad gives two faces as the
    solver numbers them)."""
    verts, tris = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                verts.append([float(x) for x in p[1:4]])
            elif p[0] == "f":
                idx = [int(x.split("/")[0]) for x in p[1:]]
                idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
                for k in range(1, len(idx) - 1):
                    tris.append([idx[0], idx[k], idx[k + 1]])
    return np.array(verts, float), np.array(tris, int)


def load_problem(path):
    """(the problem document, {mesh name: (vertices #V by 3 m, triangles #F by 3)}),
    file meshes read relative to the problem's folder."""
    with open(path) as f:
        prob = json.load(f)
    base = os.path.dirname(path)
    meshes = {}
    for m in prob["environment"]["meshes"]:
        if "file" in m:
            meshes[m["name"]] = read_obj(os.path.join(base, m["file"]))
        else:
            meshes[m["name"]] = (np.array(m["vertices"], float), np.array(m["triangles"], int))
    return prob, meshes


def rivet_area_mesh(prob, ra):
    """The name of the mesh a rivet area lies on (its "mesh" is a name or an index)."""
    return ra["mesh"] if isinstance(ra["mesh"], str) else prob["environment"]["meshes"][ra["mesh"]]["name"]


def problem_of_result(out_dir, result):
    """The absolute path of the problem a result.json was solved from (its
    "problem" is relative to the real output folder)."""
    return os.path.normpath(os.path.join(os.path.realpath(out_dir), result["problem"]))


def with_absolute_files(doc, problem_dir):
    """A copy of a problem document whose file meshes name their files by
    absolute path, so it can be written into any folder."""
    q = copy.deepcopy(doc)
    for m in q["environment"]["meshes"]:
        if "file" in m:
            m["file"] = os.path.join(problem_dir, m["file"])
    return q


def one_load_problem(doc, problem_dir, load, thickness, obstacles, path, base_room=0.0):
    """Writes to `path` the problem `doc` (read from problem_dir) with only
    `load`, the sheet `thickness` (m), the other loads' boxes and `obstacles`
    (inline meshes) added: what sheetgen's own run of the load would avoid
    (every load box and the parts before it). Each other box is lowered by
    `base_room` (m): the room its own base tab needs under it
    (docs/gauge_baseline.md "Reading")."""
    q = with_absolute_files(doc, problem_dir)
    q["environment"]["meshes"] += [box_mesh(other, base_room) for other in doc["loads"] if other["name"] != load["name"]]
    q["environment"]["meshes"] += obstacles
    q["loads"] = [load]
    q.setdefault("material", {})["thickness"] = thickness
    q["material"]["gauges"] = []  # the caller tries the gauges itself
    q["description"] = (f"{doc.get('name', '')}: load {load['name']} alone at {thickness * 1e3:.3f} mm sheet, "
                        f"right angles, the other parts as obstacles (bench/gauge_baseline.py)")
    with open(path, "w") as f:
        json.dump(q, f)


# --- Sheet gauges (docs/problem-format.md "material"), read from the file.

INCH = 0.0254  # m
# AMS-QQ-A-250/4, 2024-T3 clad sheet, 0.016 to 0.160 in: material.gauges' default
# is those thicker than material.thickness.
STANDARD_GAUGES_IN = (0.016, 0.020, 0.025, 0.032, 0.040, 0.050, 0.063, 0.071, 0.080, 0.090, 0.100, 0.125, 0.160)
DEFAULT_THICKNESS = 1.6e-3  # m


def sheets(prob):
    """The sheets a part of the problem may be made of, m: material.thickness,
    then material.gauges (default: for a file in the envelope format, the
    standard gauges thicker than it; none for a one-force file)."""
    material = prob.get("material", {})
    t = material.get("thickness", DEFAULT_THICKNESS)
    gauges = material.get("gauges")
    if gauges is None:
        envelope = eigen_requirements(prob).checked  # the reader's rule for the envelope format
        gauges = [g * INCH for g in STANDARD_GAUGES_IN if g * INCH > t + 1e-6] if envelope else []
    return [t] + list(gauges)


def at_part_sheet(prob, part):
    """The problem as the part's checks need it: material.thickness the part's
    own (result.json's thickness_m, a thicker gauge when the problem's sheet
    gave the load none). Every length the checks derive from the thickness
    follows it. ValueError when the part names a sheet the problem does not
    allow."""
    t = part.get("thickness_m")
    allowed = sheets(prob)
    if t is None or abs(t - allowed[0]) <= 1e-12:
        return prob
    if not any(abs(t - g) <= 1e-9 for g in allowed[1:]):
        raise ValueError(f"{part['load']}: thickness_m {t} m is neither material.thickness nor one of its gauges "
                         f"({', '.join(f'{g * 1e3:.4g}' for g in allowed)} mm)")
    q = copy.copy(prob)
    q["material"] = {**prob.get("material", {}), "thickness": t}
    return q


# --- Load cases and requirements (docs/problem-format.md "Load cases"), read
# here from the file itself so that the checks never take them from the solver.

STANDARD_GRAVITY = 9.80665  # m/s^2, the g of the factors
# 14 CFR / CS 25.561(b)(3): (name, g along (forward, left, up)), in the solver's order.
FAR25_561 = [("forward 9 g", (9.0, 0.0, 0.0)), ("rearward 1.5 g", (-1.5, 0.0, 0.0)),
             ("left 3 g", (0.0, 3.0, 0.0)), ("right 3 g", (0.0, -3.0, 0.0)),
             ("down 6 g", (0.0, 0.0, -6.0)), ("up 3 g", (0.0, 0.0, 3.0))]
DEFAULT_MAX_DEFLECTION = 1.0e-3  # m, requirements.max_deflection's default
DEFAULT_SAFETY_FACTOR = 1.5


def envelope_axes(load_cases):
    """(forward, left, up) unit vectors of a problem's `load_cases`: up loses
    its component along forward (the reader's rule), left = up x forward."""
    forward = np.asarray(load_cases["forward"], float)
    forward /= np.linalg.norm(forward)
    up = np.asarray(load_cases["up"], float)
    up = up / np.linalg.norm(up)
    up -= np.dot(up, forward) * forward
    up /= np.linalg.norm(up)
    return forward, np.cross(up, forward), up


def envelope_factors(load_cases):
    """The factors of `load_cases` as [(name, g (3,), max_deflection m or None)], the preset expanded."""
    factors = load_cases["factors"]
    if factors == "far25.561":
        return [(name, np.array(g), None) for name, g in FAR25_561]
    if isinstance(factors, str):
        raise ValueError(f"load_cases.factors: unknown preset {factors!r}")
    return [(f["name"], np.asarray(f["g"], float), f.get("max_deflection")) for f in factors]


def load_cases(prob, load):
    """A load's cases in the solver's order: its own (`cases`, or `force`/`moment`
    as the one case "design"), then, when it has a `mass`, one per factor of the
    problem's `load_cases`. Each is {"name", "force" N (3,), "moment" N m (3,)
    about the centre of mass, "max_deflection" m or None}."""
    cases = []
    if "cases" in load:
        for c in load["cases"]:
            cases.append({"name": c["name"], "force": np.asarray(c.get("force", [0, 0, 0]), float),
                          "moment": np.asarray(c.get("moment", [0, 0, 0]), float),
                          "max_deflection": c.get("max_deflection")})
    elif "force" in load or "moment" in load:
        cases.append({"name": "design", "force": np.asarray(load.get("force", [0, 0, 0]), float),
                      "moment": np.asarray(load.get("moment", [0, 0, 0]), float), "max_deflection": None})
    if "mass" in load and "load_cases" in prob:
        axes = np.array(envelope_axes(prob["load_cases"]))  # rows: forward, left, up
        for name, g, max_deflection in envelope_factors(prob["load_cases"]):
            cases.append({"name": name, "force": load["mass"] * STANDARD_GRAVITY * (g @ axes),
                          "moment": np.zeros(3), "max_deflection": max_deflection})
    return cases


def compliance_limit(prob, case):
    """C_max of one case (J): |F| times the case's own max_deflection, else
    requirements.max_compliance, else |F| times requirements.max_deflection (1 mm)."""
    req = prob.get("requirements", {})
    f = float(np.linalg.norm(case["force"]))
    if case.get("max_deflection") is not None:
        return f * case["max_deflection"]
    if "max_compliance" in req:
        return float(req["max_compliance"])
    return f * req.get("max_deflection", DEFAULT_MAX_DEFLECTION)


@dataclasses.dataclass
class EigenRequirements:
    """The buckling and frequency floors of a problem and whether they apply."""
    checked: bool                     # the file asks for the eigen checks (see eigen_requirements)
    min_buckling_factor: float        # -, default requirements.safety_factor
    min_frequency_hz: Optional[float]  # Hz, None: no floor


def eigen_requirements(prob):
    """The rule of the C++ reader (Requirements::eigen_checks, native/sheetgen/core/problem.cpp):
    the checks apply when the file uses the envelope format (a load with "mass"
    or "cases", or a top-level "load_cases") or names min_buckling_factor or
    min_frequency_hz; an old one-force file keeps the checks it was written for."""
    req = prob.get("requirements", {})
    checked = ("load_cases" in prob or "min_buckling_factor" in req or "min_frequency_hz" in req
               or any("mass" in ld or "cases" in ld for ld in prob["loads"]))
    floor = req.get("min_buckling_factor", req.get("safety_factor", DEFAULT_SAFETY_FACTOR))
    return EigenRequirements(checked, float(floor), req.get("min_frequency_hz"))


def load_mass_properties(load):
    """(mass kg, centre of mass m (3,), inertia kg m^2 (3, 3) about it, world) of
    a load with a "mass"; the default inertia is the uniform box's, turned with it."""
    m = float(load["mass"])
    centre = np.asarray(load.get("center_of_mass", load["center"]), float)
    if "inertia" in load:
        J = np.asarray(load["inertia"], float)
        return m, centre, 0.5 * (J + J.T)
    a, b, c = load["size"]
    R = load_rotation(load)
    local = np.diag([b * b + c * c, a * a + c * c, a * a + b * b]) * m / 12.0
    return m, centre, R @ local @ R.T


def with_envelope(doc, problem_dir, mass, forward=(1.0, 0.0, 0.0), up=(0.0, 0.0, 1.0), factors="far25.561"):
    """A copy of a problem document (read from problem_dir; its file meshes made
    absolute) whose every load is a box of `mass` kg under the envelope
    `factors` (the FAR 25.561 preset by default) instead of its own force."""
    q = with_absolute_files(doc, problem_dir)
    for load in q["loads"]:
        for key in ("force", "moment", "cases"):
            load.pop(key, None)
        load["mass"] = mass
    q["load_cases"] = {"forward": list(forward), "up": list(up), "factors": factors}
    return q


def single_force(doc, problem_dir):
    """A copy of a problem document (read from problem_dir; its file meshes made
    absolute) whose every box of mass m carries one force, m * 9 * 9.81 N
    downward: the one case the sample scenes had before their envelopes
    (docs/scenes.md), without the envelope or the buckling and frequency
    floors. A load without a mass keeps its own force."""
    q = with_absolute_files(doc, problem_dir)
    for load in q["loads"]:
        if "mass" not in load:
            continue
        mass = load.pop("mass")
        for key in ("cases", "center_of_mass", "inertia"):
            load.pop(key, None)
        load["force"] = [0.0, 0.0, -round(mass * 9.0 * 9.81, 3)]
        load["moment"] = [0.0, 0.0, 0.0]
    q.pop("load_cases", None)
    for key in ("min_buckling_factor", "min_frequency_hz"):
        q.get("requirements", {}).pop(key, None)
    return q

