"""Motion generation: a four-bar or a slider crank whose coupler passes through two to
five poses, in order.

The dyads (:mod:`chaingraph.synthesis.burmester`) that can guide the coupler:

* two poses: circle points on a grid over the moving plane about the poses, each with
  its centre point at several offsets along the bisector of its two positions (the free
  choice), and a slider (its guide along the circle point's displacement);
* three poses: circle points on a grid about the poses, each with its one centre point
  (the circumcentre of its three positions), and the slider dyads: circle points whose
  three positions are collinear (on a circle of the moving plane), and centre points
  whose three positions seen from the coupler are (the blocks of an inverted slider
  crank);
* four poses: the centre-point curve sampled along :data:`LINES` lines through its
  pole (from the first pose's angle, so that the sample moves with the task), and its
  slider at infinity, with the circle-point curve's;
* five poses: the Burmester points.

Every pair (two RR dyads: a four-bar; an RR and a PR or RP: a slider crank), each dyad
driving in turn, is a candidate. A screen from the poses' exact configurations drops the
candidates that cannot do the task, counted by reason: the poses on two circuits
(*circuit defect*), on two branches of the input (*branch defect*: the input would turn
back at a limit between them; a crank whose own angle goes back between poses cannot
drive), or met out of order as the input moves one way (*order defect*); a transmission
angle out of bounds at a pose; the longest link over the shortest above
:data:`~chaingraph.synthesis.function_generation.MAX_RATIO`. The rest are ranked
(the least transmission angle at the poses in steps of :data:`BIN` degrees, largest
first; then the most compact: the farthest pivot from the poses' centre, nearest first), and certified in that
order by :func:`~chaingraph.synthesis.certification.certify` from the written chain file (solved
at the input's value at each pose, then swept from the first pose to the last) until
enough are certified. Solutions are listed by error (errors within rounding,
:data:`EXACT`, count as equal), the least transmission angle over the sweep (in steps of
:data:`BIN` degrees), then compactness.

Circuits (whatever link drives): a Grashof four-bar has two, told apart by the sign of
the turn at either end of the link opposite its shortest (those joints never pass 0
or 180 degrees); a slider crank chain (crank r, rod l, offset e) has two when r + |e| < l
(the rod never square to the guide) or l + |e| < r (the crank never square to it);
otherwise one. Branches of the input: the sign of the follower dyad's determinant, zero
exactly where the input meets a limit.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import replace

import numpy as np

from chaingraph.errors import DesignError
from chaingraph.geometry import angle_between, cross, dot
from chaingraph.model.snap import ROUNDING
from chaingraph.naming import identify
from chaingraph.synthesis.burmester import (
    Dyad,
    burmester_points,
    centre_point,
    centre_point_curve,
    circle_point,
    circle_point_curve,
    dyad_inputs,
    mechanism,
)
from chaingraph.synthesis.certification import Certified, PoseTargets, Rejected, certify
from chaingraph.synthesis.function_generation import MAX_RATIO
from chaingraph.synthesis.poses import inverted, moved, pole, task_size
from chaingraph.synthesis.result import Curve, Searched, Solution, Synthesis, ranked
from chaingraph.synthesis.task import check_options, motion_task

__all__ = ["motion", "motion_dyads", "EXACT", "GRID", "OFFSETS", "LINES", "BIN"]

#: errors within this (times the task's size, or degrees) are exact: they rank equal
EXACT = 1e-9
#: circle points per side of the grid over the moving plane (two and three poses)
GRID = {2: 3, 3: 7}
#: two poses: the centre point's offsets along the bisector, in the task's size
OFFSETS = (-1.0, -0.5, 0.5, 1.0)
#: four poses: lines through the pole sampling the centre-point curve
LINES = 72
_SLIDERS = 12         # three poses: points sampled on each circle of slider points
_CERTIFIED = 4        # candidates certified, at most, per solution asked for
_APART = 0.02         # candidates whose pivots are all this close (times the size) repeat
#: the transmission angle ranks in steps of this many degrees (then compactness)
BIN = 5.0
_KINDS = {"RR": 0, "PR": 1, "RP": 2}
#: the chain and inversion of a pair, by its slider's kind (0: none)
_INVERSIONS = {0: ("four-bar chain", "frame fixed"),
               1: ("single slider crank chain", "the guide on the frame"),
               2: ("single slider crank chain", "the guide on the coupler")}


# -- the dyads ---------------------------------------------------------------------------
def _scale(poses) -> float:
    return task_size(poses) or 1.0


def _grid(poses, count: int) -> list[tuple[float, float]]:
    """count x count points over a square of twice the task's size about the poses'
    centre, its sides along and square to the first pose's angle (so the grid moves
    with the task)."""
    cx = float(np.mean([p[0] for p in poses]))
    cy = float(np.mean([p[1] for p in poses]))
    s = _scale(poses)
    c, n = math.cos(poses[0][2]), math.sin(poses[0][2])
    steps = np.linspace(-s, s, count)
    return [(cx + u * c - v * n, cy + u * n + v * c) for v in steps for u in steps]


def _slider_circle(poses, count: int) -> list[tuple[float, float]]:
    """Three poses: ``count`` points of the moving plane whose three positions are
    collinear. The condition cross(a2 - a1, a3 - a1) is quadratic in the point a with
    leading part a multiple of |a|^2: a circle, found from four values."""
    def f(x, y):
        a = [np.array(moved(poses, (x, y), j)) for j in range(3)]
        d1, d2 = a[1] - a[0], a[2] - a[0]
        return float(d1[0] * d2[1] - d1[1] * d2[0])
    s = _scale(poses)
    x0, y0 = poses[0][0], poses[0][1]
    f0, fx, gx, fy = f(x0, y0), f(x0 + s, y0), f(x0 - s, y0), f(x0, y0 + s)
    k = (fx + gx - 2 * f0) / (2 * s * s)            # the |a|^2 coefficient
    if abs(k) * s * s <= 1e-12 * max(abs(f0), abs(fx), abs(gx), abs(fy), 1e-300):
        return []
    bx, by = (fx - gx) / (2 * s), (fy - f0) / s - k * s
    cx, cy = x0 - bx / (2 * k), y0 - by / (2 * k)
    r2 = (bx * bx + by * by) / (4 * k * k) - f0 / k
    if not r2 > 0:
        return []
    r = math.sqrt(r2)
    return [(cx + r * math.cos(t), cy + r * math.sin(t))
            for t in 2 * math.pi * np.arange(count) / count]


def _kept(make, *args, **kwargs) -> list[Dyad]:
    """A dyad made, or none where the point is a pole (its centre not determined)."""
    try:
        return [make(*args, **kwargs)]
    except DesignError:
        return []


def _two(poses, points) -> list[Dyad]:
    s = _scale(poses)
    out: list[Dyad] = []
    for a in points:
        for offset in OFFSETS:
            out += _kept(centre_point, poses, a, offset=offset * s)
        b = moved(poses, a, 1)
        way = (b[0] - a[0], b[1] - a[1])
        if math.hypot(*way) > 1e-12 * s:
            length = math.hypot(*way)
            out.append(Dyad("PR", None, (float(a[0]), float(a[1])),
                            (way[0] / length, way[1] / length)))
    return out


def _three(poses, points, chosen: bool) -> list[Dyad]:
    out: list[Dyad] = []
    for a in points:
        out += _kept(centre_point, poses, a)
    if not chosen:
        for a in _slider_circle(poses, _SLIDERS):
            out += [d for d in _kept(centre_point, poses, a) if d.kind == "PR"]
        for c in _slider_circle(inverted(poses), _SLIDERS):
            out += [d for d in _kept(circle_point, poses, c) if d.kind == "RP"]
    return out


def _four(poses, points) -> list[Dyad]:
    """The centre-point curve sampled, its sliders at infinity; or, for chosen circle
    points, the dyads of the circle-point curve on the line from its pole through each,
    the nearest."""
    if points is None:
        curve = centre_point_curve(poses)
        found = [d for n in range(LINES)
                 for d in curve.dyads(poses[0][2] + math.pi * n / LINES)]
        far = [curve.at_infinity, circle_point_curve(poses).at_infinity]
        return found + [d for d in far if d is not None]
    curve = circle_point_curve(poses)
    out = []
    for a in points:
        way = math.atan2(a[1] - curve.base[1], a[0] - curve.base[0])
        near = [(math.dist(d.circle, a), k, d) for k, d in enumerate(curve.dyads(way))
                if d.circle is not None]
        if near:
            out.append(min(near)[2])
    return out


def motion_dyads(poses: Sequence[Sequence[float]], *,
                 circle_points: Sequence[Sequence[float]] | None = None) -> tuple[Dyad, ...]:
    """The dyads whose pairs motion generation tries (see the module).

    Parameters
    ----------
    poses : sequence of (x, y, angle)
        Two to five poses, angles in radians (:mod:`chaingraph.synthesis.poses`).
    circle_points : sequence of (x, y), optional
        Moving pivots to use (where the first pose puts them) instead of the grid
        (two and three poses) or the sampled curve (four poses: the circle-point curve's
        dyad on the line from its pole through each point, the nearest); five poses
        determine their own.
    """
    n = len(poses)
    if circle_points is not None:
        if n == 5:
            raise DesignError("five poses determine their circle points (the Burmester "
                              "points): leave circle_points out", kind="motion",
                              parameter="circle_points")
        points = [(float(p[0]), float(p[1])) for p in circle_points]
    if n == 2:
        return tuple(_two(poses, points if circle_points is not None
                          else _grid(poses, GRID[2])))
    if n == 3:
        return tuple(_three(poses, points if circle_points is not None
                            else _grid(poses, GRID[3]), circle_points is not None))
    if n == 4:
        return tuple(_four(poses, points if circle_points is not None else None))
    return burmester_points(poses)


# -- the screen --------------------------------------------------------------------------
def _arrays(poses, dyads):
    """Per dyad: kind, moving pivot at each pose (RR, PR), fixed pivot (RR, RP), guide
    at each pose (PR, RP), the input's value at each pose when it drives."""
    n = len(poses)
    turn = np.array([p[2] - poses[0][2] for p in poses])
    kind = np.array([_KINDS[d.kind] for d in dyads])
    moving = np.full((len(dyads), n, 2), np.nan)
    fixed = np.full((len(dyads), 2), np.nan)
    guide = np.full((len(dyads), n, 2), np.nan)
    value = np.array([dyad_inputs(poses, d) for d in dyads], dtype=float).reshape(-1, n)
    for k, d in enumerate(dyads):
        if d.circle is not None:
            moving[k] = [moved(poses, d.circle, j) for j in range(n)]
        if d.centre is not None:
            fixed[k] = d.centre
        if d.kind == "PR":
            guide[k] = d.guide
        elif d.kind == "RP":
            g = np.asarray(d.guide)
            guide[k] = np.stack([np.cos(turn) * g[0] - np.sin(turn) * g[1],
                                 np.sin(turn) * g[0] + np.cos(turn) * g[1]], axis=1)
    return kind, moving, fixed, guide, value


