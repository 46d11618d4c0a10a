"""`sheetgen solve` as a function: the one place the tools run the solver and
read its result.json.

    run = runner.solve(paths.scene_problem("corner"), out_dir, runner.SolveOptions(chains=4, iterations=200))
    run.check()                 # SolveError unless sheetgen exited 0 or 2 and wrote result.json
    run.result["parts"][0]["area_m2"]

The solver's own peak memory and CPU time come from os.wait4 (the kernel's
count for that process alone), for the benchmarks.
"""
import dataclasses
import json
import os
import subprocess
import tempfile
import time
from typing import Optional

from . import paths

# sheetgen's exit codes (docs/pipeline.md): 0 every load has a part, 2 some
# load has none, 1 bad input, 3 internal error, 130 interrupted.
FINISHED = (0, 2)


class SolveError(RuntimeError):
    """sheetgen did not finish (exit code other than 0 or 2, or no result.json)."""


@dataclasses.dataclass
class SolveOptions:
    threads: int = 2                  # worker threads: the machine is shared, one solve at a time on 2 cores
    chains: Optional[int] = None      # MCMC chains; None keeps the problem's search.chains
    iterations: Optional[int] = None  # iterations per chain; None keeps search.iterations
    seed: Optional[int] = None        # None keeps search.seed
    beam: Optional[int] = None        # beam width of the composition; None keeps search.beam_width
    flags: tuple = ()                 # further `sheetgen solve` flags, e.g. ("--right-angles",)
    env: Optional[dict] = None        # variables added to the solver's environment
    log: Optional[str] = None         # a file that gets stdout and stderr as they come (to follow a long run)
    sheetgen: str = paths.DEFAULT_SHEETGEN


@dataclasses.dataclass
class SolveRun:
    problem: str
    out_dir: str
    command: list
    exit_code: int
    wall_s: float                     # s, the whole run
    cpu_s: float                      # s, user + system time of the solver process
    user_s: float                     # s, user time of the solver process
    system_s: float                   # s, system time (the kernel's: page faults, mmap/munmap)
    minor_faults: int                 # pages the kernel handed out (ru_minflt)
    peak_rss_mb: float                # MiB, the solver's peak resident memory
    stdout: str                       # with SolveOptions.log: the log, both streams interleaved
    stderr: str                       # with SolveOptions.log: empty
    result: Optional[dict]            # result.json, None when the run wrote none

    @property
    def finished(self):
        return self.exit_code in FINISHED and self.result is not None

    @property
    def parts(self):
        return self.result["parts"] if self.result else []

    def check(self):
        """self, or SolveError naming the problem, the exit code and the end of the solver's output."""
        if not self.finished:
            tail = (self.stdout + self.stderr)[-2000:]
            missing = " without writing result.json" if self.exit_code in FINISHED else ""
            raise SolveError(f"{self.problem}: sheetgen exited {self.exit_code}{missing}:\n{tail}")
        return self


def command(problem, out_dir, options):
    """The `sheetgen solve` command line of a run."""
    cmd = [options.sheetgen, "solve", problem, "--out", out_dir, "--threads", str(options.threads)]
    for flag, value in (("--chains", options.chains), ("--iterations", options.iterations), ("--seed", options.seed),
                        ("--beam", options.beam)):
        if value is not None:
            cmd += [flag, str(value)]
    return cmd + list(options.flags)


def solve(problem, out_dir=None, options=None):
    """Runs `sheetgen solve PROBLEM --out OUT_DIR` (a fresh temporary folder
    when out_dir is None) and returns a SolveRun whatever the exit code."""
    options = options or SolveOptions()
    if not os.path.isfile(options.sheetgen):
        raise SolveError(f"sheetgen not found at {options.sheetgen} (cmake --build build --target sheetgen)")
    out_dir = out_dir or tempfile.mkdtemp(prefix="sheetgen_solve_")
    cmd = command(problem, out_dir, options)
    env = dict(os.environ, **options.env) if options.env else None
    with tempfile.TemporaryDirectory() as tmp:
        out_path = options.log or os.path.join(tmp, "stdout")
        err_path = os.path.join(tmp, "stderr")
        t0 = time.monotonic()
        with open(out_path, "w") as out, open(err_path, "w") as err:
            proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=out,
                                    stderr=subprocess.STDOUT if options.log else err, env=env)
            _, status, usage = os.wait4(proc.pid, 0)
        wall = time.monotonic() - t0
        proc.returncode = code = os.waitstatus_to_exitcode(status)  # reaped by wait4: tell Popen
        stdout, stderr = open(out_path).read(), open(err_path).read()
    result_path = os.path.join(out_dir, "result.json")
    result = None
    if os.path.isfile(result_path):
        with open(result_path) as f:
            result = json.load(f)
    return SolveRun(problem=problem, out_dir=out_dir, command=cmd, exit_code=code, wall_s=wall,
                    cpu_s=usage.ru_utime + usage.ru_stime, user_s=usage.ru_utime, system_s=usage.ru_stime,
                    minor_faults=usage.ru_minflt, peak_rss_mb=usage.ru_maxrss / 1024.0,
                    stdout=stdout, stderr=stderr, result=result)


def strip_timing(doc, out_dir):
    """result.json `doc` without what differs between equal runs (timing, threads,
    every "*_s" field) and with its problem path made absolute against `out_dir`,
    so that runs on other machines or thread counts compare equal."""
    def strip(x):
        if isinstance(x, dict):
            return {k: strip(v) for k, v in x.items() if k not in ("timing", "threads") and not k.endswith("_s")}
        if isinstance(x, list):
            return [strip(v) for v in x]
        return x
    doc = strip(doc)
    doc["problem"] = os.path.normpath(os.path.join(out_dir, doc["problem"]))
    return doc
