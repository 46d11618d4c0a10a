"""Small geometry and number helpers (pure Python)."""
import math
import struct
from typing import Dict, Iterable, List, Optional, Sequence, Tuple


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


# Tolerance of the native reader (native/sheetgen/core/load_cases.cpp): on |cos|
# between the aircraft's forward and up, and on an inertia tensor's relative
# asymmetry. Far above float32 rounding (1e-7), far below any intended angle.
AXIS_TOLERANCE = 1e-6


def unit(v: Sequence[float]) -> Tuple[float, float, float]:
    """v / |v|; raises ValueError for a zero vector."""
    n = math.sqrt(sum(x * x for x in v))
    if not n > 0:
        raise ValueError("zero length")
    return (v[0] / n, v[1] / n, v[2] / n)


def axes_problem(forward: Sequence[float], up: Sequence[float]) -> Optional[str]:
    """Why (forward, up) cannot be the aircraft's axes, or None (the native reader's rule)."""
    try:
        f = unit(forward)
    except ValueError:
        return "forward has zero length"
    try:
        u = unit(up)
    except ValueError:
        return "up has zero length"
    c = f[0] * u[0] + f[1] * u[1] + f[2] * u[2]
    if abs(c) > AXIS_TOLERANCE:
        return ("forward and up are not orthogonal (%.6g degrees apart, |cos| = %.3g > %.0e)"
                % (math.degrees(math.acos(max(-1.0, min(1.0, c)))), abs(c), AXIS_TOLERANCE))
    return None


def left_axis(forward: Sequence[float], up: Sequence[float]) -> Tuple[float, float, float]:
    """left = up x forward (unit): (forward, left, up) is right-handed, forward x left = up."""
    f, u = unit(forward), unit(up)
    return unit((u[1] * f[2] - u[2] * f[1], u[2] * f[0] - u[0] * f[2], u[0] * f[1] - u[1] * f[0]))


def symmetric_eigenvalues(m: Sequence[Sequence[float]]) -> Tuple[float, float, float]:
    """Eigenvalues of a symmetric 3x3 matrix, ascending (closed form: Smith 1961, trigonometric)."""
    a = [[float(m[r][c]) for c in range(3)] for r in range(3)]
    p1 = a[0][1] ** 2 + a[0][2] ** 2 + a[1][2] ** 2
    q = (a[0][0] + a[1][1] + a[2][2]) / 3.0
    if p1 == 0.0:
        return tuple(sorted((a[0][0], a[1][1], a[2][2])))  # type: ignore[return-value]
    p2 = sum((a[i][i] - q) ** 2 for i in range(3)) + 2 * p1
    p = math.sqrt(p2 / 6.0)
    b = [[(a[r][c] - (q if r == c else 0.0)) / p for c in range(3)] for r in range(3)]
    det = (b[0][0] * (b[1][1] * b[2][2] - b[1][2] * b[2][1]) - b[0][1] * (b[1][0] * b[2][2] - b[1][2] * b[2][0])
           + b[0][2] * (b[1][0] * b[2][1] - b[1][1] * b[2][0]))
    phi = math.acos(max(-1.0, min(1.0, det / 2.0))) / 3.0
    e3 = q + 2 * p * math.cos(phi)
    e1 = q + 2 * p * math.cos(phi + 2 * math.pi / 3)
    return (e1, 3 * q - e1 - e3, e3)


def inertia_problem(m) -> Optional[str]:
    """Why ``m`` (3 by 3, kg m^2) is not a rigid body's inertia tensor, or None (the native reader's rules:
    symmetric to 1e-6 of its largest entry, positive definite, largest principal moment <= sum of the others)."""
    try:
        ok = len(m) == 3 and all(is_finite_vec(row, 3) for row in m)
    except TypeError:
        ok = False
    if not ok:
        return "expected 3 rows of 3 finite numbers (kg·m²)"
    scale = max(abs(float(x)) for row in m for x in row)
    if not scale > 0:
        return "inertia is all zeros: not positive definite"
    for r in range(3):
        for c in range(r + 1, 3):
            if abs(m[r][c] - m[c][r]) / scale > AXIS_TOLERANCE:
                return ("inertia is not symmetric: [%d][%d] = %.6g but [%d][%d] = %.6g"
                        % (r, c, m[r][c], c, r, m[c][r]))
    sym = [[0.5 * (m[r][c] + m[c][r]) / scale for c in range(3)] for r in range(3)]
    p = [e * scale for e in symmetric_eigenvalues(sym)]
    moments = "principal moments %.6g, %.6g, %.6g kg·m²" % tuple(p)
    if not p[0] > 0:
        return "inertia is not positive definite (%s)" % moments
    if p[2] > (p[0] + p[1]) * (1 + AXIS_TOLERANCE):
        return "inertia is not that of a rigid body (%s: the largest exceeds the sum of the other two)" % moments
    return None
