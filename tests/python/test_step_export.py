#!/usr/bin/python3
"""part.step and flat.step (docs/cad.md) read back by two readers that share
no code with the writer's checks: gmsh (its OpenCASCADE import, python3-gmsh)
and FreeCAD (`freecadcmd`, tests/python/step_freecad_probe.py). Sample parts
solved at the fast tier's reduced settings: corner, slanted, shelf, and the
self-rivet problem of bench/ablation_self_rivet.py (wall_standoff with a
100 mm wall strip, 0.35 kg, 4 mm limit), whose part has two self-rivets.

For every part, both readers find part.step to be one solid (FreeCAD: valid
and closed); its volume is the flat area (minus the holes) times t within
0.5 % (for a self-riveted part less the overlap of each self-rivet's two
gussets, which sheetgen bends into one plane and the solid holds once,
computed here from result.json's tab corners with shapely); its bounding box
is part.obj's within t on every side; its cylindrical faces of radius R or
R + t number 2 per bend and the others one per hole (a self-rivet's two holes
are one through the joined plate; gmsh counts all cylinders). flat.step is one
solid whose outline vertices at z = 0 are flat.dxf's CUT polyline (ezdxf)
within 0.01 mm both ways (the others lie on the DXF's hole circles) and whose
volume is the flat area minus the holes times t. The native module's
write_step writes the same part.step for a run made in Python.

With --all-samples it checks instead every part of every sample scene at the
scene's own settings (the parts `sheetgen solve` gives a user), avionics bay
included; that run is not a test of the suite (about 15 min) but the record
of docs/cad.md "Measured".

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_step_export.py --sheetgen build/native/cli/sheetgen [--keep DIR] [--all-samples]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

import ezdxf
import gmsh
from shapely.geometry import Polygon

from sheetgen_tools import paths, runner

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(paths.ROOT, "bench"))
from ablation_self_rivet import strip_problem  # noqa: E402  (the self-rivet problem of docs/ablation_self_rivet.md)

REDUCED = {"chains": 6, "iterations": 300, "beam": 4, "seed": 1}
VOLUME_TOL = 0.005      # relative
OUTLINE_TOL_MM = 0.01


def problems(tmp, all_samples):
    """(name, problem path) of the parts this test checks."""
    if all_samples:
        return [(s, paths.scene_problem(s)) for s in paths.sample_scene_names()]
    out = [(s, paths.scene_problem(s)) for s in ("corner", "slanted", "shelf")]
    os.makedirs(os.path.join(tmp, "self_rivet_problem"))
    strip, _ = strip_problem(os.path.join(paths.SAMPLE_SCENES, "wall_standoff"), 0.50, 0.60, 0.35, 4e-3,
                             os.path.join(tmp, "self_rivet_problem"))
    return out + [("self_rivet_strip", strip)]


def gmsh_read(path):
    """(volume entities, volume mm^3 of each, bbox mm, surface types, points [(x, y, z)]) of a STEP file."""
    gmsh.clear()
    gmsh.model.occ.importShapes(path)
    gmsh.model.occ.synchronize()
    vols = gmsh.model.getEntities(3)
    masses = [gmsh.model.occ.getMass(3, v[1]) for v in vols]
    types = [gmsh.model.getType(2, s[1]) for s in gmsh.model.getEntities(2)]
    points = [tuple(gmsh.model.getValue(0, p[1], [])) for p in gmsh.model.getEntities(0)]
    return vols, masses, gmsh.model.getBoundingBox(-1, -1), types, points


def freecad_probe(files):
    """{path: probe} from one freecadcmd run over all files."""
    env = dict(os.environ, STEP_FILES=json.dumps(files))
    proc = subprocess.run(["freecadcmd", os.path.join(HERE, "step_freecad_probe.py")], env=env,
                          capture_output=True, text=True, timeout=600)
    probes = [json.loads(line[6:]) for line in proc.stdout.splitlines() if line.startswith("PROBE ")]
    if len(probes) != len(files):
        raise RuntimeError(f"freecadcmd read {len(probes)} of {len(files)} files:\n{proc.stdout[-2000:]}{proc.stderr[-2000:]}")
    return {p["path"]: p for p in probes}


def obj_bbox_mm(path):
    pts = [[float(c) * 1e3 for c in line.split()[1:4]] for line in open(path) if line.startswith("v ")]
    return [min(p[k] for p in pts) for k in range(3)] + [max(p[k] for p in pts) for k in range(3)]


def plane_polygon(corners, origin, e1, e2):
    return Polygon([(sum((c[k] - origin[k]) * e1[k] for k in range(3)), sum((c[k] - origin[k]) * e2[k] for k in range(3)))
                    for c in corners])


def self_rivet_overlap_mm2(part):
    """Area (mm^2) where the two gussets of each self-rivet overlap in their common plane, less one hole each
    (both sheets' holes coincide there)."""
    tabs = {t["index"]: t for t in part["tabs"]}
    holes = [h for h in part["flat_pattern"]["holes"] if h["kind"] == "self"]
    total = 0.0
    for s in part.get("self_rivets", []):
        a, b = (tabs[i] for i in s["tabs"])
        n = a["normal"]
        o = a["corners"][0]
        helper = [1, 0, 0] if abs(n[0]) < 0.9 else [0, 1, 0]
        e1 = [helper[1] * n[2] - helper[2] * n[1], helper[2] * n[0] - helper[0] * n[2], helper[0] * n[1] - helper[1] * n[0]]
        norm = math.sqrt(sum(c * c for c in e1))
        e1 = [c / norm for c in e1]
        e2 = [n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]]
        total += plane_polygon(a["corners"], o, e1, e2).intersection(plane_polygon(b["corners"], o, e1, e2)).area * 1e6
    hole_area = sum(math.pi * (h["diameter"] * 1e3 / 2) ** 2 for h in holes) / 2  # one per self-rivet
    return total - hole_area


