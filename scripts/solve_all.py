#!/usr/bin/python3
"""Solves the whole scene library with one command, verifies every output with
sheetgen_tools.verify and prints a table (issue 8).

    PYTHONPATH=tools /usr/bin/python3 scripts/solve_all.py                 # default settings (10 chains x 1000 iterations)
    PYTHONPATH=tools /usr/bin/python3 scripts/solve_all.py --quick         # 6 chains x 300 iterations, for scene design
    PYTHONPATH=tools /usr/bin/python3 scripts/solve_all.py --scenes shelf,maze --chains 4 --iterations 200
    PYTHONPATH=tools /usr/bin/python3 scripts/solve_all.py --no-solve      # re-verify and re-print existing outputs
    PYTHONPATH=tools /usr/bin/python3 scripts/solve_all.py --no-verify     # solve only; verify later with --no-solve
    PYTHONPATH=tools /usr/bin/python3 scripts/solve_all.py --tabulate      # re-print the table from run.json and verify.log

Writes out/<scene>/ (sheetgen's result.json and per-load folders, plus solve.log,
verify.log and run.json with the wall time, exit code and verify status) and
out/summary.json (the table's rows, in the library's order, read by
scripts/make_report.py). The avionics bay is solved twice: as given, and with
--right-angles (the expert's practice of the paper's Sec. 6.2) into
out/avionics_bay_right_angles/. Solves run one at a time (the machine is
shared); --threads defaults to 2. Exit 0 when every run finished (exit 0 or 2
of sheetgen) and every produced part passed verification; 1 otherwise. Loads
without a part are reported in the table ("loads ok" column and the reasons
below it), not counted as failures.
"""
import argparse
import json
import os
import sys
import time
import traceback

from sheetgen_tools import paths, runner
from sheetgen_tools.scenes import LIBRARY
from sheetgen_tools.verify import SUMMARY, VerifyOptions, verify_output

# The library in order of difficulty (docs/scenes.md), then the bay at right
# angles. (run name, scene folder, extra sheetgen flags)
RUNS = [(scene, scene, ()) for scene in LIBRARY] + [("avionics_bay_right_angles", "avionics_bay", ("--right-angles",))]


def summarise(run, out_dir, wall_s, exit_code, verify_status):
    """One table row from a run's result.json (totals over loads)."""
    row = {"run": run, "wall_s": wall_s, "exit": exit_code, "verify": verify_status, "loads": 0, "ok": 0,
           "area_m2": 0.0, "mass_kg": 0.0, "bends": 0, "cost": 0.0, "currency": "", "worst_c_ratio": None, "min_ms": None, "solver_s": None,
           "failures": []}
    path = os.path.join(out_dir, "result.json")
    if not os.path.exists(path):
        return row
    res = json.load(open(path))
    row["solver_s"] = res.get("timing", {}).get("total_s")
    row["settings"] = res.get("search")
    for p in res["parts"]:
        row["loads"] += 1
        if p["status"] != "ok":
            row["failures"].append({"load": p["load"], "reason": p.get("reason", "")})
            continue
        row["ok"] += 1
        row["area_m2"] += p["area_m2"]
        row["mass_kg"] += p["mass_kg"]
        row["bends"] += p["bends"]
        row["cost"] += p.get("cost", {}).get("total", 0.0)
        row["currency"] = p.get("cost", {}).get("currency", "")
        ratio = p["compliance"] / p["compliance_limit"]
        row["worst_c_ratio"] = ratio if row["worst_c_ratio"] is None else max(row["worst_c_ratio"], ratio)
        ms = p["margin_of_safety"]
        row["min_ms"] = ms if row["min_ms"] is None else min(row["min_ms"], ms)
    return row


