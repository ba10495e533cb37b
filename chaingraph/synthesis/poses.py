"""Poses of a moving plane and the displacements between them: where every construction
of motion generation (:mod:`chaingraph.synthesis.burmester`) starts.

A pose is ``(x, y, angle)``: a point of the guided link is at ``(x, y)`` and the link
is turned by ``angle`` (radians). Pose ``i`` is a rigid motion of the plane, the frame
``(angle, x, y)`` of :mod:`chaingraph.geometry`; the *displacement* from pose ``i`` to
pose ``j`` takes each point of the plane from where pose ``i`` puts it to where pose
``j`` does. A point "of the moving plane" is given where the first pose puts it.

Pose numbers are from 0 in the functions, as Python counts, and from 1 in messages, as
the task lists them (``poses 2 and 4 are the same``).

Examples
--------
Half a turn about (1, 1) takes the origin to (2, 2):

>>> p = pole([(0.0, 0.0, 0.0), (2.0, 2.0, math.pi)], 0, 1)
>>> [round(v, 12) for v in p.at], p.angle == math.pi, p.at_infinity
([1.0, 1.0], True, False)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from chaingraph.errors import DesignError
from chaingraph.geometry import apply, compose, inverse, normalised, perp

__all__ = ["Pose", "AT_INFINITY", "SAME", "checked_poses", "task_size", "frame_of",
           "pose_of", "displacement", "moved", "Pole", "pole", "inverted"]

#: a pose: ``(x, y, angle)``, the angle in radians
Pose = tuple[float, float, float]

#: a point farther than this many times the task's size is at infinity (a rotation
#: below this many radians is a translation: its pole is at infinity)
AT_INFINITY = 1e10
#: two poses closer than this (radians, and times the task's size) are the same
SAME = 1e-12


def checked_poses(poses: Sequence[Sequence[float]], *, counts: Sequence[int] | None = None,
                  method: str = "motion generation") -> tuple[Pose, ...]:
    """The poses as float triples, checked: three finite numbers each, as many as
    ``counts`` allows (any number when None), no two the same.

    Raises
    ------
    DesignError
        Naming the pose at fault (from 1), or the two that are the same, or how many
        poses ``method`` needs (``parameter == "poses"``).

    Examples
    --------
    >>> checked_poses([(0, 0, 0), (1, 0, 0.5)])
    ((0.0, 0.0, 0.0), (1.0, 0.0, 0.5))
    >>> checked_poses([(0, 0, 0), (1, 0, 0.5), (0, 0, 2 * math.pi)])
    Traceback (most recent call last):
    ...
    chaingraph.errors.DesignError: design motion: poses 1 and 3 are the same pose (the same point and angle): a task needs distinct poses
    """
    out = []
    for n, pose in enumerate(poses, 1):
        try:
            x, y, a = (float(v) for v in pose)
        except (TypeError, ValueError):
            _fail(f"pose {n} must be three numbers (x, y, angle), got {pose!r}")
        if not all(math.isfinite(v) for v in (x, y, a)):
            _fail(f"pose {n} must be three finite numbers (x, y, angle), got {pose!r}")
        out.append((x, y, a))
    if counts is not None and len(out) not in counts:
        wanted = " or ".join(str(c) for c in counts)
        _fail(f"{method} needs {wanted} poses, got {len(out)}")
    size = task_size(out)
    for i in range(len(out)):
        for j in range(i + 1, len(out)):
            turn = math.remainder(out[j][2] - out[i][2], 2 * math.pi)
            apart = math.hypot(out[j][0] - out[i][0], out[j][1] - out[i][1])
            if abs(turn) <= SAME and apart <= SAME * size:
                _fail(f"poses {i + 1} and {j + 1} are the same pose (the same point and "
                      "angle): a task needs distinct poses")
    return tuple(out)


def _fail(problem: str):
    raise DesignError(problem, kind="motion", parameter="poses")


def task_size(poses: Sequence[Pose]) -> float:
    """The task's size: the largest distance between two poses' points (0 when they are
    all at one point)."""
    return max((math.hypot(p[0] - q[0], p[1] - q[1]) for p in poses for q in poses),
               default=0.0)


def frame_of(pose: Pose) -> tuple[float, float, float]:
    """The pose as a :mod:`chaingraph.geometry` frame ``(angle, x, y)``."""
    return (pose[2], pose[0], pose[1])


def pose_of(frame: Sequence[float]) -> Pose:
    """The frame ``(angle, x, y)`` as a pose ``(x, y, angle)``."""
    return (float(frame[1]), float(frame[2]), float(frame[0]))


def displacement(poses: Sequence[Pose], i: int, j: int) -> tuple[float, float, float]:
    """The rigid motion, a frame ``(angle, x, y)``, that takes each point of the plane
    from where pose ``i`` puts it to where pose ``j`` does; its angle is in [-pi, pi].

    >>> [round(v, 12) + 0.0 for v in displacement([(1, 0, 0), (0, 1, math.pi / 2)], 0, 1)]
    [1.570796326795, 0.0, 0.0]
    """
    d = compose(frame_of(poses[j]), inverse(frame_of(poses[i])))
    return (math.remainder(d[0], 2 * math.pi), float(d[1]), float(d[2]))


def moved(poses: Sequence[Pose], point: Sequence[float], j: int) -> tuple[float, float]:
    """Where pose ``j`` puts the plane's point that the first pose puts at ``point``."""
    p = apply(displacement(poses, 0, j), (float(point[0]), float(point[1])))
    return (float(p[0]), float(p[1]))


