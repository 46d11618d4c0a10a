"""A generate result in the scene: one collection "sheetgen run N" per run (bpy builder; no decisions).

Per load with a valid part: ``<load> part`` (the bent tabs, Solidify to the
sheet thickness, bend edges marked), ``<load> flat`` (the flat pattern laid
beside the scene, bend lines as edges), ``<load> flat holes`` (its rivet and
self-rivet holes, discs on the flat's top face), ``<load> rivets`` and
``<load> self-rivets`` (markers; the latter only on a self-riveted part). The
plain mesh data comes from core.result. Every generated object is marked
*Not in environment*, so a later Generate does not see it. The run's
result.json text and its export files are stored on the collection (saved
with the .blend), which is what the Results panel and Export read.
"""
import json

import bpy
from mathutils import Vector

from . import scene_io
from .core import result as core_result

BEND_ATTR = "sheetgen_bend"          # INT edge attribute: bend number, 0 = not a bend
RUN_PREFIX = "sheetgen run "
KEY_RESULT = "sheetgen_result"       # collection property: result.json text
KEY_FILES = "sheetgen_files"         # collection property: {relative path: text} of the exports
FLAT_GAP = 0.1                       # m between the scene and the flat patterns laid beside it


def _material(name, colour, metallic=0.0, roughness=0.5, alpha=1.0):
    mat = bpy.data.materials.get(name)
    if mat is None:
        mat = bpy.data.materials.new(name)
        mat.use_nodes = True
    mat.diffuse_color = (colour[0], colour[1], colour[2], alpha)   # Solid view colour
    mat.metallic = metallic
    mat.roughness = roughness
    bsdf = mat.node_tree.nodes.get("Principled BSDF")
    if bsdf is not None:
        bsdf.inputs["Base Color"].default_value = (colour[0], colour[1], colour[2], 1.0)
        bsdf.inputs["Metallic"].default_value = metallic
        bsdf.inputs["Roughness"].default_value = roughness
        bsdf.inputs["Alpha"].default_value = alpha
    if alpha < 1.0:
        mat.blend_method = 'BLEND'
    return mat


def part_material():
    return _material("sheetgen metal", (0.78, 0.80, 0.83), metallic=1.0, roughness=0.32)


def rivet_material():
    return _material("sheetgen rivet", (0.85, 0.12, 0.08), roughness=0.4)


def self_rivet_material():
    return _material("sheetgen self-rivet", (0.05, 0.65, 0.75), roughness=0.4)


def flat_material():
    return _material("sheetgen flat", (0.70, 0.74, 0.80), metallic=0.6, roughness=0.45)


def modes_material():
    return _material("sheetgen modes", (0.30, 0.62, 0.95), roughness=0.5)


def mesh_from_plain(name, plain):
    """A Blender mesh from core.result.MeshPlain, with the bend edges in BEND_ATTR and as seams."""
    me = bpy.data.meshes.new(name)
    me.from_pydata(plain.vertices, list(plain.loose_edges), plain.faces)
    me.update()
    if plain.bend_edges:
        number = {}
        for a, b, n in plain.bend_edges:
            number[(min(a, b), max(a, b))] = n
        attr = me.attributes.new(BEND_ATTR, 'INT', 'EDGE')
        values = [0] * len(me.edges)
        for e in me.edges:
            v = e.vertices
            n = number.get((min(v[0], v[1]), max(v[0], v[1])))
            if n is not None:
                values[e.index] = n if n > 0 else -1
                e.use_seam = True
        attr.data.foreach_set("value", values)
    return me


def _object(name, me, collection, material, run, load):
    obj = bpy.data.objects.new(name, me)
    collection.objects.link(obj)
    me.materials.append(material)
    obj.sheetgen.exclude = True   # never environment for a later run
    obj["sheetgen_run"] = run
    obj["sheetgen_load"] = load
    return obj


def _solidify(obj, thickness):
    mod = obj.modifiers.new("Thickness", 'SOLIDIFY')
    mod.thickness = thickness
    mod.offset = 0.0             # the tabs' corners are on the mid-surface
    mod.use_even_offset = True
    return mod


def scene_bounds(scene, view_layer):
    """World bounding box (lo, hi) of the environment meshes and loads, or None."""
    lo = Vector((float("inf"),) * 3)
    hi = -lo
    objs = scene_io.environment_objects(scene, view_layer) + scene_io.load_objects(scene, view_layer)
    for o in objs:
        for c in o.bound_box:
            w = o.matrix_world @ Vector(c)
            lo = Vector(map(min, lo, w))
            hi = Vector(map(max, hi, w))
    return (lo, hi) if objs else None