def fmt_row(r):
    def f(v, spec):
        return "-" if v is None else format(v, spec)
    ok = "%d/%d" % (r["ok"], r["loads"]) if r["loads"] else "-"
    area = f(r["area_m2"] * 1e4, ".0f") if r["ok"] else "-"
    mass = f(r["mass_kg"], ".3f") if r["ok"] else "-"
    bends = str(r["bends"]) if r["ok"] else "-"
    cost = f(r.get("cost"), ".2f") if r["ok"] else "-"
    return [r["run"], ok, area, mass, bends, cost, f(r["worst_c_ratio"], ".3f"), f(r["min_ms"], ".3f"),
            f(r["wall_s"], ".0f"), r["verify"]]


HEADER = ["scene", "loads ok", "area cm2", "mass kg", "bends", "cost", "C/Cmax", "MS", "wall s", "verify"]


def print_table(rows):
    table = [HEADER] + [fmt_row(r) for r in rows]
    widths = [max(len(str(t[i])) for t in table) for i in range(len(HEADER))]
    for k, t in enumerate(table):
        print("  ".join(str(c).ljust(widths[i]) if i == 0 or i == len(HEADER) - 1 else str(c).rjust(widths[i])
                        for i, c in enumerate(t)))
        if k == 0:
            print("  ".join("-" * w for w in widths))
    print("(area, mass, bends: sums over the loads with a part; C/Cmax: worst load; MS: lowest load)")
    for r in rows:
        for fl in r["failures"]:
            print("no part: %s/%s: %s" % (r["run"], fl["load"], fl["reason"]))


def verify_status_from_log(out_dir):
    """The verify column as the checker's saved log (verify.log) gives it."""
    path = os.path.join(out_dir, "verify.log")
    if not os.path.exists(path):
        return "not verified"
    lines = open(path).read().splitlines()
    n_parts = sum(p["status"] == "ok" for p in json.load(open(os.path.join(out_dir, "result.json")))["parts"])
    if not lines or not lines[-1].startswith(SUMMARY.split(":")[0] + ":"):
        return "FAIL (verify crashed)"
    n_bad = len({l.split(":")[1].strip() for l in lines if l.startswith("FAIL:")})
    if n_bad:
        return "FAIL (%d of %d parts)" % (n_bad, n_parts)
    return "ok (%d part%s)" % (n_parts, "" if n_parts == 1 else "s") if n_parts else "n/a (no part)"


def parse_args():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(paths.ROOT, "out"), help="output root (default out/)")
    ap.add_argument("--scenes", help="comma-separated run names (default: all): " + ",".join(r[0] for r in RUNS))
    ap.add_argument("--chains", type=int, help="override search.chains")
    ap.add_argument("--iterations", type=int, help="override search.iterations")
    ap.add_argument("--seed", type=int, help="override search.seed")
    ap.add_argument("--quick", action="store_true", help="--chains 6 --iterations 300 (scene design)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--no-solve", action="store_true", help="only verify and tabulate existing outputs")
    ap.add_argument("--no-ccx", action="store_true", help="verify without CalculiX")
    ap.add_argument("--no-verify", action="store_true",
                    help="solve only (verify later with --no-solve; the bay's brute-force check takes ~20 min)")
    ap.add_argument("--tabulate", action="store_true",
                    help="neither solve nor verify: rebuild the table and summary.json from run.json and verify.log")
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    args = ap.parse_args()
    if args.quick:
        args.chains = args.chains or 6
        args.iterations = args.iterations or 300
    if args.scenes:
        unknown = set(args.scenes.split(",")) - {r[0] for r in RUNS}
        if unknown:
            ap.error("unknown scene(s): " + ", ".join(sorted(unknown)))
    if not args.no_solve and not args.tabulate and not os.path.exists(args.sheetgen):
        ap.error("sheetgen not found at %s (cmake --build build --target sheetgen)" % args.sheetgen)
    return args


