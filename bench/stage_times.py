#!/usr/bin/python3
"""How many cores each stage of a solve kept busy: reads the result.json of
one or more `sheetgen solve` output folders and prints, per stage (the
environment, discovery, composition, sizing, and the rest of each load:
planning and the bookkeeping between stages), the wall seconds, the process's
CPU seconds and CPU over wall, summed over every load of every folder
(docs/benchmarks.md "Cores busy, stage by stage").

Usage: /usr/bin/python3 bench/stage_times.py OUT_DIR [OUT_DIR ...] [--per-load]

The numbers are the solver's own (result.json `timing`, binaries from the
commit that added `*_cpu_s` on); a folder without them is named and skipped.
"""
import argparse
import json
import os
import sys

STAGES = ("environment", "discovery", "composition", "sizing")


def stage_times(timing):
    """{stage: (wall s, cpu s)} of one load, with 'other' the total's rest and 'total'."""
    out = {s: (timing[f"{s}_s"], timing[f"{s}_cpu_s"]) for s in STAGES}
    total = (timing["total_s"], timing["total_cpu_s"])
    out["other"] = (total[0] - sum(w for w, _ in out.values()), total[1] - sum(c for _, c in out.values()))
    out["total"] = total
    return out


def row(name, wall, cpu):
    busy = cpu / wall if wall > 0 else float("nan")
    return f"{name:<28} {wall:9.1f} {cpu:9.1f} {busy:6.2f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--per-load", action="store_true", help="also print each load's total")
    args = ap.parse_args()
    sums = {s: [0.0, 0.0] for s in STAGES + ("other", "total")}
    print(f"{'stage':<28} {'wall s':>9} {'CPU s':>9} {'cores':>6}")
    for d in args.dirs:
        path = os.path.join(d, "result.json")
        try:
            parts = json.load(open(path))["parts"]
        except (OSError, ValueError, KeyError) as e:
            print(f"{path}: cannot read the parts ({e})", file=sys.stderr)
            return 1
        for p in parts:
            if "total_cpu_s" not in p.get("timing", {}):
                print(f"{path}: load '{p['load']}' has no CPU times (a solver before they were written); skipped",
                      file=sys.stderr)
                continue
            t = stage_times(p["timing"])
            for s, (w, c) in t.items():
                sums[s][0] += w
                sums[s][1] += c
            if args.per_load:
                print(row(f"  {os.path.basename(os.path.normpath(d))}/{p['load']}", *t["total"]))
    for s, (w, c) in sums.items():
        print(row(s, w, c))
    return 0


if __name__ == "__main__":
    sys.exit(main())
