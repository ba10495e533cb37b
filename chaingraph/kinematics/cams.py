"""Disc cams: the follower's motion laws, its displacement over a turn, the pitch curve,
the cam's profile, the pressure angle, the radius of curvature and the smallest base
circle. Vectorised over the cam's angles (numpy arrays of radians).

Conventions: the cam turns counter-clockwise about its centre (the origin) by ``theta``;
at ``theta = 0`` a translating follower slides along +y on the line ``x = offset``, and an
oscillating follower swings counter-clockwise (away from the cam) about ``pivot``. The
pitch curve and the profile are in the cam's own frame (the world frame at ``theta = 0``):
a point ``p`` of the world at angle ``theta`` is ``R(-theta) p`` on the cam.

Examples
--------
>>> import numpy as np
>>> s, ds, dds, ddds = law("cycloidal", np.array([0.0, 0.5, 1.0]))
>>> [round(float(x), 12) for x in s], [round(float(x), 12) for x in ds]
([0.0, 0.5, 1.0], [0.0, 2.0, 0.0])
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from chaingraph.errors import DesignError
from chaingraph.geometry import cross, dot, perp, rotate
from chaingraph.model.cams import LAWS, Cam

__all__ = ["law", "follower_motion", "CamAnalysis", "analyse_cam", "smallest_base",
           "turn_angles", "profile_curvature", "cam_summary", "cam_table", "CSV_COLUMNS"]

Array = NDArray[np.float64]


def law(name: str, u: Array) -> tuple[Array, Array, Array, Array]:
    """The normalised law ``f(u)`` and its first three derivatives for ``u`` in [0, 1]
    (a rise of 1 over a turn of 1): ``uniform``, ``shm`` (simple harmonic), ``parabolic``
    (constant acceleration), ``cycloidal``, ``poly345`` and ``poly4567``."""
    u = np.asarray(u, dtype=float)
    one, zero = np.ones_like(u), np.zeros_like(u)
    if name == "uniform":
        return u.copy(), one, zero, zero.copy()
    if name == "shm":
        pi = math.pi
        return ((1 - np.cos(pi * u)) / 2, pi / 2 * np.sin(pi * u),
                pi ** 2 / 2 * np.cos(pi * u), -pi ** 3 / 2 * np.sin(pi * u))
    if name == "parabolic":
        first = u < 0.5
        w = 1 - u
        return (np.where(first, 2 * u ** 2, 1 - 2 * w ** 2), np.where(first, 4 * u, 4 * w),
                np.where(first, 4.0, -4.0), zero)
    if name == "cycloidal":
        t = 2 * math.pi * u
        return (u - np.sin(t) / (2 * math.pi), 1 - np.cos(t), 2 * math.pi * np.sin(t),
                4 * math.pi ** 2 * np.cos(t))
    if name == "poly345":
        return (10 * u**3 - 15 * u**4 + 6 * u**5, 30 * u**2 - 60 * u**3 + 30 * u**4,
                60 * u - 180 * u**2 + 120 * u**3, 60 - 360 * u + 360 * u**2)
    if name == "poly4567":
        return (35 * u**4 - 84 * u**5 + 70 * u**6 - 20 * u**7,
                140 * u**3 - 420 * u**4 + 420 * u**5 - 140 * u**6,
                420 * u**2 - 1680 * u**3 + 2100 * u**4 - 840 * u**5,
                840 * u - 5040 * u**2 + 8400 * u**3 - 4200 * u**4)
    raise ValueError(f"unknown law {name!r}: one of {', '.join(LAWS)}")


def follower_motion(cam: Cam, theta: Array) -> tuple[Array, Array, Array, Array]:
    """The follower's displacement ``s`` from its lowest place and its derivatives with
    respect to the cam's angle (radians) at the angles ``theta`` (any, taken modulo a
    turn): file units, or radians for an oscillating follower. A segment's end belongs to
    the segment that follows it."""
    t = np.mod(np.asarray(theta, dtype=float), 2 * math.pi)
    out = [np.zeros_like(t) for _ in range(4)]
    start, level = 0.0, 0.0
    for i, seg in enumerate(cam.motion):
        end = start + seg.over
        last = i == len(cam.motion) - 1
        inside = (t >= start) & ((t <= end) if last else (t < end))
        if seg.kind == "dwell":
            out[0][inside] = level
        else:
            f = law(seg.law or "", (t[inside] - start) / seg.over)
            for k in range(4):
                out[k][inside] = seg.change * f[k] / seg.over ** k
            out[0][inside] += level
            level += seg.change
        start = end
    return out[0], out[1], out[2], out[3]


def _turn(theta: Array, v: Array) -> Array:
    """World vectors ``v`` (n x 2) seen from the cam turned by ``theta``: R(-theta) v."""
    x, y = rotate(v.T, -theta)
    return np.stack([x, y], axis=1)


def _quarter(v: Array) -> Array:
    """Vectors ``v`` (n x 2) turned a quarter turn counter-clockwise."""
    x, y = perp(v.T)
    return np.stack([x, y], axis=1)


def _follower_point(cam: Cam, base: float, s: Array, ds: Array, dds: Array,
                    ) -> tuple[Array, Array, Array, Array]:
    """The follower's reference point in the world (the roller's centre, the knife's
    tip, or the flat face's foot on the follower's line), its first and second
    derivatives in the cam's angle, and the unit direction it moves in as ``s`` grows."""
    prime = base + cam.roller
    n = len(s)
    if cam.moves == "translating":
        e = cam.offset
        y = math.sqrt(prime ** 2 - e ** 2) if cam.contact != "flat" else base
        w = np.stack([np.full(n, e if cam.contact != "flat" else 0.0), y + s], axis=1)
        up = np.tile([0.0, 1.0], (n, 1))
        return w, up * ds[:, None], up * dds[:, None], up
    q = np.asarray(cam.pivot, dtype=float)
    arm = float(cam.arm or 0.0)
    d = float(np.hypot(*q))
    c = (prime ** 2 - d ** 2 - arm ** 2) / (2 * arm)
    psi = math.atan2(q[1], q[0]) - math.acos(max(-1.0, min(1.0, c / d))) + s
    u = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    v = _quarter(u)
    w = q + arm * u
    return (w, arm * v * ds[:, None], arm * (v * dds[:, None] - u * (ds ** 2)[:, None]), v)


