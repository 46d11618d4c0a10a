"""The end of a farm run: one row per problem (loads with a part, total mass,
the worst check, time), printed as a table and written as DIR/summary.csv
(docs/farm.md "Summary").

The worst check of a problem is its part's check with the least reserve,
as a utilisation (1.0 = at the limit): stiffness C / C_max, strength
(1 + MS_min) / (1 + MS), buckling λ_min / λ and frequency f_min / f1 (the last
two where the problem asks for them, result.json envelope.required).
"""
import csv
import dataclasses
import json
import os
from typing import Optional


@dataclasses.dataclass
class Row:
    problem: str                     # the output folder's name
    status: str                      # ok | no part | failed | cancelled
    loads_ok: int = 0
    loads: int = 0
    mass_kg: Optional[float] = None  # kg, the parts of the loads that have one
    worst_check: str = ""            # stiffness | strength | buckling | frequency | "no part"
    worst_load: str = ""
    worst_utilisation: Optional[float] = None  # 1.0 = at the limit
    time_s: Optional[float] = None   # s, the solver's wall time
    cpu_s: Optional[float] = None
    peak_rss_mb: Optional[float] = None
    worker: str = ""
    run: str = ""                    # "this run" or "earlier" (skipped on resume)
    reason: str = ""                 # one line when failed
    result: str = ""                 # DIR/<name>/result.json when there is one
    file: str = ""                   # the problem file


def _min_margin(problem):
    try:
        with open(problem) as f:
            return float(json.load(f).get("requirements", {}).get("min_margin_of_safety", 0.0))
    except (OSError, ValueError, AttributeError, TypeError):
        return 0.0


def part_checks(part, min_margin=0.0):
    """[(check, utilisation)] of a valid part (result.json parts[i])."""
    checks = [("stiffness", part["compliance"] / part["compliance_limit"]),
              ("strength", (1.0 + min_margin) / (1.0 + part["margin_of_safety"]))]
    envelope = part.get("envelope", {})
    required = envelope.get("required", {})
    if required.get("checked"):
        if envelope.get("buckling_factor") and required.get("min_buckling_factor"):
            checks.append(("buckling", required["min_buckling_factor"] / envelope["buckling_factor"]))
        if envelope.get("frequencies_hz") and required.get("min_frequency_hz"):
            checks.append(("frequency", required["min_frequency_hz"] / envelope["frequencies_hz"][0]))
    return checks


def _fill_from_result(row, result, min_margin):
    parts = result["parts"]
    ok = [p for p in parts if p["status"] == "ok"]
    row.loads, row.loads_ok = len(parts), len(ok)
    row.mass_kg = sum(p["mass_kg"] for p in ok)
    missing = [p["load"] for p in parts if p["status"] != "ok"]
    if missing:
        row.status, row.worst_check, row.worst_load = "no part", "no part", ", ".join(missing)
        return
    row.status = "ok"
    worst = max(((u, check, p["load"]) for p in ok for check, u in part_checks(p, min_margin)), default=None)
    if worst:
        row.worst_utilisation, row.worst_check, row.worst_load = worst


def row_of(planned, record, out_root, run_id):
    """The summary row of a planned problem from its record (None: never ran) and, when solved, its result.json."""
    row = Row(problem=planned.name, status="cancelled", file=planned.problem, reason="interrupted before it finished")
    if record is None:
        return row
    row.status, row.reason, row.worker = record.status, record.reason, record.worker
    row.time_s, row.cpu_s, row.peak_rss_mb = record.wall_s or None, record.cpu_s or None, record.peak_rss_mb or None
    row.run = "this run" if record.run_id == run_id else "earlier"
    if record.status != "solved":
        return row
    result_path = os.path.join(out_root, planned.name, "result.json")
    try:
        with open(result_path) as f:
            result = json.load(f)
    except (OSError, ValueError) as e:
        row.status, row.reason = "failed", f"cannot read {result_path}: {e}"
        return row
    row.result = result_path
    _fill_from_result(row, result, _min_margin(planned.problem))
    return row


def _fmt(value, spec, empty="-"):
    return empty if value is None else format(value, spec)


def worst_text(row):
    """"stiffness 93% (load)", or "no part (loads)"."""
    if row.worst_check == "no part":
        return f"no part ({row.worst_load})"
    if row.worst_utilisation is None:
        return row.worst_check or "-"
    return f"{row.worst_check} {row.worst_utilisation:.0%} ({row.worst_load})"


def table(rows):
    """The summary as text: a fixed-width table, then the failures with their reasons."""
    header = ("problem", "status", "loads ok", "mass kg", "worst check", "time s", "run")
    lines = [(r.problem, r.status, f"{r.loads_ok}/{r.loads}" if r.loads else "-", _fmt(r.mass_kg, ".3f"),
              worst_text(r) if r.status in ("ok", "no part") else "-", _fmt(r.time_s, ".1f"), r.run or "-")
             for r in rows]
    widths = [max(len(str(x)) for x in col) for col in zip(header, *lines)]
    out = ["  ".join(str(x).ljust(w) for x, w in zip(line, widths)).rstrip() for line in [header] + lines]
    out += [f"{r.problem}: {r.reason}" for r in rows if r.status in ("failed", "cancelled")]
    return "\n".join(out)


def write_csv(rows, path):
    """The rows as CSV (units in the column names), written beside and renamed: a reader never sees half of it."""
    fields = [f.name for f in dataclasses.fields(Row)]
    tmp = path + ".tmp"
    with open(tmp, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        for r in rows:
            writer.writerow({k: ("" if v is None else v) for k, v in dataclasses.asdict(r).items()})
    os.replace(tmp, path)


def counts(rows):
    """{status: number of problems}."""
    out = {}
    for r in rows:
        out[r.status] = out.get(r.status, 0) + 1
    return out


def exit_code(rows, interrupted):
    """130 interrupted, 3 some problem failed, 2 some load has no part, 0 every load of every problem has one."""
    c = counts(rows)
    if interrupted:
        return 130
    if c.get("failed") or c.get("cancelled"):
        return 3
    return 2 if c.get("no part") else 0
