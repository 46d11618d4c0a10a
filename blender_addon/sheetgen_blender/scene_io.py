"""Blender scene <-> plain scene data (core.model). Reads and builds; no decisions.

Meshes are read without modifiers, triangulated with Blender's loop triangles
(the triangles of polygon p are consecutive), in world space. Blender stores
coordinates, matrices and float properties as float32, so every number read
from Blender is written as the shortest decimal with the same float32 (world
coordinates too: they carry no more precision than the float32 data they come
from). A problem file read into Blender and written back gives the file's
numbers again, whenever they were float32-representable to 7 digits.
"""
import bmesh
import bpy
import numpy as np
from mathutils import Quaternion, Vector

from . import loads, tagging
from .core import model
from .core import problem as core_problem
from .core.geometry import rivet_area_areas, shortest_float32, shortest_float32_list
from .core.model import Envelope, FactorData, LoadCaseData, LoadData, MeshData, SceneData, Settings

_OWN_TO_CORE = {'FORCE': model.OWN_FORCE, 'CASES': model.OWN_CASES, 'NONE': model.OWN_NONE}
_OWN_FROM_CORE = {v: k for k, v in _OWN_TO_CORE.items()}


# ---------------------------------------------------------------------------
# reading

def _mesh_snapshot(obj):
    """(mesh, temporary) with the current geometry; edit-mode meshes are copied out of the edit BMesh."""
    if obj.mode == 'EDIT':
        bm = bmesh.from_edit_mesh(obj.data).copy()
        tmp = bpy.data.meshes.new("~sheetgen_snapshot")
        bm.to_mesh(tmp)
        bm.free()
        return tmp, True
    return obj.data, False


def read_mesh(obj, clean=True):
    """MeshData of a mesh object: world-space vertices, loop triangles, per-triangle area ids and names.

    ``clean``: write coordinates as shortest float32 decimals (for files; areas do not need it).
    """
    me, temporary = _mesh_snapshot(obj)
    try:
        nv = len(me.vertices)
        co = np.empty(nv * 3, dtype=np.float32)
        me.vertices.foreach_get("co", co)
        co = co.reshape(nv, 3).astype(np.float64)
        m = np.array(obj.matrix_world, dtype=np.float64)
        world = co if np.array_equal(m, np.eye(4)) else co @ m[:3, :3].T + m[:3, 3]
        vertices = [shortest_float32_list(v) for v in world.tolist()] if clean else world.tolist()
        me.calc_loop_triangles()
        nt = len(me.loop_triangles)
        tris = np.empty(nt * 3, dtype=np.int32)
        me.loop_triangles.foreach_get("vertices", tris)
        poly = np.empty(nt, dtype=np.int32)
        me.loop_triangles.foreach_get("polygon_index", poly)
        attr = me.attributes.get(tagging.ATTR)
        if attr is not None and attr.domain == 'FACE' and attr.data_type == 'INT' and len(me.polygons):
            ids = np.empty(len(me.polygons), dtype=np.int32)
            attr.data.foreach_get("value", ids)
            face_areas = ids[poly].tolist()
        else:
            face_areas = [0] * nt
        names = {a.area_id: a.name for a in obj.sheetgen.rivet_areas}
        order = {a.area_id: a.problem_order for a in obj.sheetgen.rivet_areas if a.problem_order}
        return MeshData(name=obj.name, vertices=vertices, triangles=tris.reshape(nt, 3).tolist(),
                        face_areas=face_areas, area_names=names, area_order=order)
    finally:
        if temporary:
            bpy.data.meshes.remove(me)


def refresh_area_stats(obj):
    """Update area_m2 and face_count of obj's rivet areas (world space, current transform)."""
    md = read_mesh(obj, clean=False)
    stats = rivet_area_areas(md.vertices, md.triangles, md.face_areas)
    polys = tagging.face_ids(obj)
    for a in obj.sheetgen.rivet_areas:
        a.area_m2 = stats.get(a.area_id, (0.0, 0))[0]
        a.face_count = sum(1 for k in polys if k == a.area_id)
    return stats


