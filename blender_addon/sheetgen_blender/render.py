"""Presentation render of a run (bpy): the environment and the part(s), plus the flat pattern(s).

The render happens in a temporary scene holding copies of the objects (their
own mesh copies, so materials can be assigned without touching the user's
data) and is removed afterwards: the user's scene, materials and render
settings stay as they were.

- camera: perspective, a slightly elevated 3/4 view of the bounding box of the
  parts and load boxes, the distance solved so all 8 box corners are inside the
  frame; of 8 candidate directions the one seeing most of the part (ray casts
  against the environment) wins; environment objects that still hide part of
  it from there are drawn translucent;
- materials: environment neutral grey with the rivet areas in their tag colour
  (the ``sheetgen_rivet_color`` attribute), part metallic, rivet markers red,
  load boxes translucent blue (2 mm inset, camera rays only), candidates of
  loads without a valid part (``CANDIDATE_KEY``) translucent magenta;
- sun + a grey world, Cycles on the CPU without denoising (docs/platform.md: this build
  has no OpenImageDenoise), 640 x 400, few samples;
- the flat pattern: matplotlib from the stored result.json (core.flatplot).
"""
import math
import os

import bpy
from mathutils import Matrix, Vector

from . import results, scene_io, tagging
from .core import flatplot

RES = (640, 400)
# Object property marking a run object as the nearest candidate of a load without a valid part
# (scripts/render_results.py adds them): rendered translucent magenta (the rivet areas are red).
CANDIDATE_KEY = "sheetgen_candidate"
# An environment object hiding more than this fraction of the part corners from the chosen camera
# (walls of an enclosed bay) is drawn translucent, with this alpha.
HIDE_FRACTION = 0.02
FADED_ALPHA = 0.22
# m: the load boxes are drawn this much smaller on every side: the part's seat lies on the box's bottom
# face, and coplanar translucent faces render as noise.
BOX_INSET = 2e-3


class RenderError(Exception):
    pass


def _mat(name, colour, metallic=0.0, roughness=0.5, alpha=1.0, attribute=None):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    nt = mat.node_tree
    bsdf = nt.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (colour[0], colour[1], colour[2], 1.0)
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Alpha"].default_value = alpha
    if attribute:
        # The tag colours (untagged faces light grey), darkened to the environment's grey.
        node = nt.nodes.new("ShaderNodeAttribute")
        node.attribute_name = attribute
        mix = nt.nodes.new("ShaderNodeMixRGB")
        mix.blend_type = 'MULTIPLY'
        mix.inputs["Fac"].default_value = 1.0
        mix.inputs["Color2"].default_value = (0.7, 0.7, 0.7, 1.0)
        nt.links.new(node.outputs["Color"], mix.inputs["Color1"])
        nt.links.new(mix.outputs["Color"], bsdf.inputs["Base Color"])
    if alpha < 1.0:
        mat.blend_method = 'BLEND'
    return mat


def _copy(obj, scene, material, made):
    o = obj.copy()
    if obj.data is not None:
        o.data = obj.data.copy()
        made["meshes"].append(o.data)
        o.data.materials.clear()
        o.data.materials.append(material)
    o.parent = None
    o.matrix_world = obj.matrix_world.copy()
    scene.collection.objects.link(o)
    made["objects"].append(o)
    return o


def _inset(obj, d):
    """Shrink obj about its local bounding-box centre by ``d`` (m, world) on every side."""
    corners = [Vector(c) for c in obj.bound_box]
    c = sum(corners, Vector()) / 8.0
    f = [max(1.0 - 2.0 * d / size, 0.5) if size > 0 else 1.0 for size in obj.dimensions]
    obj.matrix_world = (obj.matrix_world @ Matrix.Translation(c) @ Matrix.Diagonal((f[0], f[1], f[2], 1.0))
                        @ Matrix.Translation(-c))


def _bbox(objs):
    lo = Vector((float("inf"),) * 3)
    hi = -lo
    for o in objs:
        for c in o.bound_box:
            w = o.matrix_world @ Vector(c)
            lo = Vector(map(min, lo, w))
            hi = Vector(map(max, hi, w))
    return lo, hi


