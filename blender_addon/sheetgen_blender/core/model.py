"""The scene as plain data: what the bpy layer reads from Blender and builds into it.

Units are SI (m, N, N*m, Pa, kg/m^3), as in docs/problem-format.md; shapes are
given as "#V by 3". Defaults are the ones of docs/problem-format.md (docs/architecture.md
"Units and defaults"); a test checks them against that table.
"""
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Sequence

PROBLEM_FORMAT = "sheetgen-problem/1"


@dataclass
class MeshData:
    """One environment mesh: a Blender mesh object, triangulated, in world space."""
    name: str                                  # object name = problem mesh name
    vertices: List[Sequence[float]]            # #V by 3, m, world space
    triangles: List[Sequence[int]]             # #F by 3, 0-based vertex indices
    face_areas: Optional[List[int]] = None     # #F: 0 = no rivet area, k = area id (local to this mesh)
    area_names: Dict[int, str] = field(default_factory=dict)  # area id -> rivet area name (unique in the problem)
    # area id -> its 1-based position in an imported problem's rivet_areas: written in that order again, so the
    # solver numbers the areas as the file did (result.json's rivet_area); areas without one follow.
    area_order: Dict[int, int] = field(default_factory=dict)

    def area_of_face(self, f: int) -> int:
        return self.face_areas[f] if self.face_areas else 0


@dataclass
class LoadCaseData:
    """One explicit case of a load (``loads[i].cases[k]``): force and moment on the centre of mass."""
    name: str
    force: Sequence[float] = (0.0, 0.0, 0.0)    # N, world
    moment: Sequence[float] = (0.0, 0.0, 0.0)   # N*m, world, about the centre of mass
    max_deflection: Optional[float] = None      # m; this case's own stiffness limit


# What a load's own cases are (docs/problem-format.md "Load cases"): the one
# force/moment case "design", an explicit case list, or none (a box with a
# mass held under the problem's envelope only).
OWN_FORCE, OWN_CASES, OWN_NONE = "force", "cases", "none"


@dataclass
class LoadData:
    """A load box: an oriented box, its own cases (world frame) and its mass properties."""
    name: str
    center: Sequence[float]                     # m, world, box centroid
    size: Sequence[float]                       # m, along the box's local x, y, z
    rotation: Sequence[float] = (1.0, 0.0, 0.0, 0.0)  # quaternion w, x, y, z, local -> world
    force: Sequence[float] = (0.0, 0.0, 0.0)    # N, world (own == OWN_FORCE)
    moment: Sequence[float] = (0.0, 0.0, 0.0)   # N*m, world, about the centroid (own == OWN_FORCE)
    own: str = OWN_FORCE                        # OWN_FORCE, OWN_CASES or OWN_NONE
    cases: List[LoadCaseData] = field(default_factory=list)   # own == OWN_CASES
    mass: Optional[float] = None                # kg; None: no mass (no inertia cases, no box in the frequencies)
    center_of_mass: Optional[Sequence[float]] = None    # m, world; None: the box centroid
    inertia: Optional[Sequence[Sequence[float]]] = None  # kg*m^2, 3 by 3, world, about the centre of mass;
    #                                                     None: the uniform box's


@dataclass
class Material:
    youngs_modulus: float = 73.1e9      # Pa (Al 2024-T3)
    poisson_ratio: float = 0.33
    density: float = 2780.0             # kg/m^3
    yield_strength: float = 345e6       # Pa, Fty
    ultimate_strength: float = 483e6    # Pa, Ftu
    thickness: float = 1.6e-3           # m (0.063 in)
    # Thicker sheets tried, m, thinnest first, where `thickness` gives a load no
    # part; None: the format's default (the standard 2024-T3 gauges above
    # `thickness`); []: the problem's sheet only.
    gauges: Optional[List[float]] = None


@dataclass
class Requirements:
    # Exactly one of max_deflection (m) and max_compliance (J) is set.
    max_deflection: Optional[float] = 1e-3   # m, at the load point; C_max = |F| * delta_max
    max_compliance: Optional[float] = None   # J
    min_margin_of_safety: float = 0.0
    safety_factor: float = 1.5
    clearance: float = 1e-3                  # m, beyond t/2 from the mid-surface
    # Written only when set: naming either turns the buckling and frequency
    # checks on (docs/problem-format.md "requirements"), so an old scene keeps
    # solving as before.
    min_buckling_factor: Optional[float] = None   # -; None: the format's default, safety_factor
    min_frequency_hz: Optional[float] = None      # Hz; None: no floor