def is_environment(obj, view_layer):
    """A visible mesh that is not a load, a force arrow, or excluded by the user."""
    s = obj.sheetgen
    return (obj.type == 'MESH' and not s.is_load and not s.is_arrow and not s.exclude
            and obj.visible_get(view_layer=view_layer))


def _problem_order(o):
    """An imported problem's order first (the solver then numbers meshes and loads, and result.json lists the
    parts, as the file did), then the others by name."""
    k = o.sheetgen.problem_order
    return (k == 0, k, o.name)


def environment_objects(scene, view_layer):
    return sorted((o for o in scene.objects if is_environment(o, view_layer)), key=_problem_order)


def load_objects(scene, view_layer):
    return sorted((o for o in scene.objects if o.sheetgen.is_load and o.visible_get(view_layer=view_layer)),
                  key=_problem_order)


def read_load(obj):
    """LoadData of a load object: its bounding box (local size x world scale), world centre and rotation."""
    corners = [Vector(c) for c in obj.bound_box]
    lo = Vector((min(c[i] for c in corners) for i in range(3)))
    hi = Vector((max(c[i] for c in corners) for i in range(3)))
    mw = obj.matrix_world
    _, rot, scale = mw.decompose()
    if obj.parent is None:
        # The stored values, not ones rebuilt from the float32 matrix (which differ in the last bits).
        scale = obj.scale
        if obj.rotation_mode == 'QUATERNION':
            rot = obj.rotation_quaternion.copy()
        elif obj.rotation_mode != 'AXIS_ANGLE':
            rot = obj.rotation_euler.to_quaternion()
    if rot.w < 0:
        rot.negate()
    center = mw @ ((lo + hi) * 0.5)
    size = [(hi[i] - lo[i]) * abs(scale[i]) for i in range(3)]
    s = obj.sheetgen
    ld = LoadData(name=obj.name, center=shortest_float32_list(center), size=shortest_float32_list(size),
                  rotation=shortest_float32_list(rot), force=shortest_float32_list(s.force),
                  moment=shortest_float32_list(s.moment), own=_OWN_TO_CORE[s.own_cases])
    ld.cases = [LoadCaseData(name=c.name, force=shortest_float32_list(c.force), moment=shortest_float32_list(c.moment),
                             max_deflection=_si(c.max_deflection_mm, 1e-3) if c.use_max_deflection else None)
                for c in s.cases]
    if s.use_mass:
        ld.mass = _si(s.mass, 1)
        if s.use_center_of_mass:
            ld.center_of_mass = shortest_float32_list(s.center_of_mass)
        if s.use_inertia:
            i = shortest_float32_list(s.inertia)
            ld.inertia = [i[0:3], i[3:6], i[6:9]]
    return ld


def read_envelope(p):
    """The scene's envelope (``load_cases``) as core data, or None when it is off."""
    if not p.use_envelope:
        return None
    env = Envelope(forward=shortest_float32_list(p.envelope_forward), up=shortest_float32_list(p.envelope_up))
    if p.envelope_kind == 'PRESET':
        env.preset = model.PRESET_FAR25_561
    else:
        env.preset = None
        env.factors = [FactorData(name=f.name, g=shortest_float32_list(f.g),
                                  max_deflection=_si(f.max_deflection_mm, 1e-3) if f.use_max_deflection else None)
                       for f in p.envelope_factors]
    return env


def _si(value, factor):
    """A float32 property in engineering units (GPa, MPa, mm) as an SI float."""
    return float("%.15g" % (shortest_float32(value) * factor))