def frame_camera(cam_obj, lo, hi, direction, aspect, margin=1.08):
    """Place cam_obj looking at the box centre from ``direction`` so the 8 corners fit (perspective)."""
    cam = cam_obj.data
    c = (lo + hi) * 0.5
    d = Vector(direction).normalized()
    # Camera axes: forward = -d, right = forward x up_world, up = right x forward.
    fwd = -d
    right = fwd.cross(Vector((0, 0, 1)))
    if right.length < 1e-6:
        right = Vector((1, 0, 0))
    right.normalize()
    up = right.cross(fwd).normalized()
    tan_h = (cam.sensor_width / 2) / cam.lens        # sensor_fit AUTO: the width spans the wider side
    tan_v = tan_h * (aspect[1] / aspect[0]) if aspect[0] >= aspect[1] else tan_h
    if aspect[1] > aspect[0]:
        tan_h = tan_h * aspect[0] / aspect[1]
    dist = 0.0
    for x in (lo.x, hi.x):
        for y in (lo.y, hi.y):
            for z in (lo.z, hi.z):
                p = Vector((x, y, z)) - c
                along = p.dot(d)
                dist = max(dist, along + abs(p.dot(right)) * margin / tan_h, along + abs(p.dot(up)) * margin / tan_v)
    cam_obj.location = c + d * dist
    cam_obj.rotation_euler = fwd.to_track_quat('-Z', 'Y').to_euler()
    cam.clip_start = max(dist * 0.01, 1e-3)
    cam.clip_end = dist * 20
    return dist


def _occluders(objs):
    """One BVH tree of the environment meshes in world space (what may hide the part)."""
    from mathutils.bvhtree import BVHTree
    verts, polys = [], []
    for o in objs:
        m = o.matrix_world
        base = len(verts)
        verts += [m @ v.co for v in o.data.vertices]
        polys += [[base + i for i in p.vertices] for p in o.data.polygons]
    return BVHTree.FromPolygons(verts, polys) if polys else None


def _visible_fraction(tree, eye, targets):
    if tree is None:
        return 1.0
    seen = 0
    for t in targets:
        v = t - eye
        hit = tree.ray_cast(eye, v.normalized(), v.length * 0.999)
        if hit[0] is None:
            seen += 1
    return seen / max(len(targets), 1)


CANDIDATES = [(math.cos(a), math.sin(a), 0.55) for a in [math.radians(-60 + 90 * k) for k in range(4)]] + \
             [(math.cos(a), math.sin(a), 0.55) for a in [math.radians(-30 + 90 * k) for k in range(4)]]


