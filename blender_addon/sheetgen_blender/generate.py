"""Generate: the scene's problem -> native ``generate()`` -> a run collection with the parts.

Two paths over one ``Run`` (docs/platform.md "Blender 3.4 facts"):

- ``invoke()`` (the button in the UI): the problem is built and parsed on the
  main thread, ``generate`` runs in a worker thread (the native code releases
  the GIL; the worker never touches bpy), a window-manager timer polls the
  atomics of ``GenerateProgress`` into the progress bar and the status bar,
  Esc cancels (the native search stops within a second) and leaves the scene
  unchanged; the results are built in the modal's last step, one undo step.
- ``execute()`` (scripts, ``blender -b``, where INVOKE_DEFAULT calls it): the
  same run, waited for on the main thread, with progress lines on stdout.

Another thread may cancel a running ``execute()`` through ``active_run()``.
"""
import json
import os
import shutil
import sys
import tempfile
import threading
import time
import types

import bpy
from bpy.props import StringProperty

from . import native, operators, results
from .core import jsonio
from .core import result as core_result
from .core.problem import ProblemError

_active = None   # the Run in progress (one at a time)


def active_run():
    return _active


def problem_label(context):
    """The name the native parser gives the scene's problem (its messages, the drawing sheet's title block)."""
    return "scene '%s'" % context.scene.name


class GenerateError(Exception):
    """One sentence for self.report."""


class Run:
    """One generate call: inputs copied on the main thread, the native call in a worker thread."""

    def __init__(self, context):
        sg = native.get()
        if sg is None:
            raise GenerateError(native.error())
        self.sg = sg
        self.problem_dict, self.warnings = operators.build_problem(context)   # ProblemError goes up
        self.problem_text = jsonio.dumps(self.problem_dict)
        self.thickness = self.problem_dict["material"]["thickness"]
        base = bpy.path.abspath("//") or os.getcwd()
        try:
            self.problem = sg.parse_problem(self.problem_text, problem_label(context), base)
        except ValueError as e:   # sg.InputError: one sentence naming the field
            raise GenerateError(str(e)) from None
        self.progress = sg.GenerateProgress()
        self.result = None
        self.error = None
        self.thread = None
        self.started = None
        self.cancel_requested = False
        self.shown = None   # (percent, text): what the modal last put in the progress and status bars
        self.ended = None   # time.monotonic() when the native call returned

    def start(self):
        global _active
        if _active is not None and _active.alive():
            raise GenerateError("a Generate run is already in progress (Esc cancels it)")
        _active = self
        self.started = time.monotonic()
        self.thread = threading.Thread(target=self._work, name="sheetgen generate", daemon=True)
        self.thread.start()

    def _work(self):
        # No bpy here: only the native problem and progress objects made on the main thread.
        try:
            self.result = self.sg.generate(self.problem, self.progress)
        except Exception as e:  # noqa: BLE001 - reported on the main thread
            self.error = e
        finally:
            self.ended = time.monotonic()

    def alive(self):
        return self.thread is not None and self.thread.is_alive()

    def cancel(self):
        self.cancel_requested = True
        self.progress.cancel()

    def cancelled(self):
        # The request counts even when the native result is not flagged: a cancel that arrives while
        # the environment is being built is only seen at the end of that stage and the result comes
        # back unflagged (seen with the native module of this tree), and the user asked for nothing.
        return self.cancel_requested or (self.result is not None and self.result.cancelled)

    def join(self, timeout=None):
        self.thread.join(timeout)
        return not self.thread.is_alive()

    def done(self):
        global _active
        if _active is self:
            _active = None

    def snapshot(self):
        """The progress counters read once (the worker moves them between reads): one snapshot gives the bar's
        percentage and the status line the same iteration."""
        p = self.progress
        names = ("stage", "load", "loads", "iterations", "total_iterations", "evaluated", "best_cost_m2", "gauge")
        return types.SimpleNamespace(**{n: getattr(p, n) for n in names})

    def fraction(self, snap=None):
        p = snap or self.snapshot()
        if p.stage == "done":
            return 1.0
        loads = max(p.loads, 1)
        inner = p.iterations / p.total_iterations if p.total_iterations else 0.0
        return min((p.load + min(inner, 1.0)) / loads, 1.0)

    def percent(self, snap=None):
        """The progress bar's whole percent (1e-9: 100 * 0.29 is 28.999… in floating point)."""
        return int(100 * self.fraction(snap) + 1e-9)

    def text(self, snap=None):
        p = snap or self.snapshot()
        best = ("best %.1f cm²" % (p.best_cost_m2 * 1e4)) if p.best_cost_m2 > 0 else "no part yet"
        if p.stage == "composition":   # discovery's iterations are all done: count the candidates instead
            work = "%d candidates evaluated" % p.evaluated
        else:
            work = "iteration %d/%d" % (p.iterations, p.total_iterations)
        # A load the problem's sheet gave no part is searched again in thicker gauges (docs/pipeline.md).
        stage = p.stage + (" (thicker gauge %d)" % p.gauge if getattr(p, "gauge", 0) else "")
        return ("sheetgen: load %d/%d, %s, %s, %s, %.0f s — Esc cancels"
                % (min(p.load + 1, max(p.loads, 1)), max(p.loads, 1), stage, work, best,
                   time.monotonic() - self.started))

    def outputs(self):
        """(result document, {relative path: text}) of a finished run: write_outputs into a temporary
        folder beside a problem.json, read back (stored on the run collection for Export)."""
        if self.error is not None:
            raise GenerateError("generate failed: %s" % self.error)
        tmp = tempfile.mkdtemp(prefix="sheetgen-run-")
        try:
            ppath = os.path.join(tmp, "problem.json")
            with open(ppath, "w", encoding="utf-8") as f:
                f.write(self.problem_text)
            self.sg.write_outputs(tmp, self.problem, self.result, ppath)
            files = {}
            for root, _dirs, names in os.walk(tmp):
                for n in names:
                    full = os.path.join(root, n)
                    with open(full, "rb") as f:  # convergence.png is binary: kept as base64 text
                        files[os.path.relpath(full, tmp)] = jsonio.file_to_text(f.read())
            doc = json.loads(files["result.json"])
            return doc, files
        finally:
            shutil.rmtree(tmp, ignore_errors=True)