def read_settings(scene):
    p = scene.sheetgen
    s = Settings()
    s.material = model.Material(youngs_modulus=_si(p.youngs_modulus_gpa, 1e9), poisson_ratio=_si(p.poisson_ratio, 1),
                                density=_si(p.density, 1), yield_strength=_si(p.yield_strength_mpa, 1e6),
                                ultimate_strength=_si(p.ultimate_strength_mpa, 1e6),
                                thickness=_si(p.thickness_mm, 1e-3),
                                gauges=core_problem.gauges_from_mm_text(p.thicker_gauges, p.gauges_mm))
    r = model.Requirements(min_margin_of_safety=_si(p.min_margin_of_safety, 1), safety_factor=_si(p.safety_factor, 1),
                           clearance=_si(p.clearance_mm, 1e-3),
                           min_buckling_factor=_si(p.min_buckling_factor, 1) if p.use_min_buckling_factor else None,
                           min_frequency_hz=_si(p.min_frequency_hz, 1) if p.use_min_frequency else None)
    if p.stiffness_limit == 'DEFLECTION':
        r.max_deflection, r.max_compliance = _si(p.max_deflection_mm, 1e-3), None
    else:
        r.max_deflection, r.max_compliance = None, _si(p.max_compliance, 1)
    s.requirements = r
    s.search = model.Search(chains=p.chains, iterations=p.iterations, beam_width=p.beam_width, seed=p.seed,
                            alpha=_si(p.alpha, 1), beta=_si(p.beta, 1), scene_unit=_si(p.scene_unit, 1),
                            threads=p.threads)
    s.load_cases = read_envelope(p)
    import json
    try:
        s.manufacturing = json.loads(p.manufacturing_json or "{}")
    except ValueError:
        s.manufacturing = "manufacturing_json is not valid JSON"  # reported by core validation
    return s


def read_scene(scene, view_layer):
    """(SceneData, warnings) for the visible environment meshes and loads of ``scene``."""
    warnings = []
    data = SceneData(name=scene.sheetgen.problem_name or scene.name, description=scene.sheetgen.description)
    for obj in environment_objects(scene, view_layer):
        md = read_mesh(obj)
        if not md.triangles:
            if any(k for k in md.area_names):
                warnings.append("object '%s': mesh has no faces; left out with its rivet areas" % obj.name)
            continue
        data.meshes.append(md)
    data.loads = [read_load(o) for o in load_objects(scene, view_layer)]
    data.settings = read_settings(scene)
    return data, warnings


# ---------------------------------------------------------------------------
# building

def write_settings(scene, s):
    p = scene.sheetgen
    m = s.material
    p.youngs_modulus_gpa = m.youngs_modulus / 1e9
    p.poisson_ratio = m.poisson_ratio
    p.density = m.density
    p.yield_strength_mpa = m.yield_strength / 1e6
    p.ultimate_strength_mpa = m.ultimate_strength / 1e6
    p.thickness_mm = m.thickness * 1e3
    p.thicker_gauges, p.gauges_mm = core_problem.gauges_to_mm_text(m.gauges)
    r = s.requirements
    if r.max_compliance is not None:
        p.stiffness_limit = 'COMPLIANCE'
        p.max_compliance = r.max_compliance
    else:
        p.stiffness_limit = 'DEFLECTION'
        p.max_deflection_mm = r.max_deflection * 1e3
    p.min_margin_of_safety = r.min_margin_of_safety
    p.safety_factor = r.safety_factor
    p.clearance_mm = r.clearance * 1e3
    p.use_min_buckling_factor = r.min_buckling_factor is not None
    if r.min_buckling_factor is not None:
        p.min_buckling_factor = r.min_buckling_factor
    p.use_min_frequency = r.min_frequency_hz is not None
    if r.min_frequency_hz is not None:
        p.min_frequency_hz = r.min_frequency_hz
    write_envelope(p, s.load_cases)
    for key in ("chains", "iterations", "beam_width", "seed", "alpha", "beta", "scene_unit", "threads"):
        setattr(p, key, getattr(s.search, key))
    import json
    p.manufacturing_json = json.dumps(s.manufacturing or {})


def write_envelope(p, env):
    """The scene's envelope properties from core data (None: off)."""
    p.use_envelope = env is not None
    p.envelope_factors.clear()
    if env is None:
        return
    p.envelope_forward = env.forward
    p.envelope_up = env.up
    p.envelope_kind = 'PRESET' if env.preset is not None else 'LIST'
    for f in env.factors:
        item = p.envelope_factors.add()
        item.name = f.name
        item.g = f.g
        item.use_max_deflection = f.max_deflection is not None
        if f.max_deflection is not None:
            item.max_deflection_mm = f.max_deflection * 1e3


