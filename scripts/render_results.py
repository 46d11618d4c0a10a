"""Presentation render of an existing run folder (no solve): the command of docs/blender.md.

    blender -b --factory-startup --python-exit-code 1 --python scripts/render_results.py -- \
        OUT_DIR [--samples N] [--resolution W H] [--build-dir DIR]

OUT_DIR is a finished run (``sheetgen solve --out``, scripts/solve_all.py or
scripts/blender_batch.py): it holds result.json, whose ``problem`` is the path
of the problem file relative to OUT_DIR. The scene is rebuilt with the add-on's
own code — the problem import (core.problem.problem_to_scene + scene_io.build_scene,
file meshes through the native reader, as *Import* does) and the run collection
(results.build_run) — and rendered by render.render_run, as **Render
Presentation** does in the UI. Writes:

  OUT_DIR/render.png                  the scene and every part (Cycles CPU)
  OUT_DIR/render_<load>_flat.png      the flat pattern of every load with a valid part

A load without a valid part has its nearest candidate (result.json
``parts[i].tabs``) shown in translucent magenta. Exit 0 on success, 1 on bad input
or an error (one sentence on stderr, no traceback).

The add-on is used from this source tree (blender_addon/) and the native
module from build/python/ (``--build-dir``).
"""
import argparse
import os
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# Blender runs this file by path and no PYTHONPATH reaches its Python: the one
# bootstrap line that makes the tools package importable (tools/sheetgen_tools/__init__.py).
sys.path.insert(0, os.path.join(ROOT, "tools"))
from sheetgen_tools import addon_loader  # noqa: E402
PREFIX = "render_results: "
LARGE_RES = (960, 600)       # px: scenes with many loads (the avionics bay) have small parts in a large frame
LARGE_SAMPLES = 16           # Cycles samples at LARGE_RES: keeps the render near 10 s on 2 cores
SMALL_SCENE_LOADS = 2


