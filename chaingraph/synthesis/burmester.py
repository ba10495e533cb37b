"""Motion generation by Burmester theory: the dyads that guide a plane through two to five
poses (:mod:`chaingraph.synthesis.poses`), and the mechanisms two of them make.

A *dyad* joins the fixed link to the guided link through one binary link:

* ``"RR"``: a crank; its fixed pivot is the *centre point*, its moving pivot the
  *circle point*, whose positions in the poses lie on a circle about the centre point;
* ``"PR"``: a slider on the fixed link, pinned to the guided link at the circle point,
  whose positions lie on a line, the guide (the centre point is at infinity);
* ``"RP"``: a block turning about a fixed pivot (the centre point) and sliding in a
  guide of the guided link (the circle point is at infinity): the inversion of a PR.

A circle point is given where the first pose puts it. Its position in pose ``j`` is
``a_j = D_j(a)``, ``D_j`` the displacement from the first pose, and a centre point
``c`` fits when ``|a_j - c| = |a - c|`` for every j. In homogeneous coordinates
``a = (x, y, w)`` and ``c = (u, v, t)`` (``w = 0``: a point at infinity) each pose gives
one equation bilinear in the two, ``c^T B_j a = 0``: for a chosen circle point the
equations are linear in its centre point, and for a chosen centre point linear in its
circle point, which is the same as the circle point of the inverted poses
(:func:`~chaingraph.synthesis.poses.inverted`).

* two poses: a circle point's centre point anywhere on the bisector of its positions
  (:func:`centre_point` with ``offset``); three poses: the circumcentre of its three
  positions, at infinity when they are collinear (a slider);
* four poses: the centre points form a cubic, the *centre-point curve*, and their
  circle points the *circle-point curve* (:func:`centre_point_curve`,
  :func:`circle_point_curve`); every line through the pole ``P_1k`` meets a curve in
  two more points, found by a quadratic, and each curve has one real point at infinity
  (a slider);
* five poses: the centre-point curves of poses 1234 and 1235 meet in the *Burmester
  points* (0, 2 or 4 real dyads, :func:`burmester_points`), found here as the real
  roots of the resultant of two circle-point cubics through the pole ``P_1k``, a
  polynomial of degree 7 in the direction from that pole, each polished by Newton's
  method on the five equations; the same on the inverted poses finds the dyads whose
  circle point is at infinity.

Two dyads make a four-bar (two RR), a slider crank (an RR and a PR, or an RP) or a
double slider (:func:`mechanism`, :func:`candidates`), drawn at the first pose.

Examples
--------
The plane turning about (5, 0): the origin's centre point is (5, 0).

>>> poses = [(0.0, 0.0, 0.0), (5 - 5 * math.cos(0.4), -5 * math.sin(0.4), 0.4),
...          (5 - 5 * math.cos(1.1), -5 * math.sin(1.1), 1.1)]
>>> d = centre_point(poses, (0.0, 0.0))
>>> d.kind, [round(v, 12) + 0.0 for v in d.centre]
('RR', [5.0, 0.0])
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import Polynomial

from chaingraph.errors import DesignError
from chaingraph.geometry import direction_deg, normalised, perp
from chaingraph.model.chain import Chain, Input, Joint, Mechanism, Point
from chaingraph.synthesis.poses import (
    AT_INFINITY,
    SAME,
    Pose,
    checked_poses,
    displacement,
    inverted,
    moved,
    pole,
    task_size,
)

__all__ = ["Dyad", "centre_point", "circle_point", "BurmesterCurve", "centre_point_curve",
           "circle_point_curve", "burmester_points", "FITS", "residual", "dyad_inputs",
           "mechanism", "candidates"]

#: a dyad fits the poses when every equation ``c^T B_j a`` of unit homogeneous ``a``
#: and ``c`` is within this of 0 (about the relative error of its points)
FITS = 1e-9
_KIND = "motion"


@dataclass(frozen=True)
class Dyad:
    """A dyad guiding the plane: its ``kind`` (``"RR"``, ``"PR"``, ``"RP"``, see the
    module), its ``centre`` point (the fixed pivot; None for a PR), its ``circle``
    point where the first pose puts it (the moving pivot; None for an RP) and, for a
    slider, the unit direction of its ``guide`` where the first pose puts it (on the
    fixed link through the circle point for a PR, on the guided link through the
    centre point for an RP), turned to [0, 180) degrees."""

    kind: str
    centre: tuple[float, float] | None
    circle: tuple[float, float] | None
    guide: tuple[float, float] | None = None

    def __post_init__(self):
        needs = {"RR": ("centre", "circle"), "PR": ("circle", "guide"),
                 "RP": ("centre", "guide")}
        if self.kind not in needs:
            _fail(f"a dyad's kind is 'RR', 'PR' or 'RP', got {self.kind!r}", "dyad")
        for name in needs[self.kind]:
            if getattr(self, name) is None:
                _fail(f"an {self.kind} dyad needs its {name}", "dyad")

    def swapped(self) -> "Dyad":
        """The dyad of the inverted poses: centre and circle points swapped (a PR
        becomes an RP)."""
        kind = {"RR": "RR", "PR": "RP", "RP": "PR"}[self.kind]
        return Dyad(kind, self.circle, self.centre, self.guide)


def _fail(problem: str, parameter: str = "poses"):
    raise DesignError(problem, kind=_KIND, parameter=parameter)


def _given(p: tuple[float, float] | None) -> tuple[float, float]:
    """A dyad's point or guide that its kind has (:class:`Dyad` checks it)."""
    if p is None:
        raise TypeError("a point or guide that the dyad's kind has is None")
    return p


