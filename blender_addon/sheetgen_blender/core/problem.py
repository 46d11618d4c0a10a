"""Scene data <-> ``sheetgen-problem/1`` dict (docs/problem-format.md), both ways.

``scene_to_problem`` checks what the Blender user can get wrong and names the
object and the field; the native parser (``parse_problem``) remains the
authority on the file. ``problem_to_scene`` reads a problem dict (inline meshes,
or file meshes through a ``mesh_reader``) into plain scene data.
"""
import math
from typing import Callable, Dict, List, Optional, Sequence, Tuple

from . import model
from .geometry import is_finite_vec, quat_unit, rivet_area_areas
from .model import LoadData, MeshData, SceneData, Settings


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
    if scene.meshes and not rivet_areas and not errors:
        errors.append("no rivet areas: select faces of an environment mesh in Edit Mode and press "
                      "'Mark' (Sheet Metal tab > Rivet Areas)")

    loads_json: List[dict] = []
    load_names = set()
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
        ok = True
        for key, n in (("center", 3), ("size", 3), ("rotation", 4), ("force", 3), ("moment", 3)):
            if not is_finite_vec(getattr(ld, key), n):
                errors.append("%s: %s must be %d finite numbers" % (where, key, n))
                ok = False
        if not ok:
            continue
        if not all(s > 0 for s in ld.size):
            errors.append("%s: size must be positive on every axis, got %s m (a flat object cannot be a load box)"
                          % (where, _fmt(ld.size)))
        try:
            rot = quat_unit(ld.rotation)
        except ValueError:
            errors.append("%s: rotation quaternion has zero length" % where)
            continue
        if all(x == 0 for x in ld.force) and all(x == 0 for x in ld.moment):
            errors.append("%s: force and moment are both zero (set Force in the Loads panel)" % where)
        loads_json.append({"name": ld.name, "center": [float(x) for x in ld.center],
                           "size": [float(x) for x in ld.size], "rotation": [float(x) for x in rot],
                           "force": [float(x) for x in ld.force], "moment": [float(x) for x in ld.moment]})

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


def _check_number(value, kind: str, where: str, errors: List[str]) -> None:
    if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
        errors.append("%s: expected a finite number, got %r" % (where, value))
    elif kind == "pos" and not value > 0:
        errors.append("%s: must be positive, got %g" % (where, value))
    elif kind == "nonneg" and not value >= 0:
        errors.append("%s: must not be negative, got %g" % (where, value))
    elif kind == "poisson" and not -1 < value < 0.5:
        errors.append("%s: must lie in (-1, 0.5), got %g" % (where, value))


def settings_to_json(s: Settings, errors: List[str]) -> dict:
    """The material, requirements, manufacturing and search sections; checks go to ``errors``."""
    mat = {}
    for key, label, kind in model.MATERIAL_FIELDS:
        v = getattr(s.material, key)
        _check_number(v, kind, "material.%s (%s)" % (key, label), errors)
        mat[key] = float(v)
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
    return {"material": mat, "requirements": req, "manufacturing": dict(s.manufacturing or {}), "search": search}


# ---------------------------------------------------------------------------
# problem -> scene

MeshReader = Callable[[int, dict], Tuple[Sequence[Sequence[float]], Sequence[Sequence[int]]]]
TOP_FIELDS = ("format", "name", "description", "units", "environment", "rivet_areas", "loads", "material",
              "requirements", "manufacturing", "search")


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
            _unknown(lj, ("name", "center", "size", "rotation", "force", "moment"), field, err)
            name = lj.get("name")
            why = name_problem(name)
            if why:
                err.add(field + ".name", why)
                continue
            if any(l.name == name for l in scene.loads):
                err.add(field + ".name", "duplicate load name '%s'" % name)
            center = _vec(lj.get("center"), 3, field + ".center", err)
            size = _vec(lj.get("size"), 3, field + ".size", err)
            rot = _vec(lj.get("rotation", [1, 0, 0, 0]), 4, field + ".rotation", err)
            force = _vec(lj.get("force"), 3, field + ".force", err)
            moment = _vec(lj.get("moment", [0, 0, 0]), 3, field + ".moment", err)
            if None in (center, size, rot, force, moment):
                continue
            if not all(s > 0 for s in size):
                err.add(field + ".size", "must be positive on every axis, got %s" % _fmt(size))
            try:
                rot = list(quat_unit(rot))
            except ValueError:
                err.add(field + ".rotation", "quaternion has zero length")
                continue
            scene.loads.append(LoadData(name=name, center=center, size=size, rotation=rot, force=force, moment=moment))

    scene.settings = settings_from_json(problem, err)
    if err.items:
        raise ProblemError(err.items, warnings)
    return scene, warnings


def settings_from_json(problem: dict, err: _Errors) -> Settings:
    s = Settings()
    mat = problem.get("material", {})
    if _obj(mat, "material", err):
        _unknown(mat, ("name",) + tuple(k for k, _, _ in model.MATERIAL_FIELDS), "material", err)
        for key, label, kind in model.MATERIAL_FIELDS:
            if key in mat:
                before = len(err.items)
                _check_number(mat[key], kind, "material." + key, err.items)
                if len(err.items) == before:
                    setattr(s.material, key, float(mat[key]))
    req = problem.get("requirements", {})
    if _obj(req, "requirements", err):
        _unknown(req, ("max_compliance", "max_deflection") + tuple(k for k, _, _ in model.REQUIREMENT_FIELDS),
                 "requirements", err)
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
