"""Scene data <-> ``sheetgen-problem/1`` dict (docs/problem-format.md), both ways.

``scene_to_problem`` checks what the Blender user can get wrong and names the
object and the field; the native parser (``parse_problem``) remains the
authority on the file. ``problem_to_scene`` reads a problem dict (inline meshes,
or file meshes through a ``mesh_reader``) into plain scene data.
"""
import math
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from . import model
from .geometry import axes_problem, inertia_problem, is_finite_vec, quat_rotate, quat_unit, rivet_area_areas
from .model import Envelope, FactorData, LoadCaseData, LoadData, MeshData, SceneData, Settings


class ProblemError(ValueError):
    """The scene or the problem cannot be converted. ``errors`` holds one sentence each."""

    def __init__(self, errors: List[str], warnings: Optional[List[str]] = None):
        self.errors = list(errors)
        self.warnings = list(warnings or [])
        super().__init__(self.errors[0] if len(self.errors) == 1 else
                         "%s (and %d more problem%s)" % (self.errors[0], len(self.errors) - 1,
                                                         "" if len(self.errors) == 2 else "s"))


def name_problem(name) -> Optional[str]:
    """Why ``name`` cannot name a mesh, rivet area or load (they become folder names), or None."""
    if not isinstance(name, str) or not name:
        return "name must not be empty"
    if "/" in name or "\\" in name or "\0" in name or name in (".", ".."):
        return "name '%s' must not contain '/' or '\\' or be '.' or '..'" % name
    return None


def _fmt(v) -> str:
    return "[" + ", ".join("%g" % x for x in v) + "]"


def default_area_name(mesh_name: str, area_id: int) -> str:
    return "%s_rivets_%d" % (mesh_name, area_id)


# ---------------------------------------------------------------------------
# scene -> problem

def scene_to_problem(scene: SceneData) -> Tuple[dict, List[str]]:
    """The problem dict for ``scene`` and a list of warnings; raises ProblemError."""
    errors: List[str] = []
    warnings: List[str] = []
    meshes_json: List[dict] = []
    rivet_areas: List[dict] = []
    area_owner: Dict[str, str] = {}
    area_rank: List[int] = []     # per entry of rivet_areas: its MeshData.area_order (0: none)
    mesh_names = set()

    if not scene.meshes:
        errors.append("no environment meshes: the scene has no visible mesh object other than the loads")
    for m in scene.meshes:
        where = "object '%s'" % m.name
        why = name_problem(m.name)
        if why:
            errors.append("%s: %s (rename the object)" % (where, why))
        if m.name in mesh_names:
            errors.append("%s: duplicate mesh name" % where)
        mesh_names.add(m.name)
        nv, nf = len(m.vertices), len(m.triangles)
        if nf == 0:
            errors.append("%s: mesh has no faces" % where)
            continue
        bad = next((i for i, v in enumerate(m.vertices) if not is_finite_vec(v)), None)
        if bad is not None:
            errors.append("%s: vertex %d is not 3 finite numbers" % (where, bad))
            continue
        bad = next((f for f, t in enumerate(m.triangles)
                    if len(t) != 3 or any(not (0 <= i < nv) for i in t)), None)
        if bad is not None:
            errors.append("%s: triangle %d has a vertex index outside 0..%d" % (where, bad, nv - 1))
            continue
        meshes_json.append({"name": m.name,
                            "vertices": [[float(x) for x in v] for v in m.vertices],
                            "triangles": [[int(i) for i in t] for t in m.triangles]})
        if m.face_areas is None:
            continue
        if len(m.face_areas) != nf:
            errors.append("%s: %d rivet-area face tags for %d triangles" % (where, len(m.face_areas), nf))
            continue
        faces_of: Dict[int, List[int]] = {}
        for f, k in enumerate(m.face_areas):
            if k > 0:
                faces_of.setdefault(int(k), []).append(f)
            elif k < 0:
                errors.append("%s: face %d has rivet-area id %d (ids are 0 = none or positive)" % (where, f, k))
                break
        areas = rivet_area_areas(m.vertices, m.triangles, m.face_areas)
        for k in sorted(set(m.area_names) - set(faces_of)):
            warnings.append("%s: rivet area '%s' has no faces and is left out" % (where, m.area_names[k]))
        for k in sorted(faces_of):
            name = m.area_names.get(k)
            if not name:
                name = default_area_name(m.name, k)
                warnings.append("%s: faces tagged with rivet-area id %d have no area name; named '%s'" % (where, k, name))
            why = name_problem(name)
            if why:
                errors.append("%s: rivet area: %s" % (where, why))
            elif name in area_owner:
                errors.append("rivet area name '%s' is used on object '%s' and on object '%s': rename one"
                              % (name, area_owner[name], m.name))
            area_owner.setdefault(name, m.name)
            if not areas[k][0] > 0:
                errors.append("%s: rivet area '%s' has zero area (degenerate faces)" % (where, name))
            rivet_areas.append({"name": name, "mesh": m.name, "faces": faces_of[k]})
            area_rank.append(m.area_order.get(k, 0))
    # An imported problem's order first, then the rest as emitted (sorted is stable).
    order = sorted(range(len(rivet_areas)), key=lambda i: (area_rank[i] == 0, area_rank[i]))
    rivet_areas = [rivet_areas[i] for i in order]
    if scene.meshes and not rivet_areas and not errors:
        errors.append("no rivet areas: select faces of an environment mesh in Edit Mode and press "
                      "'Mark' (Sheet Metal tab > Rivet Areas)")

    loads_json: List[dict] = []
    load_names = set()
    factor_names = (envelope_factor_names(scene.settings.load_cases) if scene.settings.load_cases is not None
                    else None)
    if not scene.loads:
        errors.append("no loads: select a box object and press 'Make Load' (Sheet Metal tab > Loads)")
    for ld in scene.loads:
        where = "load '%s'" % ld.name
        why = name_problem(ld.name)
        if why:
            errors.append("%s: %s (rename the object)" % (where, why))
        if ld.name in load_names:
            errors.append("%s: duplicate load name" % where)
        if ld.name in mesh_names:
            # Not an error for the solver, but confusing in reports and output folders.
            warnings.append("%s: an environment mesh has the same name" % where)
        load_names.add(ld.name)
        lj = load_to_json(ld, factor_names, errors)
        if lj is not None:
            loads_json.append(lj)
    if scene.settings.load_cases is not None and scene.loads and not any(ld.mass is not None for ld in scene.loads):
        errors.append("envelope: no load has a mass, so no load gets its cases (set a load's Mass in the Loads "
                      "panel, or turn the envelope off)")

    settings_json = settings_to_json(scene.settings, errors)
    if errors:
        raise ProblemError(errors, warnings)
    problem = {"format": model.PROBLEM_FORMAT, "name": scene.name or "scene"}
    if scene.description:
        problem["description"] = scene.description
    problem.update({"units": "m", "environment": {"meshes": meshes_json},
                    "rivet_areas": rivet_areas, "loads": loads_json})
    problem.update(settings_json)
    return problem, warnings