def _xy(p) -> tuple[float, float]:
    return (float(p[0]), float(p[1]))


def _line(v) -> tuple[float, float]:
    """A unit direction turned to [0, 180) degrees (a line's, either way along it; a
    line within rounding of the x axis points along +x)."""
    u = normalised(v)
    if u is None:
        raise ValueError(f"the direction {v!r} is zero or not finite")
    if u[1] < -1e-12 or (abs(u[1]) <= 1e-12 and u[0] < 0):
        u = -u
    return _xy(u)


# -- the equations, in coordinates about the first pose's point over the task's size --
@dataclass(frozen=True)
class _System:
    """The poses about ``origin`` over ``size``, and ``B[j]`` of the displacement from
    the first pose to pose ``j + 1``."""

    origin: tuple[float, float]
    size: float
    poses: tuple[Pose, ...]
    B: tuple[np.ndarray, ...]

    def world(self, h) -> tuple[tuple[float, float] | None, tuple[float, float] | None]:
        """A homogeneous point as ``(point, None)``, or ``(None, direction)`` at
        infinity."""
        h = np.asarray(h, dtype=float)
        if abs(h[2]) * AT_INFINITY <= math.hypot(h[0], h[1]):
            return None, _xy(normalised(h[:2]))
        return _xy((self.origin[0] + self.size * h[0] / h[2],
                    self.origin[1] + self.size * h[1] / h[2])), None

    def local(self, p) -> np.ndarray:
        """A point of the world as a homogeneous point of the system."""
        return np.array([(p[0] - self.origin[0]) / self.size,
                         (p[1] - self.origin[1]) / self.size, 1.0])

    def dyad(self, a, c) -> Dyad | None:
        """The dyad of homogeneous circle point ``a`` and centre point ``c`` (None when
        both are at infinity)."""
        circle, a_way = self.world(a)
        centre, c_way = self.world(c)
        if circle is not None and centre is not None:
            return Dyad("RR", centre, circle)
        if circle is not None and c_way is not None:
            return Dyad("PR", None, circle, _line(perp(c_way)))
        if centre is not None and a_way is not None:
            return Dyad("RP", centre, None, _line(perp(a_way)))
        return None


def _system(poses: Sequence[Pose]) -> _System:
    origin = (poses[0][0], poses[0][1])
    size = task_size(poses) or 1.0
    local = tuple(((x - origin[0]) / size, (y - origin[1]) / size, a) for x, y, a in poses)
    bs = []
    for j in range(1, len(local)):
        theta, tx, ty = displacement(local, 0, j)
        c, s = math.cos(theta), math.sin(theta)
        r, t = np.array([[c, -s], [s, c]]), np.array([tx, ty])
        b = np.empty((3, 3))
        b[:2, :2] = r - np.eye(2)
        b[:2, 2] = t
        b[2, :2] = -(r.T @ t)
        b[2, 2] = -0.5 * (t @ t)
        bs.append(b)
    return _System(origin, size, local, tuple(bs))


