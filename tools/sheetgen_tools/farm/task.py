"""One problem of a farm run, on a Dask worker: `sheetgen solve` in its own
process, with a timeout, into a staging folder renamed into place when the
solve has finished (docs/farm.md "Tasks").

Everything here runs on the worker; the client only builds SolveTask values
and reads TaskRecord values back. Workers therefore need this package on
their path (PYTHONPATH=<checkout>/tools) and the same file system as the
client (docs/farm.md "Workers").

A task returns a TaskRecord for every outcome of the solver, bad input, a
timeout and a cancellation included; it raises only when the solver was killed
by a signal that was not ours (SolverCrashed: an out-of-memory kill, a
segfault) or the file system failed, which Dask's `retries` then re-runs.
A worker that dies mid-task is the scheduler's business: it runs the task
again elsewhere (`distributed.scheduler.allowed-failures`), and the solver of
the dead worker dies with it (setpriv --pdeathsig), so two attempts never
write the same folder. A task whose client cancels it or goes away (Ctrl-C,
a killed client) sees the scheduler release it and stops its solver: Dask
cannot stop a running task's thread, so the task watches for that itself.
"""
import dataclasses
import datetime
import errno
import json
import os
import shutil
import signal
import socket
import subprocess
import threading
import time
import uuid
from typing import Optional

import distributed
from distributed.worker import thread_state

from .. import runner

TASK_FORMAT = "sheetgen-farm-task/1"
RECORD_FILE = "farm.json"        # in DIR/<name>/ beside result.json: how and from what it was solved
LOG_FILE = "solve.log"           # sheetgen's stdout and stderr, in the same folder
FAILED_LOG = ".failed.log"       # DIR/<name>.failed.log: the log of a problem that failed (removed once it solves)
STAGING_MARK = ".farm-"          # staging folders are DIR/.<name>.farm-<run>-<attempt>
POLL_S = 0.2                     # s, how often a task looks at its solver
TERM_GRACE_S = 10.0              # s, SIGTERM to SIGKILL; sheetgen stops within a second of SIGTERM


class SolverCrashed(RuntimeError):
    """sheetgen was killed by a signal nobody here sent; Dask's retries run it again."""


@dataclasses.dataclass(frozen=True)
class SolveTask:
    """What to solve: one problem into DIR/<name>/. Paths are absolute and the
    same on every worker (a shared file system)."""
    problem: str                     # the problem file
    name: str                        # the output folder's name under out_root
    out_root: str                    # DIR of `sheetgen-farm --out DIR`
    options: runner.SolveOptions     # the `sheetgen solve` command: binary, threads, search settings
    settings: dict                   # the settings that decide the answer (plan.solve_settings), for resume
    inputs_sha256: str               # the problem file and its mesh files (plan.inputs_sha256), for resume
    run_id: str                      # this farm run; names staging folders and the record
    timeout_s: Optional[float] = None  # s, wall time of the solve; None = no limit


@dataclasses.dataclass
class TaskRecord:
    """What became of one task; written as DIR/<name>/farm.json when the solve finished."""
    name: str
    problem: str
    status: str                      # "solved" (sheetgen exit 0 or 2, result.json written), "failed" or "cancelled"
    reason: str = ""                 # one line when not solved
    exit_code: Optional[int] = None  # sheetgen's exit code; None when it did not run or was killed
    wall_s: float = 0.0              # s, the solver process
    cpu_s: float = 0.0               # s, user + system time of the solver process
    peak_rss_mb: float = 0.0         # MiB, the solver's peak resident memory
    worker: str = ""                 # host:pid of the Dask worker that ran it
    run_id: str = ""
    inputs_sha256: str = ""
    settings: dict = dataclasses.field(default_factory=dict)
    command: list = dataclasses.field(default_factory=list)
    finished_at: str = ""            # UTC, ISO 8601

    def to_json(self):
        return dict(format=TASK_FORMAT, **dataclasses.asdict(self))

    @staticmethod
    def from_json(doc):
        fields = {f.name for f in dataclasses.fields(TaskRecord)}
        return TaskRecord(**{k: v for k, v in doc.items() if k in fields})


