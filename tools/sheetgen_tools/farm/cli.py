"""`sheetgen-farm`: many problem files solved at once on a Dask cluster
(docs/farm.md). The build installs it beside `sheetgen`
(build/native/cli/sheetgen-farm, from native/cli/sheetgen-farm.in).

Exit codes: 0 every load of every problem has a part; 2 every problem solved
but some load has none; 3 some problem failed (bad input, timeout, crash);
1 the farm cannot run (bad arguments, unreachable scheduler, unusable output
folder); 130 interrupted (Ctrl-C or SIGTERM).
"""
import argparse
import os
import sys

from .. import paths, runner
from . import run as farm_run
from . import summary as farm_summary

EXAMPLE = """examples:
  sheetgen-farm sample_scenes/*/problem.json --out out/farm
  sheetgen-farm @bay_list.txt --out /shared/run1 --scheduler tcp://head:8786 --threads-per-task 2 --timeout 3600
"""


def parser(default_sheetgen):
    ap = argparse.ArgumentParser(
        prog="sheetgen-farm", fromfile_prefix_chars="@", epilog=EXAMPLE, formatter_class=argparse.RawDescriptionHelpFormatter,
        description="Solve many problem files at once on a Dask cluster: `sheetgen solve` per problem, "
                    "each in its own process, into DIR/<problem>/; re-running resumes.")
    ap.add_argument("problems", nargs="+", metavar="PROBLEM.json",
                    help="problem files (@FILE reads more, one per line); the output folder of a/b/x.json is DIR/x, "
                         "of a/b/problem.json DIR/b")
    ap.add_argument("--out", required=True, metavar="DIR", help="output folder (on a file system every worker shares)")
    ap.add_argument("--scheduler", metavar="ADDRESS", help="a Dask scheduler (tcp://host:8786); default: a local cluster")
    ap.add_argument("--workers", type=int, metavar="N",
                    help="local cluster: solves at once (default: cores / threads per task); "
                         "with --scheduler: wait for N workers before starting (default 1)")
    ap.add_argument("--threads-per-task", type=int, default=1, metavar="T", help="sheetgen --threads of each solve (default 1)")
    ap.add_argument("--timeout", type=float, metavar="S", help="seconds one solve may take (default: no limit)")
    ap.add_argument("--connect-timeout", type=float, default=10.0, metavar="S", help="seconds to reach the scheduler (default 10)")
    ap.add_argument("--retries", type=int, default=1, metavar="R",
                    help="runs again of a solve killed by a signal (out of memory, crash); default 1")
    ap.add_argument("--force", action="store_true", help="solve every problem again, even those a previous run finished")
    ap.add_argument("--sheetgen", default=default_sheetgen, metavar="PATH",
                    help=f"the sheetgen binary, at the same path on every worker (default {default_sheetgen})")
    search = ap.add_argument_group("search settings, passed to every `sheetgen solve` (default: each problem's own)")
    for flag, metavar in (("--seed", "S"), ("--chains", "M"), ("--iterations", "N"), ("--beam", "B")):
        search.add_argument(flag, type=int, metavar=metavar)
    for flag in ("--right-angles", "--flat-extensions", "--no-self-rivet", "--no-lips", "--no-web-roots", "--no-flat-fallback",
                 "--no-right-angle-pass", "--no-right-angle-search", "--no-sizing"):
        search.add_argument(flag, action="store_true")
    return ap


def options_of(args):
    """FarmOptions of the parsed arguments; argparse's error (exit 1 via main) on a value out of range."""
    for name in ("workers", "threads_per_task", "timeout", "connect_timeout"):
        value = getattr(args, name)
        if value is not None and value <= 0:
            raise ValueError(f"--{name.replace('_', '-')} must be positive, not {value}")
    if args.retries < 0:
        raise ValueError(f"--retries must be 0 or more, not {args.retries}")
    flags = tuple(f"--{name.replace('_', '-')}" for name in ("right_angles", "flat_extensions", "no_self_rivet",
                                                            "no_lips", "no_web_roots", "no_flat_fallback",
                                                            "no_right_angle_pass", "no_right_angle_search", "no_sizing")
                  if getattr(args, name))
    solve = runner.SolveOptions(threads=args.threads_per_task, chains=args.chains, iterations=args.iterations,
                                seed=args.seed, beam=args.beam, flags=flags, sheetgen=os.path.abspath(args.sheetgen))
    return farm_run.FarmOptions(out_root=args.out, solve=solve, scheduler=args.scheduler, workers=args.workers,
                                timeout_s=args.timeout, connect_timeout_s=args.connect_timeout, retries=args.retries,
                                force=args.force)


def main(argv=None, default_sheetgen=paths.DEFAULT_SHEETGEN):
    farm_run.interrupt_on_sigterm()
    ap = parser(default_sheetgen)
    try:
        args = ap.parse_args(argv)
        options = options_of(args)
    except SystemExit as e:
        return 0 if e.code == 0 else 1   # --help, or argparse's own message
    except ValueError as e:
        print(f"sheetgen-farm: {e}", file=sys.stderr)
        return 1
    try:
        result = farm_run.run_farm(args.problems, options)
    except farm_run.FarmError as e:
        print(f"sheetgen-farm: {e}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("sheetgen-farm: interrupted", file=sys.stderr)
        return 130
    print(farm_summary.table(result.rows))
    c = farm_summary.counts(result.rows)
    print(f"sheetgen-farm: {len(result.rows)} problems: " + ", ".join(f"{n} {s}" for s, n in sorted(c.items())) +
          f"; {result.solved_this_run} solved this run; {result.wall_s:.0f} s; {result.csv_path}")
    return result.exit_code
