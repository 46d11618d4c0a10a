"""Checks the parts of a `sheetgen solve` output folder with tools independent of
the code that made them:

* clearance (clearance.py): every tab sampled every 1.5 mm, brute-force
  point-triangle distance to every environment triangle and load box, except
  the documented allowed contacts; every rivet flange flush on its rivet area;
* every case of the load, re-computed by CalculiX with the loads, masses and
  limits rebuilt from the problem file (ccx_check.py): each static case's
  compliance on the solid model of solid_reference.py against its limit, its
  margin of safety from the S4 deck's stresses and, where the problem asks for
  them (problem.eigen_requirements), the lowest buckling factor (*BUCKLE) and
  the first natural frequency (*FREQUENCY) against their floors; one line per
  part sums it up (worst C/C_max, lowest MS, buckling factor and f1, CalculiX's
  and ours); docs/testing.md "The independent check" gives the rules, the
  tolerances and the cost. Off with VerifyOptions.calculix;
* the DXF (dxf_check.py, ezdxf): one simple closed CUT outline of the
  flat-pattern area, and the rivet holes;
* the cost (cost_check.py): result.json's cost against the one rebuilt from
  the problem's prices, flat.dxf's outline and holes and bends.csv;
* parts of a multi-load problem avoid each other: each part's clearance is
  also measured to both faces of every part before it in result.json (the
  order sheetgen solves the loads in, each part an obstacle for the later ones).

    PYTHONPATH=tools python3 -m sheetgen_tools.verify OUT_DIR [--sheetgen build/native/cli/sheetgen]
                                                      [--no-ccx] [--allow-no-part] [--loads A,B]

Exits 1 with one line per failure; prints the measured numbers.
"""
import argparse
import dataclasses
import json
import os
import sys
from typing import Optional

from . import paths
from .ccx_check import check_calculix
from .clearance import check_clearance
from .cost_check import check_cost
from .dxf_check import check_holes, check_outline
from .findings import Findings
from .geometry import part_faces
from .problem import DEFAULT_THICKNESS, at_part_sheet, load_problem, problem_of_result

# The last line of the report; solve_all.py's table reads it back from verify.log
# (the name is the checker's old one, which saved logs carry).
SUMMARY = "verify_result: %d passed, %d failed"


@dataclasses.dataclass
class VerifyOptions:
    calculix: bool = True             # every case by CalculiX (needs ccx and gmsh); off: geometry and DXF only
    allow_no_part: bool = False       # a load without a valid part is reported, not a failure
    loads: Optional[set] = None       # check only these loads; the parts before them still count as obstacles
    sheetgen: str = paths.DEFAULT_SHEETGEN  # for `sheetgen export-ccx` (CalculiX only)


@dataclasses.dataclass
class VerifyReport:
    findings: Findings
    checked: int                      # loads checked

    @property
    def failed(self):
        return len(self.findings.failed_loads())

    @property
    def passed(self):
        return self.checked - self.failed

    @property
    def ok(self):
        return not self.findings.failures

    def text(self):
        """What the command prints: the measured numbers, the failures, the summary line."""
        lines = self.findings.lines + ["FAIL: " + f for f in self.findings.failures]
        return "\n".join(lines + [SUMMARY % (self.passed, self.failed)])


def check_part(out_dir, prob, meshes, part, options, findings):
    """Every check of one part with a valid design, in the sheet it is made of
    (a thicker gauge when the problem's sheet gave the load none)."""
    try:
        prob = at_part_sheet(prob, part)
    except ValueError as e:
        findings.fail(str(e))
        return
    check_clearance(prob, meshes, part, findings)
    if options.calculix:
        check_calculix(out_dir, prob, part, options.sheetgen, findings)
    doc = check_outline(out_dir, part, findings)
    check_holes(out_dir, prob, part, findings, doc)
    check_cost(out_dir, prob, part, findings, doc)


def _sheet_thickness(prob, part):
    """The part's sheet, m, as an obstacle for the parts after it."""
    try:
        return at_part_sheet(prob, part).get("material", {}).get("thickness", DEFAULT_THICKNESS)
    except ValueError:
        return part["thickness_m"]  # check_part has failed it; as an obstacle it is what it says


def verify_output(out_dir, options=None):
    """Checks every part of out_dir/result.json; ValueError when options.loads
    names a load the result does not have."""
    options = options or VerifyOptions()
    with open(os.path.join(out_dir, "result.json")) as f:
        result = json.load(f)
    prob, meshes = load_problem(problem_of_result(out_dir, result))
    unknown = sorted(set(options.loads or ()) - {p["load"] for p in result["parts"]})
    if unknown:
        raise ValueError(f"loads {unknown} are not in {out_dir}/result.json")
    findings, checked = Findings(), 0
    earlier = {}  # the parts of the loads before this one: both faces of every tab (mid-surface +- t/2)
    for part in result["parts"]:
        if options.loads is None or part["load"] in options.loads:
            checked += 1
            if part["status"] != "ok":
                line = f"{part['load']}: no valid part: {part.get('reason')}"
                if options.allow_no_part:
                    findings.note(line)
                else:
                    findings.fail(line)
            else:
                check_part(out_dir, prob, {**meshes, **earlier}, part, options, findings)
        if part["status"] == "ok":
            earlier["part:" + part["load"]] = part_faces(part, _sheet_thickness(prob, part))
    return VerifyReport(findings, checked)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m sheetgen_tools.verify",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("out_dir")
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    ap.add_argument("--no-ccx", action="store_true", help="leave out the CalculiX checks")
    ap.add_argument("--allow-no-part", action="store_true", help="do not fail on loads without a valid part")
    ap.add_argument("--loads", help="check only these loads (comma-separated names); the parts before them still count as obstacles")
    args = ap.parse_args(argv)
    options = VerifyOptions(calculix=not args.no_ccx, allow_no_part=args.allow_no_part,
                            loads=set(args.loads.split(",")) if args.loads else None, sheetgen=args.sheetgen)
    try:
        report = verify_output(args.out_dir, options)
    except ValueError as e:
        sys.exit(f"verify: --loads: {e}")
    print(report.text())
    return 0 if report.ok else 1


if __name__ == "__main__":
    sys.exit(main())
