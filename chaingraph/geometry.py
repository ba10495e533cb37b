"""The one 2-D kit: vectors, rigid motions, and the intersections a dyad is made of.

Angles are radians inside; a name that takes or gives degrees says so (``unit_deg``,
``direction_deg``). Every function works on plain floats and, where the arithmetic
allows, on numpy arrays of the same shape (a whole sweep at once).

Three shapes of rigid motion are used, each for its reason:

* a *frame* ``(phi, x, y)``: a body's rotation and position, as assembly places links;
* a *pose entry* ``(x, y, phi, cos phi, sin phi)``: the same with the trigonometry
  done once, as the solver carries a link over a sweep (arrays, or the fixed link's
  constants :data:`FIXED`, which numpy broadcasts);
* a *line* ``(angle, offset)``: the points p with ``normal(angle) . p == offset``.

Examples
--------
>>> [round(v, 12) for v in rotate((1.0, 0.0), math.pi / 2)]
[0.0, 1.0]
>>> mid, across, raw = circle_circle((0.0, 0.0), 5.0, (8.0, 0.0), 5.0)
>>> [float(v) for v in mid + across + (raw,)]
[4.0, 0.0, -0.0, 1.0, 9.0]
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from typing import Any, TypeAlias

import numpy as np

__all__ = [
    "sub", "dot", "cross", "perp", "distance", "angle_between", "normalised", "rotate", "unit", "normal",
    "unit_deg", "direction_deg",
    "apply", "compose", "inverse", "frame_from_two", "fit_frame", "line_in",
    "FIXED", "cos_sin", "make_pose", "turn_by", "world", "fit_two_points", "from_point",
    "DISC_TOL", "clamp_disc", "circle_circle", "circle_line", "line_by_two_distances",
    "convex_hull", "polygon_area", "segment_distance", "Scalar", "Vec", "Frame", "PoseEntry",
    "Line",
]


#: a coordinate, length or angle: a float, or a numpy array of them (a sweep at once)
Scalar: TypeAlias = Any
#: a point or vector (x, y), or a numpy array of the two
Vec: TypeAlias = "tuple[Scalar, Scalar] | np.ndarray"
#: a frame (phi, x, y)
Frame: TypeAlias = tuple[Scalar, Scalar, Scalar]
#: a pose entry (x, y, phi, cos phi, sin phi)
PoseEntry: TypeAlias = tuple[Scalar, Scalar, Scalar, Scalar, Scalar]
#: a line (angle, offset): the points p with normal(angle) . p == offset
Line: TypeAlias = tuple[Scalar, Scalar]


# -- vectors ---------------------------------------------------------------------------
def sub(a: Vec, b: Vec) -> Vec:
    """a - b."""
    return (a[0] - b[0], a[1] - b[1])


def dot(a: Vec, b: Vec) -> Scalar:
    return a[0] * b[0] + a[1] * b[1]


def cross(a: Vec, b: Vec) -> Scalar:
    """The z component of a x b (positive when b is counter-clockwise of a)."""
    return a[0] * b[1] - a[1] * b[0]


def perp(v: Vec) -> Vec:
    """The vector turned a quarter turn counter-clockwise (k x v)."""
    return (-v[1], v[0])


def distance(p: Vec, q: Vec) -> Scalar:
    return math.hypot(p[0] - q[0], p[1] - q[1])


def angle_between(u: Vec, v: Vec) -> Scalar:
    """The angle between ``u`` and ``v`` in degrees, in [0, 180] (a transmission
    angle's measure: from |u x v| and u . v, exact near 0 and 180 as an arccos is not).

    >>> float(angle_between((1.0, 0.0), (-1.0, 1.0)))
    135.0
    """
    return np.degrees(np.arctan2(np.abs(cross(u, v)), dot(u, v)))


def normalised(v: Vec) -> np.ndarray | None:
    """``v`` as a unit numpy vector, or None when it has no direction (zero, or not
    finite)."""
    u = np.asarray(v, dtype=float)
    n = float(np.linalg.norm(u))
    return u / n if n > 0 and math.isfinite(n) else None


def rotate(v: Vec, angle: Scalar) -> Vec:
    """``v`` turned by ``angle`` (radians) counter-clockwise."""
    c, s = np.cos(angle), np.sin(angle)
    if not isinstance(angle, np.ndarray):
        c, s = float(c), float(s)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


def unit(angle: Scalar) -> Vec:
    """The unit vector at ``angle`` (radians)."""
    return (math.cos(angle), math.sin(angle))


def normal(angle: Scalar) -> Vec:
    """The unit normal of the direction ``angle`` (radians): ``unit`` turned a quarter."""
    return (-math.sin(angle), math.cos(angle))


def unit_deg(degrees: Scalar) -> Vec:
    """The unit vector at ``degrees``."""
    return math.cos(math.radians(degrees)), math.sin(math.radians(degrees))


def direction_deg(v: Vec) -> Scalar:
    """The direction of ``v`` in degrees in [0, 360), or None for the zero vector.

    >>> direction_deg((0.0, -2.0)), direction_deg((0.0, 0.0))
    (270.0, None)
    """
    return math.degrees(math.atan2(v[1], v[0])) % 360.0 if (v[0] or v[1]) else None


# -- frames (phi, x, y) ----------------------------------------------------------------
def apply(frame: Frame, p: Vec) -> Vec:
    """The point ``p`` of a body, where the body's ``frame`` puts it."""
    q = rotate(p, frame[0])
    return (q[0] + frame[1], q[1] + frame[2])


def compose(a: Frame, b: Frame) -> Frame:
    """The frame ``a`` after ``b``."""
    t = apply(a, (b[1], b[2]))
    return (a[0] + b[0], t[0], t[1])


def inverse(a: Frame) -> Frame:
    t = rotate((-a[1], -a[2]), -a[0])
    return (-a[0], t[0], t[1])


def frame_from_two(q1: Vec, w1: Vec, q2: Vec, w2: Vec) -> Frame:
    """The frame taking body points q1, q2 to w1, w2 (the rotation from the chord)."""
    phi = (math.atan2(w2[1] - w1[1], w2[0] - w1[0])
           - math.atan2(q2[1] - q1[1], q2[0] - q1[0]))
    r = rotate(q1, phi)
    return (phi, w1[0] - r[0], w1[1] - r[1])


def fit_frame(pairs: Sequence[tuple[Vec, Vec]]) -> Frame:
    """The frame that best takes body points to given places, ``pairs`` of
    ``(body point, place)`` (least squares)."""
    q = np.array([p for p, _ in pairs], dtype=float)
    w = np.array([s for _, s in pairs], dtype=float)
    qc, wc = q - q.mean(0), w - w.mean(0)
    phi = math.atan2(np.sum(qc[:, 0] * wc[:, 1] - qc[:, 1] * wc[:, 0]),
                     np.sum(qc[:, 0] * wc[:, 0] + qc[:, 1] * wc[:, 1]))
    r = rotate(tuple(q.mean(0)), phi)
    m = w.mean(0)
    return (phi, float(m[0] - r[0]), float(m[1] - r[1]))


def line_in(frame: Frame, line: Line) -> Line:
    """A body's line ``(angle, offset)`` where the body's ``frame`` puts it."""
    angle = line[0] + frame[0]
    return (angle, line[1] + dot(normal(angle), (frame[1], frame[2])))


# -- pose entries (x, y, phi, cos phi, sin phi), scalar or over a sweep ----------------
FIXED = (0.0, 0.0, 0.0, 1.0, 0.0)


_HALF_ANGLE_FROM = 64     # arrays this long or longer: cos and sin by the half angle


def cos_sin(phi: Scalar) -> tuple[Scalar, Scalar]:
    """The cosine and sine of ``phi`` (radians). Over a long array, from the tangent of
    the half angle, t: cos = (1 - t^2) / (1 + t^2), sin = 2 t / (1 + t^2), within 3e-16
    of numpy's cos and sin (numpy's float64 tangent is vectorised, its cosine and sine
    are not: a sweep's crank costs a fifth as much).

    >>> c, s = cos_sin(np.radians(np.arange(0.0, 360.0, 1.0)))
    >>> bool(np.allclose(c, np.cos(np.radians(np.arange(360.0))), rtol=0, atol=1e-15))
    True
    >>> [float(v) for v in cos_sin(np.pi / 2)]
    [6.123233995736766e-17, 1.0]
    """
    if np.ndim(phi) == 0 or np.size(phi) < _HALF_ANGLE_FROM:
        return np.cos(phi), np.sin(phi)
    t = np.tan(0.5 * phi)
    t2 = t * t
    d = 1.0 + t2
    c = 1.0 - t2
    c /= d
    s = t + t
    s /= d
    return c, s


def make_pose(x: Scalar, y: Scalar, phi: Scalar, c: Scalar = None,
              s: Scalar = None) -> PoseEntry:
    """A pose entry from a motion (x, y, phi)."""
    if c is None:
        c, s = cos_sin(phi)
    return (x, y, phi, c, s)


def turn_by(entry: PoseEntry, p: Vec) -> Vec:
    """The drawn vector ``p`` turned by the pose entry's rotation."""
    c, s = entry[3], entry[4]
    return c * p[0] - s * p[1], s * p[0] + c * p[1]


def world(pose: Mapping[str, PoseEntry], link: str, p: Vec) -> Vec:
    """Where the pose puts the drawn point ``p`` of ``link`` (``pose`` maps links to
    entries)."""
    e = pose[link]
    rx, ry = turn_by(e, p)
    return rx + e[0], ry + e[1]


def fit_two_points(p1: Vec, w1: Vec, p2: Vec, w2: Vec) -> PoseEntry:
    """The pose entry taking drawn points p1, p2 to w1, w2 (rotation from the chord)."""
    dpx, dpy = p2[0] - p1[0], p2[1] - p1[1]
    dwx, dwy = w2[0] - w1[0], w2[1] - w1[1]
    c = dpx * dwx + dpy * dwy
    s = dpx * dwy - dpy * dwx
    norm = np.sqrt(c * c + s * s)       # (np.hypot costs three times as much)
    c, s = c / norm, s / norm
    rx, ry = turn_by((0.0, 0.0, None, c, s), p1)
    return make_pose(w1[0] - rx, w1[1] - ry, np.arctan2(s, c), c, s)


def from_point(entry: PoseEntry, p: Vec, w: Vec) -> PoseEntry:
    """The pose entry with the rotation of ``entry`` that puts drawn point p at w."""
    rx, ry = turn_by(entry, p)
    return make_pose(w[0] - rx, w[1] - ry, entry[2], entry[3], entry[4])


# -- the intersections of a dyad -------------------------------------------------------
DISC_TOL = 1e-13   # dimensionless discriminant: rounding is about 1e-16


def clamp_disc(disc: Scalar, scale: Scalar, double: Scalar = False) -> Scalar:
    """A discriminant where the modes exist (within rounding of zero: zero), NaN
    elsewhere, and where it is; zero where ``double`` (the modes' double root).
    ``scale`` is the discriminant's magnitude (a length squared, or 1)."""
    tol = DISC_TOL * scale
    ok = (disc >= -tol) | double
    return np.where(double, 0.0, np.where(ok, np.maximum(disc, 0.0), np.nan)), ok


def circle_circle(c1: Vec, r1: Scalar, c2: Vec, r2: Scalar) -> tuple[Vec, Vec, Scalar]:
    """Where two circles meet: ``(mid, across, raw)``, the points being
    ``mid +- sqrt(raw) * across`` (``+``: left of the line from c1 to c2), ``raw`` the
    squared half-chord (negative where the circles do not meet; judge it with
    :func:`clamp_disc`), ``across`` the unit normal of that line.

    >>> mid, across, raw = circle_circle((0.0, 0.0), 5.0, (6.0, 0.0), 5.0)
    >>> [float(v) for v in mid + across + (raw,)]
    [3.0, 0.0, -0.0, 1.0, 16.0]
    """
    dx, dy = c2[0] - c1[0], c2[1] - c1[1]
    d2 = dx * dx + dy * dy
    d = np.sqrt(d2)
    ux, uy = dx / d, dy / d
    # measured from the centre of the smaller circle, as (r - along) (r + along): the
    # half-chord squared then carries a rounding of about eps * r * d, not eps * d**2,
    # so that a link far shorter than the other keeps its length at a fold
    first = r1 <= r2
    if isinstance(first, (bool, np.bool_)):    # radii as numbers: only the branch taken
        if first:
            along1 = (r1 * r1 - r2 * r2 + d2) / (2 * d)
            return ((c1[0] + along1 * ux, c1[1] + along1 * uy), (-uy, ux),
                    (r1 - along1) * (r1 + along1))
        along2 = (r2 * r2 - r1 * r1 + d2) / (2 * d)
        return ((c2[0] - along2 * ux, c2[1] - along2 * uy), (-uy, ux),
                (r2 - along2) * (r2 + along2))
    along1 = (r1 * r1 - r2 * r2 + d2) / (2 * d)
    along2 = (r2 * r2 - r1 * r1 + d2) / (2 * d)
    raw = np.where(first, (r1 - along1) * (r1 + along1), (r2 - along2) * (r2 + along2))
    mx = np.where(first, c1[0] + along1 * ux, c2[0] - along2 * ux)
    my = np.where(first, c1[1] + along1 * uy, c2[1] - along2 * uy)
    return (mx, my), (-uy, ux), raw


def circle_line(centre: Vec, r: Scalar, base: Vec,
                direction: Vec) -> tuple[Vec, Vec, Scalar]:
    """Where a circle meets the line through ``base`` along the unit ``direction``:
    ``(foot, direction, raw)``, the points being ``foot +- sqrt(raw) * direction``
    (``+``: ahead along the line), ``foot`` the centre's foot on the line, ``raw`` the
    squared half-chord (negative where they do not meet).

    >>> foot, u, raw = circle_line((0.0, 0.0), 5.0, (-10.0, 3.0), (1.0, 0.0))
    >>> [float(v) for v in foot + u + (raw,)]
    [0.0, 3.0, 1.0, 0.0, 16.0]
    """
    ex, ey = base[0] - centre[0], base[1] - centre[1]
    beta = direction[0] * ex + direction[1] * ey
    h = direction[0] * ey - direction[1] * ex       # the centre's distance to the line
    raw = (r - h) * (r + h)     # rounding about eps * r * |base - centre|
    foot = (base[0] - beta * direction[0], base[1] - beta * direction[1])
    return foot, direction, raw


def line_by_two_distances(a: Vec, b: Vec, c: Scalar) -> tuple[Vec, Scalar, Scalar]:
    """The lines that pass at signed distances ``h_a`` from ``a`` and ``h_b`` from
    ``b`` with ``c = h_b - h_a``: their unit normal n satisfies ``n . (b - a) = c``.
    Returns ``(u, ratio, raw)``: ``u`` the unit vector from a to b, ``ratio = c / |b - a|``
    (the cosine of the normal's turn from u) and ``raw = 1 - ratio**2`` (negative where
    no such line exists); the normals are u turned by ``+- acos(ratio)``.

    >>> u, ratio, raw = line_by_two_distances((0.0, 0.0), (0.0, 2.0), 1.0)
    >>> [float(v) for v in u + (ratio, raw)]
    [0.0, 1.0, 0.5, 0.75]
    """
    dx, dy = b[0] - a[0], b[1] - a[1]
    dist = np.hypot(dx, dy)
    ratio = c / dist
    return (dx / dist, dy / dist), ratio, 1.0 - ratio * ratio


# -- polygons --------------------------------------------------------------------------
def convex_hull(points: Iterable[Vec]) -> list[Vec]:
    """The convex hull of 2-D points, counter-clockwise (monotone chain).

    >>> convex_hull([(0, 0), (2, 0), (1, 1), (2, 2), (0, 2)])
    [(0, 0), (2, 0), (2, 2), (0, 2)]
    """
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts

    def half(seq):
        out: list[Any] = []
        for p in seq:
            while len(out) >= 2 and cross(sub(out[-1], out[-2]), sub(p, out[-2])) <= 0:
                out.pop()
            out.append(p)
        return out

    lower, upper = half(pts), half(reversed(pts))
    return lower[:-1] + upper[:-1]


def segment_distance(p: Vec, a: Vec, b: Vec) -> float:
    """The distance from the point ``p`` to the segment ``a``-``b`` (a point when the two
    ends coincide).

    >>> segment_distance((1, 1), (0, 0), (2, 0)), segment_distance((3, 0), (0, 0), (0, 0))
    (1.0, 3.0)
    """
    ax, ay = b[0] - a[0], b[1] - a[1]
    length = ax * ax + ay * ay
    t = 0.0 if length == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * ax + (p[1] - a[1]) * ay)
                                         / length))
    return math.dist(p, (a[0] + t * ax, a[1] + t * ay))


def polygon_area(polygon: Sequence[Vec]) -> float:
    """The area of a simple polygon (shoelace).

    >>> polygon_area([(0, 0), (2, 0), (2, 2), (0, 2)])
    4.0
    """
    points = list(polygon)
    return 0.5 * abs(sum(cross(p, q) for p, q in zip(points, points[1:] + points[:1])))
