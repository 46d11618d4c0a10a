#!/usr/bin/python3
"""sheetgen-farm end to end with real processes (docs/farm.md, issue 36).

Every farm result is compared with a serial `sheetgen solve` of the same
problem and settings (2 threads; the farm's solves use 1): result.json
identical timing fields aside ("timing", keys ending in "_s", "threads";
"problem" compared as the absolute path it names) and every load's flat.dxf
byte for byte.

1. cluster: `dask scheduler` and two `dask worker` processes on 127.0.0.1,
   each in its own process group; the farm connects with --scheduler. One
   worker is killed (SIGKILL) while its sheetgen runs: its solver must die with
   it, its problem run again on the other worker, and every problem end with
   exactly one complete folder, no staging folder left. A missing and a
   malformed problem file ride along and fail alone, each with its one-line
   reason in summary.csv. Then a second farm client is killed outright
   (SIGKILL) while solves run: the workers stop them.
2. interrupt and resume (fast tier): a local-cluster run (one worker) gets
   SIGINT once its first problem is published: exit 130, the finished
   folders complete, no staging folder and no solver left; the same command
   again solves only the unfinished problems (the finished ones keep their
   farm.json byte for byte) and gives the serial answers.
3. an unreachable scheduler: one sentence on stderr, nothing on stdout, exit 1.

Fast tier: four small scenes at 2 chains x 50 iterations. --full: the ten
sample problems at their own settings on the cluster (check 1 only).

Run: PYTHONPATH=tools /usr/bin/python3 tests/python/test_farm.py --sheetgen build/native/cli/sheetgen [--full]
"""
import argparse
import csv
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

import psutil
from distributed import Client

from sheetgen_tools import paths, runner

FAST_SCENES = ["shelf", "slanted", "maze", "bulkhead_hole"]   # 3-6 s each at FAST_SEARCH on one thread
FAST_SEARCH = ["--chains", "2", "--iterations", "50"]
KILL_AFTER_S = {False: 1.0, True: 5.0}   # s a solve has run before its worker is killed (fast, full)
TOOLS = os.path.join(paths.ROOT, "tools")
DASK = shutil.which("dask", path="/usr/bin:" + os.environ.get("PATH", "")) or "dask"  # Debian's, beside /usr/bin/python3


class Checks:
    def __init__(self):
        self.failed = 0
        self.passed = 0

    def __call__(self, name, ok, detail=""):
        print(("ok    " if ok else "FAIL  ") + name + (f" ({detail})" if detail else ""), flush=True)
        self.passed += bool(ok)
        self.failed += not ok
        return ok


def answer(out_dir):
    """(result.json timing aside, {load: flat.dxf text})."""
    with open(os.path.join(out_dir, "result.json")) as f:
        doc = json.load(f)
    dxf = {}
    for part in doc["parts"]:
        path = os.path.join(out_dir, part["load"], "flat.dxf")
        if os.path.exists(path):
            with open(path) as f:
                dxf[part["load"]] = f.read()
    return runner.strip_timing(doc, out_dir), dxf