@dataclass(frozen=True)
class CamAnalysis:
    """A cam over a turn, one entry per angle of ``theta`` (radians).

    ``s``, ``ds``, ``dds``, ``ddds``: the follower's displacement and its derivatives
    with respect to the cam's angle (file units, radians for an oscillating follower);
    ``pressure``: the pressure angle (radians, signed), the angle between the common
    normal at the contact and the direction the follower's contact point moves in;
    ``pitch`` and ``profile`` (n x 2): the pitch curve (the roller's centre, the knife's
    tip, for a flat face its foot on the follower's line) and the cam's surface, in the
    cam's frame; ``curvature``: the radius of curvature of the pitch curve (knife, roller)
    or of the profile (flat), positive where convex, infinite where straight.
    """

    theta: Array
    s: Array
    ds: Array
    dds: Array
    ddds: Array
    pressure: Array
    pitch: Array
    profile: Array
    curvature: Array


def analyse_cam(cam: Cam, theta: Array, *, base: float | None = None) -> CamAnalysis:
    """The cam's motion, pitch curve, profile, pressure angle and curvature at the
    angles ``theta`` (radians); ``base`` replaces the cam's base circle radius."""
    theta = np.asarray(theta, dtype=float)
    base = cam.base if base is None else base
    s, ds, dds, ddds = follower_motion(cam, theta)
    w, dw, ddw, up = _follower_point(cam, base, s, ds, dds)
    pitch = _turn(theta, w)
    dp = dw - _quarter(w)                          # the pitch curve's tangent, world-aligned
    ddp = ddw - 2 * _quarter(dw) - w
    if cam.contact == "flat":
        # the face y = base + s: envelope of the lines n . p = d with n = R(-theta) (0, 1)
        d, dd = base + s, ds
        contact_world = np.stack([dd, d], axis=1)    # R(theta) of the envelope point
        profile = _turn(theta, contact_world)
        pressure = np.zeros_like(theta)
        radius = d + dds
        return CamAnalysis(theta, s, ds, dds, ddds, pressure, pitch, profile, radius)
    normal = _quarter(dp)       # the pitch curve's normal, world-aligned (convex: radius > 0)
    normal /= np.hypot(normal[:, 0], normal[:, 1])[:, None]
    normal *= np.sign(dot(normal.T, w.T))[:, None]                  # away from the cam
    contact_world = w - cam.roller * normal
    profile = _turn(theta, contact_world)
    pressure = np.arctan2(cross(up.T, normal.T), dot(up.T, normal.T))
    speed = np.hypot(dp[:, 0], dp[:, 1])
    turning = cross(dp.T, ddp.T)
    with np.errstate(divide="ignore"):
        radius = np.where(turning == 0, np.inf,
                          -speed ** 3 / np.where(turning == 0, 1.0, turning))
    return CamAnalysis(theta, s, ds, dds, ddds, pressure, pitch, profile, radius)


def turn_angles(cam: Cam, steps: int = 360) -> Array:
    """``steps`` equal angles over a turn, with every segment's ends and middle added (where
    the laws' extremes and jumps are), sorted (radians)."""
    marks, start = [], 0.0
    for seg in cam.motion:
        marks += [start, start + seg.over / 2]
        start += seg.over
    return np.unique(np.concatenate([np.linspace(0, 2 * math.pi, steps, endpoint=False),
                                     marks]))


