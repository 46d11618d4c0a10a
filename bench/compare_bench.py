#!/usr/bin/python3
"""Two sheetgen binaries side by side in one run: per scene the wall, user and
system time, the page faults and the peak memory of each, their ratios, and
whether the parts are the same.

Usage: PYTHONPATH=tools /usr/bin/python3 bench/compare_bench.py --old OLD/sheetgen --new build/native/cli/sheetgen
           [--scenes avionics_bay,corner,...] [--repeat 1] [--threads 2] [--env-old K=V] [--env-new K=V]
           [--old-scenes OLD_COMMIT/sample_scenes]

The scenes are solved at their own settings (the default: every sample scene).
The two binaries alternate per scene (old first on odd repeats, new first on
even ones) so that a change in the machine's load between scenes falls on both;
with --repeat N each figure is the fastest of N runs. Parts are compared per
load: "same" when the tabs (corners, bends, thickness) agree to 1e-9 m,
otherwise the new part's mass against the old one's. Prints a Markdown table
for docs/benchmarks.md and exits 1 when a run fails. With --old-scenes the old
binary solves that folder's problem files (an older commit's scenes, e.g. before
the load envelopes) and the new one today's; the parts are then not compared.
"""
import argparse
import os
import platform
import sys

from sheetgen_tools import paths, runner


def rounded(x, digits=9):
    """x with every float rounded (to compare tab geometry written by two builds)."""
    if isinstance(x, float):
        return round(x, digits)
    if isinstance(x, dict):
        return {k: rounded(v, digits) for k, v in x.items()}
    if isinstance(x, list):
        return [rounded(v, digits) for v in x]
    return x


def part_change(old, new):
    """One load's parts compared: 'same', 'lighter x %', 'heavier x %', or what differs in status."""
    if old.get("status") != new.get("status"):
        return "status %s -> %s" % (old.get("status"), new.get("status"))
    if old.get("status") != "ok":
        return "no part in both"
    if rounded(old.get("tabs")) == rounded(new.get("tabs")):
        return "same"
    key = "mass_kg" if "mass_kg" in old and "mass_kg" in new else "area_m2"
    change = 100.0 * (new[key] / old[key] - 1.0)
    return "%s %+.2f %% (%s)" % ("lighter" if change < 0 else "heavier", change, key.split("_")[0])


def solve(binary, problem, threads, env):
    """One solve at the problem's own settings; SolveError when it did not finish."""
    options = runner.SolveOptions(threads=threads, sheetgen=binary, env=env)
    return runner.solve(problem, options=options).check()


def old_problem(scene, args):
    """The problem the old binary solves: the scene's own, or with --old-scenes that folder's."""
    return os.path.join(args.old_scenes, scene, "problem.json") if args.old_scenes else paths.scene_problem(scene)


def best(runs):
    """The fastest run of several of one binary on one scene."""
    return min(runs, key=lambda r: r.wall_s)


def compare_scene(scene, args):
    """(old run, new run) of one scene: the fastest of args.repeat each, the binaries alternating."""
    old, new = [], []
    for k in range(args.repeat):
        order = [("old", old), ("new", new)] if k % 2 == 0 else [("new", new), ("old", old)]
        for which, runs in order:
            binary, env = (args.old, args.env_old) if which == "old" else (args.new, args.env_new)
            problem = old_problem(scene, args) if which == "old" else paths.scene_problem(scene)
            runs.append(solve(binary, problem, args.threads, env))
    return best(old), best(new)


def parts_verdict(old, new, same_problem):
    """The parts column: per load the same or how it changed, or, when the two
    solved different problem files, only how many loads have a part."""
    if not same_problem:
        ok = lambda run: sum(p.get("status") == "ok" for p in run.parts)
        return "other problem files: old %d/%d parts, new %d/%d" % (ok(old), len(old.parts), ok(new), len(new.parts))
    changes = [part_change(a, b) for a, b in zip(old.parts, new.parts)]
    if len(old.parts) != len(new.parts):
        changes.append("%d loads against %d" % (len(old.parts), len(new.parts)))
    same = sum(c == "same" for c in changes)
    others = "; ".join("%s: %s" % (p["load"], c) for p, c in zip(new.parts, changes) if c != "same")
    return "%d/%d same%s" % (same, len(changes), ("; " + others) if others else "")


def row(scene, old, new, same_problem=True):
    """The Markdown row of one scene: times, faults, memory and the parts' verdict."""
    return ("| %s | %.1f | %.1f | **%.2f** | %.1f / %.1f | %.1f / %.1f | %.2f / %.2f | %.0f / %.0f | %s |" %
            (scene, old.wall_s, new.wall_s, old.wall_s / new.wall_s, old.user_s, new.user_s, old.system_s,
             new.system_s, old.minor_faults / 1e6, new.minor_faults / 1e6, old.peak_rss_mb, new.peak_rss_mb,
             parts_verdict(old, new, same_problem)))


def parse_env(pairs):
    """--env-old/--env-new K=V pairs as a dict (None when there are none)."""
    env = {}
    for pair in pairs or []:
        key, sep, value = pair.partition("=")
        if not sep:
            raise SystemExit("compare_bench: --env takes KEY=VALUE, got '%s'" % pair)
        env[key] = value
    return env or None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--old", required=True, help="the older sheetgen binary")
    ap.add_argument("--new", default=paths.DEFAULT_SHEETGEN, help="the sheetgen binary of this commit")
    ap.add_argument("--scenes", default=",".join(paths.sample_scene_names()))
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--env-old", action="append", help="KEY=VALUE added to the old binary's environment")
    ap.add_argument("--env-new", action="append", help="KEY=VALUE added to the new binary's environment")
    ap.add_argument("--old-scenes", help="a folder of scenes (e.g. an older commit's sample_scenes) whose "
                    "problem files the old binary solves, for a binary that cannot read today's")
    args = ap.parse_args()
    args.env_old, args.env_new = parse_env(args.env_old), parse_env(args.env_new)
    for label, binary in (("--old", args.old), ("--new", args.new)):
        if not os.access(binary, os.X_OK):
            raise SystemExit("compare_bench: %s %s is not an executable" % (label, binary))
    print("Machine: %s, %d cores; load average before: %.2f; old %s, new %s; fastest of %d" %
          (platform.machine(), os.cpu_count(), os.getloadavg()[0], args.old, args.new, args.repeat))
    print()
    print("| scene | old wall (s) | new wall (s) | ratio | user old / new (s) | system old / new (s) "
          "| minor faults old / new (M) | peak old / new (MiB) | parts |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    total_old = total_new = 0.0
    for scene in args.scenes.split(","):
        old, new = compare_scene(scene, args)
        total_old, total_new = total_old + old.wall_s, total_new + new.wall_s
        print(row(scene, old, new, same_problem=not args.old_scenes), flush=True)
    print()
    print("Total wall: old %.1f s, new %.1f s, ratio %.2f" % (total_old, total_new, total_old / total_new))


if __name__ == "__main__":
    try:
        main()
    except runner.SolveError as e:
        sys.exit(f"compare_bench: {e}")