def residual(poses: Sequence[Pose], dyad: Dyad) -> float:
    """How far a dyad is from fitting the poses: the largest ``|c^T B_j a|`` over the
    poses, ``a`` and ``c`` its circle and centre points as unit homogeneous vectors
    (about the first pose's point, over the task's size); 0 for an exact fit.

    >>> poses = [(0, 0, 0), (1, 0, 0.3), (1, 1, 0.9), (0, 2, 1.4)]
    >>> residual(poses, centre_point_curve(poses).dyads(0.5)[0]) < 1e-14
    True
    """
    s = _system(checked_poses(poses))
    a, c = _homogeneous(s, dyad)
    return max((abs(float(c @ b @ a)) for b in s.B), default=0.0)


def _homogeneous(s: _System, dyad: Dyad) -> tuple[np.ndarray, np.ndarray]:
    """A dyad's circle and centre points as unit homogeneous vectors of the system."""
    def point(p, way):
        h = s.local(p) if p is not None else np.array([-way[1], way[0], 0.0])
        return h / np.linalg.norm(h)
    return point(dyad.circle, dyad.guide), point(dyad.centre, dyad.guide)


# -- two and three poses -------------------------------------------------------------
def centre_point(poses: Sequence[Sequence[float]], circle: Sequence[float], *,
                 offset: float = 0.0) -> Dyad:
    """The dyad that guides a chosen circle point through two or three poses.

    Parameters
    ----------
    poses : sequence of (x, y, angle)
        Two or three poses.
    circle : (x, y)
        The circle point, where the first pose puts it.
    offset : float
        Two poses only (the free choice): the centre point's signed distance from the
        midpoint of the circle point's two positions, along their bisector (positive to
        the left of the way from the first to the second).

    Returns
    -------
    Dyad
        An RR dyad; a PR dyad (its guide along the line) when three positions are
        collinear (the circumcentre is at infinity).

    Raises
    ------
    DesignError
        Not two or three poses, two the same, or a circle point at a pole (two of its
        positions coincide, so the centre point is not determined).
    """
    poses = checked_poses(poses, counts=(2, 3), method="a centre point")
    return _through(poses, _xy(circle), float(offset), "circle")


def circle_point(poses: Sequence[Sequence[float]], centre: Sequence[float], *,
                 offset: float = 0.0) -> Dyad:
    """The dyad whose fixed pivot is a chosen centre point, through two or three poses:
    the centre point of the inverted poses (:func:`centre_point`).

    Returns an RR dyad, or an RP dyad (the circle point at infinity) when the centre
    point's three positions seen from the guided link are collinear; ``offset`` as for
    :func:`centre_point`, along the bisector of those positions.

    >>> poses = [(0, 0, 0), (4, 0, 0.5), (7, 3, 1.2)]
    >>> d = circle_point(poses, (2.0, -6.0))
    >>> [round(v, 9) for v in centre_point(poses, d.circle).centre]
    [2.0, -6.0]
    """
    poses = checked_poses(poses, counts=(2, 3), method="a circle point")
    return _through(inverted(poses), _xy(centre), float(offset), "centre").swapped()


def _through(poses, point, offset, what) -> Dyad:
    at = [np.array(moved(poses, point, j)) for j in range(len(poses))]
    scale = max(task_size(poses), max(float(np.linalg.norm(p - at[0])) for p in at), 1e-300)
    for i in range(len(at)):
        for j in range(i + 1, len(at)):
            if np.linalg.norm(at[j] - at[i]) <= SAME * scale:
                seen = "" if what == "circle" else " (seen from the guided link)"
                _fail(f"the {what} point {point} is the pole of poses {i + 1} and {j + 1}: "
                      f"its positions{seen} there coincide, so any point of one line "
                      f"fits; choose another {what} point")
    d = [p - at[0] for p in at[1:]]
    if len(d) == 1:
        n = normalised(perp(d[0]))
        c = at[0] + 0.5 * d[0] + offset * n
        return Dyad("RR", _xy(c), point)
    rows = [np.array([v[0], v[1], -0.5 * (v @ v)]) for v in d]
    h = np.cross(rows[0], rows[1])          # the circumcentre about at[0], homogeneous
    if abs(h[2]) * AT_INFINITY * scale <= math.hypot(h[0], h[1]):
        return Dyad("PR", None, point, _line(max(d, key=np.linalg.norm)))
    return Dyad("RR", _xy(at[0] + h[:2] / h[2]), point)