def _crosses(u, v):
    """:func:`~chaingraph.geometry.cross` of arrays of vectors (x, y on the last axis)."""
    return cross(np.moveaxis(u, -1, 0), np.moveaxis(v, -1, 0))


def _dots(u, v):
    """:func:`~chaingraph.geometry.dot` of arrays of vectors (x, y on the last axis)."""
    return dot(np.moveaxis(u, -1, 0), np.moveaxis(v, -1, 0))


def _angle(u, v):
    """The angle between u and v, degrees in [0, 180]."""
    return angle_between(np.moveaxis(u, -1, 0), np.moveaxis(v, -1, 0))


def _to_normal(u, g):
    """The angle between u and the normal of the guide g, degrees in [0, 90]."""
    n = np.stack([-g[..., 1], g[..., 0]], axis=-1)
    return np.degrees(np.arccos(np.clip(np.abs(_dots(u, n)) / np.hypot(u[..., 0], u[..., 1]),
                                        0.0, 1.0)))


def _circuit_four_bar(a, b, c, d, joints):
    """The circuit's sign at each pose: the turn at the far end of the link opposite the
    shortest (Grashof), else 1. ``joints`` (m, n, 4, 2) are A, B, C, D; the links AB,
    BC, CD, DA have lengths a, b, c, d."""
    lengths = np.stack([a, b, c, d], axis=1)
    s, l = lengths.min(axis=1), lengths.max(axis=1)
    grashof = s + l < lengths.sum(axis=1) - s - l - 1e-12 * l
    k = (np.argmin(lengths, axis=1) + 2) % 4
    m = np.arange(len(k))
    here = joints[m, :, k]
    before = joints[m, :, (k - 1) % 4]
    after = joints[m, :, (k + 1) % 4]
    turn = np.sign(_crosses(before - here, after - here))
    return np.where(grashof[:, None], turn, 1.0)