def _case_vectors_problem(force, moment) -> Optional[str]:
    if not is_finite_vec(force, 3):
        return "force must be 3 finite numbers"
    if not is_finite_vec(moment, 3):
        return "moment must be 3 finite numbers"
    if all(x == 0 for x in force) and all(x == 0 for x in moment):
        return "force and moment are both zero"
    return None


def _optional_positive(value, where: str, errors: List[str]) -> Optional[float]:
    if value is None:
        return None
    _check_number(value, "pos", where, errors)
    return float(value) if isinstance(value, (int, float)) else None


def _outside_box(ld: LoadData, point) -> float:
    """How far (m) ``point`` lies outside ld's box, 0 inside (box frame: R^T (p - centre))."""
    w, x, y, z = quat_unit(ld.rotation)
    local = quat_rotate((w, -x, -y, -z), [point[i] - ld.center[i] for i in range(3)])
    return max(0.0, max(abs(local[i]) - 0.5 * ld.size[i] for i in range(3)))


def _own_cases_json(ld: LoadData, where: str, errors: List[str]) -> Tuple[dict, List[str]]:
    """A load's own cases as fields of ``loads[i]`` ({force, moment}, {cases} or {}) and their names."""
    if ld.own == model.OWN_NONE:
        return {}, []
    if ld.own == model.OWN_FORCE:
        if not is_finite_vec(ld.force, 3) or not is_finite_vec(ld.moment, 3):
            errors.append("%s: force and moment must be 3 finite numbers each" % where)
        elif all(x == 0 for x in ld.force) and all(x == 0 for x in ld.moment):
            errors.append("%s: force and moment are both zero (set Force in the Loads panel)" % where)
        return {"force": [float(x) for x in ld.force], "moment": [float(x) for x in ld.moment]}, ["design"]
    if ld.own != model.OWN_CASES:
        errors.append("%s: unknown kind of cases %r (expected force, cases or none)" % (where, ld.own))
        return {}, []
    if not ld.cases:
        errors.append("%s: the case list is empty (add a case in the Loads panel, or use Force)" % where)
    cases, names = [], []
    for k, c in enumerate(ld.cases):
        label = "%s, case %d" % (where, k + 1)
        why = name_problem(c.name)
        if why:
            errors.append("%s: %s" % (label, why))
        elif c.name in names:
            errors.append("%s: duplicate case name '%s'" % (label, c.name))
        names.append(c.name)
        why = _case_vectors_problem(c.force, c.moment)
        if why:
            errors.append("%s '%s': %s" % (label, c.name, why))
            continue
        cj = {"name": c.name, "force": [float(x) for x in c.force]}
        if any(x != 0 for x in c.moment):   # as a file would write it: no moment, no field
            cj["moment"] = [float(x) for x in c.moment]
        dmax = _optional_positive(c.max_deflection, "%s '%s': max deflection (m)" % (label, c.name), errors)
        if dmax is not None:
            cj["max_deflection"] = dmax
        cases.append(cj)
    return {"cases": cases}, names