# -- four poses: the Burmester curves ------------------------------------------------
def _base(s: _System) -> int:
    """The pose (index of ``B``) whose pole with the first is the best conditioned: the
    largest rotation; DesignError when every pose has the first one's angle."""
    turns = [abs(math.sin(0.5 * displacement(s.poses, 0, j)[0]))
             for j in range(1, len(s.poses))]
    k = int(np.argmax(turns))
    if turns[k] * AT_INFINITY <= 1:
        _fail("every pose has the first one's angle: the guided link only translates, "
              "and no four or more such poses lie on one dyad's circles in general "
              "(a parallelogram's coupler needs translations on one circle)")
    return k


def _base_point(s: _System, k: int) -> np.ndarray:
    """The pole of the first pose and pose ``k + 1`` (finite: :func:`_base` chose it)."""
    return np.asarray(_given(pole(s.poses, 0, k + 1).at))


def _det(r0, r1, r2):
    """The determinant of three rows whose entries are numbers or polynomials
    (:class:`numpy.polynomial.Polynomial`)."""
    return (r0[0] * (r1[1] * r2[2] - r1[2] * r2[1]) - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0])
            + r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]))


def _quadratic(base, way, rows):
    """The coefficients (lowest first) of ``det(M(base + s way)) / s``, the Burmester
    cubic of the three ``rows`` (``B`` matrices, the first the base's) on the line
    from the base point along ``way``; the entries of ``way`` numbers or polynomials
    (then so are the coefficients)."""
    fixed = [np.zeros(3)] + [b @ np.append(base, 1.0) for b in rows[1:]]   # base: a pole
    along = [[b[i, 0] * way[0] + b[i, 1] * way[1] for i in range(3)] for b in rows]
    c1 = _det(along[0], fixed[1], fixed[2])
    c2 = _det(along[0], along[1], fixed[2]) + _det(along[0], fixed[1], along[2])
    c3 = _det(along[0], along[1], along[2])
    return c1, c2, c3


def _real_roots(c0: float, c1: float, c2: float) -> list[float]:
    """The real roots of ``c0 + c1 s + c2 s^2`` (a double root once), stably."""
    if c2 == 0:
        return [-c0 / c1] if c1 != 0 else []
    disc = c1 * c1 - 4 * c2 * c0
    if disc < -1e-12 * (c1 * c1 + abs(4 * c2 * c0)):
        return []
    q = -0.5 * (c1 + math.copysign(math.sqrt(max(disc, 0.0)), c1))
    roots = [q / c2] + ([c0 / q] if q != 0 and disc > 0 else [])
    return [r for r in roots if math.isfinite(r)]


def _kernel(rows) -> np.ndarray:
    """The unit vector the rows (three numbers each) are most nearly square to."""
    v = np.linalg.svd(np.asarray(rows, dtype=float))[2][-1]
    return -v if v[2] < 0 else v


@dataclass(frozen=True)
class BurmesterCurve:
    """The centre-point curve (``side == "centre"``) or circle-point curve
    (``side == "circle"``) of four poses: the points of that side of every dyad that
    guides the plane through them, a cubic through the poles ``P_1j``.

    Sample it along the lines through ``base``, the pole ``P_1k`` of the largest
    rotation: :meth:`dyads` gives the (0 to 2) dyads on one such line, :meth:`sample`
    the dyads over half a turn of lines; :attr:`at_infinity` is the curve's real point
    at infinity (a PR dyad on the centre-point curve, an RP on the circle-point curve).
    """

    poses: tuple[Pose, ...]
    side: str
    base: tuple[float, float]

    def _work(self) -> tuple[_System, int]:
        s = _system(self.poses if self.side == "circle" else inverted(self.poses))
        return s, _base(s)

    def _out(self, dyad: Dyad | None) -> Dyad | None:
        return dyad if dyad is None or self.side == "circle" else dyad.swapped()

    def dyads(self, direction: float) -> tuple[Dyad, ...]:
        """The dyads whose point on this curve lies on the line through :attr:`base` at
        ``direction`` (radians; the base itself excluded)."""
        s, k = self._work()
        return tuple(d for d in (self._out(x) for x in _on_line(s, k, direction))
                     if d is not None)

    def sample(self, count: int = 180) -> tuple[Dyad, ...]:
        """The dyads on ``count`` lines through :attr:`base` evenly over half a turn,
        after the dyad at the base and before :attr:`at_infinity`."""
        s, k = self._work()
        found = [_at_base(s, k)]
        for n in range(count):
            found.extend(_on_line(s, k, math.pi * n / count))
        found.append(_at_far(s, k))
        return tuple(d for d in (self._out(x) for x in found) if d is not None)

    @property
    def at_infinity(self) -> Dyad | None:
        """The curve's real point at infinity, a slider dyad (None when the curve has
        none)."""
        s, k = self._work()
        return self._out(_at_far(s, k))