def _circuit_slider(r, l, e, rod, crank, g):
    """A slider crank chain's circuit sign at each pose: (rod . guide) when r + |e| < l,
    (crank . guide) when l + |e| < r, else 1."""
    first = (r + np.abs(e) < l)[:, None]
    second = (l + np.abs(e) < r)[:, None]
    return np.where(first, np.sign(_dots(rod, g)),
                    np.where(second, np.sign(_dots(crank, g)), 1.0))


def _gaps(kind, moving, fixed, guide, d, f):
    """The middle of the angles the input cannot take (degrees), where it rocks; NaN
    where it turns fully (or slides). An RR crank AB with an RR follower DC: it cannot
    point at D when |a - AD| < |b - c|, else not away from D when a + AD > b + c; with a
    PR follower (the pin C on a fixed line at h from A): not square to the line towards
    the side h + a > l, else the other; with an RP follower (a block about T, the guide
    at e from B): not at T when |AT - a| < |e|. An RP block driving an RR follower (the
    pin C at h from the guide, the rocker c about D): the guide's normal cannot point
    at D when |DT| - h > c, else away when |DT| + h > c."""
    kd, kf = kind[d], kind[f]
    A, B0 = fixed[d], moving[d][:, 0]
    D, C0 = fixed[f], moving[f][:, 0]
    gd, gf = guide[d][:, 0], guide[f][:, 0]
    def length(v):
        return np.hypot(v[:, 0], v[:, 1])

    def towards(v):
        return np.degrees(np.arctan2(v[:, 1], v[:, 0]))
    a, b, c, ad = length(B0 - A), length(C0 - B0), length(C0 - D), length(D - A)
    at_d, away = towards(D - A), towards(D - A) + 180.0
    four = np.where(np.abs(a - ad) < np.abs(b - c), at_d,
                    np.where(a + ad > b + c, away, np.nan))
    h = _crosses(gf, A - C0)                         # A from the PR's line
    line = towards(gf)
    pr = np.where(np.abs(h) + a <= b, np.nan, np.where(h + a > b, line + 90.0, line - 90.0))
    e = _crosses(gf, D - B0)                         # B from the RP's guide (through T = D)
    rp = np.where(np.abs(length(D - A) - a) < np.abs(e), towards(D - A), np.nan)
    hc = _crosses(gd, C0 - A)                        # C from the driving block's guide
    dt = length(D - A)
    block = np.where(dt + np.abs(hc) <= c, np.nan,
                     np.where(dt - hc > c, towards(D - A) - 90.0, towards(D - A) + 90.0))
    return np.select([(kd == 0) & (kf == 0), (kd == 0) & (kf == 1), (kd == 0) & (kf == 2),
                      kd == 2], [four, pr, rp, block], np.nan)


