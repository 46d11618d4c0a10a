"""A farm run on the client: plan the batch, start a local Dask cluster or
connect to a scheduler, submit one task per problem, follow them to the end
(or to Ctrl-C), then write the summary (docs/farm.md).

    result = run.run_farm(["a.json", "b.json"], run.FarmOptions(out_root="out", solve=runner.SolveOptions(threads=1)))
    result.exit_code, result.rows
"""
import contextlib
import dataclasses
import logging
import os
import signal
import sys
import time
import uuid
from typing import Optional

import dask
import distributed
from distributed import Client, LocalCluster, as_completed
from tqdm import tqdm

from .. import runner
from . import plan as farm_plan
from . import summary as farm_summary
from . import task as farm_task

REFRESH_S = 1.0   # s, how often the progress line is redrawn (and the scheduler asked what runs)


class FarmError(RuntimeError):
    """The farm cannot run (one sentence for the user; exit 1)."""


@dataclasses.dataclass
class FarmOptions:
    out_root: str                            # DIR: DIR/<problem>/ per problem, DIR/summary.csv
    solve: runner.SolveOptions = dataclasses.field(default_factory=lambda: runner.SolveOptions(threads=1))
    #                                          the `sheetgen solve` of every task; its threads are per task
    scheduler: Optional[str] = None          # a Dask scheduler's address; None starts a local cluster
    workers: Optional[int] = None            # local: worker count (default cores / threads per task);
    #                                          with a scheduler: wait until this many have joined (default 1)
    timeout_s: Optional[float] = None        # s, wall time of one solve; None = no limit
    connect_timeout_s: float = 10.0          # s, to reach the scheduler
    retries: int = 1                         # Dask retries of a task whose solver was killed by a foreign signal
    force: bool = False                      # solve again problems a previous run finished
    progress: Optional[bool] = None          # a progress bar on stderr; None = when stderr is a terminal


@dataclasses.dataclass
class FarmResult:
    rows: list                               # summary.Row per problem, in the order given
    exit_code: int                           # 0, 2, 3 or 130 (summary.exit_code)
    interrupted: bool
    solved_this_run: int
    wall_s: float                            # s, the whole run
    csv_path: str


