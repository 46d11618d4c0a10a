#!/usr/bin/python3
"""Reads a flat-pattern DXF written by sheetgen with ezdxf and checks what a
laser shop relies on (docs/manufacturing.md): R12, millimetres, layers CUT /
BEND_UP / BEND_DOWN / ANNOTATION, a DASHED linetype on the bend lines, one
closed outline whose area matches the plan, one bend line per bend on the layer
of its direction, the bend number + angle as TEXT on ANNOTATION only, and the
rivet holes as CIRCLEs on RIVET_HOLES / SELF_RIVET_HOLES where the plan puts
them, each inside the outline, with a "S<n> AFTER B<k>" note per self-rivet hole.

Usage (exits non-zero on failure):
  /usr/bin/python3 test_part_dxf.py --writer build/tests/native/sheetgen_part_tests
  /usr/bin/python3 test_part_dxf.py --dxf DIR/flat.dxf   (DIR/expected.json beside it)
Under pytest the writer is taken from $SHEETGEN_PART_TESTS.
Needs the Debian python3-ezdxf (the system /usr/bin/python3, not pyenv's).
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

import ezdxf

# The sample part of tests/native/part/exports_test.cpp: (direction, angle_deg, length_mm).
SAMPLE_BENDS = sorted([("UP", 90.0, 20.0), ("DOWN", 90.0, 16.0), ("DOWN", 45.0, 20.0), ("UP", 120.0, 20.0)])
LABEL = re.compile(r"^B(\d+) (UP|DOWN) ([0-9]+\.[0-9]+)(?:%%d|°)$")
NOTE = re.compile(r"^S(\d+)(?: AFTER B(\d+))?$")


def write_sample(writer, out_dir):
    dxf = os.path.join(out_dir, "flat.dxf")
    env = dict(os.environ, SHEETGEN_PART_DXF_OUT=dxf)
    subprocess.run([writer, "--gtest_filter=Exports.WritesSampleDxfForPython"], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    return dxf


def shoelace(points):
    return 0.5 * sum(x0 * y1 - x1 * y0 for (x0, y0), (x1, y1) in zip(points, points[1:] + points[:1]))


def _check_tables(doc):
    """R12, millimetres, the four layers and the DASHED linetype."""
    bad = []
    if doc.dxfversion != "AC1009":
        bad.append(f"DXF version {doc.dxfversion}, want AC1009 (R12)")
    if doc.header.get("$INSUNITS") != 4:
        bad.append(f"$INSUNITS {doc.header.get('$INSUNITS')}, want 4 (mm)")
    layers = {layer.dxf.name for layer in doc.layers}
    for name in ("CUT", "BEND_UP", "BEND_DOWN", "ANNOTATION"):
        if name not in layers:
            bad.append(f"layer {name} missing (have {sorted(layers)})")
    if "DASHED" not in doc.linetypes:
        bad.append("linetype DASHED not defined in the LTYPE table")
    else:
        pattern = doc.linetypes.get("DASHED").dxf
        if not getattr(pattern, "description", None):
            bad.append("DASHED has no description")
    return bad


def _check_outline(msp, expected):
    """One closed POLYLINE on CUT with the plan's vertices and area: (failures, the outline or None)."""
    bad = []
    cut = [e for e in msp if e.dxf.layer == "CUT"]
    outlines = [e for e in cut if e.dxftype() == "POLYLINE"]
    if len(outlines) != 1 or len(cut) != 1:
        bad.append(f"want exactly one POLYLINE on CUT, got {[e.dxftype() for e in cut]}")
    else:
        pl = outlines[0]
        if not pl.is_closed:
            bad.append("the outline POLYLINE is not closed (flag 70 bit 1)")
        pts = [(v.dxf.location.x, v.dxf.location.y) for v in pl.vertices]
        if len(pts) != expected["outline_vertices"]:
            bad.append(f"outline has {len(pts)} vertices, want {expected['outline_vertices']}")
        area = shoelace(pts)
        if abs(area - expected["area_mm2"]) > 1e-6 * expected["area_mm2"]:
            bad.append(f"outline area {area:.6f} mm^2, want {expected['area_mm2']:.6f}")
        if min(x for x, _ in pts) < -1e-9 or min(y for _, y in pts) < -1e-9:
            bad.append("outline has negative coordinates (drawings start at 0,0)")
    return bad, outlines[0] if len(outlines) == 1 else None


