"""Operators: tagging, loads, problem export / import / check.

Operators read the scene into plain data (scene_io), let the core convert and
validate it, and turn every domain error into ``self.report`` — never a
traceback. Generate, its Export and Render are in generate.py.
"""
import os

import bpy
from bpy.props import BoolProperty, StringProperty
from bpy_extras.io_utils import ExportHelper, ImportHelper

from . import loads, native, scene_io, tagging
from .core import jsonio
from .core.problem import ProblemError, problem_to_scene, scene_to_problem


def build_problem(context):
    """(problem dict, warnings) for the current scene; raises ProblemError.

    The one place the scene becomes a problem: Export, Check and
    Generate all start here.
    """
    data, warnings = scene_io.read_scene(context.scene, context.view_layer)
    problem, more = scene_to_problem(data)
    return problem, warnings + more


def report_problem_error(op, e):
    for w in e.warnings:
        op.report({'WARNING'}, w)
    for msg in e.errors[:10]:
        op.report({'ERROR'}, msg)
    if len(e.errors) > 10:
        op.report({'ERROR'}, "... and %d more problems" % (len(e.errors) - 10))


def _mesh_poll(context):
    obj = context.active_object
    return obj is not None and obj.type == 'MESH' and not obj.sheetgen.is_load and not obj.sheetgen.is_arrow


# ---------------------------------------------------------------------------
# rivet areas

class SHEETGEN_OT_rivet_area_add(bpy.types.Operator):
    """Add an empty rivet area to the active mesh"""
    bl_idname = "sheetgen.rivet_area_add"
    bl_label = "Add Rivet Area"
    bl_options = {'REGISTER', 'UNDO'}

    name: StringProperty(name="Name", default="", description="Area name (empty: OBJECT_rivets_K)")

    @classmethod
    def poll(cls, context):
        return _mesh_poll(context)

    def execute(self, context):
        item = tagging.new_area(context.active_object, self.name or None)
        self.report({'INFO'}, "Added rivet area '%s'" % item.name)
        return {'FINISHED'}


class SHEETGEN_OT_rivet_area_remove(bpy.types.Operator):
    """Remove the active rivet area and untag its faces"""
    bl_idname = "sheetgen.rivet_area_remove"
    bl_label = "Remove Rivet Area"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _mesh_poll(context) and tagging.active_area(context.active_object) is not None

    def execute(self, context):
        obj = context.active_object
        s = obj.sheetgen
        item = tagging.active_area(obj)
        name = item.name
        n = tagging.clear_area(obj, item.area_id)
        s.rivet_areas.remove(s.rivet_area_index)
        s.rivet_area_index = min(s.rivet_area_index, len(s.rivet_areas) - 1)
        self.report({'INFO'}, "Removed rivet area '%s' (%d faces untagged)" % (name, n))
        return {'FINISHED'}


class SHEETGEN_OT_rivet_area_mark(bpy.types.Operator):
    """Tag the selected faces as the active rivet area (a new area when there is none)"""
    bl_idname = "sheetgen.rivet_area_mark"
    bl_label = "Mark"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _mesh_poll(context) and context.mode == 'EDIT_MESH'

    def execute(self, context):
        obj = context.active_object
        if not tagging.selected_faces(obj):
            self.report({'WARNING'}, "No faces selected: select faces in Edit Mode (face select) first")
            return {'CANCELLED'}
        item = tagging.active_area(obj) or tagging.new_area(obj)
        tagging.assign_selected(obj, item.area_id)
        scene_io.refresh_area_stats(obj)
        tagging.show_in_viewports(context.screen)
        self.report({'INFO'}, "Rivet area '%s': %d faces, %.6g m²" % (item.name, item.face_count, item.area_m2))
        return {'FINISHED'}


class SHEETGEN_OT_rivet_area_unmark(bpy.types.Operator):
    """Untag the selected faces (remove them from any rivet area)"""
    bl_idname = "sheetgen.rivet_area_unmark"
    bl_label = "Unmark"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _mesh_poll(context) and context.mode == 'EDIT_MESH'

    def execute(self, context):
        obj = context.active_object
        n = tagging.assign_selected(obj, 0)
        scene_io.refresh_area_stats(obj)
        self.report({'INFO'}, "Untagged %d faces" % n)
        return {'FINISHED'}