def _curve(poses, side) -> BurmesterCurve:
    poses = checked_poses(poses, counts=(4,), method=f"the {side}-point curve")
    s = _system(poses)
    base = pole(poses, 0, _base(s) + 1).at
    return BurmesterCurve(poses, side, _xy(base))


def centre_point_curve(poses: Sequence[Sequence[float]]) -> BurmesterCurve:
    """The centre-point curve of four poses (:class:`BurmesterCurve`).

    >>> poses = [(0, 0, 0), (1, 0, 0.3), (1, 1, 0.9), (0, 2, 1.4)]
    >>> curve = centre_point_curve(poses)
    >>> all(residual(poses, d) < 1e-12 for d in curve.sample(12))
    True
    >>> curve.at_infinity.kind
    'PR'
    """
    return _curve(poses, "centre")


def circle_point_curve(poses: Sequence[Sequence[float]]) -> BurmesterCurve:
    """The circle-point curve of four poses (:class:`BurmesterCurve`); its point at
    infinity is an RP dyad."""
    return _curve(poses, "circle")


def _others(s: _System, k: int) -> list[int]:
    return [j for j in range(len(s.B)) if j != k]


def _on_line(s: _System, k: int, direction: float) -> list[Dyad | None]:
    base = _base_point(s, k)
    way = np.array([math.cos(direction), math.sin(direction)])
    rows = [s.B[k]] + [s.B[j] for j in _others(s, k)]
    c1, c2, c3 = (float(c) for c in _quadratic(base, way, rows))
    out = []
    for t in _real_roots(c1, c2, c3):
        a = np.append(base + t * way, 1.0)
        if np.linalg.norm(a[:2]) < AT_INFINITY:
            out.append(s.dyad(a, _kernel([b @ a for b in rows])))
    return out


def _at_base(s: _System, k: int) -> Dyad | None:
    a = np.append(_base_point(s, k), 1.0)
    return s.dyad(a, _kernel([s.B[j] @ a for j in _others(s, k)]))


def _at_far(s: _System, k: int) -> Dyad | None:
    """The curve's real point at infinity: its highest terms are ``(x^2 + y^2)(p x + q
    y)`` (the circular points are on it), so the direction is ``(q, -p)``."""
    def top(u):
        return float(np.linalg.det(np.array([b @ np.append(u, 0.0) for b in s.B])))
    p, q = top((1.0, 0.0)), top((0.0, 1.0))
    if math.hypot(p, q) == 0:
        return None
    way = normalised((q, -p))
    if way is None:
        return None
    a = np.append(way, 0.0)
    return s.dyad(a, _kernel([b @ a for b in s.B]))


# -- five poses: the Burmester points ---------------------------------------------------
def burmester_points(poses: Sequence[Sequence[float]]) -> tuple[Dyad, ...]:
    """The dyads that guide the plane through five poses: the Burmester points, where
    the centre-point curves of poses 1234 and 1235 meet (0, 2 or 4 of them; sliders
    among them when the poses allow one).

    Returns
    -------
    tuple of Dyad
        Each fits the five poses to the rounding of its points (:func:`residual` below
        :data:`FITS`), in no particular order.

    Examples
    --------
    >>> poses = [(0, 0, 0), (1, 0, 0.3), (1, 1, 0.9), (0, 2, 1.4), (-1, 2, 1.6)]
    >>> found = burmester_points(poses)
    >>> len(found) in (0, 2, 4), all(residual(poses, d) < 1e-12 for d in found)
    (True, True)
    """
    poses = checked_poses(poses, counts=(5,), method="the Burmester points")
    found = _side_points(_system(poses))
    found += [d.swapped() for d in _side_points(_system(inverted(poses)))]
    return _distinct(found, _system(poses))


