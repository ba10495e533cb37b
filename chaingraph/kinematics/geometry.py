"""Small geometry on arrays: a link's pose and the points it carries.

Every link carries a rigid motion from its drawn pose: position ``(x, y)`` and rotation
``phi``, so a drawn point p is at ``R(phi) p + (x, y)``. A pose entry is
``(x, y, phi, cos phi, sin phi)``: the trigonometry is done once per link. Entries are
numpy arrays over a sweep, or constants (the fixed link's), which numpy broadcasts.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["make_pose", "rotate", "tidy"]


DISC_TOL = 1e-13   # dimensionless discriminant: rounding is about 1e-16


# -- small geometry on arrays --------------------------------------------------------
# A pose is (x, y, phi, cos phi, sin phi): the trigonometry is done once per link.
# The fixed link's is constants, which numpy broadcasts.
FIXED = (0.0, 0.0, 0.0, 1.0, 0.0)
def make_pose(x, y, phi, c=None, s=None):
    """A link's pose entry from its motion (x, y, phi)."""
    if c is None:
        c, s = np.cos(phi), np.sin(phi)
    return (x, y, phi, c, s)


def rotate(entry, p):
    """Rotate the drawn vector p by the pose entry's rotation."""
    c, s = entry[3], entry[4]
    return c * p[0] - s * p[1], s * p[0] + c * p[1]


def world(pose, link, p):
    e = pose[link]
    rx, ry = rotate(e, p)
    return rx + e[0], ry + e[1]


def fit_two_points(p1, w1, p2, w2):
    """The rigid motion taking drawn points p1, p2 to w1, w2 (rotation from the chord)."""
    dpx, dpy = p2[0] - p1[0], p2[1] - p1[1]
    dwx, dwy = w2[0] - w1[0], w2[1] - w1[1]
    c = dpx * dwx + dpy * dwy
    s = dpx * dwy - dpy * dwx
    norm = np.hypot(c, s)
    c, s = c / norm, s / norm
    e = (0.0, 0.0, None, c, s)
    rx, ry = rotate(e, p1)
    return make_pose(w1[0] - rx, w1[1] - ry, np.arctan2(s, c), c, s)


def from_point(entry, p, w):
    """The pose with the rotation of ``entry`` that puts drawn point p at w."""
    rx, ry = rotate(entry, p)
    return make_pose(w[0] - rx, w[1] - ry, entry[2], entry[3], entry[4])


def unit_vector(deg):
    return math.cos(math.radians(deg)), math.sin(math.radians(deg))


def line_of(pose, attach, unknown, through):
    """The line on which the unknown link's drawn point ``through`` must stay, for a P
    attachment to a known link: (base point, direction, the unknown link's rotation)."""
    known = pose[attach.other(unknown)]
    base = world(pose, attach.other(unknown), attach.point)
    dx, dy = through[0] - attach.point[0], through[1] - attach.point[1]
    ox, oy = rotate(known, (dx, dy))
    u = rotate(known, unit_vector(attach.axis))
    return (base[0] + ox, base[1] + oy), u, known


def clamp_disc(disc, scale, double=False):
    """A discriminant where the modes exist (within rounding of zero: zero), NaN
    elsewhere, and where it is; zero where ``double`` (the modes' double root)."""
    tol = DISC_TOL * scale
    ok = (disc >= -tol) | double
    return np.where(double, 0.0, np.where(ok, np.maximum(disc, 0.0), np.nan)), ok


def tidy(value, scale):
    """``value`` (a figure of magnitude up to about ``scale``) as the round number it
    is within rounding of (1e-12 of the scale): the nearest number with six
    significant digits at the scale's magnitude, where that is so near; else as it is
    (a figure that merely happens to lie so near a round number moves by at most 1e-12
    of the scale, far inside the solver's precision).
    The sweep's figures carry rounding that a reader would take for a digit
    (1.35704e-14 for 0, 179.9999999999999 for 180).

    Examples
    --------
    >>> tidy(1.3570374e-14, 360.0), tidy(179.9999999999999, 360.0), tidy(47.1563500001, 360.0)
    (0.0, 180.0, 47.1563500001)
    >>> tidy(1.7000000000000015, 1.0), tidy(None, 1.0)
    (1.7, None)
    """
    if value is None or not math.isfinite(value) or scale <= 0:
        return value
    digits = 6 - math.floor(math.log10(scale))
    near = round(value, digits) + 0.0          # + 0.0: no negative zero
    return near if abs(value - near) <= 1e-12 * scale else value