def _mass_json(ld: LoadData, where: str, errors: List[str]) -> dict:
    """A load's mass, centre of mass and inertia as fields of ``loads[i]`` (only those given)."""
    if ld.mass is None:
        if ld.center_of_mass is not None or ld.inertia is not None:
            errors.append("%s: a centre of mass or inertia is given without a mass (set Mass in the Loads panel)"
                          % where)
        return {}
    out = {}
    _check_number(ld.mass, "pos", "%s: mass (kg)" % where, errors)
    out["mass"] = float(ld.mass) if isinstance(ld.mass, (int, float)) else ld.mass
    if ld.center_of_mass is not None:
        if not is_finite_vec(ld.center_of_mass, 3):
            errors.append("%s: centre of mass must be 3 finite numbers (m)" % where)
        else:
            outside = _outside_box(ld, ld.center_of_mass)
            if outside > 1e-6:  # the native reader's slack for float32 coordinates
                errors.append("%s: centre of mass %s m lies %.4g mm outside the load box"
                              % (where, _fmt(ld.center_of_mass), outside * 1e3))
            out["center_of_mass"] = [float(x) for x in ld.center_of_mass]
    if ld.inertia is not None:
        why = inertia_problem(ld.inertia)
        if why:
            errors.append("%s: %s" % (where, why))
        else:
            out["inertia"] = [[float(x) for x in row] for row in ld.inertia]
    return out


def load_to_json(ld: LoadData, factor_names: Optional[List[str]], errors: List[str]) -> Optional[dict]:
    """``loads[i]`` for one load box, or None after adding its problems to ``errors`` (docs/problem-format.md).

    ``factor_names``: the case names of the problem's envelope, None without one.
    """
    where = "load '%s'" % ld.name
    for key, n in (("center", 3), ("size", 3), ("rotation", 4)):
        if not is_finite_vec(getattr(ld, key), n):
            errors.append("%s: %s must be %d finite numbers" % (where, key, n))
            return None
    if not all(s > 0 for s in ld.size):
        errors.append("%s: size must be positive on every axis, got %s m (a flat object cannot be a load box)"
                      % (where, _fmt(ld.size)))
    try:
        rot = quat_unit(ld.rotation)
    except ValueError:
        errors.append("%s: rotation quaternion has zero length" % where)
        return None
    lj = {"name": ld.name, "center": [float(x) for x in ld.center], "size": [float(x) for x in ld.size],
          "rotation": [float(x) for x in rot]}
    before = len(errors)
    own, own_names = _own_cases_json(ld, where, errors)
    lj.update(own)
    if ld.own == model.OWN_NONE and (ld.mass is None or factor_names is None):
        errors.append("%s: it has no force and no cases of its own, so it needs a Mass and the envelope "
                      "(Loads panel)" % where)
    if ld.mass is not None and factor_names:
        for name in own_names:
            if name in factor_names:
                errors.append("%s: its case '%s' has the name of an envelope factor; names must be unique per load "
                              "(rename one)" % (where, name))
    lj.update(_mass_json(ld, where, errors))
    return lj if len(errors) == before else None


def envelope_to_json(env: Envelope, errors: List[str]) -> dict:
    """The problem-level ``load_cases``; problems go to ``errors`` (named "envelope", as in the Loads panel)."""
    out = {"forward": [float(x) for x in env.forward] if is_finite_vec(env.forward, 3) else None,
           "up": [float(x) for x in env.up] if is_finite_vec(env.up, 3) else None}
    if out["forward"] is None or out["up"] is None:
        errors.append("envelope: forward and up must be 3 finite numbers each")
    else:
        why = axes_problem(env.forward, env.up)
        if why:
            errors.append("envelope: %s (set the aircraft's axes in the Loads panel)" % why)
    if env.preset is not None:
        if env.preset not in model.PRESETS:
            errors.append("envelope: unknown preset '%s' (the one preset is '%s')" % (env.preset,
                                                                                     model.PRESET_FAR25_561))
        out["factors"] = env.preset
        return out
    if not env.factors:
        errors.append("envelope: the factor list is empty (add a factor, or pick the preset)")
    factors, names = [], set()
    for k, f in enumerate(env.factors):
        label = "envelope, factor %d" % (k + 1)
        why = name_problem(f.name)
        if why:
            errors.append("%s: %s" % (label, why))
        elif f.name in names:
            errors.append("%s: duplicate factor name '%s'" % (label, f.name))
        names.add(f.name)
        if not is_finite_vec(f.g, 3):
            errors.append("%s '%s': g must be 3 finite numbers (forward, left, up)" % (label, f.name))
            continue
        if all(x == 0 for x in f.g):
            errors.append("%s '%s': g is [0, 0, 0]: a case with no force" % (label, f.name))
        fj = {"name": f.name, "g": [float(x) for x in f.g]}
        dmax = _optional_positive(f.max_deflection, "%s '%s': max deflection (m)" % (label, f.name), errors)
        if dmax is not None:
            fj["max_deflection"] = dmax
        factors.append(fj)
    out["factors"] = factors
    return out


