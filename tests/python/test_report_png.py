#!/usr/bin/python3
"""Reads a convergence plot PNG written by sheetgen (drawn and encoded with
cairo) with PIL, a decoder independent of it, and checks it: a valid PNG (PIL's
verify checks the chunk CRCs), 8-bit RGB, the size asked for, and every plotted
point's colour where its panel's axis mapping puts it (the marker covers that
pixel whole, so the colour is exact despite anti-aliasing).

Usage (exits non-zero on failure):
  /usr/bin/python3 test_report_png.py --writer build/tests/native/sheetgen_report_tests
  /usr/bin/python3 test_report_png.py --png DIR/<load>/convergence.png   (a solve's output: format checks only)
Needs the Debian python3-pil (the system /usr/bin/python3, not pyenv's).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

from PIL import Image


def write_sample(writer, out_dir):
    png = os.path.join(out_dir, "convergence.png")
    env = dict(os.environ, SHEETGEN_REPORT_PNG_OUT=png)
    subprocess.run([writer, "--gtest_filter=ConvergencePlotSample.WritesSamplePngForPython"], check=True, env=env,
                   stdout=subprocess.DEVNULL)
    return png


def check_format(path):
    bad = []
    with Image.open(path) as im:
        im.verify()  # chunk CRCs, IEND
    with Image.open(path) as im:
        if im.format != "PNG":
            bad.append(f"format {im.format}, want PNG")
        if im.mode != "RGB":
            bad.append(f"mode {im.mode}, want RGB")
        im.load()
    return bad


def check_sample(png):
    bad = check_format(png)
    with open(png + ".json") as f:
        layout = json.load(f)
    with Image.open(png) as im:
        want = (layout["width_px"], layout["height_px"])
        if im.size != want:
            bad.append(f"size {im.size}, want {want}")
            return bad
        for k, p in enumerate(layout["panels"]):
            for x, y in p["points"]:
                px = p["left_px"] + (x - p["x_min"]) / (p["x_max"] - p["x_min"]) * (p["right_px"] - p["left_px"])
                py = p["bottom_px"] - (y - p["y_min"]) / (p["y_max"] - p["y_min"]) * (p["bottom_px"] - p["top_px"])
                got = im.getpixel((math.floor(px), math.floor(py)))
                if list(got) != p["colour"]:
                    bad.append(f"panel {k} point ({x}, {y}) at ({px:.1f}, {py:.1f}) px is {got}, want {p['colour']}")
    return bad


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    group = ap.add_mutually_exclusive_group(required=True)
    group.add_argument("--writer", help="sheetgen_report_tests binary: writes the sample plot")
    group.add_argument("--png", help="a convergence.png to check for format only")
    args = ap.parse_args()
    if args.png:
        bad = check_format(args.png)
    else:
        with tempfile.TemporaryDirectory() as tmp:
            bad = check_sample(write_sample(args.writer, tmp))
    for b in bad:
        print("FAIL:", b)
    print("ok" if not bad else f"{len(bad)} failure(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
