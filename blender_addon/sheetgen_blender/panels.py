"""The "Sheet Metal" tab of the 3D View sidebar (N panel)."""
import bpy

from . import native

CATEGORY = "Sheet Metal"


class _Panel:
    bl_space_type = 'VIEW_3D'
    bl_region_type = 'UI'
    bl_category = CATEGORY


class SHEETGEN_UL_rivet_areas(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        row = layout.row(align=True)
        row.prop(item, "color", text="")
        row.prop(item, "name", text="", emboss=False)
        sub = row.row()
        sub.alignment = 'RIGHT'
        sub.label(text="%.4g m²  (%d)" % (item.area_m2, item.face_count))


class SHEETGEN_UL_load_cases(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        row = layout.row(align=True)
        row.prop(item, "name", text="", emboss=False)
        sub = row.row()
        sub.alignment = 'RIGHT'
        sub.label(text="%.4g N" % sum(x * x for x in item.force) ** 0.5)


class SHEETGEN_UL_factors(bpy.types.UIList):
    def draw_item(self, context, layout, data, item, icon, active_data, active_propname, index):
        row = layout.row(align=True)
        row.prop(item, "name", text="", emboss=False)
        sub = row.row()
        sub.alignment = 'RIGHT'
        sub.label(text="(%g, %g, %g) g" % tuple(item.g))


def _optional(layout, data, use, value, label):
    """A checkbox and its value on one row; the value greyed out while the box is off."""
    row = layout.row(align=True)
    row.prop(data, use, text="")
    sub = row.row(align=True)
    sub.active = getattr(data, use)
    sub.prop(data, value, text=label)


class SHEETGEN_PT_main(_Panel, bpy.types.Panel):
    bl_label = "sheetgen"
    bl_idname = "SHEETGEN_PT_main"

    def draw(self, context):
        layout = self.layout
        p = context.scene.sheetgen
        err = native.error()
        if err:
            box = layout.box()
            box.alert = True
            box.label(text="Native module not loaded", icon='ERROR')
            col = box.column(align=True)
            # A long sentence: wrap it by hand, the label does not.
            words, line = err.split(), ""
            for w in words:
                if len(line) + len(w) > 48:
                    col.label(text=line)
                    line = ""
                line += (" " if line else "") + w
            if line:
                col.label(text=line)
        layout.prop(p, "problem_name")
        row = layout.row(align=True)
        row.operator("sheetgen.import_problem", icon='IMPORT', text="Import")
        row.operator("sheetgen.export_problem", icon='EXPORT', text="Export")
        layout.operator("sheetgen.check_problem", icon='CHECKMARK')
        col = layout.column(align=True)
        row = col.row(align=True)
        row.prop(p, "chains")
        row.prop(p, "iterations")
        row = col.row(align=True)
        row.prop(p, "beam_width", text="Beam")
        row.prop(p, "seed")
        from . import generate
        run = generate.active_run()
        if run is not None and run.alive():
            box = layout.box()   # the sidebar is narrow: the full line is in the status bar
            snap = run.snapshot()
            box.label(text="%s, %d %%" % (snap.stage, run.percent(snap)), icon='TIME')
            box.label(text="Esc cancels")
        else:
            layout.operator("sheetgen.generate", icon='MOD_SOLIDIFY')


class SHEETGEN_PT_rivet_areas(_Panel, bpy.types.Panel):
    bl_label = "Rivet Areas"
    bl_parent_id = "SHEETGEN_PT_main"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        if obj is None or obj.type != 'MESH':
            layout.label(text="Select an environment mesh")
            return
        if obj.sheetgen.is_load:
            layout.label(text="'%s' is a load, not environment" % obj.name, icon='INFO')
            return
        layout.prop(obj.sheetgen, "exclude")
        row = layout.row()
        row.template_list("SHEETGEN_UL_rivet_areas", "", obj.sheetgen, "rivet_areas", obj.sheetgen,
                          "rivet_area_index", rows=3)
        col = row.column(align=True)
        col.operator("sheetgen.rivet_area_add", icon='ADD', text="")
        col.operator("sheetgen.rivet_area_remove", icon='REMOVE', text="")
        col.separator()
        col.operator("sheetgen.rivet_area_refresh", icon='FILE_REFRESH', text="")
        if context.mode == 'EDIT_MESH':
            row = layout.row(align=True)
            row.operator("sheetgen.rivet_area_mark")
            row.operator("sheetgen.rivet_area_unmark")
            row.operator("sheetgen.rivet_area_select")
        else:
            layout.label(text="Edit Mode: select faces, then Mark", icon='EDITMODE_HLT')
        layout.operator("sheetgen.show_rivet_areas", icon='SHADING_SOLID')


class SHEETGEN_PT_loads(_Panel, bpy.types.Panel):
    bl_label = "Loads"
    bl_idname = "SHEETGEN_PT_loads"
    bl_parent_id = "SHEETGEN_PT_main"

    def draw(self, context):
        layout = self.layout
        obj = context.active_object
        if obj is not None and obj.sheetgen.is_load:
            s = obj.sheetgen
            layout.label(text=obj.name, icon='CUBE')
            layout.row().prop(s, "own_cases", expand=True)
            if s.own_cases == 'FORCE':
                layout.prop(s, "force", text="Force (N)")
                layout.prop(s, "moment", text="Moment (N·m)")
            elif s.own_cases == 'CASES':
                self.draw_cases(layout, s)
            else:
                layout.label(text="Cases: the envelope's, for the box's mass", icon='INFO')
            col = layout.column(align=True)
            _optional(col, s, "use_mass", "mass", "Mass (kg)")
            if s.use_mass:
                col.prop(s, "use_center_of_mass", text="Centre of mass (m, world)")
                if s.use_center_of_mass:
                    col.prop(s, "center_of_mass", text="")
                col.prop(s, "use_inertia", text="Inertia (kg·m², world)")
                if s.use_inertia:
                    for r in range(3):
                        row = col.row(align=True)
                        for c in range(3):
                            row.prop(s, "inertia", index=3 * r + c, text="")
                    col.separator()
            d = obj.dimensions
            layout.label(text="Box %.4g × %.4g × %.4g m" % (d[0], d[1], d[2]))
            layout.operator("sheetgen.load_clear", icon='X')
        elif obj is not None and obj.type == 'MESH':
            layout.operator("sheetgen.load_make", icon='ORIENTATION_GLOBAL')
        names = [o.name for o in context.scene.objects if o.sheetgen.is_load]
        layout.label(text="Loads in scene: %s" % (", ".join(names) if names else "none"))

    @staticmethod
    def draw_cases(layout, s):
        row = layout.row()
        row.template_list("SHEETGEN_UL_load_cases", "", s, "cases", s, "case_index", rows=3)
        col = row.column(align=True)
        col.operator("sheetgen.load_case_add", icon='ADD', text="")
        col.operator("sheetgen.load_case_remove", icon='REMOVE', text="")
        if 0 <= s.case_index < len(s.cases):
            c = s.cases[s.case_index]
            col = layout.column(align=True)
            col.prop(c, "force", text="Force (N)")
            col.prop(c, "moment", text="Moment (N·m)")
            _optional(col, c, "use_max_deflection", "max_deflection_mm", "Max deflection (mm)")


class SHEETGEN_PT_envelope(_Panel, bpy.types.Panel):
    bl_label = "Envelope"
    bl_parent_id = "SHEETGEN_PT_loads"
    bl_options = {'DEFAULT_CLOSED'}

    def draw_header(self, context):
        self.layout.prop(context.scene.sheetgen, "use_envelope", text="")

    def draw(self, context):
        from .core import model
        p = context.scene.sheetgen
        layout = self.layout
        layout.active = p.use_envelope
        layout.label(text="Inertia cases of every load with a mass")
        col = layout.column(align=True)
        col.prop(p, "envelope_forward", text="Forward")
        col.prop(p, "envelope_up", text="Up")
        layout.row().prop(p, "envelope_kind", expand=True)
        if p.envelope_kind == 'PRESET':
            col = layout.column(align=True)
            for name, g in model.PRESETS[model.PRESET_FAR25_561]:
                col.label(text="%s  (%g, %g, %g)" % ((name,) + tuple(g)))
            layout.operator("sheetgen.envelope_factors_from_preset", icon='DUPLICATE', text="Edit as List")
            return
        row = layout.row()
        row.template_list("SHEETGEN_UL_factors", "", p, "envelope_factors", p, "envelope_factor_index", rows=3)
        col = row.column(align=True)
        col.operator("sheetgen.envelope_factor_add", icon='ADD', text="")
        col.operator("sheetgen.envelope_factor_remove", icon='REMOVE', text="")
        if 0 <= p.envelope_factor_index < len(p.envelope_factors):
            f = p.envelope_factors[p.envelope_factor_index]
            col = layout.column(align=True)
            col.label(text="g along forward, left, up:")
            row = col.row(align=True)
            for i, axis in enumerate(("Fwd", "Left", "Up")):
                row.prop(f, "g", index=i, text=axis)
            _optional(col, f, "use_max_deflection", "max_deflection_mm", "Max deflection (mm)")


class SHEETGEN_PT_material(_Panel, bpy.types.Panel):
    bl_label = "Material"
    bl_parent_id = "SHEETGEN_PT_main"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        p = context.scene.sheetgen
        col = self.layout.column(align=True)
        for key in ("youngs_modulus_gpa", "poisson_ratio", "density", "yield_strength_mpa", "ultimate_strength_mpa",
                    "thickness_mm"):
            col.prop(p, key)
        col.prop(p, "thicker_gauges")
        row = col.row()
        row.enabled = p.thicker_gauges
        row.prop(p, "gauges_mm")


class SHEETGEN_PT_requirements(_Panel, bpy.types.Panel):
    bl_label = "Requirements"
    bl_parent_id = "SHEETGEN_PT_main"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        p = context.scene.sheetgen
        col = self.layout.column(align=True)
        col.prop(p, "stiffness_limit", text="")
        col.prop(p, "max_deflection_mm" if p.stiffness_limit == 'DEFLECTION' else "max_compliance")
        for key in ("min_margin_of_safety", "safety_factor", "clearance_mm"):
            col.prop(p, key)
        col.separator()
        _optional(col, p, "use_min_buckling_factor", "min_buckling_factor", "Min buckling factor")
        _optional(col, p, "use_min_frequency", "min_frequency_hz", "Min frequency (Hz)")


class SHEETGEN_PT_search(_Panel, bpy.types.Panel):
    bl_label = "Search"
    bl_parent_id = "SHEETGEN_PT_main"
    bl_options = {'DEFAULT_CLOSED'}

    def draw(self, context):
        p = context.scene.sheetgen
        col = self.layout.column(align=True)
        for key in ("chains", "iterations", "beam_width", "seed", "threads"):
            col.prop(p, key)
        col.separator()
        for key in ("alpha", "beta", "scene_unit"):
            col.prop(p, key)


_doc_cache = {}


def _run_document(col):
    """The parsed result.json of a run collection, cached (draw() runs on every redraw)."""
    from . import results
    if col is None:
        return None
    text = col.get(results.KEY_RESULT)
    key = (col.name, len(text) if text else 0, hash(text))
    if key not in _doc_cache:
        _doc_cache.clear()
        _doc_cache[key] = results.run_document(col)
    return _doc_cache[key]


class SHEETGEN_PT_results(_Panel, bpy.types.Panel):
    bl_label = "Results"
    bl_parent_id = "SHEETGEN_PT_main"

    def draw(self, context):
        from .core import result as core_result
        layout = self.layout
        p = context.scene.sheetgen
        layout.prop(p, "result_collection", text="Run")
        doc = _run_document(p.result_collection)
        if doc is None:
            layout.label(text="Generate to see results here")
            return
        for part in doc.get("parts", []):
            box = layout.box()
            if part.get("status") != "ok":
                box.alert = True
                box.label(text="%s: no valid part" % part.get("load"), icon='ERROR')
                if part.get("reason"):
                    box.label(text=part["reason"])
                continue
            box.label(text=part.get("load", "?"), icon='MOD_SOLIDIFY')
            col = box.column(align=True)
            values = core_result.report(part)
            for label, text in core_result.report_rows(part):
                row = col.split(factor=0.62)
                if label == "Compliance (J)" and values["compliance_limit"] is not None:
                    row.alert = values["compliance"] > values["compliance_limit"]
                if label == "MS" and values["margin_of_safety"] is not None:
                    row.alert = values["margin_of_safety"] < context.scene.sheetgen.min_margin_of_safety
                if label == "Press brake":
                    row.alert = text.startswith("no:")
                row.label(text=label)
                row.label(text=text)
            rows = core_result.envelope_rows(part)
            if rows:
                col = box.column(align=True)
                col.label(text="Envelope (governing cases):")
                for label, text, alert in rows:
                    row = col.split(factor=0.38)
                    row.alert = alert
                    row.label(text=label)
                    row.label(text=text)
                box.operator("sheetgen.show_modes", icon='SHAPEKEY_DATA').load = part.get("load", "")
            row = box.row(align=True)   # this part's files for CAD and the shop (core/part_export.py)
            row.operator("sheetgen.export_step", icon='EXPORT', text="STEP").load = part.get("load", "")
            op = row.operator("sheetgen.export_step", text="Flat STEP")
            op.load, op.flat = part.get("load", ""), True
            row.operator("sheetgen.export_drawing", icon='FILE', text="Drawing").load = part.get("load", "")
        row = layout.row(align=True)
        row.operator("sheetgen.export_results", icon='EXPORT', text="Export")
        row.operator("sheetgen.generate", icon='FILE_REFRESH', text="Re-run")
        layout.operator("sheetgen.render", icon='RENDER_STILL')


CLASSES = (SHEETGEN_UL_rivet_areas, SHEETGEN_UL_load_cases, SHEETGEN_UL_factors, SHEETGEN_PT_main,
           SHEETGEN_PT_rivet_areas, SHEETGEN_PT_loads, SHEETGEN_PT_envelope, SHEETGEN_PT_material,
           SHEETGEN_PT_requirements, SHEETGEN_PT_search, SHEETGEN_PT_results)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)


def unregister():
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