def _side_points(s: _System) -> list[Dyad]:
    """The dyads with a finite circle point, as the real roots of the resultant of the
    two circle-point cubics (rows k, m, p and k, m, q) on the lines through the pole
    ``P_1k``, polished."""
    k = _base(s)
    base = _base_point(s, k)
    m = max(_others(s, k), key=lambda j: abs(math.sin(0.5 * displacement(s.poses, 0, j + 1)[0])))
    p, q = (j for j in _others(s, k) if j != m)
    # the lines through the base are e1 + t e2, with e2 towards the pole P_1m: both
    # cubics pass through that pole, so t = infinity is a root and the degree drops to 7
    far = pole(s.poses, 0, m + 1)
    towards = far.direction if far.at is None else np.subtract(far.at, base)
    e2 = None if towards is None else normalised(towards)
    if e2 is None:                           # the two poles at one point: any line will do
        e2 = np.array([1.0, 0.0])
    e1 = np.array(perp(e2))
    way = [Polynomial([e1[i], e2[i]]) for i in range(2)]
    a0, a1, a2 = _quadratic(base, way, [s.B[k], s.B[m], s.B[p]])
    b0, b1, b2 = _quadratic(base, way, [s.B[k], s.B[m], s.B[q]])
    res = (a2 * b0 - a0 * b2) ** 2 - (a2 * b1 - a1 * b2) * (a1 * b0 - a0 * b1)
    res = np.pad(res.coef, (0, 9))[:8]                # the t^8 term is zero: drop it
    nonzero = np.flatnonzero(res)
    ts = list(np.roots(res[: nonzero[-1] + 1][::-1])) if nonzero.size else []
    found = []
    for t in [t.real for t in ts if abs(t.imag) <= 1e-4 * (1 + abs(t))] + [math.inf]:
        u = e2 if math.isinf(t) else e1 + t * e2
        for at in _candidates_on(base, u, s.B[k], [s.B[j] for j in (m, p, q)]):
            polished = _polish(s, at)
            if polished is not None:
                found.append(polished)
    at_base = _polish(s, np.asarray(base, dtype=float))
    return found + ([at_base] if at_base is not None else [])


def _candidates_on(base, u, bk, rest) -> list[np.ndarray]:
    """The circle points on the line ``base + s u`` where one of the two cubics
    vanishes, or both by elimination."""
    q1 = [float(c) for c in _quadratic(base, u, [bk, rest[0], rest[1]])]
    q2 = [float(c) for c in _quadratic(base, u, [bk, rest[0], rest[2]])]
    ss = _real_roots(*q1) + _real_roots(*q2)
    den = q1[1] * q2[2] - q1[2] * q2[1]
    if den != 0:
        ss.append((q1[2] * q2[0] - q1[0] * q2[2]) / den)
    return [base + t * np.asarray(u) for t in ss if math.isfinite(t)]


def _polish(s: _System, a: np.ndarray) -> Dyad | None:
    """Newton's method on the equations ``c^T B_j a = 0`` (and ``n . c = 1``) from the
    circle point ``a``, when the equations nearly hold there; the dyad when it converges
    to a fit, else None."""
    a = np.array(a, dtype=float)
    if not np.all(np.isfinite(a)) or np.linalg.norm(a) >= AT_INFINITY:
        return None
    bs = np.array(s.B)
    sv = np.linalg.svd(bs @ np.append(a, 1.0), compute_uv=False)
    if sv[-1] > 1e-2 * sv[0]:                 # not near a solution (a spurious root)
        return None
    c = _kernel(bs @ np.append(a, 1.0))
    n, last = c.copy(), math.inf
    for _ in range(30):
        ah = np.append(a, 1.0)
        f = np.append(np.einsum("i,jik,k->j", c, bs, ah), n @ c - 1.0)
        jac = np.vstack([np.hstack([np.einsum("i,jik->jk", c, bs)[:, :2], bs @ ah]),
                         np.append([0.0, 0.0], n)])
        step = np.linalg.lstsq(jac, -f, rcond=None)[0]
        a, c = a + step[:2], c + step[2:]
        size = float(np.linalg.norm(step))
        if size <= 1e-15 * (1 + np.linalg.norm(a)) or size >= last:   # done, or at rounding
            break
        last = size
    ah = np.append(a, 1.0)
    ah, c = ah / np.linalg.norm(ah), c / np.linalg.norm(c)
    if not np.all(np.isfinite(ah)) or np.max(np.abs(np.einsum("i,jik,k->j", c, bs, ah))) > FITS:
        return None
    return s.dyad(ah, c)