def finish(context, run, op=None):
    """Build the finished run into the scene; returns (collection, document). Reports through ``op``."""
    doc, files = run.outputs()
    col = results.build_run(context, doc, files, run.thickness)
    if op is not None:
        for part in doc["parts"]:
            op.report({'INFO'} if part.get("status") == "ok" else {'WARNING'}, core_result.status_line(part))
    return col, doc


def run_sync(context, op=None, log=None, log_every=2.0):
    """Generate synchronously (execute, batch). Returns (collection or None, document or None, run).

    Raises ProblemError / GenerateError. A cancelled run builds nothing and returns (None, None, run).
    """
    run = Run(context)
    if op is not None:
        for w in run.warnings:
            op.report({'WARNING'}, w)
    run.start()
    try:
        last = 0.0
        while not run.join(0.1):
            if log is not None and time.monotonic() - last >= log_every:
                last = time.monotonic()
                log(run.text().replace(" — Esc cancels", ""))
    finally:
        run.done()
    if run.error is None and run.cancelled():
        return None, None, run
    col, doc = finish(context, run, op)
    return col, doc, run


def _redraw_sidebars(context):
    """Redraw the 3D views' sidebars (the main panel shows the run's progress), not the views themselves."""
    for area in context.screen.areas if context.screen is not None else ():
        if area.type == 'VIEW_3D':
            for region in area.regions:
                if region.type == 'UI':
                    region.tag_redraw()