def render_run(context, col, path, samples=32, resolution=RES, flat=True):
    """Render ``col`` (a run collection) to ``path``; with ``flat`` also <path stem>_<load>_flat.png.

    Returns the written paths.
    """
    doc = results.run_document(col)
    if doc is None:
        raise RenderError("no result to render: run Generate first")
    src = context.scene
    parts = [o for o in col.objects if o.name.endswith(" part")]
    candidates = [o for o in col.objects if o.get(CANDIDATE_KEY)]
    if not parts and not candidates:
        raise RenderError("run '%s' has no valid part to render" % col.name)
    # Flange rivets and self-rivets alike: the red markers of where the part is riveted.
    rivet_objs = [o for o in col.objects if o.name.endswith(" rivets") or o.name.endswith(" self-rivets")]
    env = scene_io.environment_objects(src, context.view_layer)
    load_objs = scene_io.load_objects(src, context.view_layer)
    made = {"objects": [], "meshes": [], "materials": []}
    scene = bpy.data.scenes.new("~sheetgen render")
    try:
        grey = _mat("~sg grey", (0.56, 0.56, 0.56), roughness=0.8)
        tagged = _mat("~sg tagged", (0.56, 0.56, 0.56), roughness=0.8, attribute=tagging.COLOR_ATTR)
        # Gold anodised: half metallic (a full metal is noisy at few samples), and distinct from the grey scene and the red/blue rivet areas.
        metal = _mat("~sg metal", (0.95, 0.64, 0.18), metallic=0.6, roughness=0.35)
        red = _mat("~sg rivet", (0.9, 0.1, 0.05), roughness=0.4)
        box = _mat("~sg load", (0.25, 0.45, 0.85), roughness=0.6, alpha=0.3)
        cand = _mat("~sg candidate", (0.75, 0.1, 0.85), roughness=0.5, alpha=0.45)  # magenta: stands out on red rivet areas
        made["materials"] += [grey, tagged, metal, red, box, cand]
        env_copies = []
        for o in env:
            has_tags = o.data.attributes.get(tagging.COLOR_ATTR) is not None
            env_copies.append(_copy(o, scene, tagged if has_tags else grey, made))
        part_copies = [_copy(o, scene, metal, made) for o in parts]
        part_copies += [_copy(o, scene, cand, made) for o in candidates]
        for o in rivet_objs:
            _copy(o, scene, red, made)
        load_copies = [_copy(o, scene, box, made) for o in load_objs]
        for o in load_copies:
            _inset(o, BOX_INSET)
        for o in load_copies + part_copies[len(parts):]:
            o.display_type = 'SOLID'
            # Translucent boxes cast no shadow and are seen by camera rays only: with few samples their
            # stochastic transparency only adds noise on the part.
            o.visible_shadow = False
            o.visible_glossy = False
            o.visible_diffuse = False
        # light and world
        sun_data = bpy.data.lights.new("~sg sun", 'SUN')
        sun_data.energy = 4.0
        sun_data.angle = math.radians(8)
        sun = bpy.data.objects.new("~sg sun", sun_data)
        sun.rotation_euler = (math.radians(40), math.radians(10), math.radians(30))
        scene.collection.objects.link(sun)
        made["objects"].append(sun)
        world = bpy.data.worlds.new("~sg world")
        world.use_nodes = True
        bg = world.node_tree.nodes["Background"]
        bg.inputs["Color"].default_value = (0.35, 0.38, 0.42, 1.0)
        bg.inputs["Strength"].default_value = 1.0
        scene.world = world
        # camera
        cam_data = bpy.data.cameras.new("~sg camera")
        cam_data.lens = 50
        cam = bpy.data.objects.new("~sg camera", cam_data)
        scene.collection.objects.link(cam)
        made["objects"].append(cam)
        scene.camera = cam
        lo, hi = _bbox(part_copies + load_copies)
        tree = _occluders(env)
        targets = [o.matrix_world @ v.co for o in part_copies for v in o.data.vertices]
        best = None
        for d in CANDIDATES:
            frame_camera(cam, lo, hi, d, resolution)
            frac = _visible_fraction(tree, cam.location.copy(), targets)
            if best is None or frac > best[0] + 1e-9:
                best = (frac, d)
        frame_camera(cam, lo, hi, best[1], resolution)
        faded = {}
        for o in env_copies:
            if _visible_fraction(_occluders([o]), cam.location.copy(), targets) < 1.0 - HIDE_FRACTION:
                has_tags = o.data.attributes.get(tagging.COLOR_ATTR) is not None
                if has_tags not in faded:
                    faded[has_tags] = _mat("~sg faded", (0.56, 0.56, 0.56), roughness=0.8, alpha=FADED_ALPHA,
                                           attribute=tagging.COLOR_ATTR if has_tags else None)
                    made["materials"].append(faded[has_tags])
                o.data.materials[0] = faded[has_tags]
        r = scene.render
        r.engine = 'CYCLES'
        scene.cycles.device = 'CPU'
        scene.cycles.samples = samples
        scene.cycles.use_denoising = False
        scene.cycles.use_adaptive_sampling = True
        # No denoiser in this build: blur sharp highlights of the metal and clamp indirect fireflies instead.
        scene.cycles.blur_glossy = 1.0
        scene.cycles.sample_clamp_indirect = 5.0
        r.resolution_x, r.resolution_y = resolution
        r.resolution_percentage = 100
        r.image_settings.file_format = 'PNG'
        r.film_transparent = False
        scene.view_settings.view_transform = 'Filmic'
        scene.view_settings.look = 'Medium High Contrast'
        r.filepath = path
        os.makedirs(os.path.dirname(os.path.abspath(path)) or ".", exist_ok=True)
        bpy.ops.render.render(write_still=True, scene=scene.name)
        written = [path]
    finally:
        for o in made["objects"]:
            data = o.data
            bpy.data.objects.remove(o, do_unlink=True)
            if isinstance(data, bpy.types.Light):
                bpy.data.lights.remove(data)
            elif isinstance(data, bpy.types.Camera):
                bpy.data.cameras.remove(data)
        for me in made["meshes"]:
            if me.users == 0:
                bpy.data.meshes.remove(me)
        for m in made["materials"]:
            bpy.data.materials.remove(m)
        w = scene.world
        bpy.data.scenes.remove(scene)
        if w is not None and w.users == 0:
            bpy.data.worlds.remove(w)
    if flat:
        stem = os.path.splitext(path)[0]
        if not flatplot.available():
            raise RenderError("the flat pattern image needs matplotlib (python3-matplotlib)")
        for part in doc["parts"]:
            if part.get("status") == "ok":
                fp = "%s_%s_flat.png" % (stem, part["load"])
                flatplot.draw(part, fp)
                written.append(fp)
    return written