def solve(run, scene, flags, out_dir, args):
    """Solves one run into out_dir (solve.log, run.json); returns run.json's content."""
    options = runner.SolveOptions(threads=args.threads, chains=args.chains, iterations=args.iterations, seed=args.seed,
                                  flags=flags, log=os.path.join(out_dir, "solve.log"), sheetgen=args.sheetgen)
    cmd = runner.command(paths.scene_problem(scene), out_dir, options)
    print("== %s: %s" % (run, " ".join(os.path.relpath(c, paths.ROOT) if c.startswith(paths.ROOT) else c for c in cmd)),
          flush=True)
    started = time.time()
    solved = runner.solve(paths.scene_problem(scene), out_dir, options)
    meta = {"run": run, "scene": scene, "command": solved.command, "wall_s": solved.wall_s, "exit": solved.exit_code,
            "peak_rss_mb": solved.peak_rss_mb, "cpu_s": solved.cpu_s,
            "sheetgen_mtime": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime(os.path.getmtime(args.sheetgen))),
            "started_utc": time.strftime("%Y-%m-%d %H:%M:%S", time.gmtime(started))}
    json.dump(meta, open(os.path.join(out_dir, "run.json"), "w"), indent=2)
    print("   exit %d in %.0f s" % (solved.exit_code, solved.wall_s), flush=True)
    return meta


def verify(out_dir, args):
    """Checks a run's parts into verify.log; returns (the verify column, passed)."""
    options = VerifyOptions(calculix=not args.no_ccx, allow_no_part=True, sheetgen=args.sheetgen)
    try:
        report = verify_output(out_dir, options)
        text, ok = report.text(), report.ok
    except Exception:  # a crash of the checker is a failed check of this run, the others go on
        text, ok = traceback.format_exc(), False
    open(os.path.join(out_dir, "verify.log"), "w").write(text + "\n")
    if not ok:
        for line in text.splitlines():
            if line.startswith("FAIL") or "Error" in line:
                print("   " + line)
    return verify_status_from_log(out_dir), ok


def run_one(run, scene, flags, args):
    """Solves (unless --no-solve or --tabulate) and verifies one run: (its table row, all good)."""
    out_dir = os.path.join(args.out, run)
    os.makedirs(out_dir, exist_ok=True)
    out_dir = os.path.realpath(out_dir)  # result.json's problem path is relative to the real folder
    meta_path = os.path.join(out_dir, "run.json")
    if args.no_solve or args.tabulate:
        meta = json.load(open(meta_path)) if os.path.exists(meta_path) else {"wall_s": None, "exit": None}
    else:
        meta = solve(run, scene, flags, out_dir, args)
    good = meta.get("exit") in (0, 2, None)
    if not os.path.exists(os.path.join(out_dir, "result.json")):
        status, good = "no result", False
    elif args.no_verify:
        status = "not verified"
    elif args.tabulate:
        status = verify_status_from_log(out_dir)
        good &= status.startswith(("ok", "n/a"))
    else:
        status, ok = verify(out_dir, args)
        good &= ok
    row = summarise(run, out_dir, meta.get("wall_s"), meta.get("exit"), status)
    print("   " + "  ".join(str(c) for c in fmt_row(row)), flush=True)
    return row, good


def main():
    args = parse_args()
    runs = [r for r in RUNS if not args.scenes or r[0] in args.scenes.split(",")]
    os.makedirs(args.out, exist_ok=True)
    rows, all_good = [], True
    for run, scene, flags in runs:
        row, good = run_one(run, scene, flags, args)
        rows.append(row)
        all_good &= good

    # Keep rows of runs not in this invocation (summary.json is the library's state).
    summary_path = os.path.join(args.out, "summary.json")
    old = json.load(open(summary_path)).get("rows", []) if os.path.exists(summary_path) else []
    merged = {r["run"]: r for r in old}
    merged.update({r["run"]: r for r in rows})
    json.dump({"rows": [merged[r[0]] for r in RUNS if r[0] in merged]}, open(summary_path, "w"), indent=2)
    print()
    print_table(rows)
    sys.exit(0 if all_good else 1)


if __name__ == "__main__":
    main()