class SHEETGEN_OT_generate(bpy.types.Operator):
    """Design a bracket for every load of the scene (runs in the background; Esc cancels)"""
    bl_idname = "sheetgen.generate"
    bl_label = "Generate"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _active is None or not _active.alive()

    def _start(self, context):
        try:
            return Run(context)
        except ProblemError as e:
            operators.report_problem_error(self, e)
        except GenerateError as e:
            self.report({'ERROR'}, str(e))
        return None

    def execute(self, context):
        try:
            col, doc, run = run_sync(context, op=self, log=lambda s: print(s, flush=True))
        except ProblemError as e:
            operators.report_problem_error(self, e)
            return {'CANCELLED'}
        except GenerateError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        if col is None:
            self.report({'WARNING'}, "Generate cancelled; the scene is unchanged")
            return {'CANCELLED'}
        return {'FINISHED'}

    def invoke(self, context, event):
        if bpy.app.background:
            return self.execute(context)
        self._run = self._start(context)
        if self._run is None:
            return {'CANCELLED'}
        for w in self._run.warnings:
            self.report({'WARNING'}, w)
        try:
            self._run.start()
        except GenerateError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self._cancelled = False
        wm = context.window_manager
        wm.progress_begin(0, 100)
        self._timer = wm.event_timer_add(0.1, window=context.window)   # the bars move 10 times a second
        wm.modal_handler_add(self)
        context.workspace.status_text_set(self._run.text())
        return {'RUNNING_MODAL'}

    def _end(self, context):
        wm = context.window_manager
        wm.event_timer_remove(self._timer)
        wm.progress_end()
        context.workspace.status_text_set(None)
        self._run.done()
        _redraw_sidebars(context)   # the Generate button again in place of the progress box

    def modal(self, context, event):
        run = self._run
        if event.type == 'ESC' and event.value == 'PRESS' and not self._cancelled:
            self._cancelled = True
            run.cancel()
            context.workspace.status_text_set("sheetgen: cancelling…")
            # Look for the worker's end every 50 ms from now on: the search stops within a second.
            wm = context.window_manager
            wm.event_timer_remove(self._timer)
            self._timer = wm.event_timer_add(0.05, window=context.window)
            return {'RUNNING_MODAL'}
        if event.type != 'TIMER':
            return {'PASS_THROUGH'}   # the UI stays usable while the search runs
        if run.alive():
            if not self._cancelled:
                snap = run.snapshot()
                run.shown = (run.percent(snap), run.text(snap))
                context.window_manager.progress_update(run.shown[0])
                context.workspace.status_text_set(run.shown[1])
                _redraw_sidebars(context)
            return {'RUNNING_MODAL'}
        self._end(context)
        if run.error is not None:
            self.report({'ERROR'}, "generate failed: %s" % run.error)
            return {'CANCELLED'}
        if self._cancelled or run.cancelled():
            self.report({'WARNING'}, "Generate cancelled; the scene is unchanged")
            return {'CANCELLED'}
        try:
            finish(context, run, self)   # all objects in this one call: one undo step
        except (GenerateError, core_result.ResultError, OSError) as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        return {'FINISHED'}

    def cancel(self, context):
        # Blender ends the modal (file load, window closed): stop the search too.
        self._run.cancel()
        self._run.join(2.0)
        self._end(context)


class SHEETGEN_OT_export_results(bpy.types.Operator):
    """Write the run's result.json, problem.json and per load part.obj, flat.dxf, flat.svg, bends.csv into a folder"""
    bl_idname = "sheetgen.export_results"
    bl_label = "Export Results"

    directory: StringProperty(subtype='DIR_PATH')

    @classmethod
    def poll(cls, context):
        return results.run_files(context.scene.sheetgen.result_collection) != {}

    def invoke(self, context, event):
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}

    def execute(self, context):
        folder = bpy.path.abspath(self.directory or "//")
        files = results.run_files(context.scene.sheetgen.result_collection)
        try:
            # Load folders first, result.json last (as write_outputs does): a half-written export never
            # looks finished.
            for rel in sorted(files, key=lambda r: (r == "result.json", r)):
                jsonio.write_atomic(os.path.join(folder, rel), jsonio.text_to_file(files[rel]))
        except OSError as e:
            self.report({'ERROR'}, "cannot write into %s: %s" % (folder, e.strerror or e))
            return {'CANCELLED'}
        self.report({'INFO'}, "Wrote %d files into %s" % (len(files), folder))
        return {'FINISHED'}


def _native_maker(files, label):
    """For a run that does not hold drawing.pdf: the native ``write_drawing`` on the run's own problem.json
    and result.json (the same writer write_outputs uses; atomic, errors one sentence). ``label`` names the
    problem as Generate did (the title block shows it), so an unrenamed scene gets the same bytes."""
    def make(kind, load, path):
        sg = native.get()
        if kind != "DRAWING" or sg is None or not hasattr(sg, "write_drawing") or "problem.json" not in files:
            raise NotImplementedError(kind)
        problem = sg.parse_problem(files["problem.json"], label, bpy.path.abspath("//") or os.getcwd())
        sg.write_drawing(problem, files["result.json"], load, path)
    return make


