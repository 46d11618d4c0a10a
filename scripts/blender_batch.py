"""Headless Generate of a tagged .blend: the command of docs/blender.md.

    blender -b SCENE.blend --python-exit-code 1 --python scripts/blender_batch.py -- \
        --out DIR [--render] [--iterations N] [--chains M] [--seed S] [--beam B] [--samples K]

Generates every load of the scene (the scene's Search settings, overridden by
the options), builds the run collection, and writes into DIR:
  problem.json, result.json, <load>/{part.obj, flat.dxf, flat.svg, bends.csv, history.csv}
  (the native write_outputs), scene.blend (the scene with the run), and with
  --render render.png (presentation) and render_<load>_flat.png (flat pattern).
Prints progress lines. Exit 0: every load has a valid part; 2: some load has
none; 1: bad input or an error (one line on stderr).

The add-on is used from this source tree (blender_addon/) and the native
module from build/python/ unless an installed add-on is already enabled.
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


def parse_args(argv):
    ap = argparse.ArgumentParser(prog="blender -b SCENE.blend --python scripts/blender_batch.py --")
    ap.add_argument("--out", required=True, help="output folder")
    ap.add_argument("--render", action="store_true", help="also render render.png and the flat patterns")
    ap.add_argument("--iterations", type=int)
    ap.add_argument("--chains", type=int)
    ap.add_argument("--seed", type=int)
    ap.add_argument("--beam", type=int)
    ap.add_argument("--samples", type=int, default=32, help="Cycles samples of the render (default 32)")
    ap.add_argument("--build-dir", default=os.path.join(ROOT, "build"), help="where python/_sheetgen_native* is")
    return ap.parse_args(argv)


def main(argv):
    args = parse_args(argv)
    t0 = time.monotonic()
    import bpy
    addon_loader.enable_addon(args.build_dir)
    from sheetgen_blender import generate, native, render
    from sheetgen_blender.core import result as core_result
    from sheetgen_blender.core.problem import ProblemError

    if native.get() is None:
        print("sheetgen batch: " + native.error(), file=sys.stderr)
        return 1
    context = bpy.context
    s = context.scene.sheetgen
    for key, value in (("iterations", args.iterations), ("chains", args.chains), ("seed", args.seed),
                       ("beam_width", args.beam)):
        if value is not None:
            setattr(s, key, value)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    print("sheetgen batch: %s, scene '%s', chains %d, iterations %d, beam %d, seed %d -> %s"
          % (bpy.data.filepath or "(unsaved)", context.scene.name, s.chains, s.iterations, s.beam_width, s.seed, out),
          flush=True)
    try:
        col, doc, run = generate.run_sync(context, log=lambda line: print(line, flush=True))
    except ProblemError as e:
        for w in e.warnings:
            print("warning: " + w, file=sys.stderr)
        print("sheetgen batch: " + "; ".join(e.errors), file=sys.stderr)
        return 1
    except (generate.GenerateError, core_result.ResultError) as e:
        print("sheetgen batch: %s" % e, file=sys.stderr)
        return 1
    for w in run.warnings:
        print("warning: " + w, flush=True)
    if col is None:
        print("sheetgen batch: cancelled", file=sys.stderr)
        return 130
    t_gen = time.monotonic() - t0
    for part in doc["parts"]:
        print(core_result.status_line(part), flush=True)
    problem_path = os.path.join(out, "problem.json")
    with open(problem_path, "w", encoding="utf-8") as f:
        f.write(run.problem_text)
    run.sg.write_outputs(out, run.problem, run.result, problem_path)
    print("wrote %s and the per-load exports" % os.path.join(out, "result.json"), flush=True)
    blend = os.path.join(out, "scene.blend")
    bpy.ops.wm.save_as_mainfile(filepath=blend, copy=True)
    print("wrote %s" % blend, flush=True)
    if args.render:
        if any(p.get("status") == "ok" for p in doc["parts"]):
            t1 = time.monotonic()
            written = render.render_run(context, col, os.path.join(out, "render.png"), samples=args.samples)
            print("rendered %s (%.1f s)" % (", ".join(written), time.monotonic() - t1), flush=True)
        else:
            print("no valid part: nothing to render", flush=True)
    ok = all(p.get("status") == "ok" for p in doc["parts"])
    print("sheetgen batch: %s in %.1f s (generate %.1f s)"
          % ("every load has a part" if ok else "some load has no valid part", time.monotonic() - t0, t_gen),
          flush=True)
    return 0 if ok else 2


if __name__ == "__main__":
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    try:
        code = main(argv)
    except SystemExit:
        raise
    except Exception as e:  # noqa: BLE001 - one line, non-zero exit
        import traceback
        traceback.print_exc()
        print("sheetgen batch: %s" % e, file=sys.stderr)
        code = 1
    sys.stdout.flush()
    sys.exit(code)