def envelope_factor_names(env: Optional[Envelope]) -> List[str]:
    """The case names an envelope gives every massed load, in order."""
    if env is None:
        return []
    if env.preset is not None:
        return [name for name, _g in model.PRESETS.get(env.preset, [])]
    return [f.name for f in env.factors]


def _check_number(value, kind: str, where: str, errors: List[str]) -> None:
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
        errors.append("%s: expected a finite number, got %r" % (where, value))
    elif kind == "pos" and not value > 0:
        errors.append("%s: must be positive, got %g" % (where, value))
    elif kind == "nonneg" and not value >= 0:
        errors.append("%s: must not be negative, got %g" % (where, value))
    elif kind == "poisson" and not -1 < value < 0.5:
        errors.append("%s: must lie in (-1, 0.5), got %g" % (where, value))


def _check_gauges(gauges, thickness, where: str, errors: List[str]) -> None:
    """material.gauges: a list of numbers (m), thinnest first, each thicker than the sheet."""
    if not isinstance(gauges, (list, tuple)):
        errors.append("%s: expected a list of thicknesses (m), got %r" % (where, gauges))
        return
    last = thickness
    for k, g in enumerate(gauges):
        before = len(errors)
        _check_number(g, "pos", "%s[%d]" % (where, k), errors)
        if len(errors) > before:
            return
        if isinstance(thickness, (int, float)) and g <= last:
            errors.append("%s[%d]: %g m must be thicker than %s (%g m): the gauges are thicker sheets, thinnest first"
                          % (where, k, g, "material.thickness" if k == 0 else "the gauge before it", last))
            return
        last = g


def gauges_from_mm_text(use: bool, text: str):
    """The Material panel's thicker gauges as material.gauges (m): None (the
    standard gauges) for an empty list, [] when they are off. Text that is not
    a comma-separated list of numbers (mm) is returned as it is, for
    settings_to_json to report."""
    if not use:
        return []
    if not text.strip():
        return None
    try:
        return [float(v) * 1e-3 for v in text.replace(";", ",").split(",") if v.strip()]
    except ValueError:
        return text


def gauges_to_mm_text(gauges) -> Tuple[bool, str]:
    """The inverse of gauges_from_mm_text: (use, text in mm)."""
    if gauges is None:
        return True, ""
    return bool(gauges), ", ".join("%.12g" % (g * 1e3) for g in gauges)


def settings_to_json(s: Settings, errors: List[str]) -> dict:
    """The material, requirements, manufacturing and search sections; checks go to ``errors``."""
    mat = {}
    for key, label, kind in model.MATERIAL_FIELDS:
        v = getattr(s.material, key)
        _check_number(v, kind, "material.%s (%s)" % (key, label), errors)
        mat[key] = float(v)
    if s.material.gauges is not None:
        _check_gauges(s.material.gauges, s.material.thickness, "material.gauges", errors)
        mat["gauges"] = [float(g) for g in s.material.gauges] if isinstance(s.material.gauges, (list, tuple)) else []
    r = s.requirements
    req = {}
    if (r.max_deflection is None) == (r.max_compliance is None):
        errors.append("requirements: give max_deflection or max_compliance, exactly one")
    elif r.max_deflection is not None:
        _check_number(r.max_deflection, "pos", "requirements.max_deflection (m)", errors)
        req["max_deflection"] = float(r.max_deflection)
    else:
        _check_number(r.max_compliance, "pos", "requirements.max_compliance (J)", errors)
        req["max_compliance"] = float(r.max_compliance)
    for key, label, kind in model.REQUIREMENT_FIELDS:
        v = getattr(r, key)
        _check_number(v, kind, "requirements.%s (%s)" % (key, label), errors)
        req[key] = float(v)
    for key, label in model.OPTIONAL_REQUIREMENT_FIELDS:
        v = _optional_positive(getattr(r, key), "requirements.%s (%s)" % (key, label), errors)
        if v is not None:
            req[key] = v
    search = {}
    for key, label, lo, hi in model.SEARCH_INT_FIELDS:
        v = getattr(s.search, key)
        if not isinstance(v, int) or isinstance(v, bool) or not lo <= v <= hi:
            errors.append("search.%s (%s): must be an integer in [%d, %d], got %r" % (key, label, lo, hi, v))
        search[key] = v
    for key, label, kind in model.SEARCH_FLOAT_FIELDS:
        v = getattr(s.search, key)
        _check_number(v, kind, "search.%s (%s)" % (key, label), errors)
        search[key] = float(v)
    if not isinstance(s.manufacturing, dict):
        errors.append("manufacturing: expected an object")
    out = {}
    if s.load_cases is not None:
        out["load_cases"] = envelope_to_json(s.load_cases, errors)
    out.update({"material": mat, "requirements": req, "manufacturing": dict(s.manufacturing or {}), "search": search})
    return out