class _PartExport:
    """Export STEP / Export Drawing: one load's file of the run (core/part_export.py) to a file the user names."""
    load: StringProperty(name="Load", description="The load whose part is exported")
    filepath: StringProperty(subtype='FILE_PATH')

    @classmethod
    def poll(cls, context):
        return results.run_document(context.scene.sheetgen.result_collection) is not None

    def kind(self):
        raise NotImplementedError

    def invoke(self, context, event):
        from .core import part_export
        if not self.filepath:
            self.filepath = os.path.join(bpy.path.abspath("//") or os.getcwd(),
                                         part_export.default_name(self.load, self.kind()))
        context.window_manager.fileselect_add(self)
        return {'RUNNING_MODAL'}

    def execute(self, context):
        from .core import part_export
        col = context.scene.sheetgen.result_collection
        files = results.run_files(col)
        try:
            path = part_export.export(files, results.run_document(col), self.load, self.kind(),
                                      bpy.path.abspath(self.filepath),
                                      make=_native_maker(files, problem_label(context)))
        except part_export.ExportError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, "Wrote %s" % path)
        return {'FINISHED'}


class SHEETGEN_OT_export_step(_PartExport, bpy.types.Operator):
    """Write a load's part as STEP (AP214, mm): the bent solid with true bend radii, or its flat pattern as a solid"""
    bl_idname = "sheetgen.export_step"
    bl_label = "Export STEP"

    flat: bpy.props.BoolProperty(name="Flat Pattern", default=False,
                                 description="The flat pattern as a solid of the sheet's thickness instead of the bent part")
    filter_glob: StringProperty(default="*.step;*.stp", options={'HIDDEN'})

    def kind(self):
        return "FLAT_STEP" if self.flat else "PART_STEP"


class SHEETGEN_OT_export_drawing(_PartExport, bpy.types.Operator):
    """Write a load's drawing sheet (one-page PDF: flat pattern with dimensions, bend table, rivets, checks)"""
    bl_idname = "sheetgen.export_drawing"
    bl_label = "Export Drawing"

    filter_glob: StringProperty(default="*.pdf", options={'HIDDEN'})

    def kind(self):
        return "DRAWING"


class SHEETGEN_OT_render(bpy.types.Operator):
    """Render the latest run: a presentation PNG of the scene and the part(s), and the flat pattern(s)"""
    bl_idname = "sheetgen.render"
    bl_label = "Render Presentation"

    filepath: StringProperty(subtype='FILE_PATH', default="//sheetgen_render.png")
    samples: bpy.props.IntProperty(name="Samples", default=32, min=1, max=4096)

    @classmethod
    def poll(cls, context):
        return results.run_document(context.scene.sheetgen.result_collection) is not None

    def execute(self, context):
        from . import render
        path = bpy.path.abspath(self.filepath)
        try:
            written = render.render_run(context, context.scene.sheetgen.result_collection, path, samples=self.samples)
        except (render.RenderError, OSError, RuntimeError) as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, "Rendered %s" % ", ".join(written))
        return {'FINISHED'}


class SHEETGEN_OT_show_modes(bpy.types.Operator):
    """Add the buckling mode (governing case) and the first vibration mode of a load's part as shape keys of a new
    object "<load> modes" (its FEM mesh); scrub the keys' values from -1 to 1"""
    bl_idname = "sheetgen.show_modes"
    bl_label = "Show Modes"
    bl_options = {'REGISTER', 'UNDO'}

    load: StringProperty(name="Load", description="The load whose part's modes are shown")

    @classmethod
    def poll(cls, context):
        return results.run_document(context.scene.sheetgen.result_collection) is not None

    def execute(self, context):
        from . import modes
        from .core import modes as core_modes
        col = context.scene.sheetgen.result_collection
        doc = results.run_document(col)
        files = results.run_files(col)
        try:
            raw = modes.run_modes(files, doc, self.load, base_dir=bpy.path.abspath("//") or os.getcwd())
            plain = core_modes.modes_mesh(raw)
        except core_modes.ModesError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        try:
            thickness = float(json.loads(files["problem.json"])["material"]["thickness"])
        except (KeyError, TypeError, ValueError):
            from .core import model
            thickness = model.Material().thickness
        part = next((p for p in doc.get("parts", []) if p.get("load") == self.load), {})
        thickness = core_result.part_sheet(part, thickness)
        obj = results.build_modes(col, self.load, plain, thickness)
        if not plain.keys:
            self.report({'WARNING'}, "%s: no mode moves the sheet (%s)" % (self.load, plain.summary))
        else:
            self.report({'INFO'}, "%s: %s; shape keys on '%s'" % (self.load, plain.summary, obj.name))
        return {'FINISHED'}


CLASSES = (SHEETGEN_OT_generate, SHEETGEN_OT_export_results, SHEETGEN_OT_export_step, SHEETGEN_OT_export_drawing,
           SHEETGEN_OT_render, SHEETGEN_OT_show_modes)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
