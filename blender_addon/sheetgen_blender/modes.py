"""A part's modes from the native module (no bpy): the glue between a run's files and ``part_modes``.

``part_modes`` (native/python/bind_modes.cpp) re-analyses one part of a
result on the final check's mesh and keeps the mode shapes; this module finds
the problem and the part for it, from a run collection's stored files or
from a result.json on disk. Every failure is a ``ModesError`` (a ValueError)
with one sentence.
"""
import json
import os

from . import native
from .core.modes import ModesError


def _module(sg):
    sg = sg or native.get()
    if sg is None:
        raise ModesError(native.error())
    return sg


def _part(doc, load):
    parts = doc.get("parts") if isinstance(doc, dict) else None
    part = next((p for p in parts or [] if isinstance(p, dict) and p.get("load") == load), None)
    if part is None:
        raise ModesError("the result has no part for load '%s'" % load)
    if part.get("status") != "ok" or not part.get("tabs"):
        raise ModesError("load '%s' has no valid part, so it has no modes to show" % load)
    return part


def part_modes(problem, doc, load, sg=None, source="result.json"):
    """The native ``part_modes`` dict of ``load``'s part in ``doc`` (a result document) for a parsed problem."""
    sg = _module(sg)
    part = _part(doc, load)
    names = [ld.name for ld in problem.loads]
    if load not in names:
        raise ModesError("the problem has no load named '%s'" % load)
    try:
        return sg.part_modes(problem, names.index(load), json.dumps(part), source)
    except (ValueError, RuntimeError) as e:   # sg.InputError, sg.FemError: one sentence each
        raise ModesError("modes of load '%s': %s" % (load, e)) from None


def run_modes(files, doc, load, sg=None, base_dir="."):
    """Modes of a run collection's part: ``files`` are its stored exports (``problem.json`` among them)."""
    sg = _module(sg)
    text = files.get("problem.json")
    if text is None:
        raise ModesError("the run has no stored problem.json: generate again")
    try:
        problem = sg.parse_problem(text, "problem.json", base_dir)
    except ValueError as e:
        raise ModesError(str(e)) from None
    return part_modes(problem, doc, load, sg)


def modes_from_result(result_json_path, load, sg=None):
    """Modes of ``load``'s part in a result.json on disk (its ``problem`` resolved beside it, as export-ccx does)."""
    sg = _module(sg)
    try:
        with open(result_json_path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError) as e:
        raise ModesError("cannot read %s: %s" % (result_json_path, e)) from None
    ref = doc.get("problem") if isinstance(doc, dict) else None
    if not isinstance(ref, str):
        raise ModesError("%s: field 'problem' is missing (the problem file this result solves)" % result_json_path)
    path = ref if os.path.isabs(ref) else os.path.join(os.path.dirname(os.path.abspath(result_json_path)), ref)
    try:
        problem = sg.load_problem(path)
    except ValueError as e:
        raise ModesError(str(e)) from None
    return part_modes(problem, doc, load, sg, source=result_json_path)