@dataclass(frozen=True)
class Pole:
    """The pole of the displacement from pose ``i`` to pose ``j``: the plane's one point
    that the displacement leaves where it is.

    Attributes
    ----------
    poses : tuple of int
        ``(i, j)``, from 0.
    angle : float
        theta_ij, the plane's rotation from pose i to pose j (radians, in [-pi, pi]).
    at : tuple of float or None
        The pole; None when it is at infinity (a translation: ``angle`` is below
        ``1 / AT_INFINITY``).
    direction : tuple of float or None
        For a pole at infinity, the unit direction in which it lies (square to the
        translation, on the side the plane turns about); None for a pole at a point.
    """

    poses: tuple[int, int]
    angle: float
    at: tuple[float, float] | None
    direction: tuple[float, float] | None = None

    @property
    def at_infinity(self) -> bool:
        """True when the displacement is a translation (the pole is at infinity)."""
        return self.at is None


def pole(poses: Sequence[Pose], i: int, j: int) -> Pole:
    """The pole P_ij of poses ``i`` and ``j`` (from 0) and the rotation theta_ij.

    The pole is ``p_i + d / 2 + cot(theta / 2) / 2 * k x d``, with ``d = p_j - p_i``
    the displacement of the poses' point: on the bisector of ``p_i p_j``, seeing the
    chord under the angle theta.

    Examples
    --------
    A translation's pole is at infinity, square to it:

    >>> p = pole([(0, 0, 0.3), (3, 4, 0.3)], 0, 1)
    >>> p.at_infinity, p.direction
    (True, (-0.8, 0.6))
    """
    theta = math.remainder(poses[j][2] - poses[i][2], 2 * math.pi)
    d = (poses[j][0] - poses[i][0], poses[j][1] - poses[i][1])
    if abs(theta) * AT_INFINITY < 1 and (d[0] or d[1]):
        square = normalised(perp(d))
        assert square is not None                       # d is not zero
        way = square * (-1.0 if theta < 0 else 1.0)
        return Pole((i, j), theta, None, (float(way[0]), float(way[1])))
    if theta == 0:
        raise DesignError(f"poses {i + 1} and {j + 1} are the same pose: they have no pole",
                          kind="motion", parameter="poses")
    k = 0.5 / math.tan(0.5 * theta)
    n = perp(d)
    return Pole((i, j), theta, (poses[i][0] + 0.5 * d[0] + k * n[0],
                                poses[i][1] + 0.5 * d[1] + k * n[1]))


def inverted(poses: Sequence[Pose]) -> tuple[Pose, ...]:
    """The inverted task: the fixed plane's poses seen from the moving plane, drawn where
    the first pose puts the moving plane. A dyad of the poses (centre point, circle
    point) is a dyad of the inverted poses with the two points swapped: centre points
    of the one are circle points of the other.

    The first pose is kept; pose ``j`` becomes the displacement from pose ``j`` to the
    first, applied to the first.

    >>> inverted([(0, 0, 0), (3, 4, 0)])
    ((0.0, 0.0, 0.0), (-3.0, -4.0, 0.0))
    """
    first = frame_of(poses[0])
    return tuple(pose_of(compose(compose(first, inverse(frame_of(p))), first))
                 for p in poses)