def dxf_outline_and_holes(path):
    msp = ezdxf.readfile(path).modelspace()
    (cut,) = [e for e in msp if e.dxftype() == "POLYLINE" and e.dxf.layer == "CUT"]
    outline = [(v.dxf.location.x, v.dxf.location.y) for v in cut.vertices]
    holes = [(e.dxf.center.x, e.dxf.center.y, e.dxf.radius) for e in msp if e.dxftype() == "CIRCLE"]
    return outline, holes


def outline_deviation_mm(step_points, t, dxf_outline, dxf_holes):
    """Largest distance from a DXF outline vertex to the nearest STEP vertex at z = 0 and from a STEP vertex
    at z = 0 that is on no hole circle to the nearest DXF vertex; and how many STEP vertices were compared."""
    bottom = [(x, y) for x, y, z in step_points if abs(z) < 1e-6]
    on_outline = [p for p in bottom if not any(abs(math.hypot(p[0] - cx, p[1] - cy) - r) < OUTLINE_TOL_MM for cx, cy, r in dxf_holes)]
    d1 = max(min(math.hypot(a - x, b - y) for x, y in on_outline) for a, b in dxf_outline)
    d2 = max(min(math.hypot(a - x, b - y) for a, b in dxf_outline) for x, y in on_outline)
    return max(d1, d2), len(on_outline)