def serial_answers(problems, search, sheetgen, root):
    """{name: answer} of `sheetgen solve` run one after another, 2 threads."""
    out = {}
    flags = dict(zip(search[::2], search[1::2]))
    for name, problem in problems.items():
        options = runner.SolveOptions(threads=2, sheetgen=sheetgen, chains=flags.get("--chains"),
                                      iterations=flags.get("--iterations"))
        run = runner.solve(problem, os.path.join(root, name), options).check()
        print(f"   serial {name}: exit {run.exit_code}, {run.wall_s:.1f} s", flush=True)
        out[name] = (answer(run.out_dir), run.exit_code)
    return out


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class LocalhostCluster:
    """`dask scheduler` and `dask worker`s as separate processes on 127.0.0.1,
    the workers with this checkout's tools/ on their path (docs/farm.md)."""

    def __init__(self, workers, log_dir):
        self.n, self.log_dir, self.procs = workers, log_dir, []
        self.address = f"tcp://127.0.0.1:{free_port()}"
        self.workers = {}   # worker address -> Popen

    def _start(self, name, cmd):
        env = dict(os.environ, PYTHONPATH=TOOLS)
        log = open(os.path.join(self.log_dir, name + ".log"), "w")
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, env=env,
                                start_new_session=True)
        self.procs.append(proc)
        return proc

    def __enter__(self):
        port = self.address.rsplit(":", 1)[1]
        self._start("scheduler", [DASK, "scheduler", "--host", "127.0.0.1", "--port", port, "--no-dashboard"])
        by_name = {}
        for i in range(self.n):
            by_name[f"w{i}"] = self._start(f"worker{i}", [DASK, "worker", self.address, "--host", "127.0.0.1",
                                                          "--nthreads", "1", "--no-nanny", "--no-dashboard",
                                                          "--name", f"w{i}"])
        try:
            with Client(self.address, timeout=60) as client:
                client.wait_for_workers(self.n, timeout=120)
                for address, info in client.scheduler_info()["workers"].items():
                    self.workers[address] = by_name[info["name"]]
        except BaseException:
            self.__exit__()
            raise
        return self

    def __exit__(self, *exc):
        for proc in reversed(self.procs):
            if proc.poll() is None:
                proc.terminate()
        for proc in self.procs:
            try:
                proc.wait(20)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()


def solver_children(pid):
    """The sheetgen processes under a process (setpriv execs into sheetgen)."""
    try:
        return [c for c in psutil.Process(pid).children(recursive=True) if c.name() == "sheetgen"]
    except psutil.NoSuchProcess:
        return []


def solvers_writing(out_root):
    """Every sheetgen process whose --out lies under out_root."""
    found = []
    for p in psutil.process_iter(["name", "cmdline"]):
        if p.info["name"] == "sheetgen" and any(a.startswith(out_root) for a in p.info["cmdline"] or []):
            found.append(p)
    return found


def read_summary(out_root):
    with open(os.path.join(out_root, "summary.csv")) as f:
        return {row["problem"]: row for row in csv.DictReader(f)}


def staging_left(out_root):
    return [e for e in os.listdir(out_root) if ".farm-" in e]


def check_same_answers(check, out_root, serial, names, what):
    for name in names:
        farm = answer(os.path.join(out_root, name))
        check(f"{what}: {name} result.json and flat.dxf equal the serial solve", farm == serial[name][0])


def expected_exit(serial, names):
    return 2 if any(serial[n][1] == 2 for n in names) else 0


def bad_inputs(root):
    """{name: path} of a missing file and a malformed one (an unknown field, which the reader refuses)."""
    malformed = os.path.join(root, "malformed.json")
    with open(paths.scene_problem("shelf")) as f:
        doc = json.load(f)
    doc["requirments"] = {}
    with open(malformed, "w") as f:
        json.dump(doc, f)
    return {"missing": os.path.join(root, "missing.json"), "malformed": malformed}