# ---------------------------------------------------------------------------
# problem -> scene

MeshReader = Callable[[int, dict], Tuple[Sequence[Sequence[float]], Sequence[Sequence[int]]]]
TOP_FIELDS = ("format", "name", "description", "units", "environment", "rivet_areas", "loads", "load_cases",
              "material", "requirements", "manufacturing", "search")
LOAD_FIELDS = ("name", "center", "size", "rotation", "force", "moment", "mass", "center_of_mass", "inertia", "cases")


class _Errors:
    def __init__(self):
        self.items: List[str] = []

    def add(self, field: str, problem: str) -> None:
        self.items.append("%s: %s" % (field, problem))


def _unknown(node: dict, allowed, field: str, err: _Errors) -> None:
    for key in node:
        if key not in allowed:
            err.add(field or "(top level)", "unknown field '%s' (expected one of: %s)" % (key, ", ".join(allowed)))


def _obj(node, field: str, err: _Errors) -> bool:
    if not isinstance(node, dict):
        err.add(field, "expected an object")
        return False
    return True


def _list(node, field: str, err: _Errors) -> bool:
    if not isinstance(node, list):
        err.add(field, "expected an array")
        return False
    return True


def _vec(node, n: int, field: str, err: _Errors):
    if not isinstance(node, list) or not is_finite_vec(node, n):
        err.add(field, "expected %d finite numbers" % n)
        return None
    return [float(x) for x in node]