def _lifted(value, slides, gap):
    """The input's values at the poses as it moves one way from the first, NaN rows
    where there is none: a slide's as they are; an input that rocks, each within its
    range (the arc that holds the first, clear of the ``gap``); one that turns fully,
    each step taken the way of travel, the whole under a turn (for two poses the
    shorter way)."""
    steps = np.diff(value, axis=1)
    out = np.full(value.shape, np.nan)
    travel = np.full(len(value), np.inf)
    for way in (1.0, -1.0):
        s = np.mod(steps * way, 360.0)
        ok = np.all(s > 0, axis=1) & (s.sum(axis=1) < 360.0) & (s.sum(axis=1) < travel)
        lift = value[:, :1] + way * np.concatenate([np.zeros((len(value), 1)),
                                                    np.cumsum(s, axis=1)], axis=1)
        out[ok] = lift[ok]
        travel[ok] = s.sum(axis=1)[ok]
    g = gap[:, None]
    arc = value[:, :1] + np.mod(value - g, 360.0) - np.mod(value[:, :1] - g, 360.0)
    out = np.where(np.isnan(g), out, arc)
    steps = np.diff(out, axis=1)
    monotone = np.all(steps > 0, axis=1) | np.all(steps < 0, axis=1)
    out = np.where(monotone[:, None], out, np.nan)
    steps = np.diff(value, axis=1)
    monotone = np.all(steps > 0, axis=1) | np.all(steps < 0, axis=1)
    return np.where(slides[:, None], np.where(monotone[:, None], value, np.nan), out)


