"""Blender properties: per-object rivet areas and load data, per-scene settings.

Settings are shown in engineering units (GPa, MPa, mm) and converted to SI by
scene_io.read_settings; the defaults are docs/problem-format.md's.
"""
import bpy
from bpy.props import (BoolProperty, CollectionProperty, EnumProperty, FloatProperty, FloatVectorProperty,
                       IntProperty, PointerProperty, StringProperty)

from .core import model

_M = model.Material()
_R = model.Requirements()
_S = model.Search()


def _recolor(self, context):
    from . import tagging
    obj = self.id_data
    if isinstance(obj, bpy.types.Object) and obj.type == 'MESH':
        tagging.recolor(obj)


def _update_arrow(self, context):
    from . import loads
    obj = self.id_data
    if isinstance(obj, bpy.types.Object) and self.is_load:
        loads.update_arrow(obj)


class SheetgenRivetArea(bpy.types.PropertyGroup):
    # ``name`` (the rivet area name in the problem) comes with PropertyGroup.
    area_id: IntProperty(name="Id", min=1, description="Value of the sheetgen_rivet_area face attribute for this area")
    area_m2: FloatProperty(name="Area", precision=6, description="World-space area in m² (refresh after transforms)")
    face_count: IntProperty(name="Faces", description="Number of faces (polygons) tagged with this area")
    problem_order: IntProperty(default=0, description="Position in the imported problem's rivet_areas (0: none); "
                                                      "exported in that order")
    color: FloatVectorProperty(name="Colour", subtype='COLOR_GAMMA', size=3, min=0.0, max=1.0,
                               default=(1.0, 0.3, 0.1),
                               update=_recolor, description="Viewport colour of the area's faces")


def _update_own(self, context):
    from . import loads
    obj = self.id_data
    if isinstance(obj, bpy.types.Object) and self.is_load:
        loads.update_arrow(obj)


class SheetgenLoadCase(bpy.types.PropertyGroup):
    """One explicit case of a load (``loads[i].cases[k]``); ``name`` comes with PropertyGroup."""
    force: FloatVectorProperty(name="Force", size=3, subtype='XYZ', default=(0.0, 0.0, -100.0), precision=3,
                               description="Force on the centre of mass, N, world axes")
    moment: FloatVectorProperty(name="Moment", size=3, subtype='XYZ', default=(0.0, 0.0, 0.0), precision=3,
                                description="Moment about the centre of mass, N·m, world axes")
    use_max_deflection: BoolProperty(name="Own max deflection", default=False,
                                     description="This case has its own stiffness limit")
    max_deflection_mm: FloatProperty(name="Max deflection (mm)", default=1.0, min=1e-9, precision=3,
                                     description="This case's deflection limit along its force, mm")


class SheetgenFactor(bpy.types.PropertyGroup):
    """One acceleration of the envelope (``load_cases.factors[k]``); ``name`` comes with PropertyGroup."""
    g: FloatVectorProperty(name="g", size=3, default=(0.0, 0.0, -1.0), precision=3,
                           description="Load factor along the aircraft's forward, left, up axes, in g (9.80665 m/s²)")
    use_max_deflection: BoolProperty(name="Own max deflection", default=False,
                                     description="The cases of this factor have their own stiffness limit")
    max_deflection_mm: FloatProperty(name="Max deflection (mm)", default=1.0, min=1e-9, precision=3,
                                     description="Deflection limit of this factor's cases along the force, mm")