def check_part(out_dir, prob, part, fc, failures):
    """Checks one load's STEP files; returns the line of numbers to print."""
    name = part["load"]
    folder = os.path.join(out_dir, name)
    t = prob.get("material", {}).get("thickness", 1.6e-3) * 1e3
    R = prob.get("manufacturing", {}).get("bend_radius", 4 * t * 1e-3) * 1e3
    holes = part["flat_pattern"]["holes"]
    net_mm2 = part["flat_pattern"]["area_m2"] * 1e6 - sum(math.pi * (h["diameter"] * 1e3 / 2) ** 2 for h in holes)
    overlap = self_rivet_overlap_mm2(part) if part.get("self_rivets") else 0.0
    expected = (net_mm2 - overlap) * t
    bends = part["bends"]

    def fail(what):
        failures.append(f"{name}: {what}")

    part_step, flat_step = os.path.join(folder, "part.step"), os.path.join(folder, "flat.step")
    if not os.path.exists(part_step):
        error = os.path.join(folder, "part_step_error.txt")
        why = open(error).read().strip() if os.path.exists(error) else "and no part_step_error.txt"
        fail(f"no part.step: {why}")
        return f"{name}: no part.step"
    vols, masses, box, types, _ = gmsh_read(part_step)
    if len(vols) != 1:
        fail(f"gmsh reads {len(vols)} volumes in part.step")
    p = fc[part_step]
    if not (p["solids"] == 1 and p["shells"] == 1 and p["valid"] and p["closed"]):
        fail(f"FreeCAD: part.step is {p['solids']} solids, {p['shells']} shells, valid {p['valid']}, closed {p['closed']}")
    err_gmsh, err_fc = sum(masses) / expected - 1, p["volume"] / expected - 1
    for who, err in (("gmsh", err_gmsh), ("FreeCAD", err_fc)):
        if abs(err) > VOLUME_TOL:
            fail(f"{who}: volume {err * 100:+.3f} % from (flat area - holes - overlap) x t")
    obj = obj_bbox_mm(os.path.join(folder, "part.obj"))
    box_err = max(max(abs(a - b) for a, b in zip(bx, obj)) for bx in (box, p["bbox"]))
    if box_err > t:
        fail(f"bounding box {box_err:.3f} mm from part.obj's (limit t = {t} mm)")
    bend_cyl = sum(1 for r in p["cylinders"] if abs(r - R) < 1e-3 or abs(r - R - t) < 1e-3)
    hole_cyl = len(p["cylinders"]) - bend_cyl
    # A self-rivet's two holes are one hole through the joined plate.
    unique_holes = len(holes) - len(part.get("self_rivets", []))
    gmsh_cyl = types.count("Cylinder")
    if bend_cyl != 2 * bends or hole_cyl != unique_holes or gmsh_cyl != 2 * bends + unique_holes:
        fail(f"cylinders: FreeCAD {bend_cyl} of radius R or R + t (expected 2 x {bends}) and {hole_cyl} others "
             f"(expected {unique_holes} hole walls), gmsh {gmsh_cyl} in all")
    fvols, fmasses, _, _, fpoints = gmsh_read(flat_step)
    f = fc[flat_step]
    outline, dxf_holes = dxf_outline_and_holes(os.path.join(folder, "flat.dxf"))
    dev, compared = outline_deviation_mm(fpoints, t, outline, dxf_holes)
    flat_err = f["volume"] / (net_mm2 * t) - 1
    if len(fvols) != 1 or f["solids"] != 1 or not f["valid"] or abs(flat_err) > 1e-6 or dev > OUTLINE_TOL_MM \
            or compared != len(outline):
        fail(f"flat.step: {len(fvols)} gmsh volumes, FreeCAD {f['solids']} solids valid {f['valid']}, volume "
             f"{flat_err:+.2e}, outline {dev:.2e} mm over {compared} vertices (DXF {len(outline)})")
    raw = p["volume"] / (net_mm2 * t) - 1
    return (f"{name}: bends {bends}, holes {len(holes)}, self-rivets {len(part.get('self_rivets', []))}; part.step "
            f"volume {p['volume']:.1f} mm³ vs (flat - holes{' - overlap' if overlap else ''}) x t {expected:.1f}: "
            f"gmsh {err_gmsh * 100:+.3f} %, FreeCAD {err_fc * 100:+.3f} %"
            + (f" (against flat x t without the overlap {raw * 100:+.3f} %, overlap {overlap:.1f} mm²)" if overlap else "")
            + f"; bbox vs part.obj max {box_err:.3f} mm; cylinders R/R+t {bend_cyl}, holes {hole_cyl} (gmsh all {gmsh_cyl}); "
            f"flat.step volume {flat_err:+.1e}, outline vs flat.dxf max {dev:.1e} mm over {compared} vertices")