def check_cluster(check, farm, problems, search, serial, root, full):
    """Check 1: a real scheduler and two workers, one killed mid-task."""
    out_root = os.path.join(root, "cluster")
    bad = bad_inputs(root)
    with LocalhostCluster(2, root) as cluster:
        cmd = [farm, *problems.values(), *bad.values(), "--out", out_root, "--scheduler", cluster.address,
               "--workers", "2", *search]
        t0 = time.monotonic()
        proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
        victim, solver, ran = None, None, 0.0
        while proc.poll() is None and victim is None:
            for address, worker in cluster.workers.items():
                for child in solver_children(worker.pid):
                    ran = time.time() - child.create_time()
                    if ran >= KILL_AFTER_S[full]:
                        victim, solver = address, child
            time.sleep(0.1)
        problem_killed = None
        if victim:
            problem_killed = next(name for name in problems if f"/.{name}.farm-" in " ".join(solver.cmdline()))
            os.kill(cluster.workers[victim].pid, signal.SIGKILL)
            print(f"   killed worker {victim} after its sheetgen on {problem_killed} ran {ran:.1f} s", flush=True)
        stdout, stderr = proc.communicate(timeout=7200)
        wall = time.monotonic() - t0
        print(stdout + stderr, flush=True)
        check_client_killed(check, farm, problems, search, cluster, os.path.join(root, "client_killed"))
    check("cluster: a worker was killed while its sheetgen ran", victim is not None)
    if victim:
        check("cluster: the killed worker's sheetgen died with it", not solver.is_running())
    good = list(problems)
    check("cluster: exit 3 (the bad inputs failed), the rest as the serial solves",
          proc.returncode == 3, f"exit {proc.returncode}, {wall:.0f} s")
    summary = read_summary(out_root)
    check("cluster: summary.csv has one row per problem", sorted(summary) == sorted(good + list(bad)))
    for name in good:
        record = json.load(open(os.path.join(out_root, name, "farm.json")))
        check(f"cluster: {name} complete, solved once this run", record["status"] == "solved"
              and summary.get(name, {}).get("run") == "this run"
              and os.path.isfile(os.path.join(out_root, name, "result.json")))
    if problem_killed:
        record = json.load(open(os.path.join(out_root, problem_killed, "farm.json")))
        check(f"cluster: {problem_killed} was run again on the surviving worker", record["worker"] != victim,
              record["worker"])
    check("cluster: no staging folder left", not staging_left(out_root), ", ".join(staging_left(out_root)))
    check_same_answers(check, out_root, serial, good, "cluster")
    for name, path in bad.items():
        row = summary.get(name, {})
        reason = row.get("reason", "")
        check(f"cluster: {name} failed alone with a one-line reason naming the file",
              row.get("status") == "failed" and "\n" not in reason and path in reason
              and not os.path.exists(os.path.join(out_root, name)), reason)
    check("cluster: the malformed file's reason is sheetgen's (the unknown field)",
          "requirments" in summary.get("malformed", {}).get("reason", ""))


def check_client_killed(check, farm, problems, search, cluster, out_root):
    """Check 1b: a farm client killed outright (SIGKILL, no clean-up of its own) stops its solves on the
    workers: the scheduler releases its tasks and each task stops its solver."""
    cmd = [farm, *problems.values(), "--out", out_root, "--scheduler", cluster.address, *search]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    while proc.poll() is None and not solvers_writing(out_root):
        time.sleep(0.1)
    running = len(solvers_writing(out_root))
    proc.kill()
    proc.wait()
    t0 = time.monotonic()
    while solvers_writing(out_root) and time.monotonic() - t0 < 30:
        time.sleep(0.1)
    left = solvers_writing(out_root)
    check("client killed: its running solves on the workers stop", running and not left,
          f"{running} running, stopped in {time.monotonic() - t0:.1f} s")
    time.sleep(1.0)  # the tasks remove their staging folders after their solver ends
    check("client killed: no staging folder left", not staging_left(out_root), ", ".join(staging_left(out_root)))