def _distinct(dyads: Iterable[Dyad | None], s: _System) -> tuple[Dyad, ...]:
    """The dyads without repeats: the same kind, and circle and centre points whose unit
    homogeneous vectors (:func:`_homogeneous`) are within 1e-7 (a far point's rounding
    grows with its distance), either way along a line at infinity."""
    out: list[Dyad] = []
    seen: list[tuple[np.ndarray, np.ndarray]] = []
    for d in dyads:
        if d is None:
            continue
        h = _homogeneous(s, d)
        if not any(e.kind == d.kind and all(min(np.linalg.norm(x - y), np.linalg.norm(x + y))
                                            <= 1e-7 for x, y in zip(h, g))
                   for e, g in zip(out, seen)):
            out.append(d)
            seen.append(h)
    return tuple(out)


# -- two dyads: a mechanism ------------------------------------------------------------
def dyad_inputs(poses: Sequence[Sequence[float]], dyad: Dyad) -> tuple[float, ...]:
    """The dyad's input at each pose, as :func:`chaingraph.solve` measures it when the
    dyad drives (:func:`mechanism`): an RR crank's direction from its fixed pivot, an RP
    block's direction (its guide's), in degrees, each within half a turn of the first;
    a PR slider's slide from the first pose along its guide.

    >>> poses = [(0, 0, 0), (4, 0, 0.5), (7, 3, 1.2)]
    >>> [round(v, 9) for v in dyad_inputs(poses, Dyad("RP", (1.0, 2.0), None, (1.0, 0.0)))]
    [0.0, 28.647889757, 68.754935416]
    """
    poses = checked_poses(poses)
    if dyad.kind == "PR":
        a, g = _given(dyad.circle), _given(dyad.guide)
        return tuple((p[0] - a[0]) * g[0] + (p[1] - a[1]) * g[1]
                     for p in (moved(poses, a, j) for j in range(len(poses))))
    if dyad.kind == "RP":
        first = direction_deg(_given(dyad.guide))
        turns = [displacement(poses, 0, j)[0] for j in range(len(poses))]
    else:
        c = _given(dyad.centre)
        at = [moved(poses, _given(dyad.circle), j) for j in range(len(poses))]
        angles = [math.atan2(p[1] - c[1], p[0] - c[0]) for p in at]
        first = math.degrees(angles[0])
        turns = [math.remainder(a - angles[0], 2 * math.pi) for a in angles]
    return tuple(first + math.degrees(t) for t in turns)


#: the chain's family by the number of sliding pairs
_FAMILIES = ("four-bar chain", "single slider crank chain", "double slider crank chain")
_NAMES = ("Four-bar", "Slider crank", "Double slider")


