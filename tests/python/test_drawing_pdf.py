#!/usr/bin/python3
"""The drawing sheet (drawing.pdf, docs/drawing.md) of a solved part, read
back with poppler (independent of cairo, which wrote it): one page of A3
landscape (pdfinfo); its text (pdftotext) holds every row of bends.csv (bend
number, angle to 0.1 degree, direction), the mass and flat area of
result.json, the scale and the overall dimensions; and the stated scale is
true: the flat pattern's outline, found in the page's vector content
(pdftocairo -svg: the one path filled with the sheet's tint), is as wide and
as tall on the paper as the outline of result.json divided by the scale,
within 0.1 mm. With --sheetgen it solves shelf twice, on 1 and on 2 threads, and
the two drawing.pdf must be the same bytes (no creation date in the PDF; the
same search gives the same part on any thread count).

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_drawing_pdf.py --sheetgen build/native/cli/sheetgen
     PYTHONPATH=tools /usr/bin/python3 tests/python/test_drawing_pdf.py --out DIR   (a solved folder: every part)
Needs poppler-utils (pdfinfo, pdftotext, pdftocairo).
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile

from sheetgen_tools import paths, runner

PT = 25.4 / 72  # mm per PostScript point
SHEET_TINT = "93.998718%"  # the flat pattern's fill, rgb(0.94, 0.94, 0.94) as pdftocairo prints it


def run(*cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True).stdout


def page_size_mm(pdf):
    info = run("pdfinfo", pdf)
    pages = int(re.search(r"^Pages:\s+(\d+)", info, re.M).group(1))
    w, h = map(float, re.search(r"^Page size:\s+([\d.]+) x ([\d.]+) pts", info, re.M).groups())
    return pages, w * PT, h * PT, info


def outline_on_paper_mm(pdf, tmp):
    """Width and height (mm) of the path filled with the sheet's tint, from the PDF's vector content."""
    svg = os.path.join(tmp, "drawing.svg")
    run("pdftocairo", "-svg", pdf, svg)
    paths_found = re.findall(r'<path style="[^"]*fill:rgb\(' + re.escape(SHEET_TINT) + r'[^"]*"\s+d="([^"]+)"([^>]*)>',
                             open(svg).read())
    if len(paths_found) != 1:
        raise AssertionError("%d paths carry the sheet's tint, want 1" % len(paths_found))
    d, rest = paths_found[0]
    # pdftocairo may wrap a path in a near-identity matrix of its own (0.9996 here, its fit of the page's
    # size in whole units); the path's coordinates are the page's points.
    t = re.search(r'transform="matrix\(([^)]*)\)"', rest)
    if t:
        a, b, c, dd = (float(v) for v in t.group(1).split(",")[:4])
        if abs(a - 1) > 1e-3 or abs(dd - 1) > 1e-3 or b or c:
            raise AssertionError("the outline path has a transform that is not near the identity: " + t.group(0))
    nums = [float(v) for v in re.findall(r"-?\d+(?:\.\d+)?", d)]
    xs, ys = nums[0::2], nums[1::2]
    return (max(xs) - min(xs)) * PT, (max(ys) - min(ys)) * PT


def check_part(out_dir, part, tmp):
    """Failures (strings) of one part's drawing.pdf."""
    load = part["load"]
    folder = os.path.join(out_dir, load)
    pdf = os.path.join(folder, "drawing.pdf")
    if not os.path.exists(pdf):
        return ["%s: no drawing.pdf" % load]
    bad = []
    pages, w, h, info = page_size_mm(pdf)
    if pages != 1 or abs(w - 420) > 0.5 or abs(h - 297) > 0.5:
        bad.append("%s: %d pages of %.1f x %.1f mm, want 1 of 420 x 297 (A3 landscape)" % (load, pages, w, h))
    if "CreationDate" in info:
        bad.append("%s: the PDF carries a creation date (outputs must not depend on the time)" % load)
    text = run("pdftotext", "-layout", pdf, "-")
    flat_text = " ".join(text.split())
    with open(os.path.join(folder, "bends.csv")) as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        want = "B%s %.1f° %s" % (r["order"], float(r["angle_deg"]), r["direction"])
        if want not in flat_text:
            bad.append("%s: bend table row '%s' (bends.csv) not in the text" % (load, want))
    if "BEND TABLE (%d bend%s)" % (len(rows), "" if len(rows) == 1 else "s") not in flat_text:
        bad.append("%s: the bend table's title does not count %d bends" % (load, len(rows)))
    for what, want in (("mass", "%.3f kg" % part["mass_kg"]), ("flat area", "%.1f cm²" % (part["area_m2"] * 1e4))):
        if want not in flat_text:
            bad.append("%s: %s '%s' (result.json) not in the text" % (load, what, want))
    m = re.search(r"FLAT PATTERN 1:(\d+)", flat_text)
    if not m:
        return bad + ["%s: no 'FLAT PATTERN 1:n' scale in the text" % load]
    n = int(m.group(1))
    outline = part["flat_pattern"]["outline"][0]
    ex = (max(p[0] for p in outline) - min(p[0] for p in outline)) * 1e3
    ey = (max(p[1] for p in outline) - min(p[1] for p in outline)) * 1e3
    for dim in ("%.1f" % ex, "%.1f" % ey):
        if dim not in flat_text.split():
            bad.append("%s: overall dimension %s mm not in the text" % (load, dim))
    pw, ph = outline_on_paper_mm(pdf, tmp)
    if abs(pw - ex / n) > 0.1 or abs(ph - ey / n) > 0.1:
        bad.append("%s: the outline is %.3f x %.3f mm on the paper, want %.3f x %.3f (%.1f x %.1f mm at 1:%d)"
                   % (load, pw, ph, ex / n, ey / n, ex, ey, n))
    print("%s %-16s 1:%d, outline %.2f x %.2f mm on paper (%.1f x %.1f mm true), %d bends, %s"
          % ("ok  " if not bad else "FAIL", load, n, pw, ph, ex, ey, len(rows), "ok" if not bad else "; ".join(bad)))
    return bad


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", help="solve shelf (6 x 300, beam 4) with this CLI and check its drawing")
    ap.add_argument("--out", help="check the drawings of an already solved folder instead")
    args = ap.parse_args()
    if not args.out and not args.sheetgen:
        ap.error("give --sheetgen or --out")
    out = args.out
    if not out:
        # shelf has a valid part with four bends at the fast tier's sample settings (6 x 300, beam 4;
        # test_solve_samples_fast.py) in about 8 s on one thread, a third of corner's time.
        runs = [runner.solve(paths.scene_problem("shelf"), options=runner.SolveOptions(
            chains=6, iterations=300, beam=4, threads=t, sheetgen=os.path.abspath(args.sheetgen))) for t in (1, 2)]
        for solved in runs:
            if not solved.finished:
                raise SystemExit("solve failed: " + solved.stderr)
        out = runs[1].out_dir

        def pdfs_of(run):
            return {p["load"]: open(os.path.join(run.out_dir, p["load"], "drawing.pdf"), "rb").read()
                    for p in run.result["parts"] if os.path.exists(os.path.join(run.out_dir, p["load"], "drawing.pdf"))}
        pdfs = [pdfs_of(r) for r in runs]
        if not pdfs[0] or pdfs[0] != pdfs[1]:
            print("FAIL  drawing.pdf of 1 and 2 threads: %s" % ("missing" if not pdfs[0] else "different bytes"))
            print("drawing_pdf: 0 passed, 1 failed")
            sys.exit(1)
        print("ok    drawing.pdf of 1 and 2 threads: the same %d bytes" % sum(map(len, pdfs[0].values())))
    doc = json.load(open(os.path.join(out, "result.json")))
    parts = [p for p in doc["parts"] if p["status"] == "ok"]
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for part in parts:
            bad = check_part(out, part, tmp)
            for b in bad:
                print("FAIL  " + b)
            failed += bool(bad)
    if not parts:
        print("FAIL  no valid part to check in " + out)
        failed += 1
    print("drawing_pdf: %d passed, %d failed" % (len(parts) - failed if parts else 0, failed))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