def _screen(poses, dyads, min_transmission):
    """Every pair of dyads, each driving in turn (two sliders left out), screened from
    the poses' exact configurations. Returns the survivors ``(driver, follower,
    inputs, least transmission angle, extent)``, the rejected counted by reason, and
    the number of candidates and their kinds ``(driver's, follower's)``."""
    kind, moving, fixed, guide, value = _arrays(poses, dyads)
    i, j = np.triu_indices(len(dyads), 1)
    keep = (kind[i] == 0) | (kind[j] == 0)
    d, f = np.concatenate([i[keep], j[keep]]), np.concatenate([j[keep], i[keep]])
    kd, kf = kind[d], kind[f]
    B, C = moving[d], moving[f]
    A, D = fixed[d][:, None, :], fixed[f][:, None, :]
    gd, gf = guide[d], guide[f]
    with np.errstate(all="ignore"):
        kd, kf = kd[:, None], kf[:, None]
        sigma = np.select([kf == 0, kf == 1, kf == 2],
                          [np.where(kd == 2, _dots(C - D, gd), _crosses(C - B, D - C)),
                           _dots(C - B, gf), _dots(B - D, gf)])
        mu = np.select([(kf == 0) & (kd < 2), kf == 0, kf == 1, kf == 2],
                       [_angle(B - C, D - C), _to_normal(D - C, gd), _to_normal(B - C, gf),
                        _to_normal(B - D, gf)])
        chi, lengths, off = _circuits(kind, moving, fixed, guide, d, f)
        kd, kf = kd[:, 0], kf[:, 0]
        lifted = _lifted(value[d], kd == 1, _gaps(kind, moving, fixed, guide, d, f))
        worst = np.minimum(mu.min(axis=1), 180.0 - mu.max(axis=1))
        ratio = lengths.max(axis=1) / lengths.min(axis=1)
        centre = np.mean(np.asarray(poses)[:, :2], axis=0)
        pivots = np.concatenate([fixed[d][:, None], fixed[f][:, None], B[:, :1], C[:, :1]],
                                axis=1)
        extent = np.nanmax(np.hypot(*(pivots - centre).transpose(2, 0, 1)), axis=1)
        point = np.asarray(poses[0][:2])
        every = np.concatenate([pivots, np.broadcast_to(point, (len(d), 1, 2))], axis=1)
        span = np.maximum(np.nanmax(every[..., 0], axis=1) - np.nanmin(every[..., 0], axis=1),
                          np.nanmax(every[..., 1], axis=1) - np.nanmin(every[..., 1], axis=1))
        rp = np.where(kd == 2, d, np.where(kf == 2, f, -1))
        off_p = np.where(rp >= 0, np.abs(_crosses(guide[rp, 0], point - fixed[rp])), np.nan)
        rounding = np.fmin(np.where(off > 1e-12 * span, off, np.nan),
                           np.where(off_p > 1e-12 * span, off_p, np.nan)) <= 2 * ROUNDING * span
    checks = [("circuit defect", ~np.all(chi == chi[:, :1], axis=1) | np.any(chi == 0, axis=1)),
              ("branch defect", ~np.all(np.sign(sigma) == np.sign(sigma[:, :1]), axis=1)
               | np.any(sigma == 0, axis=1)),
              ("order defect", np.isnan(lifted).any(axis=1)),
              ("transmission angle", ~(worst >= min_transmission)),
              ("link ratio", ~(ratio <= MAX_RATIO)),
              ("offset at rounding", rounding)]
    rejected: Counter = Counter()
    left = np.ones(len(d), dtype=bool)
    for reason, bad in checks:
        rejected[reason] += int(np.sum(left & bad))
        left &= ~bad
    size = _scale(poses)
    survivors = [(int(d[k]), int(f[k]), tuple(float(v) for v in lifted[k]), float(worst[k]),
                  float(extent[k]) / size) for k in np.flatnonzero(left)]
    kinds = {(int(a), int(b)) for a, b in zip(kd, kf)}
    return survivors, +rejected, len(d), kinds