class SHEETGEN_OT_rivet_area_select(bpy.types.Operator):
    """Select the faces of the active rivet area"""
    bl_idname = "sheetgen.rivet_area_select"
    bl_label = "Select"
    bl_options = {'REGISTER', 'UNDO'}

    extend: BoolProperty(name="Extend", default=False, description="Keep the current selection")

    @classmethod
    def poll(cls, context):
        return (_mesh_poll(context) and context.mode == 'EDIT_MESH'
                and tagging.active_area(context.active_object) is not None)

    def execute(self, context):
        obj = context.active_object
        item = tagging.active_area(obj)
        n = tagging.select_area(obj, item.area_id, self.extend)
        self.report({'INFO'}, "Selected %d faces of '%s'" % (n, item.name))
        return {'FINISHED'}


class SHEETGEN_OT_rivet_area_refresh(bpy.types.Operator):
    """Recompute the areas (m², world space) and colours of the active mesh's rivet areas"""
    bl_idname = "sheetgen.rivet_area_refresh"
    bl_label = "Refresh Areas"
    bl_options = {'REGISTER'}

    @classmethod
    def poll(cls, context):
        return _mesh_poll(context)

    def execute(self, context):
        obj = context.active_object
        scene_io.refresh_area_stats(obj)
        tagging.recolor(obj)
        return {'FINISHED'}


class SHEETGEN_OT_show_rivet_areas(bpy.types.Operator):
    """Show rivet-area colours: Solid shading with Attribute colour in the 3D views"""
    bl_idname = "sheetgen.show_rivet_areas"
    bl_label = "Show Colours"

    def execute(self, context):
        for obj in context.scene.objects:
            if obj.type == 'MESH' and len(obj.sheetgen.rivet_areas):
                tagging.recolor(obj)
        tagging.show_in_viewports(context.screen)
        return {'FINISHED'}


# ---------------------------------------------------------------------------
# loads

class SHEETGEN_OT_load_make(bpy.types.Operator):
    """Make the active object (a box) a load: its bounding box is held, the force acts on its centre"""
    bl_idname = "sheetgen.load_make"
    bl_label = "Make Load"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.type == 'MESH' and not obj.sheetgen.is_load and not obj.sheetgen.is_arrow

    def execute(self, context):
        obj = context.active_object
        if min(obj.dimensions) <= 0:
            self.report({'ERROR'}, "object '%s' is flat (dimensions %s m): a load must be a box"
                        % (obj.name, ", ".join("%g" % d for d in obj.dimensions)))
            return {'CANCELLED'}
        if len(obj.sheetgen.rivet_areas):
            self.report({'WARNING'}, "object '%s' had rivet areas; a load is not part of the environment" % obj.name)
        loads.make_load(obj)
        self.report({'INFO'}, "'%s' is a load; set its force (N) and moment (N·m)" % obj.name)
        return {'FINISHED'}


class SHEETGEN_OT_load_clear(bpy.types.Operator):
    """Make the active object an ordinary object again (removes its force arrow)"""
    bl_idname = "sheetgen.load_clear"
    bl_label = "Clear Load"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        obj = context.active_object
        return obj is not None and obj.sheetgen.is_load

    def execute(self, context):
        loads.clear_load(context.active_object)
        return {'FINISHED'}


def _load_poll(context):
    obj = context.active_object
    return obj is not None and obj.sheetgen.is_load


def _unique_name(existing, base):
    names = set(existing)
    if base not in names:
        return base
    k = 2
    while "%s %d" % (base, k) in names:
        k += 1
    return "%s %d" % (base, k)


class SHEETGEN_OT_load_case_add(bpy.types.Operator):
    """Add a named case to the active load (its force and moment act on the centre of mass)"""
    bl_idname = "sheetgen.load_case_add"
    bl_label = "Add Case"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _load_poll(context)

    def execute(self, context):
        s = context.active_object.sheetgen
        item = s.cases.add()
        item.name = _unique_name([c.name for c in s.cases if c != item], "case %d" % len(s.cases))
        s.case_index = len(s.cases) - 1
        s.own_cases = 'CASES'
        return {'FINISHED'}


class SHEETGEN_OT_load_case_remove(bpy.types.Operator):
    """Remove the active case of the active load"""
    bl_idname = "sheetgen.load_case_remove"
    bl_label = "Remove Case"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        return _load_poll(context) and 0 <= context.active_object.sheetgen.case_index < len(
            context.active_object.sheetgen.cases)

    def execute(self, context):
        s = context.active_object.sheetgen
        s.cases.remove(s.case_index)
        s.case_index = max(min(s.case_index, len(s.cases) - 1), 0)
        return {'FINISHED'}


