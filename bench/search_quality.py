#!/usr/bin/python3
"""How good the default search is, load by load: its part's cost against the
best part known for the load, and the spread of the cost over seeds.

* Default runs: each scene at its own settings (10 chains x 1000 iterations,
  beam 8) with each seed of --seeds. The problem's own seed (1) is the
  default result.
* Longer runs: the same with --factor times the iterations, at each seed of
  --long-seeds.
* The best-known part of a load is the cheapest valid part of all those runs.

Cost is result.json's `cost.total` (USD, docs/cost.md), the quantity the
search minimises. A load whose default run has no part says so; the spread
is over the seeds that found one.

    PYTHONPATH=tools /usr/bin/python3 bench/search_quality.py [--scenes a,b] [--seeds 1-5] [--long-seeds 1-5]
        [--factor 10] [--jobs 2] [--out DIR] [--reuse] [--sheetgen S]

Each run keeps its output folder, OUT/<scene>/<seed>x<factor>/, so
`python3 -m sheetgen_tools.verify` can check its parts; --reuse reads a run's
result.json where one exists. --jobs N solves N problems at once with one
thread each (a solve's parts do not depend on its thread count: docs/discovery.md,
docs/pipeline.md).
Prints a Markdown table (and writes it to OUT/search_quality.md).
"""
import argparse
import json
import os
import statistics
import sys
from concurrent.futures import ThreadPoolExecutor

from sheetgen_tools import paths, runner
from sheetgen_tools.scenes import LIBRARY


def seed_list(text):
    """'1-5' or '1,3,4' as a list of ints."""
    if "-" in text:
        first, last = text.split("-")
        return list(range(int(first), int(last) + 1))
    return [int(s) for s in text.split(",") if s]


def iterations_of(scene):
    """The scene's own search.iterations (per chain)."""
    with open(paths.scene_problem(scene), encoding="utf-8") as f:
        return json.load(f).get("search", {}).get("iterations", 1000)


def run(args, scene, seed, factor):
    """One solve (or its kept result with --reuse): {load: cost in USD or None}."""
    out = os.path.join(args.out, scene, "%dx%d" % (seed, factor))
    result_path = os.path.join(out, "result.json")
    if not (args.reuse and os.path.exists(result_path)):
        options = runner.SolveOptions(threads=1, seed=seed, iterations=iterations_of(scene) * factor,
                                      sheetgen=args.sheetgen)
        runner.solve(paths.scene_problem(scene), out, options).check()
    with open(result_path, encoding="utf-8") as f:
        parts = json.load(f)["parts"]
    return {p["load"]: (p["cost"]["total"] if p.get("status") == "ok" else None) for p in parts}


def all_runs(args, scenes):
    """{(scene, seed, factor): {load: cost}} of every default and longer run, --jobs at a time."""
    jobs = [(s, seed, 1) for s in scenes for seed in args.seeds]
    jobs += [(s, seed, args.factor) for s in scenes for seed in args.long_seeds]
    jobs = list(dict.fromkeys(jobs))  # --factor 1 repeats the default runs
    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        costs = list(pool.map(lambda j: run(args, *j), jobs))
    return dict(zip(jobs, costs))


def load_row(args, scene, load, runs):
    """The Markdown row of one load and whether its default part is within 5 % of the best-known."""
    default = {seed: runs[(scene, seed, 1)][load] for seed in args.seeds}
    longer = {seed: runs[(scene, seed, args.factor)][load] for seed in args.long_seeds}
    found = [c for c in default.values() if c is not None]
    known = [(c, "seed %d" % s) for s, c in default.items() if c is not None]
    known += [(c, "seed %d, %d x iterations" % (s, args.factor)) for s, c in longer.items() if c is not None]
    own = default.get(args.seeds[0])
    if not known:
        return "| %s | %s | no part | 0 of %d | – | – | no part in any run |" % (scene, load, len(args.seeds)), None
    best, where = min(known)
    spread = ("%.2f / %.2f / %.2f" % (min(found), statistics.median(found), max(found))) if found else "–"
    gap = (own / best - 1.0) if own is not None else None
    return ("| %s | %s | %s | %d of %d | %s | %.2f (%s) | %s |" %
            (scene, load, "%.2f" % own if own is not None else "no part", len(found), len(args.seeds), spread, best,
             where, "%+.1f %%" % (100 * gap) if gap is not None else "–")), gap


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scenes", default=",".join(s for s in LIBRARY if s != "avionics_bay"),
                    help="default: every single-load scene (the bay takes about 7 minutes a run)")
    ap.add_argument("--seeds", type=seed_list, default=seed_list("1-5"))
    ap.add_argument("--long-seeds", type=seed_list, default=seed_list("1-5"))
    ap.add_argument("--factor", type=int, default=10, help="iterations of the longer runs, times the scene's own")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--out", default=os.path.join(paths.DEFAULT_BUILD, "search_quality"))
    ap.add_argument("--reuse", action="store_true")
    ap.add_argument("--sheetgen", default=paths.DEFAULT_SHEETGEN)
    args = ap.parse_args()
    scenes = args.scenes.split(",")
    runs = all_runs(args, scenes)
    lines = ["| scene | load | default cost (USD, seed %d) | seeds with a part | min / median / max over the seeds "
             "| best-known (run) | default vs best-known |" % args.seeds[0], "|" + " --- |" * 7]
    gaps = []
    for scene in scenes:
        for load in runs[(scene, args.seeds[0], 1)]:
            line, gap = load_row(args, scene, load, runs)
            lines.append(line)
            gaps.append(gap)
    with_part = [g for g in gaps if g is not None]
    within = sum(1 for g in with_part if g <= 0.05)
    lines += ["", "%d of the %d loads with a default part (of %d loads) are within 5 %% of the best-known part." %
              (within, len(with_part), len(gaps))]
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "search_quality.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"search_quality: {e}")