def smallest_base(cam: Cam, limit: float, *, steps: int = 3600) -> float:
    """The smallest base circle radius that keeps the pressure angle's size at most
    ``limit`` (radians) over a turn. For a translating knife or roller follower in closed
    form from ``tan(alpha) = (s' - e) / (s + sqrt(Rp^2 - e^2))``; for an oscillating one by
    bisection; for a flat face (whose pressure angle is always 0) the smallest base circle
    whose profile is nowhere concave, ``base + s + s'' >= 0``. A limit outside (0, 90)
    degrees, or one no base circle meets, raises
    :class:`~chaingraph.errors.DesignError`."""
    if not 0 < limit < math.pi / 2:
        raise DesignError(f"the pressure angle's limit must lie strictly between 0 and 90 "
                          f"degrees, got {math.degrees(limit):g}", parameter="limit")
    theta = turn_angles(cam, steps)
    s, ds, dds, _ = follower_motion(cam, theta)
    if cam.contact == "flat":
        return max(0.0, float(np.max(-(s + dds))))    # (0.0 first: never -0.0)
    if cam.moves == "translating":
        e = cam.offset
        y0 = float(np.max(np.abs(ds - e) / math.tan(limit) - s))
        y0 = max(y0, 0.0)
        return math.hypot(y0, e) - cam.roller

    def worst(b: float) -> float:
        return float(np.max(np.abs(analyse_cam(cam, theta, base=b).pressure)))
    q, arm = math.hypot(*(cam.pivot or (0.0, 0.0))), float(cam.arm or 0.0)
    low = max(abs(q - arm) - cam.roller, 0.0)
    high = q + arm - cam.roller
    grid = np.linspace(low, high, 202)[1:-1]    # the pressure angle is not monotonic here
    ok = [b for b in grid if worst(b) <= limit]
    if not ok:
        raise DesignError(f"cam {cam.id!r}: no base circle the arm can reach keeps the "
                          f"pressure angle under {math.degrees(limit):g} degrees",
                          parameter="limit")
    good = ok[0]
    bad = grid[int(np.searchsorted(grid, good)) - 1] if good > grid[0] else low
    for _ in range(50):
        mid = (bad + good) / 2
        bad, good = (bad, mid) if worst(mid) <= limit else (mid, good)
    return float(good)


def profile_curvature(cam: Cam, result: CamAnalysis) -> Array:
    """The profile's radius of curvature at each angle where it is convex (the pitch
    curve's less the roller's; a flat face's profile's own), NaN where concave or
    straight: negative where the profile is undercut (the roller or the face cannot
    follow it)."""
    if cam.contact == "flat":
        return result.curvature.copy()
    convex = np.isfinite(result.curvature) & (result.curvature > 0)
    return np.where(convex, result.curvature - cam.roller, np.nan)


def cam_summary(cam: Cam, *, name: str = "", limit: float | None = None,
                steps: int = 3600) -> dict[str, object]:
    """What ``chaingraph cam --json`` prints: the cam's data, the stroke, the largest
    pressure angle and where, the profile's smallest radius of curvature and where, the
    undercut check, and with a pressure angle ``limit`` (radians) the smallest base circle
    that keeps under it (else None). Angles in degrees of cam turn; an oscillating
    follower's stroke in degrees, its ``offset`` None, its ``arm`` and ``pivot`` added. ``steps`` equal angles are analysed, with every
    segment's ends and middle."""
    theta = turn_angles(cam, steps)
    result = analyse_cam(cam, theta)
    k = int(np.argmax(np.abs(result.pressure)))
    rho = profile_curvature(cam, result)
    j = int(np.nanargmin(rho))
    stroke = math.degrees(cam.stroke) if cam.moves == "oscillating" else cam.stroke
    out: dict[str, object] = {
        "name": name, "cam": cam.cam, "follower": cam.follower, "contact": cam.contact,
        "base": cam.base, "roller": cam.roller, "offset": cam.offset, "stroke": stroke,
        "pressure_angle": {"max": math.degrees(abs(float(result.pressure[k]))),
                           "at": math.degrees(float(theta[k]))},
        "curvature": {"min": float(rho[j]), "at": math.degrees(float(theta[j]))},
        "undercut": bool(rho[j] < 0),
        "min_base": None if limit is None else smallest_base(cam, limit, steps=steps)}
    if cam.moves == "oscillating":
        out.update(offset=None, arm=cam.arm, pivot=list(cam.pivot or ()))
    return out


CSV_COLUMNS = ("theta", "s", "ds", "dds", "ddds", "pressure_angle", "x_pitch", "y_pitch",
               "x_profile", "y_profile")


def cam_table(cam: Cam, *, steps: int = 360) -> tuple[tuple[float, ...], ...]:
    """``steps`` + 1 rows over a turn (0 to 360 degrees), one number per column of
    :data:`CSV_COLUMNS`: the angle (degrees), the follower's displacement and its
    derivatives with respect to the cam's angle in radians (file units, degrees for an
    oscillating follower), the pressure angle (degrees), and the pitch curve's and the
    profile's points in the cam's frame."""
    theta = np.linspace(0.0, 2 * math.pi, steps + 1)
    r = analyse_cam(cam, theta)
    scale = math.degrees(1.0) if cam.moves == "oscillating" else 1.0
    cols = [np.degrees(theta), r.s * scale, r.ds * scale, r.dds * scale, r.ddds * scale,
            np.degrees(r.pressure), r.pitch[:, 0], r.pitch[:, 1], r.profile[:, 0],
            r.profile[:, 1]]
    return tuple(map(tuple, np.column_stack(cols).tolist()))
