"""One part's files for CAD and the shop, beside Export Results (no bpy): the bent part and the flat
pattern as STEP, the drawing sheet as PDF.

A run's files (the native ``write_outputs`` folder, stored on the run collection) hold, per load
with a valid part, ``<load>/part.step``, ``<load>/flat.step`` and ``<load>/drawing.pdf``. ``export``
writes one of them to a file the user names: the path is checked first, the bytes are written
through a temporary file in the target folder and a rename, so a failure leaves nothing behind,
and every failure is one sentence (``ExportError``). A run made before sheetgen wrote these files
can still give its drawing sheet: the operator passes ``make``, the native ``write_drawing`` on the
run's problem.json and result.json.
"""
import os

from . import jsonio

# kind -> (the run's file in the load's folder, the extensions the target may have (the first is added
# when it has none), what it is in a sentence)
KINDS = {
    "PART_STEP": ("part.step", (".step", ".stp"), "bent part STEP"),
    "FLAT_STEP": ("flat.step", (".step", ".stp"), "flat pattern STEP"),
    "DRAWING": ("drawing.pdf", (".pdf",), "drawing sheet"),
}


# What write_outputs leaves in the load's folder instead of part.step when OpenCASCADE cannot build or
# check the bent solid (docs/cad.md).
STEP_ERROR = "part_step_error.txt"


class ExportError(Exception):
    """One sentence for the user (self.report in the operator)."""


def default_name(load, kind):
    """A file name for the file dialog: '<load>.step', '<load>_flat.step', '<load>_drawing.pdf'."""
    stem = "".join(c if c.isalnum() or c in "-_." else "_" for c in load) or "part"
    return {"PART_STEP": stem + ".step", "FLAT_STEP": stem + "_flat.step", "DRAWING": stem + "_drawing.pdf"}[kind]


def target_path(path, kind):
    """The file to write: ``path`` with the kind's extension added when it has none of them.

    ExportError when the path is empty, names a folder, or its folder does not exist.
    """
    _name, extensions, what = KINDS[kind]
    if not path or not path.strip():
        raise ExportError("no file name given for the %s" % what)
    if path.endswith(os.sep) or os.path.isdir(path):
        raise ExportError("%s is a folder: give a file name for the %s" % (path, what))
    if not path.lower().endswith(extensions):
        path += extensions[0]
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise ExportError("cannot write %s: the folder %s does not exist" % (path, folder))
    return path


def stored_file(files, doc, load, kind):
    """The bytes (or text) of the run's file for ``load``; ExportError when the load has no such file."""
    name, _extensions, what = KINDS[kind]
    parts = {p.get("load"): p for p in (doc or {}).get("parts", [])}
    if load not in parts:
        raise ExportError("load '%s' is not in this run (loads: %s)" % (load, ", ".join(sorted(map(str, parts))) or "none"))
    if parts[load].get("status") != "ok":
        raise ExportError("load '%s' has no valid part in this run, so no %s" % (load, what))
    rel = load + "/" + name
    if rel not in files:
        why = files.get(load + "/" + STEP_ERROR) if kind == "PART_STEP" else None
        if why and why.strip():   # OpenCASCADE refused the solid: the run kept its other files and said why
            raise ExportError("no bent part STEP for '%s': %s" % (load, why.strip().splitlines()[0]))
        raise ExportError(_missing(load, kind))
    return jsonio.text_to_file(files[rel])


def _missing(load, kind):
    name, _extensions, what = KINDS[kind]
    return ("this run has no %s for '%s' (%s/%s): it was made before sheetgen wrote one; Re-run to make it"
            % (what, load, load, name))


def export(files, doc, load, kind, path, make=None):
    """Write the run's ``kind`` file of ``load`` to ``path`` (extension added when missing); returns the path
    written. Raises ExportError (one sentence) and leaves no file behind on any failure.

    ``make(kind, load, path)``, when given, writes the file itself for a run that does not hold it (a run made
    before sheetgen wrote that file: the add-on passes the native drawing writer); it must write atomically
    and raise ValueError or RuntimeError with one sentence, or NotImplementedError when it cannot make that kind.
    """
    path = target_path(path, kind)
    try:
        data = stored_file(files, doc, load, kind)
    except ExportError:
        name = KINDS[kind][0]
        if (make is None or load + "/" + name in files or not _has_valid_part(doc, load)
                or (kind == "PART_STEP" and load + "/" + STEP_ERROR in files)):
            raise
        try:
            make(kind, load, path)
        except NotImplementedError:
            raise ExportError(_missing(load, kind)) from None
        except (ValueError, RuntimeError, OSError) as e:
            raise ExportError(str(e).strip().splitlines()[0] if str(e).strip() else
                              "cannot write %s" % path) from None
        return path
    try:
        jsonio.write_atomic(path, data)
    except OSError as e:
        raise ExportError("cannot write %s: %s" % (path, e.strerror or e)) from None
    return path


def _has_valid_part(doc, load):
    return any(p.get("load") == load and p.get("status") == "ok" for p in (doc or {}).get("parts", []))