def mechanism(poses: Sequence[Sequence[float]], first: Dyad, second: Dyad, *,
              driver: int = 0, units: str = "mm", name: str | None = None) -> Chain:
    """The mechanism of two dyads, drawn at the first pose: fixed link ``"frame"``,
    guided link ``"coupler"`` carrying the point ``"P"`` at the first pose's point (the
    mechanism's output is the coupler).

    Parameters
    ----------
    poses : sequence of (x, y, angle)
        The task's poses (the first is drawn; the others go into the notes).
    first, second : Dyad
        The dyads.
    driver : int
        Which dyad drives (0: ``first``, 1: ``second``): the driving dyad's link is
        ``"crank"`` (an RR or RP, turning about its fixed pivot, joint ``"A"``) or
        ``"slider"`` (a PR, the input its slide, joint ``"A"``); its moving joint is
        ``"B"``. The other dyad's link is ``"rocker"`` (RR), ``"block"`` (RP) or
        ``"slider"`` (PR), its joints ``"D"`` (fixed) and ``"C"`` (moving).
    units, name : str
        The chain's units and name (default: what it is and how many poses).

    Raises
    ------
    DesignError
        Dyads that make no mechanism: a link of no length (an RR dyad's centre point at
        its circle point), two dyads on one moving pivot or one fixed pivot.

    Examples
    --------
    >>> poses = [(0, 0, 0), (4, 0, 0.5), (7, 3, 1.2)]
    >>> chain = mechanism(poses, centre_point(poses, (0, 5)), centre_point(poses, (6, 1)))
    >>> chain.links, chain.mechanism.driver
    (('frame', 'crank', 'coupler', 'rocker'), 'crank')
    """
    poses = checked_poses(poses)
    if driver not in (0, 1):
        raise DesignError(f"driver must be 0 or 1 (which dyad drives), got {driver!r}",
                          kind=_KIND, parameter="driver")
    lead, other = (first, second) if driver == 0 else (second, first)
    _check_pair(lead, other, task_size(poses) or 1.0)
    lead_link = "slider" if lead.kind == "PR" else "crank"
    other_link = {"RR": "rocker", "RP": "block", "PR": "slider"}[other.kind]
    if other_link == lead_link:
        other_link += " 2"
    joints = _dyad_joints(lead, lead_link, ("A", "B")) + _dyad_joints(other, other_link,
                                                                      ("D", "C"))
    slides = sum(d.kind != "RR" for d in (lead, other))
    x, y, _ = poses[0]
    if lead.kind == "PR":
        mech = Mechanism("frame", None, 1.0, "coupler", (Input("A"),))
    else:
        mech = Mechanism("frame", lead_link, 1.0, "coupler")
    listed = "; ".join(f"{p[0]:.6g}, {p[1]:.6g}, {math.degrees(p[2]):.6g}" for p in poses)
    return Chain(name or f"{_NAMES[slides]} through {len(poses)} poses", joints,
                 family=_FAMILIES[slides], units=units, points=(Point("P", "coupler",
                                                                     (x, y)),),
                 mechanism=mech,
                 notes=f"Designed by chaingraph (motion generation): the coupler's point P "
                       f"passes through the poses (x, y, degrees) {listed}.")


def _dyad_joints(d: Dyad, link: str, ids: tuple[str, str]) -> tuple[Joint, ...]:
    fixed_id, moving_id = ids
    if d.kind == "RR":
        return (Joint(fixed_id, "R", ("frame", link), at=_xy(d.centre)),
                Joint(moving_id, "R", (link, "coupler"), at=_xy(d.circle)))
    assert d.guide is not None                          # a slider's dyad has its guide
    axis = direction_deg(d.guide)
    if d.kind == "PR":
        return (Joint(fixed_id, "P", ("frame", link), at=_xy(d.circle), axis=axis),
                Joint(moving_id, "R", (link, "coupler"), at=_xy(d.circle)))
    return (Joint(fixed_id, "R", ("frame", link), at=_xy(d.centre)),
            Joint(moving_id, "P", ("coupler", link), at=_xy(d.centre), axis=axis))


def _check_pair(d: Dyad, e: Dyad, size: float) -> None:
    near = SAME * 1e3 * size
    for x in (d, e):
        if x.kind == "RR" and math.dist(_given(x.centre), _given(x.circle)) <= near:
            _fail(f"the dyad's centre point {x.centre} is its circle point: a link of no "
                  "length")
    if d.circle is not None and e.circle is not None and math.dist(d.circle, e.circle) <= near:
        _fail(f"both dyads have their circle point at {d.circle}: one moving pivot does "
              "not guide the coupler")
    if d.centre is not None and e.centre is not None and math.dist(d.centre, e.centre) <= near:
        _fail(f"both dyads have their centre point at {d.centre}: a frame of no length")


def candidates(poses: Sequence[Sequence[float]], dyads: Iterable[Dyad], *,
               units: str = "mm") -> tuple[Chain, ...]:
    """Every mechanism of two distinct dyads, each dyad driving in turn
    (:func:`mechanism`); pairs that make no mechanism (one pivot shared, a link of no
    length) are left out. Nothing is certified: :func:`chaingraph.solve` says which
    pass the poses.

    >>> poses = [(0, 0, 0), (1, 0, 0.3), (1, 1, 0.9), (0, 2, 1.4), (-1, 2, 1.6)]
    >>> found = burmester_points(poses)
    >>> len(candidates(poses, found)) <= len(found) * (len(found) - 1)
    True
    """
    poses = checked_poses(poses)
    dyads = _distinct(dyads, _system(poses))
    out = []
    for i in range(len(dyads)):
        for j in range(i + 1, len(dyads)):
            for driver in (0, 1):
                try:
                    out.append(mechanism(poses, dyads[i], dyads[j], driver=driver,
                                         units=units))
                except DesignError:
                    break
    return tuple(out)
