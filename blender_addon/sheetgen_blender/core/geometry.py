"""Small geometry and number helpers (pure Python)."""
import math
import struct
from typing import Dict, Iterable, List, Sequence, Tuple


def triangle_area(a: Sequence[float], b: Sequence[float], c: Sequence[float]) -> float:
    """Area of triangle abc (m^2 for points in m): half the norm of (b - a) x (c - a)."""
    ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    cx, cy, cz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    return 0.5 * math.sqrt(cx * cx + cy * cy + cz * cz)


def rivet_area_areas(vertices: Sequence[Sequence[float]], triangles: Sequence[Sequence[int]],
                     face_areas: Iterable[int]) -> Dict[int, Tuple[float, int]]:
    """Area id -> (area in m^2, triangle count) for every id > 0 in face_areas (#F)."""
    out: Dict[int, Tuple[float, int]] = {}
    for f, k in enumerate(face_areas):
        if k <= 0:
            continue
        i, j, l = triangles[f]
        a, n = out.get(k, (0.0, 0))
        out[k] = (a + triangle_area(vertices[i], vertices[j], vertices[l]), n + 1)
    return out


def is_finite_vec(v, n: int = 3) -> bool:
    try:
        return len(v) == n and all(isinstance(x, (int, float)) and not isinstance(x, bool) and math.isfinite(x) for x in v)
    except TypeError:
        return False


def quat_normalized(q: Sequence[float]) -> Tuple[float, float, float, float]:
    """Unit quaternion (w, x, y, z) with w >= 0 (q and -q are the same rotation)."""
    n = math.sqrt(sum(x * x for x in q))
    if not n > 0:
        raise ValueError("quaternion has zero length")
    n = n if q[0] >= 0 else -n
    return tuple(x / n for x in q)  # type: ignore[return-value]


def quat_unit(q: Sequence[float], tol: float = 1e-6) -> Tuple[float, float, float, float]:
    """q with w >= 0, normalised only when its length is off 1 by more than ``tol``.

    A quaternion that is unit to float32 precision (what Blender stores) is kept
    digit for digit, so files round-trip; the native parser normalises anyway.
    """
    n = math.sqrt(sum(x * x for x in q))
    if abs(n - 1.0) > tol:
        return quat_normalized(q)
    s = 1.0 if q[0] >= 0 else -1.0
    return tuple(float(x) * s for x in q)  # type: ignore[return-value]


def quat_rotate(q: Sequence[float], v: Sequence[float]) -> Tuple[float, float, float]:
    """Rotate vector v by unit quaternion q = (w, x, y, z)."""
    w, x, y, z = q
    # v' = v + 2w (u x v) + 2 u x (u x v), u = (x, y, z)
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + (y * tz - z * ty),
            v[1] + w * ty + (z * tx - x * tz),
            v[2] + w * tz + (x * ty - y * tx))


def _to_float32(x: float) -> float:
    return struct.unpack("f", struct.pack("f", x))[0]


def shortest_float32(x: float) -> float:
    """The shortest decimal that rounds to the same float32 as x, as a Python float.

    Blender stores coordinates and float properties as float32: 0.3 comes back
    as 0.30000001192092896. Writing the shortest decimal with the same float32
    (what numpy prints for a float32) gives back the number the user typed or the
    file held, and loses nothing Blender had.
    """
    if not math.isfinite(x) or x == 0.0:
        return float(x)
    try:
        f = _to_float32(x)
    except OverflowError:
        return float(x)
    for digits in (6, 7, 8):
        s = float("%.*g" % (digits, f))
        if _to_float32(s) == f:
            return s
    return float("%.9g" % f)  # 9 significant digits always round-trip a float32


def shortest_float32_list(values: Iterable[float]) -> List[float]:
    return [shortest_float32(v) for v in values]