class InputError(Exception):
    """Bad input: the message is one sentence for the user."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise InputError(message)


def parse_args(argv):
    ap = _Parser(prog="blender -b --factory-startup --python scripts/render_results.py --")
    ap.add_argument("out_dir", help="run folder with result.json")
    ap.add_argument("--samples", type=int, default=None,
                    help="Cycles samples (default 32, %d with more than %d loads)" % (LARGE_SAMPLES, SMALL_SCENE_LOADS))
    ap.add_argument("--resolution", type=int, nargs=2, metavar=("W", "H"), default=None,
                    help="image size in pixels (default 640 x 400, %d x %d with more than %d loads)"
                         % (LARGE_RES + (SMALL_SCENE_LOADS,)))
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"), help="where python/_sheetgen_native* is")
    args = ap.parse_args(argv)
    if args.samples is not None and args.samples < 1:
        raise InputError("--samples must be at least 1 (got %d)" % args.samples)
    if args.resolution is not None and min(args.resolution) < 16:
        raise InputError("--resolution must be at least 16 x 16 pixels (got %d x %d)" % tuple(args.resolution))
    return args


def enable_addon(build_dir):
    try:
        addon_loader.enable_addon(build_dir)
    except RuntimeError as e:
        raise InputError(str(e)) from None


def read_run(out_dir):
    """(result document, absolute problem path) of a run folder; InputError names what is wrong."""
    from sheetgen_blender.core import result as core_result
    import json
    if not os.path.isdir(out_dir):
        raise InputError("%s is not a folder" % out_dir)
    res_path = os.path.join(out_dir, "result.json")
    if not os.path.isfile(res_path):
        raise InputError("%s has no result.json (not a finished run folder)" % out_dir)
    try:
        with open(res_path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        raise InputError("cannot read %s: %s" % (res_path, e)) from None
    try:
        core_result.check_document(doc)
    except core_result.ResultError as e:
        raise InputError("%s: %s" % (res_path, e)) from None
    prob = doc.get("problem")
    if not isinstance(prob, str) or not prob:
        raise InputError("%s: 'problem' (the problem file, relative to the folder) is missing" % res_path)
    prob_path = os.path.normpath(os.path.join(out_dir, prob))
    if not os.path.isfile(prob_path):
        raise InputError("%s: problem file %s does not exist" % (res_path, prob_path))
    return doc, prob_path


def build_scene(context, doc, prob_path):
    """The environment, loads and run collection in the current (empty) scene; returns (col, thickness, warnings)."""
    from sheetgen_blender import results, scene_io
    from sheetgen_blender.core import jsonio
    from sheetgen_blender.core import result as core_result
    from sheetgen_blender.core.problem import ProblemError, problem_to_scene
    from sheetgen_blender.operators import _native_mesh_reader   # the reader Import uses (native face numbering)
    try:
        problem = jsonio.read(prob_path)
        data, warnings = problem_to_scene(problem, _native_mesh_reader(prob_path))
    except (ProblemError, OSError, ValueError) as e:   # ProblemError is a ValueError; some name the file already
        raise InputError(str(e) if prob_path in str(e) else "%s: %s" % (prob_path, e)) from None
    try:
        scene_io.build_scene(context.scene, data)
    except ValueError as e:
        raise InputError("%s: %s" % (prob_path, e)) from None
    thickness = data.settings.material.thickness
    try:
        col = results.build_run(context, doc, {}, thickness)
        candidates = add_candidates(col, doc, thickness)
    except core_result.ResultError as e:
        raise InputError("result.json: %s" % e) from None
    # matrix_world of the new objects (the load boxes' scale, rotation, place) is only set by a depsgraph
    # update; render_run copies matrix_world.
    context.view_layer.update()
    return col, thickness, warnings, candidates


def add_candidates(col, doc, thickness):
    """``<load> candidate`` objects (marked for render.render_run) for loads without a valid part; their names."""
    import bpy
    from sheetgen_blender import results
    from sheetgen_blender.core import result as core_result
    names = []
    for part in doc["parts"]:
        if part.get("status") == "ok" or not part.get("tabs"):
            continue
        name = "%s candidate" % part.get("load", "?")
        me = results.mesh_from_plain(name, core_result.bent_mesh(part))
        obj = bpy.data.objects.new(name, me)
        col.objects.link(obj)
        obj.sheetgen.exclude = True
        obj[render_candidate_key()] = True
        mod = obj.modifiers.new("Thickness", 'SOLIDIFY')
        mod.thickness = thickness
        mod.offset = 0.0
        names.append(part.get("load", "?"))
    return names


def render_candidate_key():
    from sheetgen_blender import render
    return render.CANDIDATE_KEY


def main(argv):
    args = parse_args(argv)
    t0 = time.monotonic()
    import bpy
    bpy.ops.wm.read_homefile(use_empty=True)   # factory start-up's cube, camera and light are no environment
    enable_addon(args.build_dir)
    from sheetgen_blender import native, render
    if native.get() is None:
        raise InputError(native.error())
    out = os.path.abspath(args.out_dir)
    doc, prob_path = read_run(out)
    context = bpy.context
    col, _thickness, warnings, candidates = build_scene(context, doc, prob_path)
    for w in warnings:
        print("warning: " + w, flush=True)
    n_ok = sum(1 for p in doc["parts"] if p.get("status") == "ok")
    print("render_results: %s: %d/%d loads with a part%s" % (
        out, n_ok, len(doc["parts"]),
        "; nearest candidate in translucent magenta: " + ", ".join(candidates) if candidates else ""), flush=True)
    skipped = [p.get("load", "?") for p in doc["parts"] if p.get("status") != "ok" and not p.get("tabs")]
    if skipped:
        print("render_results: no candidate to show for %s (result.json has no tabs)" % ", ".join(skipped), flush=True)
    if n_ok == 0 and not candidates:
        raise InputError("%s: no load has a part or a candidate to render" % out)
    large = len(doc["parts"]) > SMALL_SCENE_LOADS
    kw = {"samples": args.samples or (LARGE_SAMPLES if large else 32)}
    if args.resolution is not None:
        kw["resolution"] = tuple(args.resolution)
    elif large:
        kw["resolution"] = LARGE_RES
    t1 = time.monotonic()
    try:
        written = render.render_run(context, col, os.path.join(out, "render.png"), **kw)
    except render.RenderError as e:
        raise InputError(str(e)) from None
    print("render_results: wrote %s (render %.1f s, total %.1f s)"
          % (", ".join(written), time.monotonic() - t1, time.monotonic() - t0), flush=True)
    return 0


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    try:
        code = main(argv)
    except InputError as e:
        print(PREFIX + str(e), file=sys.stderr)
        code = 1
    except OSError as e:
        print(PREFIX + "%s" % e, file=sys.stderr)
        code = 1
    except Exception as e:  # noqa: BLE001 - an unexpected error: still one line, non-zero exit
        print(PREFIX + "%s: %s" % (type(e).__name__, e), file=sys.stderr)
        code = 1
    sys.stdout.flush()
    sys.stderr.flush()
    sys.exit(code)