class SHEETGEN_OT_envelope_factor_add(bpy.types.Operator):
    """Add a load factor to the envelope's list (g along the aircraft's forward, left, up)"""
    bl_idname = "sheetgen.envelope_factor_add"
    bl_label = "Add Factor"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        p = context.scene.sheetgen
        item = p.envelope_factors.add()
        item.name = _unique_name([f.name for f in p.envelope_factors if f != item],
                                 "factor %d" % len(p.envelope_factors))
        p.envelope_factor_index = len(p.envelope_factors) - 1
        p.envelope_kind = 'LIST'
        return {'FINISHED'}


class SHEETGEN_OT_envelope_factor_remove(bpy.types.Operator):
    """Remove the active factor of the envelope's list"""
    bl_idname = "sheetgen.envelope_factor_remove"
    bl_label = "Remove Factor"
    bl_options = {'REGISTER', 'UNDO'}

    @classmethod
    def poll(cls, context):
        p = context.scene.sheetgen
        return 0 <= p.envelope_factor_index < len(p.envelope_factors)

    def execute(self, context):
        p = context.scene.sheetgen
        p.envelope_factors.remove(p.envelope_factor_index)
        p.envelope_factor_index = max(min(p.envelope_factor_index, len(p.envelope_factors) - 1), 0)
        return {'FINISHED'}


class SHEETGEN_OT_envelope_factors_from_preset(bpy.types.Operator):
    """Replace the factor list with the FAR/CS 25.561 preset's six factors, to edit them"""
    bl_idname = "sheetgen.envelope_factors_from_preset"
    bl_label = "Factors from Preset"
    bl_options = {'REGISTER', 'UNDO'}

    def execute(self, context):
        from .core import model
        p = context.scene.sheetgen
        p.envelope_factors.clear()
        for name, g in model.PRESETS[model.PRESET_FAR25_561]:
            item = p.envelope_factors.add()
            item.name = name
            item.g = g
        p.envelope_factor_index = 0
        p.envelope_kind = 'LIST'
        return {'FINISHED'}


# ---------------------------------------------------------------------------
# problem files

class SHEETGEN_OT_export_problem(bpy.types.Operator, ExportHelper):
    """Write the scene as a sheetgen problem file (sheetgen-problem/1, inline meshes)"""
    bl_idname = "sheetgen.export_problem"
    bl_label = "Export Problem"
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        try:
            problem, warnings = build_problem(context)
        except ProblemError as e:
            report_problem_error(self, e)
            return {'CANCELLED'}
        path = bpy.path.abspath(self.filepath)
        try:
            jsonio.write_atomic(path, jsonio.dumps(problem))
        except OSError as e:
            self.report({'ERROR'}, "cannot write %s: %s" % (path, e.strerror or e))
            return {'CANCELLED'}
        for w in warnings:
            self.report({'WARNING'}, w)
        context.scene.sheetgen.filepath = self.filepath
        self.report({'INFO'}, "Wrote %s: %d meshes, %d rivet areas, %d loads"
                    % (path, len(problem["environment"]["meshes"]), len(problem["rivet_areas"]),
                       len(problem["loads"])))
        return {'FINISHED'}


def _native_mesh_reader(path):
    """A core MeshReader for meshes given by file, backed by the native reader (same face numbering)."""
    cache = {}

    def read(index, mesh_json):
        if "p" not in cache:
            sg = native.get()
            if sg is None:
                raise ProblemError(["environment.meshes[%d].file: %s" % (index, native.error())])
            try:
                cache["p"] = sg.load_problem(path)
            except ValueError as e:  # sg.InputError is a ValueError
                raise ProblemError([str(e)]) from None
        m = cache["p"].meshes[index]
        return m.vertices.tolist(), m.triangles.tolist()
    return read