def read_record(folder):
    """The TaskRecord of a finished folder DIR/<name>/, or None when it has none (not a farm result)."""
    try:
        with open(os.path.join(folder, RECORD_FILE)) as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return None
    return TaskRecord.from_json(doc) if doc.get("format") == TASK_FORMAT else None


def staging_prefix(name, run_id=""):
    """The start of the staging folder names of a problem (of one run when run_id is given)."""
    return f".{name}{STAGING_MARK}{run_id}"


# The solvers running in this worker process, by farm run, so that stop_run
# can end them (client.run reaches every worker outside the task queue).
_lock = threading.Lock()
_running = {}           # run id -> set of subprocess.Popen
_stopped = set()        # run ids stopped here: a task that starts later does not start its solver


def stop_run(run_id):
    """Ends every solver of a run on this worker (SIGTERM, then SIGKILL after
    TERM_GRACE_S) and waits for them; the run's tasks then return "cancelled".
    Called by the client through client.run on Ctrl-C. Returns how many it stopped."""
    with _lock:
        _stopped.add(run_id)
        procs = list(_running.get(run_id, ()))
    for proc in procs:
        proc.terminate()
    deadline = time.monotonic() + TERM_GRACE_S
    for proc in procs:
        while proc.poll() is None and time.monotonic() < deadline:  # the task's thread reaps it; poll only looks
            time.sleep(POLL_S)
        if proc.poll() is None:
            proc.kill()
    return len(procs)


def check_worker(sheetgen):
    """"" when this worker can run tasks, else the one-line reason (called through client.run before submitting)."""
    if not os.access(sheetgen, os.X_OK):
        return f"{socket.gethostname()}: no executable sheetgen at {sheetgen} (the workers need the client's paths)"
    if shutil.which("setpriv") is None:
        return f"{socket.gethostname()}: setpriv (util-linux) is missing"
    return ""


def _worker_name():
    """The Dask worker's address (host:pid outside a worker)."""
    try:
        return distributed.get_worker().address
    except ValueError:  # not inside a Dask worker
        return f"{socket.gethostname()}:{os.getpid()}"


@dataclasses.dataclass
class _Process:
    exit_code: int                   # as subprocess reports it: negative for a signal
    wall_s: float
    cpu_s: float
    peak_rss_mb: float
    stopped: str                     # "" when it ran to its end, else "timeout" or "released"


def _released_by_scheduler():
    """A function telling whether the scheduler has released the calling task
    (its client cancelled it or went away): Dask cannot stop a running task's
    thread and only marks it, so the task asks. Outside a worker: never."""
    try:
        worker, key = distributed.get_worker(), thread_state.key
    except (ValueError, AttributeError):
        return lambda: False
    tasks = getattr(worker, "state", worker).tasks
    return lambda: key not in tasks or tasks[key].state in ("cancelled", "released", "forgotten")