def _circuits(kind, moving, fixed, guide, d, f):
    """The circuit's sign at each pose (m, n) and the link lengths (m, 4) that the link
    ratio is judged on (a slider crank's crank and rod, repeated)."""
    kd = kind[d]
    rr_dyad = np.where(kd == 0, d, f)
    other = np.where(kd == 0, f, d)
    ko = kind[other]
    A, B = fixed[rr_dyad], moving[rr_dyad]                 # the RR dyad (a crank)
    C, D, g = moving[other], fixed[other], guide[other]    # the other dyad
    a = np.hypot(*(B[:, 0] - A).T)
    # four-bar: A B C D
    b = np.hypot(*(C[:, 0] - B[:, 0]).T)
    c = np.hypot(*(C[:, 0] - D).T)
    frame = np.hypot(*(A - D).T)
    n = B.shape[1]
    joints = np.stack([np.repeat(A[:, None], n, axis=1), B, C,
                       np.repeat(D[:, None], n, axis=1)], axis=2)
    four = _circuit_four_bar(a, b, c, frame, joints)
    # slider crank chains: a PR (the rod BC, e from A to C's line) or an RP (the rod AD,
    # the frame; e from B to the guide through D)
    pr = ko == 1
    l = np.where(pr, b, frame)
    e = np.where(pr, _crosses(g[:, 0], C[:, 0] - A), _crosses(g[:, 0], D - B[:, 0]))
    rod = np.where(pr[:, None, None], C - B, (D - A)[:, None, :])
    crank = np.where(pr[:, None, None], B - A[:, None, :], A[:, None, :] - B)
    slider = _circuit_slider(a, l, e, rod, crank, g)
    chi = np.where((ko == 0)[:, None], four, slider)
    lengths = np.where((ko == 0)[:, None], np.stack([a, b, c, frame], axis=1),
                       np.stack([a, l, a, l], axis=1))
    # a pin drawn off its sliding line: the crank's pivot off a PR's guide, the crank's
    # pin or the point P off an RP's
    off = np.where(pr, np.abs(e), np.abs(_crosses(g[:, 0], B[:, 0] - D)))
    return chi, lengths, np.where(ko == 0, np.nan, off)


# -- certification and the result ------------------------------------------------------
def _repeats(chosen, dyads, d, f, size) -> bool:
    """True when an already chosen candidate has the same kinds and driver and every
    pivot and guide within :data:`_APART` of the task's size of this one's."""
    def close(p, q, scale):
        if p is None or q is None:
            return p is q
        return math.dist(p, q) <= _APART * scale
    for c, e in chosen:
        pairs = ((dyads[c], dyads[d]), (dyads[e], dyads[f]))
        if all(x.kind == y.kind and close(x.centre, y.centre, size)
               and close(x.circle, y.circle, size) and close(x.guide, y.guide, 1.0)
               for x, y in pairs):
            return True
    return False


def _dimensions(chain) -> dict[str, float]:
    """The lengths of the links between two turning pairs, and a slider's offset: the
    turning pair that is off its sliding line (the crank's pivot off a fixed guide, the
    crank's pin off a guide in the coupler), its signed distance from the line."""
    out = {}
    for link in chain.links:
        pins = [j for j in chain.joints_of(link) if j.kind == "R"]
        if len(pins) == 2 and all(j.at is not None for j in pins):
            out[link] = math.dist(pins[0].at, pins[1].at)
    for j in chain.joints:
        if j.kind == "P" and j.at is not None and j.axis is not None:
            a = math.radians(j.axis)
            off = [(p.at[1] - j.at[1]) * math.cos(a) - (p.at[0] - j.at[0]) * math.sin(a)
                   for link in j.links for p in chain.joints_of(link)
                   if p.kind == "R" and p.at is not None]
            out["offset"] = max(off, key=abs)
    return out