def problem_to_scene(problem: dict, mesh_reader: Optional[MeshReader] = None) -> Tuple[SceneData, List[str]]:
    """Scene data for a problem dict, and warnings; raises ProblemError naming the field.

    ``mesh_reader(index, mesh_json)`` returns (vertices, triangles) for meshes given
    by ``file``; the add-on passes one backed by the native reader so that face
    indices mean what the solver means by them.
    """
    err = _Errors()
    warnings: List[str] = []
    if not _obj(problem, "(top level)", err):
        raise ProblemError(err.items)
    _unknown(problem, TOP_FIELDS, "", err)
    if problem.get("format") != model.PROBLEM_FORMAT:
        err.add("format", "expected '%s', got %r" % (model.PROBLEM_FORMAT, problem.get("format")))
        raise ProblemError(err.items)
    if problem.get("units", "m") != "m":
        err.add("units", "only 'm' (metres) is supported")
    scene = SceneData(name=str(problem.get("name", "scene")), description=str(problem.get("description", "")))

    env = problem.get("environment")
    meshes = env.get("meshes") if isinstance(env, dict) else None
    if not _obj(env, "environment", err) or not _list(meshes, "environment.meshes", err):
        raise ProblemError(err.items)
    _unknown(env, ("meshes",), "environment", err)
    if not meshes:
        err.add("environment.meshes", "there are no meshes")
    for i, mj in enumerate(meshes):
        field = "environment.meshes[%d]" % i
        if not _obj(mj, field, err):
            continue
        _unknown(mj, ("name", "file", "vertices", "triangles"), field, err)
        name = mj.get("name")
        why = name_problem(name)
        if why:
            err.add(field + ".name", why)
            name = "mesh_%d" % i
        if any(m.name == name for m in scene.meshes):
            err.add(field + ".name", "duplicate mesh name '%s'" % name)
        if "file" in mj:
            if mesh_reader is None:
                err.add(field + ".file", "mesh '%s' is in file '%s': reading mesh files needs the native module"
                        % (name, mj["file"]))
                continue
            verts, tris = mesh_reader(i, mj)
            verts = [[float(x) for x in v] for v in verts]
            tris = [[int(x) for x in t] for t in tris]
        else:
            verts, tris = mj.get("vertices"), mj.get("triangles")
            if not _list(verts, field + ".vertices", err) or not _list(tris, field + ".triangles", err):
                continue
            ok = True
            for k, v in enumerate(verts):
                if _vec(v, 3, "%s.vertices[%d]" % (field, k), err) is None:
                    ok = False
                    break
            for k, t in enumerate(tris):
                if (not isinstance(t, list) or len(t) != 3 or
                        any(not isinstance(x, int) or isinstance(x, bool) or not 0 <= x < len(verts) for x in t)):
                    err.add("%s.triangles[%d]" % (field, k),
                            "expected 3 vertex indices in 0..%d" % (len(verts) - 1))
                    ok = False
                    break
            if not ok:
                continue
            if not tris:
                err.add(field + ".triangles", "mesh '%s' is empty" % name)
            verts = [[float(x) for x in v] for v in verts]
            tris = [list(t) for t in tris]
        scene.meshes.append(MeshData(name=name, vertices=verts, triangles=tris, face_areas=[0] * len(tris)))
    if err.items:
        raise ProblemError(err.items)

    ras = problem.get("rivet_areas")
    if _list(ras, "rivet_areas", err):
        if not ras:
            err.add("rivet_areas", "there are no rivet areas")
        seen = set()
        for i, rj in enumerate(ras):
            field = "rivet_areas[%d]" % i
            if not _obj(rj, field, err):
                continue
            _unknown(rj, ("name", "mesh", "faces"), field, err)
            name = rj.get("name")
            why = name_problem(name)
            if why:
                err.add(field + ".name", why)
                continue
            if name in seen:
                err.add(field + ".name", "duplicate rivet area name '%s'" % name)
            seen.add(name)
            ref = rj.get("mesh")
            if isinstance(ref, str):
                mesh = next((m for m in scene.meshes if m.name == ref), None)
                if mesh is None:
                    err.add(field + ".mesh", "no environment mesh is named '%s'" % ref)
                    continue
            elif isinstance(ref, int) and not isinstance(ref, bool) and 0 <= ref < len(scene.meshes):
                mesh = scene.meshes[ref]
            else:
                err.add(field + ".mesh", "expected a mesh name or an index in 0..%d" % (len(scene.meshes) - 1))
                continue
            faces = rj.get("faces")
            if not _list(faces, field + ".faces", err):
                continue
            if not faces:
                err.add(field + ".faces", "rivet area '%s' has no faces" % name)
            k = len(mesh.area_names) + 1  # ids are local to the mesh, in file order
            mesh.area_names[k] = name
            mesh.area_order[k] = i + 1
            for j, f in enumerate(faces):
                if not isinstance(f, int) or isinstance(f, bool) or not 0 <= f < len(mesh.triangles):
                    err.add("%s.faces[%d]" % (field, j), "face index %r is out of range (mesh '%s' has %d faces)"
                            % (f, mesh.name, len(mesh.triangles)))
                    break
                old = mesh.face_areas[f]
                if old and old != k:
                    err.add("%s.faces[%d]" % (field, j), "face %d of mesh '%s' is already in rivet area '%s'; in "
                            "Blender a face belongs to one rivet area" % (f, mesh.name, mesh.area_names[old]))
                    break
                mesh.face_areas[f] = k

    loads = problem.get("loads")
    if _list(loads, "loads", err):
        if not loads:
            err.add("loads", "there are no loads")
        for i, lj in enumerate(loads):
            field = "loads[%d]" % i
            if not _obj(lj, field, err):
                continue
            ld = load_from_json(lj, field, "load_cases" in problem, err)
            if ld is None:
                continue
            if any(l.name == ld.name for l in scene.loads):
                err.add(field + ".name", "duplicate load name '%s'" % ld.name)
            scene.loads.append(ld)

    scene.settings = settings_from_json(problem, err)
    massed = [lj for lj in loads if isinstance(lj, dict) and "mass" in lj] if isinstance(loads, list) else []
    if scene.settings.load_cases is not None and scene.loads and not massed:
        err.add("load_cases", "no load has a 'mass', so no load gets these cases (give a box its mass)")
    if err.items:
        raise ProblemError(err.items, warnings)
    return scene, warnings


def _number(node, kind: str, field: str, err: _Errors) -> Optional[float]:
    before = len(err.items)
    _check_number(node, kind, field, err.items)
    return float(node) if len(err.items) == before else None