def write_load_settings(obj, ld):
    """A load object's cases and mass properties from core data (the force arrow is updated by the caller)."""
    s = obj.sheetgen
    s["force"] = list(ld.force)   # set without the update callback; the arrow comes next
    s.moment = ld.moment
    s.own_cases = _OWN_FROM_CORE[ld.own]   # no arrow yet (not a load yet): the update does nothing
    s.cases.clear()
    for c in ld.cases:
        item = s.cases.add()
        item.name = c.name
        item.force = c.force
        item.moment = c.moment
        item.use_max_deflection = c.max_deflection is not None
        if c.max_deflection is not None:
            item.max_deflection_mm = c.max_deflection * 1e3
    s.use_mass = ld.mass is not None
    if ld.mass is not None:
        s.mass = ld.mass
    s.use_center_of_mass = ld.center_of_mass is not None
    if ld.center_of_mass is not None:
        s.center_of_mass = ld.center_of_mass
    s.use_inertia = ld.inertia is not None
    if ld.inertia is not None:
        s.inertia = [x for row in ld.inertia for x in row]


def build_mesh_object(md, collection):
    """A mesh object with md's triangles (identity transform), tagged from md.face_areas."""
    me = bpy.data.meshes.new(md.name)
    nv, nt = len(md.vertices), len(md.triangles)
    me.vertices.add(nv)
    me.vertices.foreach_set("co", np.asarray(md.vertices, dtype=np.float32).reshape(-1))
    me.loops.add(nt * 3)
    me.loops.foreach_set("vertex_index", np.asarray(md.triangles, dtype=np.int32).reshape(-1))
    me.polygons.add(nt)
    me.polygons.foreach_set("loop_start", np.arange(0, nt * 3, 3, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(nt, 3, dtype=np.int32))
    me.update(calc_edges=True)
    me.validate(clean_customdata=False)
    if len(me.polygons) != nt:
        # validate() removed degenerate triangles: face indices would no longer match the file.
        raise ValueError("mesh '%s': %d of its %d triangles are degenerate (repeated vertices); "
                         "Blender cannot hold them" % (md.name, nt - len(me.polygons), nt))
    obj = bpy.data.objects.new(md.name, me)
    collection.objects.link(obj)
    ids = md.face_areas or [0] * nt
    if any(ids) or md.area_names:
        attr = me.attributes.new(tagging.ATTR, 'INT', 'FACE')
        attr.data.foreach_set("value", np.asarray(ids, dtype=np.int32))
        for k in sorted(md.area_names):
            item = obj.sheetgen.rivet_areas.add()
            item.area_id = k
            item.name = md.area_names[k]
            item.problem_order = md.area_order.get(k, 0)
            item["color"] = tagging.palette(k)
        tagging.recolor(obj)
        refresh_area_stats(obj)
    return obj


def build_load_object(ld, collection):
    """A unit cube scaled to ld.size, rotated and placed at ld.center, marked as a load with its arrow."""
    me = bpy.data.meshes.new(ld.name)
    bm = bmesh.new()
    bmesh.ops.create_cube(bm, size=1.0)
    bm.to_mesh(me)
    bm.free()
    obj = bpy.data.objects.new(ld.name, me)
    collection.objects.link(obj)
    obj.rotation_mode = 'QUATERNION'
    obj.rotation_quaternion = Quaternion(ld.rotation)
    obj.scale = ld.size
    obj.location = ld.center
    obj.display_type = 'WIRE'
    write_load_settings(obj, ld)
    loads.make_load(obj, collection)
    return obj


def build_scene(scene, data, collection_name=None):
    """Objects for ``data`` in a new collection of ``scene``; settings written to the scene."""
    col = bpy.data.collections.new(collection_name or "sheetgen %s" % data.name)
    scene.collection.children.link(col)
    meshes = [build_mesh_object(md, col) for md in data.meshes]
    load_objs = [build_load_object(ld, col) for ld in data.loads]
    for i, obj in enumerate(meshes):
        obj.sheetgen.problem_order = i + 1
    for i, obj in enumerate(load_objs):
        obj.sheetgen.problem_order = i + 1
    write_settings(scene, data.settings)
    scene.sheetgen.problem_name = data.name
    scene.sheetgen.description = data.description
    return meshes, load_objs
