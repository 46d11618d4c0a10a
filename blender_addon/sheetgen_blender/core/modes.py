"""A part's buckling and vibration modes as shape keys of its FEM mesh (plain Python, no bpy, no numpy).

The native ``part_modes`` gives the final check's FEM mesh (nodes and
triangles, m) and two mode shapes per node (translations, largest 1): the
buckling mode of the governing case and the first vibration mode. A mode's
scale is arbitrary, so each becomes a shape key whose largest displacement is
``MODE_FRACTION`` of the part's largest extent: at value 1 (or -1, the other
half period) the shape is plain to see without turning the part inside out.

Why a mesh of its own rather than keys on the bent part (``<load> part``):
that mesh has only the tab corners as vertices, while a buckling mode is a
wave across a tab's interior and a vibration mode bends the tabs between
their rivets; the corners alone would show almost nothing of either (a
clamped flange's corners do not move at all).
"""
from dataclasses import dataclass, field
from typing import List, Optional, Sequence, Tuple

MODE_FRACTION = 0.1   # largest key displacement / largest extent of the part


class ModesError(ValueError):
    """The modes cannot be shown (one sentence)."""


@dataclass
class ModeKey:
    name: str                                   # shape key name
    positions: List[Tuple[float, float, float]]  # #V, m: basis + scale * mode
    scale: float                                # m per unit of the mode


@dataclass
class ModesMesh:
    vertices: List[Tuple[float, float, float]] = field(default_factory=list)   # #V, m (the basis)
    triangles: List[Tuple[int, int, int]] = field(default_factory=list)        # #F
    keys: List[ModeKey] = field(default_factory=list)
    summary: str = ""


def compact(vertices: Sequence[Sequence[float]], triangles: Sequence[Sequence[int]]):
    """(kept vertex indices, triangles renumbered): only the vertices a triangle uses (the FEM model also has
    the load box's master node and rigid-link nodes, which are not sheet)."""
    used = sorted({int(i) for t in triangles for i in t})
    new = {old: k for k, old in enumerate(used)}
    return used, [(new[int(t[0])], new[int(t[1])], new[int(t[2])]) for t in triangles]


def largest_extent(points: Sequence[Sequence[float]]) -> float:
    if not points:
        return 0.0
    return max(max(p[i] for p in points) - min(p[i] for p in points) for i in range(3))


def buckling_key_name(case: Optional[str], factor: float) -> str:
    return "buckling %s (factor %.3g)" % (case or "?", factor)


def vibration_key_name(frequency_hz: float) -> str:
    return "vibration 1 (%.3g Hz)" % frequency_hz


def modes_mesh(modes: dict, fraction: float = MODE_FRACTION) -> ModesMesh:
    """The mesh and shape keys for the native ``part_modes`` dict (arrays as nested lists or numpy arrays)."""
    try:
        vertices = [tuple(float(x) for x in v) for v in modes["vertices"]]
        triangles = [tuple(int(i) for i in t) for t in modes["triangles"]]
    except (KeyError, TypeError, ValueError):
        raise ModesError("the modes have no mesh (vertices and triangles)") from None
    if not triangles:
        raise ModesError("the part's FEM mesh has no triangles")
    used, tris = compact(vertices, triangles)
    out = ModesMesh(vertices=[vertices[i] for i in used], triangles=tris)
    extent = largest_extent(out.vertices)
    freqs = list(modes.get("frequencies_hz") or [])
    entries = []
    if modes.get("buckling_mode") is not None and modes.get("buckling_factor") is not None:
        entries.append((buckling_key_name(modes.get("buckling_case"), modes["buckling_factor"]), modes["buckling_mode"]))
    if modes.get("vibration_mode") is not None and freqs:
        entries.append((vibration_key_name(freqs[0]), modes["vibration_mode"]))
    for name, mode in entries:
        if len(mode) != len(vertices):
            raise ModesError("mode '%s' has %d nodes, the mesh %d" % (name, len(mode), len(vertices)))
        peak = max((sum(float(x) ** 2 for x in mode[i]) ** 0.5 for i in used), default=0.0)
        if not peak > 0:
            continue   # a mode that does not move the sheet (all in the box's master node) shows nothing
        scale = fraction * extent / peak
        pos = [(b[0] + scale * float(mode[i][0]), b[1] + scale * float(mode[i][1]), b[2] + scale * float(mode[i][2]))
               for b, i in zip(out.vertices, used)]
        out.keys.append(ModeKey(name=name, positions=pos, scale=scale))
    out.summary = modes_summary(modes)
    return out


def modes_summary(modes: dict) -> str:
    """One report line: the buckling factor with its case and the frequencies."""
    parts = []
    if modes.get("buckling_factor") is not None:
        parts.append("buckling factor %.3g (%s)" % (modes["buckling_factor"], modes.get("buckling_case") or "?"))
    else:
        parts.append("no buckling (nothing compresses the sheet)")
    freqs = list(modes.get("frequencies_hz") or [])
    if freqs:
        parts.append("frequencies " + ", ".join("%.3g" % f for f in freqs) + " Hz")
    return ", ".join(parts)
