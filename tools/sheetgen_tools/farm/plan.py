"""The client's side of a farm run before anything is submitted: each
problem's output folder name, the fingerprint of its inputs, which problems a
previous run already finished (resume), the lock on the output folder and
the sweep of staging folders left by an interrupted run (docs/farm.md).
"""
import dataclasses
import fcntl
import hashlib
import json
import os
import shutil
from typing import Optional

from . import task as farm_task

LOCK_FILE = ".sheetgen-farm.lock"
SUMMARY_CSV = "summary.csv"


class PlanError(ValueError):
    """The batch cannot run as given (one sentence for the user)."""


@dataclasses.dataclass
class PlannedProblem:
    problem: str                       # absolute path
    name: str                          # DIR/<name>/
    inputs_sha256: str = ""            # "" when the file cannot be read
    unreadable: str = ""               # why the file cannot be read; the problem fails without a task
    work: float = 0.0                  # loads x chains x iterations: the scheduling priority (largest first)
    done: Optional[farm_task.TaskRecord] = None   # the record of an earlier run whose result still stands


def output_name(problem):
    """The output folder of a problem file: its stem, or for the layout
    <scene>/problem.json (sample_scenes/) the folder's name."""
    stem = os.path.splitext(os.path.basename(problem))[0]
    return os.path.basename(os.path.dirname(os.path.abspath(problem))) if stem == "problem" else stem


def _mesh_files(doc, folder):
    meshes = doc.get("environment", {}).get("meshes", []) if isinstance(doc, dict) else []
    return [os.path.join(folder, m["file"]) for m in meshes if isinstance(m, dict) and isinstance(m.get("file"), str)]


def inputs_sha256(problem, doc):
    """SHA-256 over the problem file and the mesh files it names, in order (a
    changed mesh re-solves the problem on resume). Missing meshes hash as
    absent: sheetgen reports them."""
    h = hashlib.sha256()
    for path in [problem] + _mesh_files(doc, os.path.dirname(problem)):
        h.update(path.encode() + b"\0")
        try:
            with open(path, "rb") as f:
                for block in iter(lambda: f.read(1 << 20), b""):
                    h.update(block)
        except OSError:
            h.update(b"<missing>")
    return h.hexdigest()


def _work(doc, solve):
    """loads x chains x iterations of a problem under the farm's settings (its own where the farm sets none)."""
    try:
        search = doc.get("search", {})
        chains = solve.chains or search.get("chains", 10)
        iterations = solve.iterations or search.get("iterations", 1000)
        return float(len(doc["loads"]) * chains * iterations)
    except (AttributeError, KeyError, TypeError):
        return 0.0


def solve_settings(solve):
    """The `sheetgen solve` settings that decide the answer (threads do not:
    tests/python/test_determinism.py), as stored in farm.json and compared on resume."""
    return {"seed": solve.seed, "chains": solve.chains, "iterations": solve.iterations, "beam": solve.beam,
            "flags": sorted(solve.flags)}


def plan(problems, out_root, solve, force=False):
    """The batch: one PlannedProblem per distinct problem file, in the order given.
    PlanError when two different files would write the same folder."""
    planned, by_name = [], {}
    settings = solve_settings(solve)
    for given in problems:
        path = os.path.abspath(given)
        name = output_name(path)
        if name in by_name:
            if os.path.realpath(by_name[name].problem) == os.path.realpath(path):
                continue  # the same file twice
            raise PlanError(f"{by_name[name].problem} and {path} would both write {os.path.join(out_root, name)}; "
                            f"rename one of them")
        p = PlannedProblem(problem=path, name=name)
        doc = None
        try:
            with open(path, "rb") as f:
                raw = f.read()
            try:
                doc = json.loads(raw)
            except ValueError:
                doc = None  # malformed: sheetgen says where
        except OSError as e:
            p.unreadable = f"cannot read {path}: {e.strerror}"
        if not p.unreadable:
            p.inputs_sha256 = inputs_sha256(path, doc)
            p.work = _work(doc, solve)
            folder = os.path.join(out_root, name)
            earlier = farm_task.read_record(folder)
            if (not force and earlier is not None and earlier.status == "solved"
                    and earlier.inputs_sha256 == p.inputs_sha256 and earlier.settings == settings
                    and os.path.isfile(os.path.join(folder, "result.json"))):
                p.done = earlier
        by_name[name] = p
        planned.append(p)
    return planned


class OutputLock:
    """An exclusive lock on DIR for the length of a run (flock on DIR/.sheetgen-farm.lock):
    two runs writing the same folder would take each other's staging folders."""

    def __init__(self, out_root):
        self.path = os.path.join(out_root, LOCK_FILE)
        self.file = None

    def __enter__(self):
        self.file = open(self.path, "a+")
        try:
            fcntl.flock(self.file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            self.file.close()
            raise PlanError(f"another sheetgen-farm run is writing {os.path.dirname(self.path)}; "
                            f"wait for it or choose another --out")
        return self

    def __exit__(self, *exc):
        self.file.close()  # releases the lock


def sweep_staging(out_root, run_id=""):
    """Removes the staging folders of a run (every run when run_id is ""): those of solves
    that were killed with their worker or interrupted. Returns how many it removed."""
    removed = 0
    for entry in os.listdir(out_root):
        if entry.startswith(".") and farm_task.STAGING_MARK + run_id in entry:
            shutil.rmtree(os.path.join(out_root, entry), ignore_errors=True)
            removed += 1
    return removed