# The FAR/CS 25.561(b)(3) preset of the envelope (docs/problem-format.md "Load
# cases"), as the native reader expands it: (name, g (forward, left, up)).
PRESET_FAR25_561 = "far25.561"
PRESETS = {PRESET_FAR25_561: [("forward 9 g", (9.0, 0.0, 0.0)), ("rearward 1.5 g", (-1.5, 0.0, 0.0)),
                              ("left 3 g", (0.0, 3.0, 0.0)), ("right 3 g", (0.0, -3.0, 0.0)),
                              ("down 6 g", (0.0, 0.0, -6.0)), ("up 3 g", (0.0, 0.0, 3.0))]}
STANDARD_GRAVITY = 9.80665   # m/s^2, g0 (CGPM 1901): the g of every load factor


@dataclass
class FactorData:
    """One acceleration of the envelope: ``g`` in load factors along (forward, left, up)."""
    name: str
    g: Sequence[float] = (0.0, 0.0, 0.0)
    max_deflection: Optional[float] = None      # m; copied to the cases it makes


@dataclass
class Envelope:
    """The problem-level ``load_cases``: the aircraft's axes in the scene and the factors."""
    forward: Sequence[float] = (1.0, 0.0, 0.0)  # world direction
    up: Sequence[float] = (0.0, 0.0, 1.0)       # world direction, orthogonal to forward
    preset: Optional[str] = PRESET_FAR25_561    # a preset name, or None: ``factors`` is the list
    factors: List[FactorData] = field(default_factory=list)


@dataclass
class Search:
    chains: int = 10
    iterations: int = 1000
    beam_width: int = 8
    seed: int = 1
    alpha: float = 1.0
    beta: float = 3.0
    scene_unit: float = 0.1             # m (Eq. 1-2 of the paper measure distances in decimetres)
    threads: int = 0                    # 0 = all cores


@dataclass
class Settings:
    material: Material = field(default_factory=Material)
    requirements: Requirements = field(default_factory=Requirements)
    search: Search = field(default_factory=Search)
    # The manufacturing limits have no Blender UI yet: kept verbatim (defaults depend on t).
    manufacturing: dict = field(default_factory=dict)
    load_cases: Optional[Envelope] = None       # None: no envelope


@dataclass
class SceneData:
    name: str = "scene"
    description: str = ""
    meshes: List[MeshData] = field(default_factory=list)
    loads: List[LoadData] = field(default_factory=list)
    settings: Settings = field(default_factory=Settings)


# Field tables used for conversion and validation: (json key, label, kind).
# kind: "pos" > 0, "nonneg" >= 0, "any" finite, "poisson" in (-1, 0.5).
MATERIAL_FIELDS = [
    ("youngs_modulus", "Young's modulus (Pa)", "pos"),
    ("poisson_ratio", "Poisson's ratio", "poisson"),
    ("density", "density (kg/m^3)", "pos"),
    ("yield_strength", "yield strength Fty (Pa)", "pos"),
    ("ultimate_strength", "ultimate strength Ftu (Pa)", "pos"),
    ("thickness", "thickness (m)", "pos"),
]
REQUIREMENT_FIELDS = [
    ("min_margin_of_safety", "minimum margin of safety", "any"),
    ("safety_factor", "safety factor", "pos"),
    ("clearance", "clearance (m)", "nonneg"),
]
# Written only when set (None: the format's default), each > 0.
OPTIONAL_REQUIREMENT_FIELDS = [
    ("min_buckling_factor", "minimum buckling factor"),
    ("min_frequency_hz", "frequency floor (Hz)"),
]
# (key, label, low, high) for integers; the ranges are the native parser's.
SEARCH_INT_FIELDS = [
    ("chains", "chains", 1, 1024),
    ("iterations", "iterations", 0, 10000000),
    ("beam_width", "beam width", 1, 4096),
    ("seed", "seed", 0, 2**63 - 1),
    ("threads", "threads", 0, 1024),
]
SEARCH_FLOAT_FIELDS = [
    ("alpha", "alpha", "nonneg"),
    ("beta", "beta", "nonneg"),
    ("scene_unit", "scene unit (m)", "pos"),
]