def next_run_number(scene):
    n = 0
    for c in bpy.data.collections:
        if c.name.startswith(RUN_PREFIX):
            try:
                n = max(n, int(c.name[len(RUN_PREFIX):].split(".")[0]))
            except ValueError:
                pass
    return n + 1


def build_run(context, doc, files, thickness):
    """The run's collection with the objects of every valid part; returns the collection."""
    scene = context.scene
    bounds = scene_bounds(scene, context.view_layer)
    run = next_run_number(scene)
    col = bpy.data.collections.new(RUN_PREFIX + str(run))
    scene.collection.children.link(col)
    col[KEY_RESULT] = json.dumps(doc)
    col[KEY_FILES] = dict(files)
    metal, red, cyan, flat_mat = part_material(), rivet_material(), self_rivet_material(), flat_material()
    x0 = (bounds[1].x if bounds else 0.0) + FLAT_GAP
    y0 = bounds[0].y if bounds else 0.0
    z0 = bounds[0].z if bounds else 0.0
    for pm in core_result.part_meshes(doc, thickness):
        if pm.bent is None:
            continue
        bent = _object("%s part" % pm.load, mesh_from_plain("%s part" % pm.load, pm.bent), col, metal, run, pm.load)
        _solidify(bent, pm.thickness)
        if pm.rivets.vertices:
            _object("%s rivets" % pm.load, mesh_from_plain("%s rivets" % pm.load, pm.rivets), col, red, run, pm.load)
        if pm.self_rivets.vertices:
            _object("%s self-rivets" % pm.load, mesh_from_plain("%s self-rivets" % pm.load, pm.self_rivets), col, cyan,
                    run, pm.load)
        flat = _object("%s flat" % pm.load, mesh_from_plain("%s flat" % pm.load, pm.flat), col, flat_mat, run,
                       pm.load)
        _solidify(flat, pm.thickness)
        xs = [v[0] for v in pm.flat.vertices]
        ys = [v[1] for v in pm.flat.vertices]
        # Beside the scene on its floor level, flat patterns of several loads one after another along y.
        flat.location = (x0 - min(xs), y0 - min(ys), z0 + pm.thickness / 2)
        if pm.holes.vertices:
            # On the flat's top face, a hair above it so the discs do not z-fight with it.
            holes = _object("%s flat holes" % pm.load, mesh_from_plain("%s flat holes" % pm.load, pm.holes), col, red,
                            run, pm.load)
            holes.location = (flat.location[0], flat.location[1], flat.location[2] + pm.thickness / 2 + 1e-4)
        y0 += (max(ys) - min(ys)) + FLAT_GAP
    scene.sheetgen.result_collection = col
    return col


def run_document(col):
    """The result document stored on a run collection, or None."""
    if col is None or KEY_RESULT not in col:
        return None
    try:
        return json.loads(col[KEY_RESULT])
    except ValueError:
        return None


def run_files(col):
    if col is None or KEY_FILES not in col:
        return {}
    return {k: str(v) for k, v in col[KEY_FILES].items()}


MODES_SUFFIX = " modes"
KEY_MODES = "sheetgen_modes"       # object property: the modes' one-line summary


def build_modes(col, load, plain, thickness):
    """``<load> modes`` in the run collection: the FEM mesh (core.modes.ModesMesh) with a Basis and one shape key
    per mode (slider -1..1, value 0), Solidify to the thickness; an earlier one is replaced. The bent part is
    hidden in the viewport (both would show the same sheet at value 0). Returns the object."""
    import numpy as np
    name = load + MODES_SUFFIX
    old = col.objects.get(name)
    if old is not None:
        me_old = old.data
        bpy.data.objects.remove(old, do_unlink=True)
        if me_old is not None and me_old.users == 0:
            bpy.data.meshes.remove(me_old)
    me = bpy.data.meshes.new(name)
    me.from_pydata(plain.vertices, [], [list(t) for t in plain.triangles])
    me.update()
    part = col.objects.get("%s part" % load)
    run = part.get("sheetgen_run", 0) if part is not None else 0
    obj = _object(name, me, col, modes_material(), run, load)
    _solidify(obj, thickness)
    obj.shape_key_add(name="Basis", from_mix=False)
    for k in plain.keys:
        key = obj.shape_key_add(name=k.name, from_mix=False)
        key.data.foreach_set("co", np.asarray(k.positions, dtype=np.float32).reshape(-1))
        key.slider_min, key.slider_max, key.value = -1.0, 1.0, 0.0
    obj[KEY_MODES] = plain.summary
    if part is not None and part.name in bpy.context.view_layer.objects:
        part.hide_set(True)
    return obj