def local_workers(options):
    """The local cluster's size: the machine's cores (Dask's count, which honours
    cgroup limits) over the threads each solve uses."""
    return options.workers or max(1, dask.system.CPU_COUNT // max(1, options.solve.threads))


@contextlib.contextmanager
def _client(options):
    """A Client of the scheduler at options.scheduler, or of a local cluster (workers as threads of
    this process: the solves are processes of their own anyway)."""
    if options.scheduler:
        try:
            client = Client(options.scheduler, timeout=options.connect_timeout_s, set_as_default=False)
        except (OSError, ValueError, TimeoutError) as e:
            raise FarmError(f"cannot reach the Dask scheduler at {options.scheduler} ({e})") from None
        try:
            wanted = options.workers or 1
            if len(client.scheduler_info()["workers"]) < wanted:
                print(f"sheetgen-farm: waiting for {wanted} worker(s) to join {options.scheduler}", file=sys.stderr)
                client.wait_for_workers(wanted)
            yield client
        finally:
            client.close()
        return
    # No dashboard; the scheduler's HTTP routes on a free port (8787 may belong to another cluster).
    cluster = LocalCluster(n_workers=local_workers(options), threads_per_worker=1, processes=False,
                           dashboard_address=None, scheduler_kwargs={"dashboard_address": ":0"},
                           silence_logs=logging.ERROR)
    client = Client(cluster, set_as_default=False)
    try:
        yield client
    finally:
        client.close()
        cluster.close()


def _check_workers(client, sheetgen):
    """FarmError unless every worker can import this package and run sheetgen."""
    answers = client.run(farm_task.check_worker, sheetgen, on_error="return")
    for address, answer in answers.items():
        if isinstance(answer, BaseException):
            raise FarmError(f"worker {address} cannot run farm tasks ({answer}); "
                            f"start it with PYTHONPATH=<checkout>/tools (docs/farm.md)")
        if answer:
            raise FarmError(f"worker {address} cannot run farm tasks: {answer}")


def _record_of_future(future, planned):
    """The TaskRecord of a finished future; failures of the task itself become failed records."""
    if future.status == "finished":
        return future.result()
    record = farm_task.TaskRecord(name=planned.name, problem=planned.problem, status="failed")
    if future.status == "cancelled":
        record.status, record.reason = "cancelled", "cancelled"
        return record
    error = future.exception()
    if isinstance(error, distributed.KilledWorker):
        record.reason = "every worker that ran it died (KilledWorker; see distributed.scheduler.allowed-failures)"
    else:
        record.reason = f"{type(error).__name__}: {error}".splitlines()[0]
    return record


def _running(client, keys):
    """How many of these tasks run now: each worker's processing tasks of ours, at most its thread count."""
    try:
        workers = client.scheduler_info()["workers"]
        return sum(min(len(keys.intersection(tasks)), workers.get(address, {}).get("nthreads", 1))
                   for address, tasks in client.processing().items())
    except Exception:  # the count is cosmetic; a scheduler hiccup must not end the run
        return None


class _Progress:
    """A tqdm bar on stderr (problems finished, failed, running, ETA) and one line per finished problem
    on stdout; without a terminal only the lines."""

    def __init__(self, total, bar):
        self.total, self.done, self.failed = total, 0, 0
        self.bar = tqdm(total=total, disable=not bar, unit="problem", smoothing=0, file=sys.stderr,
                        dynamic_ncols=True,
                        bar_format="{percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} done{postfix}, {elapsed} elapsed, ETA {remaining}")

    def finished(self, row):
        self.done += 1
        self.failed += row.status in ("failed", "cancelled")
        if row.status in ("ok", "no part"):
            what = (f"{row.status}, {row.loads_ok}/{row.loads} loads, {row.mass_kg:.3f} kg, "
                    f"worst {farm_summary.worst_text(row)}, {row.time_s:.1f} s on {row.worker}")
        else:
            what = f"{row.status}: {row.reason}"
        line = f"[{self.done}/{self.total}] {row.problem}: {what}"
        if self.bar.disable:
            print(line, flush=True)
        else:
            self.bar.write(line, file=sys.stdout)
        self.bar.update(1)

    def refresh(self, running):
        running_text = "" if running is None else f", {running} running"
        self.bar.set_postfix_str(f"{self.failed} failed{running_text}", refresh=True)

    def close(self):
        self.bar.close()


def _solve_all(client, todo, options, run_id, out_root, records):
    """Submits the planned problems and collects their records into `records` as they finish."""
    settings = farm_plan.solve_settings(options.solve)
    futures = {}
    for p in todo:
        task = farm_task.SolveTask(problem=p.problem, name=p.name, out_root=out_root, options=options.solve,
                                   settings=settings, inputs_sha256=p.inputs_sha256, run_id=run_id,
                                   timeout_s=options.timeout_s)
        # Largest first (priority), so the longest problem does not start last; keys name the problem.
        future = client.submit(farm_task.solve_task, task, key=f"sheetgen-solve-{p.name}-{run_id}",
                               priority=int(p.work), retries=options.retries, pure=False)
        futures[future] = p
    progress = _Progress(len(futures), options.progress if options.progress is not None else sys.stderr.isatty())
    keys = {f.key for f in futures}
    pending = as_completed(futures, loop=client.loop)
    try:
        while not pending.is_empty():
            for future in pending.next_batch(block=False):
                p = futures[future]
                records[p.name] = _record_of_future(future, p)
                progress.finished(farm_summary.row_of(p, records[p.name], out_root, run_id))
            progress.refresh(_running(client, keys))
            time.sleep(REFRESH_S)
    except KeyboardInterrupt:
        progress.close()
        print("sheetgen-farm: interrupted; stopping the solves (finished problems stay; "
              "the same command resumes)", file=sys.stderr, flush=True)
        client.cancel(list(futures), force=True)
        client.run(farm_task.stop_run, run_id, on_error="ignore")
        raise
    progress.close()


def _finished_rows(planned, records, out_root, run_id):
    rows = []
    for p in planned:
        record = records.get(p.name)
        on_disk = farm_task.read_record(os.path.join(out_root, p.name))
        if (record is None or record.status == "cancelled") and on_disk is not None and on_disk.run_id == run_id:
            record = on_disk  # published by a task whose future was cancelled by Ctrl-C
        rows.append(farm_summary.row_of(p, record, out_root, run_id))
    return rows


def run_farm(problems, options):
    """Solves every problem (skipping those a previous run finished) and writes the summary. FarmError
    when the farm cannot run; KeyboardInterrupt stops it cleanly and gives exit code 130."""
    t0 = time.monotonic()
    out_root = os.path.abspath(options.out_root)
    try:
        os.makedirs(out_root, exist_ok=True)
    except OSError as e:
        raise FarmError(f"cannot create the output folder {out_root} ({e.strerror})") from None
    if not problems:
        raise FarmError("no problem files given")
    if not os.access(options.solve.sheetgen, os.X_OK):
        raise FarmError(f"no executable sheetgen at {options.solve.sheetgen} (build it, or give --sheetgen)")
    run_id = uuid.uuid4().hex[:10]
    interrupted = False
    with farm_plan.OutputLock(out_root):
        try:
            planned = farm_plan.plan(problems, out_root, options.solve, options.force)
        except farm_plan.PlanError as e:
            raise FarmError(str(e)) from None
        farm_plan.sweep_staging(out_root)  # of runs that were killed; the lock says none is running
        records = {p.name: p.done for p in planned if p.done}
        records.update({p.name: farm_task.TaskRecord(name=p.name, problem=p.problem, status="failed",
                                                     reason=p.unreadable, run_id=run_id)
                        for p in planned if p.unreadable})
        todo = [p for p in planned if p.name not in records]
        if records and todo:
            print(f"sheetgen-farm: {len(todo)} of {len(planned)} problems to solve "
                  f"({len(planned) - len(todo)} finished earlier or unreadable)", file=sys.stderr, flush=True)
        try:
            if todo:
                with _client(options) as client:
                    _check_workers(client, options.solve.sheetgen)
                    _solve_all(client, todo, options, run_id, out_root, records)
        except KeyboardInterrupt:
            interrupted = True
        farm_plan.sweep_staging(out_root, run_id)
        rows = _finished_rows(planned, records, out_root, run_id)
        for row in rows:
            if row.status in ("ok", "no part"):
                with contextlib.suppress(FileNotFoundError):
                    os.remove(os.path.join(out_root, row.problem + farm_task.FAILED_LOG))
        csv_path = os.path.join(out_root, farm_plan.SUMMARY_CSV)
        farm_summary.write_csv(rows, csv_path)
    return FarmResult(rows=rows, exit_code=farm_summary.exit_code(rows, interrupted), interrupted=interrupted,
                      solved_this_run=sum(r.run == "this run" and r.status in ("ok", "no part") for r in rows),
                      wall_s=time.monotonic() - t0, csv_path=csv_path)


def interrupt_on_sigterm():
    """SIGTERM (Slurm's time limit, `kill`) and SIGINT both stop a run like Ctrl-C. SIGINT is set
    explicitly: a shell that starts a job in the background leaves it ignored."""
    def raise_interrupt(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, raise_interrupt)