def _cases_from_json(node, field: str, err: _Errors) -> List[LoadCaseData]:
    out: List[LoadCaseData] = []
    if not _list(node, field, err):
        return out
    if not node:
        err.add(field, "no cases: give at least one, or 'force'")
    for k, cj in enumerate(node):
        f = "%s[%d]" % (field, k)
        if not _obj(cj, f, err):
            continue
        _unknown(cj, ("name", "force", "moment", "max_deflection"), f, err)
        name = cj.get("name")
        why = name_problem(name)
        if why:
            err.add(f + ".name", why)
            continue
        if any(c.name == name for c in out):
            err.add(f + ".name", "duplicate case name '%s'" % name)
        force = _vec(cj.get("force", [0, 0, 0]), 3, f + ".force", err)
        moment = _vec(cj.get("moment", [0, 0, 0]), 3, f + ".moment", err)
        if force is None or moment is None:
            continue
        if not any(force) and not any(moment):
            err.add(f, "case '%s' has no force and no moment" % name)
        dmax = _number(cj["max_deflection"], "pos", f + ".max_deflection", err) if "max_deflection" in cj else None
        out.append(LoadCaseData(name=name, force=force, moment=moment, max_deflection=dmax))
    return out


def load_from_json(lj: dict, field: str, has_envelope: bool, err: _Errors) -> Optional[LoadData]:
    """LoadData of ``loads[i]``, or None after adding its problems to ``err``."""
    _unknown(lj, LOAD_FIELDS, field, err)
    name = lj.get("name")
    why = name_problem(name)
    if why:
        err.add(field + ".name", why)
        return None
    center = _vec(lj.get("center"), 3, field + ".center", err)
    size = _vec(lj.get("size"), 3, field + ".size", err)
    rot = _vec(lj.get("rotation", [1, 0, 0, 0]), 4, field + ".rotation", err)
    if None in (center, size, rot):
        return None
    if not all(s > 0 for s in size):
        err.add(field + ".size", "must be positive on every axis, got %s" % _fmt(size))
    try:
        rot = list(quat_unit(rot))
    except ValueError:
        err.add(field + ".rotation", "quaternion has zero length")
        return None
    ld = LoadData(name=name, center=center, size=size, rotation=rot, force=[0.0, 0.0, 0.0], moment=[0.0, 0.0, 0.0])
    if "mass" in lj:
        ld.mass = _number(lj["mass"], "pos", field + ".mass", err)
    elif "center_of_mass" in lj or "inertia" in lj:
        key = "center_of_mass" if "center_of_mass" in lj else "inertia"
        err.add(field + "." + key, "is given without 'mass' (kg): give the box's mass too")
    if "center_of_mass" in lj:
        ld.center_of_mass = _vec(lj["center_of_mass"], 3, field + ".center_of_mass", err)
        if ld.center_of_mass is not None and _outside_box(ld, ld.center_of_mass) > 1e-6:
            err.add(field + ".center_of_mass", "centre of mass lies %.4g mm outside the load box"
                    % (_outside_box(ld, ld.center_of_mass) * 1e3))
    if "inertia" in lj:
        why = inertia_problem(lj["inertia"])
        if why:
            err.add(field + ".inertia", why)
        else:
            ld.inertia = [[float(x) for x in row] for row in lj["inertia"]]
    if "cases" in lj:
        for key in ("force", "moment"):
            if key in lj:
                err.add(field + "." + key, "give either 'cases' or 'force'/'moment', not both")
        ld.own = model.OWN_CASES
        ld.cases = _cases_from_json(lj["cases"], field + ".cases", err)
    elif "force" in lj or "moment" in lj or not (has_envelope and "mass" in lj):
        if "force" not in lj:
            err.add(field + ".force", "required field is missing (or give 'cases', or a 'mass' with a problem-level "
                    "'load_cases')")
            return None
        ld.force = _vec(lj.get("force"), 3, field + ".force", err)
        ld.moment = _vec(lj.get("moment", [0, 0, 0]), 3, field + ".moment", err)
        if ld.force is None or ld.moment is None:
            return None
    else:
        ld.own = model.OWN_NONE
    return ld