def check_binding(sheetgen_dir, problem_path, cli_out, failures):
    """The module's write_step on a run made in Python: the part.step of the CLI's run (same settings), and one
    sentence naming the path for a folder that does not exist."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(sheetgen_dir))), "python"))
    import _sheetgen_native as sg
    prob = sg.load_problem(problem_path)
    result = sg.generate(prob, seed=REDUCED["seed"], chains=REDUCED["chains"], iterations=REDUCED["iterations"],
                         beam_width=REDUCED["beam"], threads=2)
    doc = json.loads(sg.result_json(prob, result))
    load = doc["parts"][0]["load"]
    with tempfile.TemporaryDirectory() as tmp:
        rep = sg.write_step(prob, result, load, os.path.join(tmp, "p.step"), os.path.join(tmp, "f.step"))
        cli = freecad_probe([os.path.join(cli_out, load, "part.step")])[os.path.join(cli_out, load, "part.step")]
        if abs(rep["part"]["volume_mm3"] / cli["volume"] - 1) > 1e-9 or sorted(os.listdir(tmp)) != ["f.step", "p.step"]:
            failures.append(f"write_step: volume {rep['part']['volume_mm3']} against the CLI's {cli['volume']}, files {os.listdir(tmp)}")
        bad = os.path.join(tmp, "missing", "p.step")
        try:
            sg.write_step(prob, result, load, bad)
            failures.append("write_step into a missing folder did not raise")
        except RuntimeError as e:
            if bad not in str(e) or os.path.exists(os.path.dirname(bad)):
                failures.append(f"write_step into a missing folder: {e}")
    return f"write_step ({load}): volume {rep['part']['volume_mm3']:.1f} mm³ = the CLI's part.step; a missing folder raises naming it"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", required=True)
    ap.add_argument("--keep", help="solve into this folder and keep it")
    ap.add_argument("--all-samples", action="store_true",
                    help="every sample scene at its own settings instead of the four parts at reduced settings")
    args = ap.parse_args()
    settings = {} if args.all_samples else REDUCED
    sheetgen = os.path.abspath(args.sheetgen)
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    failures, lines = [], []
    with tempfile.TemporaryDirectory() as tmp:
        base = args.keep or tmp
        solved = []
        for name, problem in problems(tmp, args.all_samples):
            run = runner.solve(problem, os.path.join(base, name), runner.SolveOptions(threads=2, sheetgen=sheetgen, **settings))
            if run.exit_code != 0:
                failures.append(f"{name}: sheetgen exited {run.exit_code}: {(run.stdout + run.stderr)[-500:]}")
                continue
            solved.append((name, problem, run))
        files = [os.path.join(run.out_dir, p["load"], f) for _, _, run in solved for p in run.parts
                 for f in ("part.step", "flat.step") if os.path.exists(os.path.join(run.out_dir, p["load"], f))]
        fc = freecad_probe(files)
        for name, problem, run in solved:
            prob = json.load(open(problem))
            for part in run.parts:
                lines.append(f"{name}/" + check_part(run.out_dir, prob, part, fc, failures))
        if not any(p.get("self_rivets") for _, _, run in solved for p in run.parts):
            failures.append("no part with self-rivets was checked")
        if solved and not args.all_samples:
            lines.append(check_binding(sheetgen, solved[0][1], solved[0][2].out_dir, failures))
    gmsh.finalize()
    print("\n".join(lines))
    for f in failures:
        print("FAIL " + f)
    print(f"test_step_export: {len(lines)} lines, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