def _check_bend_lines(doc, msp, want):
    """DASHED LINEs on BEND_UP / BEND_DOWN of the plan's lengths: (failures, {layer: lengths mm})."""
    bad = []
    lines = {"BEND_UP": [], "BEND_DOWN": []}
    for e in msp:
        if e.dxf.layer in lines:
            if e.dxftype() != "LINE":
                bad.append(f"{e.dxftype()} on {e.dxf.layer}; only LINEs belong there")
                continue
            if e.dxf.linetype != "DASHED" and doc.layers.get(e.dxf.layer).dxf.linetype != "DASHED":
                bad.append(f"bend line on {e.dxf.layer} is not DASHED")
            lines[e.dxf.layer].append(math.dist(e.dxf.start, e.dxf.end))
    for layer, direction in (("BEND_UP", "UP"), ("BEND_DOWN", "DOWN")):
        got = sorted(round(x, 6) for x in lines[layer])
        ref = sorted(round(b["length_mm"], 6) for b in want if b["direction"] == direction)
        if got != ref:
            bad.append(f"{layer}: bend line lengths {got} mm, want {ref}")
    return bad, lines


def _check_annotations(msp, expected, n_lines):
    """TEXT only on ANNOTATION: one bend label per bend line matching the plan, and the self-rivet notes."""
    bad = []
    want = expected["bends"]
    texts = [e for e in msp if e.dxftype() == "TEXT"]
    stray = [e.dxf.layer for e in texts if e.dxf.layer != "ANNOTATION"]
    if stray:
        bad.append(f"TEXT on layers {stray}; annotations belong on ANNOTATION only")
    on_annotation = [e.dxftype() for e in msp if e.dxf.layer == "ANNOTATION" and e.dxftype() != "TEXT"]
    if on_annotation:
        bad.append(f"ANNOTATION holds non-text entities {on_annotation}")
    labels, notes = [], []
    for e in texts:
        m = LABEL.match(e.dxf.text)
        if NOTE.match(e.dxf.text):
            notes.append(e.dxf.text)
            continue
        if not m:
            bad.append(f"annotation {e.dxf.text!r} is not 'B<n> UP|DOWN <deg>%%d' nor 'S<n> AFTER B<k>'")
            continue
        labels.append((int(m.group(1)), m.group(2), float(m.group(3))))
    if sorted(notes) != sorted(expected.get("notes", [])):
        bad.append(f"self-rivet notes {sorted(notes)}, want {sorted(expected.get('notes', []))}")
    numbers = sorted(n for n, _, _ in labels)
    if numbers != list(range(1, len(want) + 1)):
        bad.append(f"bend numbers {numbers}, want 1..{len(want)}")
    by_number = {b["number"]: b for b in want}
    for n, direction, angle in labels:
        ref = by_number.get(n)
        if ref is None:
            continue
        if direction != ref["direction"] or abs(angle - ref["angle_deg"]) > 5e-4:
            bad.append(f"B{n}: annotated {direction} {angle}, plan says {ref['direction']} {ref['angle_deg']:.4f}")
    if len(labels) != n_lines:
        bad.append(f"{len(labels)} bend labels for {n_lines} bend lines")
    return bad


def check_dxf(path, expected):
    """Returns a list of failure messages (empty = pass)."""
    doc = ezdxf.readfile(path)
    msp = doc.modelspace()
    bad = _check_tables(doc)
    outline_bad, outline = _check_outline(msp, expected)
    lines_bad, lines = _check_bend_lines(doc, msp, expected["bends"])
    bad += outline_bad + lines_bad
    bad += _check_annotations(msp, expected, len(lines["BEND_UP"]) + len(lines["BEND_DOWN"]))
    bad += check_holes(msp, outline, expected.get("holes", []))
    return bad