def envelope_from_json(node, err: _Errors) -> Optional[Envelope]:
    """The problem-level ``load_cases`` as an Envelope, or None after adding its problems to ``err``."""
    if not _obj(node, "load_cases", err):
        return None
    _unknown(node, ("forward", "up", "factors"), "load_cases", err)
    forward = _vec(node.get("forward"), 3, "load_cases.forward", err)
    up = _vec(node.get("up"), 3, "load_cases.up", err)
    if forward is None or up is None:
        return None
    why = axes_problem(forward, up)
    if why:
        err.add("load_cases.forward" if why.startswith("forward has") else "load_cases.up", why)
    env = Envelope(forward=forward, up=up, preset=None)
    factors = node.get("factors")
    if isinstance(factors, str):
        if factors not in model.PRESETS:
            err.add("load_cases.factors", "unknown preset '%s' (the one preset is '%s')"
                    % (factors, model.PRESET_FAR25_561))
        env.preset = factors
    elif isinstance(factors, list):
        if not factors:
            err.add("load_cases.factors", "no factors: give at least one, or the preset '%s'" % model.PRESET_FAR25_561)
        for k, fj in enumerate(factors):
            f = "load_cases.factors[%d]" % k
            if not _obj(fj, f, err):
                continue
            _unknown(fj, ("name", "g", "max_deflection"), f, err)
            name = fj.get("name")
            why = name_problem(name)
            if why:
                err.add(f + ".name", why)
                continue
            if any(x.name == name for x in env.factors):
                err.add(f + ".name", "duplicate factor name '%s'" % name)
            g = _vec(fj.get("g"), 3, f + ".g", err)
            if g is None:
                continue
            if not any(g):
                err.add(f + ".g", "factor '%s' is [0, 0, 0] g: a case with no force and no moment" % name)
            dmax = _number(fj["max_deflection"], "pos", f + ".max_deflection", err) if "max_deflection" in fj else None
            env.factors.append(FactorData(name=name, g=g, max_deflection=dmax))
    else:
        err.add("load_cases.factors", "expected the preset name '%s' or an array of factors" % model.PRESET_FAR25_561)
    return env


def settings_from_json(problem: dict, err: _Errors) -> Settings:
    s = Settings()
    mat = problem.get("material", {})
    if _obj(mat, "material", err):
        _unknown(mat, ("name",) + tuple(k for k, _, _ in model.MATERIAL_FIELDS) + ("gauges",), "material", err)
        for key, label, kind in model.MATERIAL_FIELDS:
            if key in mat:
                before = len(err.items)
                _check_number(mat[key], kind, "material." + key, err.items)
                if len(err.items) == before:
                    setattr(s.material, key, float(mat[key]))
        if "gauges" in mat:
            before = len(err.items)
            _check_gauges(mat["gauges"], s.material.thickness, "material.gauges", err.items)
            if len(err.items) == before:
                s.material.gauges = [float(g) for g in mat["gauges"]]
    req = problem.get("requirements", {})
    if _obj(req, "requirements", err):
        _unknown(req, ("max_compliance", "max_deflection") + tuple(k for k, _, _ in model.REQUIREMENT_FIELDS) +
                 tuple(k for k, _ in model.OPTIONAL_REQUIREMENT_FIELDS), "requirements", err)
        if "max_compliance" in req and "max_deflection" in req:
            err.add("requirements", "give max_compliance or max_deflection, not both")
        elif "max_compliance" in req:
            _check_number(req["max_compliance"], "pos", "requirements.max_compliance", err.items)
            s.requirements.max_compliance, s.requirements.max_deflection = req["max_compliance"], None
        elif "max_deflection" in req:
            _check_number(req["max_deflection"], "pos", "requirements.max_deflection", err.items)
            s.requirements.max_deflection = req["max_deflection"]
        for key, label, kind in model.REQUIREMENT_FIELDS:
            if key in req:
                _check_number(req[key], kind, "requirements." + key, err.items)
                setattr(s.requirements, key, req[key])
        for key, _label in model.OPTIONAL_REQUIREMENT_FIELDS:
            if key in req:
                setattr(s.requirements, key, _number(req[key], "pos", "requirements." + key, err))
    if "load_cases" in problem:
        s.load_cases = envelope_from_json(problem["load_cases"], err)
    man = problem.get("manufacturing", {})
    if _obj(man, "manufacturing", err):
        s.manufacturing = dict(man)
    search = problem.get("search", {})
    if _obj(search, "search", err):
        _unknown(search, tuple(k for k, _, _, _ in model.SEARCH_INT_FIELDS) +
                 tuple(k for k, _, _ in model.SEARCH_FLOAT_FIELDS), "search", err)
        for key, label, lo, hi in model.SEARCH_INT_FIELDS:
            if key in search:
                v = search[key]
                if not isinstance(v, int) or isinstance(v, bool) or not lo <= v <= hi:
                    err.add("search." + key, "must be an integer in [%d, %d], got %r" % (lo, hi, v))
                else:
                    setattr(s.search, key, v)
        for key, label, kind in model.SEARCH_FLOAT_FIELDS:
            if key in search:
                _check_number(search[key], kind, "search." + key, err.items)
                setattr(s.search, key, search[key])
    return s


def rivet_area_table(mesh: MeshData) -> List[Tuple[int, str, float, int]]:
    """(id, name, area m^2, triangle count) per named or used area id of ``mesh``, by id."""
    areas = rivet_area_areas(mesh.vertices, mesh.triangles, mesh.face_areas or [])
    ids = sorted(set(mesh.area_names) | set(areas))
    return [(k, mesh.area_names.get(k, default_area_name(mesh.name, k)), *areas.get(k, (0.0, 0))) for k in ids]