def check_interrupt_resume(check, farm, problems, search, serial, root):
    """Check 2: SIGINT once the first problem is published, then the same command again."""
    out_root = os.path.join(root, "resume")
    cmd = [farm, *problems.values(), "--out", out_root, "--workers", "1", *search]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    while proc.poll() is None and not any(os.path.isfile(os.path.join(out_root, n, "farm.json")) for n in problems):
        time.sleep(0.1)
    time.sleep(0.5)  # let the next problem's solver start: the interrupt must stop a running solve
    running = solvers_writing(out_root)
    t0 = time.monotonic()
    proc.send_signal(signal.SIGINT)
    stdout, stderr = proc.communicate(timeout=120)
    stop_s = time.monotonic() - t0
    print(stdout + stderr, flush=True)
    check("interrupt: exit 130", proc.returncode == 130, f"exit {proc.returncode}, stopped in {stop_s:.1f} s")
    check("interrupt: a solve was running when SIGINT came", bool(running))
    check("interrupt: no sheetgen left running", not solvers_writing(out_root))
    check("interrupt: no staging folder left", not staging_left(out_root), ", ".join(staging_left(out_root)))
    done = [n for n in problems if os.path.isdir(os.path.join(out_root, n))]
    check("interrupt: some but not all problems finished", 0 < len(done) < len(problems), ", ".join(done))
    summary = read_summary(out_root)
    check("interrupt: summary.csv marks the others cancelled",
          all(summary[n]["status"] == "cancelled" for n in problems if n not in done))
    before = {n: open(os.path.join(out_root, n, "farm.json"), "rb").read() for n in done}

    rerun = subprocess.run(cmd, capture_output=True, text=True, timeout=1800)
    print(rerun.stdout + rerun.stderr, flush=True)
    check("resume: exit as the serial solves", rerun.returncode == expected_exit(serial, problems),
          f"exit {rerun.returncode}")
    summary = read_summary(out_root)
    again = sorted(n for n in problems if summary[n]["run"] == "this run")
    check("resume: exactly the unfinished problems solved again",
          again == sorted(set(problems) - set(done)), ", ".join(again))
    check("resume: the finished problems' farm.json untouched",
          all(open(os.path.join(out_root, n, "farm.json"), "rb").read() == before[n] for n in done))
    check_same_answers(check, out_root, serial, problems, "resume")


def check_unreachable(check, farm, root):
    """Check 3: nobody listens on the port."""
    address = f"tcp://127.0.0.1:{free_port()}"
    run = subprocess.run([farm, paths.scene_problem("shelf"), "--out", os.path.join(root, "unreachable"),
                          "--scheduler", address, "--connect-timeout", "2"], capture_output=True, text=True, timeout=120)
    lines = run.stderr.strip().splitlines()
    check("unreachable scheduler: exit 1, one line on stderr naming the address, nothing on stdout",
          run.returncode == 1 and len(lines) == 1 and address in lines[0] and not run.stdout, run.stderr.strip())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sheetgen", required=True)
    ap.add_argument("--farm", help="default: sheetgen-farm beside --sheetgen")
    ap.add_argument("--full", action="store_true", help="the ten sample problems at their own settings (check 1 only)")
    ap.add_argument("--keep", help="work in this folder and keep it")
    args = ap.parse_args()
    sheetgen = os.path.abspath(args.sheetgen)
    farm = os.path.abspath(args.farm or os.path.join(os.path.dirname(sheetgen), "sheetgen-farm"))
    scenes = paths.sample_scene_names() if args.full else FAST_SCENES
    search = [] if args.full else FAST_SEARCH
    problems = {s: paths.scene_problem(s) for s in scenes}
    root = args.keep or tempfile.mkdtemp(prefix="sheetgen_farm_test_")
    os.makedirs(root, exist_ok=True)
    check = Checks()
    t0 = time.monotonic()
    try:
        serial = serial_answers(problems, search, sheetgen, os.path.join(root, "serial"))
        check_cluster(check, farm, problems, search, serial, root, args.full)
        if not args.full:
            check_interrupt_resume(check, farm, problems, search, serial, root)
            check_unreachable(check, farm, root)
    finally:
        if not args.keep:
            shutil.rmtree(root, ignore_errors=True)
    print(f"farm{' (full)' if args.full else ''}: {check.passed} passed, {check.failed} failed, "
          f"{time.monotonic() - t0:.0f} s")
    return 1 if check.failed else 0


if __name__ == "__main__":
    sys.exit(main())