class SHEETGEN_OT_import_problem(bpy.types.Operator, ImportHelper):
    """Build a tagged scene from a sheetgen problem file: meshes with rivet-area tags, load boxes, settings"""
    bl_idname = "sheetgen.import_problem"
    bl_label = "Import Problem"
    filename_ext = ".json"
    filter_glob: StringProperty(default="*.json", options={'HIDDEN'})

    def execute(self, context):
        path = bpy.path.abspath(self.filepath)
        try:
            problem = jsonio.read(path)
            data, warnings = problem_to_scene(problem, _native_mesh_reader(path))
        except ProblemError as e:
            report_problem_error(self, e)
            return {'CANCELLED'}
        except (OSError, ValueError) as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        if context.mode != 'OBJECT':
            bpy.ops.object.mode_set(mode='OBJECT')
        try:
            scene_io.build_scene(context.scene, data)
        except ValueError as e:
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        for w in warnings:
            self.report({'WARNING'}, w)
        context.scene.sheetgen.filepath = self.filepath
        self.report({'INFO'}, "Imported %s: %d meshes, %d rivet areas, %d loads"
                    % (os.path.basename(path), len(data.meshes), sum(len(m.area_names) for m in data.meshes),
                       len(data.loads)))
        return {'FINISHED'}


def _load_summary(ld):
    """'radio 2.4 kg, 8 cases, |F| up to 212 N' or 'radio |F| 100 N' (one case)."""
    cases = list(ld.cases)
    peak = max(sum(x * x for x in c.force) ** 0.5 for c in cases) if cases else 0.0
    mass = "" if ld.mass is None else " %.4g kg," % ld.mass
    if len(cases) <= 1:
        return "%s%s |F| %.4g N" % (ld.name, mass, peak)
    return "%s%s %d cases, |F| up to %.4g N" % (ld.name, mass, len(cases), peak)


def problem_summary(p):
    """One line about a native Problem: what `sheetgen check` prints, shortened."""
    areas = ", ".join("%s %.4g m²" % (ra.name, ra.area_m2) for ra in p.rivet_areas)
    lds = ", ".join(_load_summary(ld) for ld in p.loads)
    return ("Problem OK: %d meshes, %d triangles; rivet areas: %s; loads: %s"
            % (len(p.meshes), p.triangle_count, areas, lds))


class SHEETGEN_OT_check_problem(bpy.types.Operator):
    """Validate the scene's problem with the native parser (what `sheetgen check` does) and report"""
    bl_idname = "sheetgen.check_problem"
    bl_label = "Check Problem"

    def execute(self, context):
        sg = native.get()
        if sg is None:
            self.report({'ERROR'}, native.error())
            return {'CANCELLED'}
        try:
            problem, warnings = build_problem(context)
        except ProblemError as e:
            report_problem_error(self, e)
            return {'CANCELLED'}
        for w in warnings:
            self.report({'WARNING'}, w)
        try:
            p = sg.parse_problem(jsonio.dumps(problem), "scene '%s'" % context.scene.name, ".")
        except ValueError as e:  # sg.InputError: one sentence naming the field
            self.report({'ERROR'}, str(e))
            return {'CANCELLED'}
        self.report({'INFO'}, problem_summary(p))
        return {'FINISHED'}


CLASSES = (SHEETGEN_OT_rivet_area_add, SHEETGEN_OT_rivet_area_remove, SHEETGEN_OT_rivet_area_mark,
           SHEETGEN_OT_rivet_area_unmark, SHEETGEN_OT_rivet_area_select, SHEETGEN_OT_rivet_area_refresh,
           SHEETGEN_OT_show_rivet_areas, SHEETGEN_OT_load_make, SHEETGEN_OT_load_clear,
           SHEETGEN_OT_load_case_add, SHEETGEN_OT_load_case_remove, SHEETGEN_OT_envelope_factor_add,
           SHEETGEN_OT_envelope_factor_remove, SHEETGEN_OT_envelope_factors_from_preset,
           SHEETGEN_OT_export_problem, SHEETGEN_OT_import_problem, SHEETGEN_OT_check_problem)


def menu_import(self, context):
    self.layout.operator(SHEETGEN_OT_import_problem.bl_idname, text="sheetgen problem (.json)")


def menu_export(self, context):
    self.layout.operator(SHEETGEN_OT_export_problem.bl_idname, text="sheetgen problem (.json)")


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.TOPBAR_MT_file_import.append(menu_import)
    bpy.types.TOPBAR_MT_file_export.append(menu_export)


def unregister():
    bpy.types.TOPBAR_MT_file_export.remove(menu_export)
    bpy.types.TOPBAR_MT_file_import.remove(menu_import)
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