def inside(p, poly):
    """Even-odd point in polygon."""
    x, y = p
    c = False
    for (x1, y1), (x2, y2) in zip(poly, poly[-1:] + poly[:-1]):
        if (y1 > y) != (y2 > y) and x < (x2 - x1) * (y - y1) / (y2 - y1) + x1:
            c = not c
    return c


def check_holes(msp, outline, want):
    """CIRCLEs on the hole layers against the expected holes (layer, centre, diameter in mm)."""
    bad = []
    got = [(e.dxf.layer, e.dxf.center.x, e.dxf.center.y, 2 * e.dxf.radius) for e in msp if e.dxftype() == "CIRCLE"]
    stray = [g[0] for g in got if g[0] not in ("RIVET_HOLES", "SELF_RIVET_HOLES")]
    if stray:
        bad.append(f"CIRCLEs on layers {stray}; holes belong on RIVET_HOLES or SELF_RIVET_HOLES")
    if len(got) != len(want):
        bad.append(f"{len(got)} holes, want {len(want)}")
    for w in want:
        match = [g for g in got if g[0] == w["layer"] and math.hypot(g[1] - w["x_mm"], g[2] - w["y_mm"]) < 1e-5]
        if len(match) != 1:
            bad.append(f"no hole on {w['layer']} at ({w['x_mm']:.4f}, {w['y_mm']:.4f}) mm")
        elif abs(match[0][3] - w["diameter_mm"]) > 1e-5:
            bad.append(f"hole at ({w['x_mm']:.4f}, {w['y_mm']:.4f}) is {match[0][3]:.5f} mm across, "
                       f"want {w['diameter_mm']:.5f}")
    if outline is not None:
        pts = [(v.dxf.location.x, v.dxf.location.y) for v in outline.vertices]
        for g in got:
            if not inside((g[1], g[2]), pts):
                bad.append(f"hole at ({g[1]:.3f}, {g[2]:.3f}) mm is outside the outline")
    return bad


def check_sample(dxf):
    with open(os.path.join(os.path.dirname(dxf), "expected.json")) as f:
        expected = json.load(f)
    bad = check_dxf(dxf, expected)
    got = sorted((b["direction"], round(b["angle_deg"], 9), round(b["length_mm"], 9)) for b in expected["bends"])
    if got != SAMPLE_BENDS:
        bad.append(f"sample bends {got}, want {SAMPLE_BENDS}")
    layers = sorted(h["layer"] for h in expected.get("holes", []))
    if layers != ["RIVET_HOLES", "SELF_RIVET_HOLES", "SELF_RIVET_HOLES"]:
        bad.append(f"sample holes on {layers}, want one rivet and one self-rivet (two holes)")
    return bad


def test_part_dxf():  # pytest entry
    import pytest
    writer = os.environ.get("SHEETGEN_PART_TESTS")
    if not writer or not os.path.exists(writer):
        pytest.skip("set SHEETGEN_PART_TESTS to the sheetgen_part_tests binary")
    with tempfile.TemporaryDirectory() as d:
        bad = check_sample(write_sample(writer, d))
    assert not bad, "\n".join(bad)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--writer", help="sheetgen_part_tests binary (writes the sample DXF)")
    ap.add_argument("--dxf", help="an existing flat.dxf with expected.json beside it")
    args = ap.parse_args()
    if not args.writer and not args.dxf:
        ap.error("give --writer or --dxf")
    with tempfile.TemporaryDirectory() as d:
        dxf = args.dxf or write_sample(args.writer, d)
        bad = check_sample(dxf)
    if bad:
        print("FAIL " + dxf, *bad, sep="\n  ")
        return 1
    print(f"ok: {dxf} passes the laser-shop checks")
    return 0


if __name__ == "__main__":
    sys.exit(main())