def _certified(task, poses, dyads, candidate, rejected):
    """The candidate's chain certified from its written file (Solution), else None
    with the reason counted."""
    d, f, inputs, _, _ = candidate
    chain = mechanism(poses, dyads[d], dyads[f], driver=0, units=task.units)
    chain = replace(chain, task=task.to_dict())
    ref = chain.reference_direction("coupler")
    angles = tuple(ref + p[2] - task.poses[0][2] for p in task.poses)
    points = tuple((p[0], p[1]) for p in task.poses)
    tries = [inputs]
    if len(inputs) == 2 and dyads[d].kind != "PR":      # two poses: either way round
        way = 360.0 - abs(inputs[1] - inputs[0])
        tries.append((inputs[0], inputs[0] - math.copysign(way, inputs[1] - inputs[0])))
    for claimed in tries:
        found = certify(chain, PoseTargets(points, angles, "P", "coupler", claimed),
                        min_transmission=task.min_transmission)
        if isinstance(found, Certified):
            return _solution(found)
    assert isinstance(found, Rejected)
    rejected[found.reason] += 1
    return None


def _solution(found: Certified) -> Solution:
    xs, ys = found.curve
    curve = Curve(np.asarray(xs), np.asarray(ys), "x", "y")
    names = identify(found.chain)
    return found.solution(names=tuple(n for n in (names.chain, names.inversion) if n),
                          curve=curve, dimensions=_dimensions(found.chain))


def _extent(s: Solution, size: float) -> float:
    pts = [j.at for j in s.mechanism.joints if j.at is not None]
    centre = np.mean([p.at for p in s.mechanism.points if p.at is not None], axis=0)
    return max(math.dist(p, centre) for p in pts) / size


def motion(*, poses: Iterable[tuple[float, float, float]], solutions: int = 5, units: str = "mm", min_transmission: float = 30.0,
           circle_points: Sequence[Sequence[float]] | None = None) -> Synthesis:
    """Synthesise a motion generator: a four-bar or a slider crank whose coupler passes
    through the poses in order.

    Parameters
    ----------
    poses : sequence of (x, y, degrees)
        Two to five poses of the coupler: its point ``P`` at x, y and its angle.
    solutions : int
        At most this many certified solutions, best first.
    units : str
        The chain files' length unit.
    min_transmission : float
        The transmission angle must stay within [min, 180 - min] degrees from the first
        pose to the last.
    circle_points : sequence of (x, y), optional
        The moving pivots to try, where the first pose puts them (see
        :func:`motion_dyads`), instead of the grid or the sampled Burmester curve.

    Returns
    -------
    Synthesis
        Certified solutions, best first: the smallest error (errors within
        :data:`EXACT` of the task's size, or degrees, rank equal), then the largest
        least transmission angle (in steps of :data:`BIN` degrees), then the most
        compact (the farthest pivot from the poses' centre); the candidates rejected by
        reason; what was searched.

    Raises
    ------
    DesignError
        For a bad task (``parameter`` names it).

    Examples
    --------
    >>> s = motion(poses=[(0, 0, 0), (40, 10, 20), (70, 40, 50)], solutions=2)
    >>> [len(x.reached_at) for x in s.solutions], s.solutions[0].mechanism.mechanism.output
    ([3, 3], 'coupler')
    """
    task = motion_task(poses=poses, units=units, min_transmission=min_transmission)
    check_options(solutions=solutions, min_transmission=min_transmission, units=units,
                  kind="motion")
    rad = task.radians()
    size = _scale(rad)
    dyads = motion_dyads(rad, circle_points=circle_points)
    survivors, rejected, count, kinds = _screen(rad, dyads, task.min_transmission)
    survivors.sort(key=lambda c: (-math.floor(c[3] / BIN), c[4]))
    found: list[Solution] = []
    chosen: list[tuple[int, int]] = []
    for candidate in survivors:
        if len(found) >= solutions or len(chosen) >= _CERTIFIED * solutions:
            break
        if _repeats(chosen, dyads, candidate[0], candidate[1], size):
            continue
        chosen.append((candidate[0], candidate[1]))
        solution = _certified(task, rad, dyads, candidate, rejected)
        if solution is not None:
            found.append(solution)

    def key(s: Solution):
        ta = s.transmission_angle
        worst = 0.0 if ta is None else min(ta[0], 180.0 - ta[1])
        exact = s.error.max <= EXACT * size and (s.error.angle or 0.0) <= EXACT
        return (0.0 if exact else s.error.max, -math.floor(worst / BIN), _extent(s, size))
    inversions = {_INVERSIONS[max(k)] for k in kinds}
    return Synthesis(task, ranked(found, solutions, key=key), dict(sorted(rejected.items())),
                     Searched(len({c for c, _ in inversions}), len(inversions), count))