class SheetgenObjectSettings(bpy.types.PropertyGroup):
    rivet_areas: CollectionProperty(type=SheetgenRivetArea)
    rivet_area_index: IntProperty(name="Active rivet area", default=0)
    problem_order: IntProperty(default=0, description="Position of this mesh or load in the imported problem (0: "
                                                      "none); exported in that order, then the others by name")
    exclude: BoolProperty(name="Not in environment", default=False,
                          description="Leave this mesh out of the environment (not an obstacle, no rivet areas)")
    is_load: BoolProperty(name="Load", default=False, description="This box is a load that a bracket must hold")
    force: FloatVectorProperty(name="Force", size=3, subtype='XYZ', default=(0.0, 0.0, -100.0), precision=3,
                               update=_update_arrow, description="Force on the box centroid, N, world axes")
    moment: FloatVectorProperty(name="Moment", size=3, subtype='XYZ', default=(0.0, 0.0, 0.0), precision=3,
                                description="Moment about the box centroid, N·m, world axes")
    own_cases: EnumProperty(name="Cases", default='FORCE', update=_update_own, items=[
        ('FORCE', "Force", "One case named 'design': the force and moment below"),
        ('CASES', "Cases", "A list of named cases, each applied separately"),
        ('NONE', "Envelope only", "No case of its own: the box's mass under the envelope's factors")])
    cases: CollectionProperty(type=SheetgenLoadCase)
    case_index: IntProperty(name="Active case", default=0)
    use_mass: BoolProperty(name="Mass", default=False,
                           description="The box has a mass: it gets the envelope's cases and counts in the frequencies")
    mass: FloatProperty(name="Mass (kg)", default=1.0, min=1e-9, precision=3, description="Mass of the box, kg")
    use_center_of_mass: BoolProperty(name="Centre of mass", default=False,
                                     description="Give the centre of mass (default: the box centroid)")
    center_of_mass: FloatVectorProperty(name="Centre of mass", size=3, subtype='XYZ', precision=4,
                                        description="Centre of mass, m, world; inside the box. It does not follow "
                                                    "the box when the box moves")
    use_inertia: BoolProperty(name="Inertia", default=False,
                              description="Give the inertia tensor (default: the uniform box's)")
    inertia: FloatVectorProperty(name="Inertia", size=9, precision=6, default=(1, 0, 0, 0, 1, 0, 0, 0, 1),
                                 description="Inertia tensor about the centre of mass, kg·m², world axes, rows "
                                             "of 3")
    arrow: PointerProperty(type=bpy.types.Object, name="Force arrow")
    is_arrow: BoolProperty(default=False, description="Force arrow drawn for a load (not part of the problem)")