def _run_solver(cmd, log, timeout_s, run_id):
    """Runs cmd to its end, its timeout or its release, with its output in log;
    None when the run was stopped before it began."""
    released = _released_by_scheduler()
    # setpriv --pdeathsig: the solver gets SIGKILL when this worker thread dies
    # (a killed worker must not leave a solver writing). A new session keeps a
    # terminal's Ctrl-C away from it: the client stops it (stop_run).
    with _lock:
        if run_id in _stopped:
            return None
        t0 = time.monotonic()
        proc = subprocess.Popen(["setpriv", "--pdeathsig", "KILL", "--"] + cmd, stdin=subprocess.DEVNULL,
                                stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
        _running.setdefault(run_id, set()).add(proc)
    stopped, kill_at = "", None
    try:
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            now = time.monotonic()
            if not stopped:
                stopped = ("timeout" if timeout_s is not None and now - t0 > timeout_s else
                           "released" if released() else "")
                if stopped:
                    proc.terminate()
                    kill_at = now + TERM_GRACE_S
            if kill_at is not None and now > kill_at:
                proc.kill()
            time.sleep(POLL_S)
    finally:
        with _lock:
            _running[run_id].discard(proc)
    proc.returncode = code = os.waitstatus_to_exitcode(status)  # reaped by wait4: tell Popen
    return _Process(exit_code=code, wall_s=time.monotonic() - t0, cpu_s=usage.ru_utime + usage.ru_stime,
                    peak_rss_mb=usage.ru_maxrss / 1024.0, stopped=stopped)


def _last_line(path):
    """The last non-empty line of sheetgen's log: its one-line error on bad input."""
    try:
        with open(path, errors="replace") as f:
            lines = [line.strip() for line in f.read().replace("\r", "\n").splitlines() if line.strip()]
    except OSError:
        return ""
    return lines[-1] if lines else ""


def _publish(staging, task, record):
    """Renames the finished staging folder to DIR/<name>/. When a folder of
    this run is already there (a second attempt of the task, e.g. after its
    worker was declared dead but finished), this attempt is dropped and the
    first one's record returned; a folder of an earlier run is replaced."""
    with open(os.path.join(staging, RECORD_FILE), "w") as f:
        json.dump(record.to_json(), f, indent=1)
    final = os.path.join(task.out_root, task.name)
    try:
        os.rename(staging, final)
        return record
    except OSError as e:
        if e.errno not in (errno.ENOTEMPTY, errno.EEXIST):
            raise
    earlier = read_record(final)
    if earlier is not None and earlier.run_id == task.run_id:
        shutil.rmtree(staging, ignore_errors=True)
        return earlier
    old = staging + "-replaced"
    os.rename(final, old)
    os.rename(staging, final)
    shutil.rmtree(old, ignore_errors=True)
    return record


def solve_task(task):
    """Solves one problem (the Dask task): a TaskRecord, or SolverCrashed for Dask to retry."""
    record = TaskRecord(name=task.name, problem=task.problem, status="failed", worker=_worker_name(),
                        run_id=task.run_id, inputs_sha256=task.inputs_sha256, settings=task.settings)
    staging = os.path.join(task.out_root, staging_prefix(task.name, task.run_id) + "-" + uuid.uuid4().hex[:8])
    os.makedirs(staging)
    published = False
    try:
        record.command = cmd = runner.command(task.problem, staging, task.options)
        log_path = os.path.join(staging, LOG_FILE)
        with open(log_path, "w") as log:
            ran = _run_solver(cmd, log, task.timeout_s, task.run_id)
        record.finished_at = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
        if ran is None:
            record.status, record.reason = "cancelled", "the run was interrupted before this problem started"
            return record
        record.wall_s, record.cpu_s, record.peak_rss_mb = ran.wall_s, ran.cpu_s, ran.peak_rss_mb
        record.exit_code = ran.exit_code if ran.exit_code >= 0 else None
        if ran.stopped == "timeout":
            record.reason = f"timed out after {task.timeout_s:g} s"
        elif ran.stopped == "released" or task.run_id in _stopped:
            record.status, record.reason = "cancelled", "interrupted"
        elif ran.exit_code < 0:
            raise SolverCrashed(f"{task.name}: sheetgen was killed by {signal.Signals(-ran.exit_code).name} "
                                f"after {ran.wall_s:.0f} s on {record.worker}")
        elif ran.exit_code in runner.FINISHED and os.path.isfile(os.path.join(staging, "result.json")):
            record.status = "solved"
            record = _publish(staging, task, record)
            published = True
        else:
            line = _last_line(log_path) or "no output"
            record.reason = f"sheetgen exited {ran.exit_code}: {line}"
        if record.status == "failed":
            shutil.copyfile(log_path, os.path.join(task.out_root, task.name + FAILED_LOG))
        return record
    finally:
        if not published:
            shutil.rmtree(staging, ignore_errors=True)
