"""The cost a part's result.json reports, rebuilt from the problem file's
prices (docs/cost.md) and the part as the shop receives it: the sheet from the
area of flat.dxf's CUT outline (ezdxf, shapely), the bends from the rows of
bends.csv, the rivets from the holes of flat.dxf (one per RIVET_HOLES circle,
one per pair of SELF_RIVET_HOLES circles).
"""
import csv
import os

from shapely.geometry import Polygon

# The documented defaults of the problem file's `cost` and `material`
# (docs/problem-format.md), restated here so the check does not read them from
# the code it checks.
DEFAULT_COST = {"currency": "USD", "material_per_kg": 15.0, "per_bend": 1.0, "per_rivet": 1.0, "setup": 60.0,
                "batch_size": 10}
DEFAULT_DENSITY = 2780.0  # kg/m^3
DEFAULT_THICKNESS = 1.6e-3  # m
RELATIVE_TOLERANCE = 1e-6  # the DXF's coordinates are written to 1e-6 mm


def expected_cost(prob, area_m2, bends, rivets):
    """{material, bends, rivets, setup, total} in the problem's currency."""
    prices = {**DEFAULT_COST, **prob.get("cost", {})}
    material = prob.get("material", {})
    kg = area_m2 * material.get("thickness", DEFAULT_THICKNESS) * material.get("density", DEFAULT_DENSITY)
    parts = {"material": prices["material_per_kg"] * kg, "bends": prices["per_bend"] * bends,
             "rivets": prices["per_rivet"] * rivets, "setup": prices["setup"] / prices["batch_size"]}
    parts["total"] = sum(parts.values())
    parts["currency"] = prices["currency"]
    return parts


def check_cost(out_dir, prob, part, findings, doc):
    """Fails when result.json's cost differs from the one rebuilt from the shop's files."""
    name = part["load"]
    reported = part.get("cost")
    if not isinstance(reported, dict):
        findings.fail(f"{name}: result.json has no cost")
        return
    msp = doc.modelspace()
    outlines = [e for e in msp if e.dxf.layer == "CUT" and e.dxftype() in ("POLYLINE", "LWPOLYLINE")]
    if len(outlines) != 1:
        return  # check_outline reports it
    area_m2 = Polygon([(v.dxf.location.x, v.dxf.location.y) for v in outlines[0].vertices]).area * 1e-6
    with open(os.path.join(out_dir, name, "bends.csv")) as f:
        bends = len(list(csv.DictReader(f)))
    holes = {layer: sum(1 for e in msp if e.dxftype() == "CIRCLE" and e.dxf.layer == layer)
             for layer in ("RIVET_HOLES", "SELF_RIVET_HOLES")}
    rivets = holes["RIVET_HOLES"] + holes["SELF_RIVET_HOLES"] // 2
    want = expected_cost(prob, area_m2, bends, rivets)
    findings.note(f"{name}: cost {want['total']:.2f} {want['currency']} (sheet {want['material']:.2f}, "
                  f"{bends} bends {want['bends']:.2f}, {rivets} rivets {want['rivets']:.2f}, set-up "
                  f"{want['setup']:.2f}) vs result {reported.get('total', float('nan')):.2f}")
    if reported.get("currency") != want["currency"]:
        findings.fail(f"{name}: cost currency {reported.get('currency')!r}, the problem's is {want['currency']!r}")
    for key in ("material", "bends", "rivets", "setup", "total"):
        got = reported.get(key)
        if not isinstance(got, (int, float)) or abs(got - want[key]) > RELATIVE_TOLERANCE * max(1.0, abs(want[key])):
            findings.fail(f"{name}: cost.{key} {got} differs from {want[key]:.6f} rebuilt from flat.dxf and bends.csv")