class SheetgenSceneSettings(bpy.types.PropertyGroup):
    problem_name: StringProperty(name="Name", default="", description="Problem name (empty: the scene name)")
    description: StringProperty(name="Description", default="")
    filepath: StringProperty(name="Problem file", subtype='FILE_PATH', default="//problem.json")
    # material
    youngs_modulus_gpa: FloatProperty(name="E (GPa)", default=_M.youngs_modulus / 1e9, min=1e-6, precision=2,
                                      description="Young's modulus, GPa")
    poisson_ratio: FloatProperty(name="ν", default=_M.poisson_ratio, min=-0.999, max=0.499, precision=3,
                                 description="Poisson's ratio")
    density: FloatProperty(name="Density (kg/m³)", default=_M.density, min=1e-6, precision=1)
    yield_strength_mpa: FloatProperty(name="Fty (MPa)", default=_M.yield_strength / 1e6, min=1e-6, precision=1,
                                      description="Yield strength, MPa")
    ultimate_strength_mpa: FloatProperty(name="Ftu (MPa)", default=_M.ultimate_strength / 1e6, min=1e-6,
                                         precision=1, description="Ultimate strength, MPa")
    thickness_mm: FloatProperty(name="Thickness (mm)", default=_M.thickness * 1e3, min=1e-6, precision=3,
                                description="Sheet thickness, mm")
    thicker_gauges: BoolProperty(name="Thicker gauges", default=True,
                                 description="Where the sheet gives a load no valid part, search it again in each "
                                             "thicker gauge in turn and keep the first part found")
    gauges_mm: StringProperty(name="Gauges (mm)", default="",
                              description="The thicker sheets the shop stocks, mm, comma-separated, thinnest first; "
                                          "empty: the format's default, the standard 2024-T3 gauges up to 0.160 in "
                                          "for loads with a mass or cases, none for loads with one force")
    # requirements
    stiffness_limit: EnumProperty(name="Stiffness", default='DEFLECTION', items=[
        ('DEFLECTION', "Max deflection", "Limit the deflection at the load point (C_max = |F|·δ_max)"),
        ('COMPLIANCE', "Max compliance", "Limit the compliance fᵀu (J)")])
    max_deflection_mm: FloatProperty(name="Max deflection (mm)", default=_R.max_deflection * 1e3, min=1e-9,
                                     precision=3)
    max_compliance: FloatProperty(name="Max compliance (J)", default=0.1, min=1e-12, precision=4)
    min_margin_of_safety: FloatProperty(name="Min MS", default=_R.min_margin_of_safety, precision=3,
                                        description="Minimum margin of safety MS = Fty/(SF·σ_vm,max) − 1")
    safety_factor: FloatProperty(name="Safety factor", default=_R.safety_factor, min=1e-6, precision=3)
    clearance_mm: FloatProperty(name="Clearance (mm)", default=_R.clearance * 1e3, min=0.0, precision=3,
                                description="Gap kept beyond t/2 between the sheet and any obstacle, mm")
    use_min_buckling_factor: BoolProperty(name="Min buckling factor", default=False,
                                          description="Set the lowest buckling factor allowed over the cases "
                                                      "(off: the safety factor)")
    min_buckling_factor: FloatProperty(name="Min buckling factor", default=1.5, min=1e-6, precision=3,
                                       description="Lowest linear buckling factor over the cases")
    use_min_frequency: BoolProperty(name="Frequency floor", default=False,
                                    description="Require a lowest first natural frequency (off: none)")
    min_frequency_hz: FloatProperty(name="Min frequency (Hz)", default=25.0, min=1e-6, precision=2,
                                    description="Floor on the part's first natural frequency with the box's mass, Hz")
    # envelope (problem-level load_cases)
    use_envelope: BoolProperty(name="Envelope", default=False,
                               description="Inertia cases for every load with a mass (the problem's load_cases)")
    envelope_forward: FloatVectorProperty(name="Forward", size=3, subtype='XYZ', default=(1.0, 0.0, 0.0),
                                          precision=4, description="The aircraft's forward direction in the scene")
    envelope_up: FloatVectorProperty(name="Up", size=3, subtype='XYZ', default=(0.0, 0.0, 1.0), precision=4,
                                     description="The aircraft's up direction in the scene (orthogonal to forward)")
    envelope_kind: EnumProperty(name="Factors", default='PRESET', items=[
        ('PRESET', "FAR/CS 25.561", "Emergency landing: 9 g forward, 1.5 g rearward, 3 g to either side, 6 g down, "
                                   "3 g up (ultimate, each separately)"),
        ('LIST', "List", "Your own list of factors")])
    envelope_factors: CollectionProperty(type=SheetgenFactor)
    envelope_factor_index: IntProperty(name="Active factor", default=0)
    # search
    chains: IntProperty(name="Chains", default=_S.chains, min=1, max=1024)
    iterations: IntProperty(name="Iterations", default=_S.iterations, min=0, max=10000000)
    beam_width: IntProperty(name="Beam width", default=_S.beam_width, min=1, max=4096)
    seed: IntProperty(name="Seed", default=_S.seed, min=0)
    alpha: FloatProperty(name="α", default=_S.alpha, min=0.0, description="Eq. 1 of the paper")
    beta: FloatProperty(name="β", default=_S.beta, min=0.0, description="Eq. 1 of the paper")
    scene_unit: FloatProperty(name="Scene unit (m)", default=_S.scene_unit, min=1e-6, precision=3,
                              description="Length unit of the distances in Eq. 1–2 of the paper, m")
    threads: IntProperty(name="Threads", default=_S.threads, min=0, max=1024, description="0 = all cores")
    # Manufacturing limits have no UI yet; an imported problem's section is kept verbatim.
    manufacturing_json: StringProperty(name="Manufacturing (JSON)", default="{}")
    # results: the run collection the Results panel shows (the latest Generate)
    result_collection: PointerProperty(type=bpy.types.Collection, name="Run",
                                       description="The sheetgen run collection shown in the Results panel")
    result_load_index: IntProperty(name="Load", default=0, min=0, description="Load shown in the Results panel")


CLASSES = (SheetgenRivetArea, SheetgenLoadCase, SheetgenFactor, SheetgenObjectSettings, SheetgenSceneSettings)


def register():
    for c in CLASSES:
        bpy.utils.register_class(c)
    bpy.types.Object.sheetgen = PointerProperty(type=SheetgenObjectSettings)
    bpy.types.Scene.sheetgen = PointerProperty(type=SheetgenSceneSettings)


def unregister():
    del bpy.types.Scene.sheetgen
    del bpy.types.Object.sheetgen
    for c in reversed(CLASSES):
        bpy.utils.unregister_class(c)
