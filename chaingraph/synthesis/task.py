"""Synthesis tasks: what a mechanism must do, checked once, and its targets.

A task is a frozen dataclass with ``kind`` (``"function"``, ``"path"`` or ``"motion"``)
and ``to_dict()`` (the JSON's ``"task"`` and, with the solution's choices, the chain
file's ``[task]`` table). :class:`FunctionTask` is the function generator's:
``y = EXPR(x)`` for x in ``A..B``; the input turns through ``IN`` degrees while x runs
from A to B, the output through ``OUT`` degrees (a slider: OUT file units) while y runs
from y(A) to y(B), both linearly. Every bad task raises one
:class:`~chaingraph.errors.DesignError` naming the parameter at fault.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property

import numpy as np
import numpy.typing as npt

from chaingraph.errors import DesignError
from chaingraph.model.values import LARGEST
from chaingraph.synthesis.expression import Expression, parse_expression
from chaingraph.synthesis.poses import checked_poses

__all__ = ["FunctionTask", "function_task", "SPACINGS", "FUNCTION_KINDS", "MOST_POINTS",
           "check_options", "precision_x", "PathTask", "path_task", "PATH_KINDS",
           "EXACT_POINTS", "MOST_TARGETS", "MotionTask", "motion_task", "POSE_COUNTS",
           "drawn_seed"]

#: the spacings of precision points
SPACINGS = ("chebyshev", "even")
#: the mechanisms a function generator can be
FUNCTION_KINDS = ("four-bar", "slider-crank")
#: the most precision points a function task may ask for
MOST_POINTS = 50
#: how densely a function is checked for finite values over its range
_CHECKED = 2001


@dataclass(frozen=True)
class FunctionTask:
    """A function generator's task (see the module's docstring); angles in degrees.

    ``start`` is ``(IN0, OUT0)``, the input's and output's values at x = A, or None
    (chosen by the synthesis); ``mechanism`` the kind of mechanism (``"four-bar"``: input
    crank, output rocker; ``"slider-crank"``: input crank, output slide).
    """

    function: Expression
    x: tuple[float, float]
    swing: tuple[float, float]
    start: tuple[float, float] | None = None
    points: int = 3
    spacing: str = "chebyshev"
    mechanism: str = "four-bar"
    units: str = "mm"
    min_transmission: float = 30.0
    kind: str = "function"

    @cached_property
    def y_range(self) -> tuple[float, float]:
        """``(y(A), y(B))``."""
        a, b = self.x
        return float(self.function(a)), float(self.function(b))

    def input_at(self, x: npt.ArrayLike) -> np.ndarray:
        """The input's turn from its start (degrees) at x."""
        a, b = self.x
        return self.swing[0] * (np.asarray(x, dtype=float) - a) / (b - a)

    def output_at(self, x: npt.ArrayLike) -> np.ndarray:
        """The output's move from its start (degrees, or file units for a slide) where
        the function is y(x), as the task asks it."""
        ya, yb = self.y_range
        return self.swing[1] * (self.function(x) - ya) / (yb - ya)

    def precision_x(self) -> np.ndarray:
        """The precision points' x values, by the task's spacing."""
        return precision_x(self.x, self.points, self.spacing)

    def to_dict(self) -> dict:
        """The JSON's ``"task"``."""
        return {"kind": self.kind, "function": self.function.text, "x": list(self.x),
                "swing": list(self.swing),
                "start": None if self.start is None else list(self.start),
                "points": self.points, "spacing": self.spacing,
                "mechanism": self.mechanism, "units": self.units,
                "min_transmission": self.min_transmission}


def precision_x(x_range: tuple[float, float], n: int, spacing: str) -> np.ndarray:
    """n precision points over ``x_range``: Chebyshev's (the roots of the n-th Chebyshev
    polynomial mapped onto the range, which minimise the largest interpolation error of
    a smooth function), or evenly spaced, both ends included.

    Examples
    --------
    >>> [round(float(v), 4) for v in precision_x((1, 2), 3, "chebyshev")]
    [1.067, 1.5, 1.933]
    >>> precision_x((0, 1), 3, "even").tolist()
    [0.0, 0.5, 1.0]
    """
    a, b = x_range
    if spacing == "even":
        return np.linspace(a, b, n)
    j = np.arange(1, n + 1)
    return (a + b) / 2 - (b - a) / 2 * np.cos((2 * j - 1) * math.pi / (2 * n))


def _number(value, parameter, what, kind):
    if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
        raise DesignError(f"{what} must be a number, got {value!r}", kind=kind,
                          parameter=parameter)
    value = float(value)
    if not math.isfinite(value):
        raise DesignError(f"{what} must be a finite number, got {value}", kind=kind,
                          parameter=parameter)
    if abs(value) > LARGEST:
        raise DesignError(f"{what} {value:g} is too large: at most {LARGEST:g}", kind=kind,
                          parameter=parameter)
    return value


def _pair(value, parameter, names, kind):
    try:
        first, second = value
    except (TypeError, ValueError):
        raise DesignError(f"{parameter} must be two numbers ({names[0]}, {names[1]}), got "
                          f"{value!r}", kind=kind, parameter=parameter) from None
    return (_number(first, parameter, f"{parameter}'s {names[0]}", kind),
            _number(second, parameter, f"{parameter}'s {names[1]}", kind))


def check_options(*, solutions: int, min_transmission: float, units: str, kind: str) -> float:
    """The options every synthesis takes: ``solutions`` (how many to list, 1 or more),
    ``min_transmission`` (degrees, 0 up to but not 90) and ``units``."""
    if isinstance(solutions, bool) or not isinstance(solutions, int) or solutions < 1:
        raise DesignError(f"solutions must be a whole number, 1 or more, got {solutions!r}",
                          kind=kind, parameter="solutions")
    mt = _number(min_transmission, "min_transmission", "the least transmission angle", kind)
    if not 0 <= mt < 90:
        raise DesignError(f"the least transmission angle must be from 0 up to 90 degrees "
                          f"(the bounds are [min, 180 - min]), got {mt:g}", kind=kind,
                          parameter="min_transmission")
    if not isinstance(units, str) or not units:
        raise DesignError(f"units must be a name such as mm, got {units!r}", kind=kind,
                          parameter="units")
    return mt


def function_task(*, function: str | Expression, x: tuple[float, float],
                  swing: tuple[float, float], start: tuple[float, float] | None = None,
                  points: int = 3, spacing: str = "chebyshev", kind: str = "four-bar",
                  units: str = "mm", min_transmission: float = 30.0) -> FunctionTask:
    """Check a function generator's task (see :func:`chaingraph.synthesis.function`)."""
    what = "function"
    if kind not in FUNCTION_KINDS:
        raise DesignError(f"unknown kind {kind!r} (expected one of "
                          f"{', '.join(FUNCTION_KINDS)})", kind=what, parameter="kind")
    if spacing not in SPACINGS:
        raise DesignError(f"unknown spacing {spacing!r} (expected one of "
                          f"{', '.join(SPACINGS)})", kind=what, parameter="spacing")
    if isinstance(points, bool) or not isinstance(points, int):
        raise DesignError(f"points must be a whole number, got {points!r}", kind=what,
                          parameter="points")
    if points < 3:
        raise DesignError(f"too few points: {points} (three precision points are matched "
                          "exactly; more are fitted)", kind=what, parameter="points")
    if points > MOST_POINTS:
        raise DesignError(f"too many points: {points} (at most {MOST_POINTS})", kind=what,
                          parameter="points")
    mt = check_options(solutions=1, min_transmission=min_transmission, units=units,
                       kind=what)
    expr = parse_expression(function, kind=what) if not isinstance(function, Expression) \
        else function
    a, b = _pair(x, "x", ("start A", "end B"), what)
    if a == b:
        raise DesignError(f"the x range {a:g}:{b:g} is empty: give two different values",
                          kind=what, parameter="x")
    turn, out = _pair(swing, "swing", ("input IN", "output OUT"), what)
    for value, name in ((turn, "input"), (out, "output")):
        if value == 0:
            raise DesignError(f"a swing of 0: the {name} must move", kind=what,
                              parameter="swing")
    if abs(turn) > 360 or (kind == "four-bar" and abs(out) > 360):
        which = "input" if abs(turn) > 360 else "output"
        raise DesignError(f"the {which}'s swing {turn if which == 'input' else out:g} is "
                          "over 360 degrees", kind=what, parameter="swing")
    begin = None if start is None else _pair(start, "start", ("input IN0", "output OUT0"),
                                              what)
    _check_finite(expr, a, b, what)
    ya, yb = float(expr(a)), float(expr(b))
    if ya == yb:
        raise DesignError(f"y({a:g}) = y({b:g}) = {ya:g}: the output's swing cannot be "
                          "spread over a function that ends where it starts", kind=what,
                          parameter="function")
    return FunctionTask(expr, (a, b), (turn, out), begin, points, spacing, kind, units, mt)


def _check_finite(expr, a, b, kind):
    xs = np.linspace(a, b, _CHECKED)
    ys = expr(xs)
    bad = ~np.isfinite(ys)
    if bad.any():
        at = float(xs[np.argmax(bad)])
        raise DesignError(f"the function {expr.text!r} is not finite over the range "
                          f"{a:g}:{b:g} (at x = {at:.6g} it is {float(ys[np.argmax(bad)])})",
                          kind=kind, parameter="function")


# -- path generation ------------------------------------------------------------------
#: the mechanisms a path generator can be (for now)
PATH_KINDS = ("four-bar",)
#: the most points a path task passes exactly; more are fitted
EXACT_POINTS = 5
#: the most points a path task may give
MOST_TARGETS = 500


@dataclass(frozen=True)
class PathTask:
    """A path generator's task: a point of one link passes through ``points`` in the
    given order; ``timing`` the input's value (degrees) at each point, or None (chosen:
    only the input's turn between points is fixed by a timing, see
    :func:`chaingraph.synthesis.path`); ``closed`` the points lie on a closed curve
    traced over a full turn of the input; ``seed`` makes the search repeatable."""

    points: tuple[tuple[float, float], ...]
    timing: tuple[float, ...] | None = None
    closed: bool = False
    mechanism: str = "four-bar"
    seed: int | None = None
    units: str = "mm"
    min_transmission: float = 30.0
    kind: str = "path"

    @property
    def exact(self) -> bool:
        """True when the points are passed exactly (at most :data:`EXACT_POINTS`, and not
        a closed curve); otherwise they are fitted."""
        return len(self.points) <= EXACT_POINTS and not self.closed

    @property
    def size(self) -> float:
        """The task's size: the largest distance between two points."""
        p = np.asarray(self.points)
        return float(np.max(np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1))))

    def to_dict(self) -> dict:
        """The JSON's ``"task"``."""
        return {"kind": self.kind, "targets": [list(p) for p in self.points],
                "timing": None if self.timing is None else list(self.timing),
                "closed": self.closed, "mechanism": self.mechanism, "seed": self.seed,
                "units": self.units, "min_transmission": self.min_transmission}


def drawn_seed(seed: int | None) -> int:
    """A search's seed: ``seed``, or a fresh one drawn when None (given back in the
    task, so that the search can be repeated)."""
    return int(np.random.default_rng().integers(0, 2 ** 31)) if seed is None else seed


def _check_seed(seed: object, what: str) -> None:
    """Refuse a seed that is not None or a whole number 0 or more."""
    if seed is not None and (isinstance(seed, bool) or not isinstance(seed, int) or seed < 0):
        raise DesignError(f"seed must be a whole number, 0 or more, got {seed!r}", kind=what,
                          parameter="seed")


def path_task(*, points: Iterable[tuple[float, float]], timing: Iterable[float] | None = None,
              closed: bool = False, kind: str = "four-bar", seed: int | None = None,
              units: str = "mm", min_transmission: float = 30.0,
              slides: bool = False) -> PathTask:
    """Check a path generator's task (see :func:`chaingraph.synthesis.path`); with
    ``slides`` (a search that drives some chains by a sliding input) the timing's values
    may be slides (file units) too, so they are not held within a turn."""
    what = "path"
    if kind not in PATH_KINDS:
        raise DesignError(f"unknown kind {kind!r} (expected one of {', '.join(PATH_KINDS)})",
                          kind=what, parameter="kind")
    _check_seed(seed, what)
    mt = check_options(solutions=1, min_transmission=min_transmission, units=units,
                       kind=what)
    try:
        given = list(points)
    except TypeError:
        raise DesignError(f"points must be a list of (x, y), got {points!r}", kind=what,
                          parameter="points") from None
    targets = tuple(_point(p, k, what) for k, p in enumerate(given, 1))
    fewest = 3 if closed else 2
    if len(targets) < fewest:
        raise DesignError(f"too few points: {len(targets)} (a "
                          f"{'closed curve' if closed else 'path'} needs {fewest} or more)",
                          kind=what, parameter="points")
    if len(targets) > MOST_TARGETS:
        raise DesignError(f"too many points: {len(targets)} (at most {MOST_TARGETS})",
                          kind=what, parameter="points")
    size = max(math.dist(p, q) for p in targets for q in targets)
    for i, p in enumerate(targets):
        for j in range(i + 1, len(targets)):
            if math.dist(p, targets[j]) <= 1e-12 * size:
                raise DesignError(f"points {i + 1} and {j + 1} are the same point "
                                  f"({p[0]:g}, {p[1]:g}): a path needs distinct points",
                                  kind=what, parameter="points")
    turns = None if timing is None else _timing(timing, len(targets), what, slides)
    return PathTask(targets, turns, bool(closed), kind, seed, units, mt)


def _point(p, k, what):
    """Point k (from 1) as two finite numbers."""
    try:
        x, y = p
    except (TypeError, ValueError):
        raise DesignError(f"point {k} must be two numbers (x, y), got {p!r}", kind=what,
                          parameter="points") from None
    return (_number(x, "points", f"point {k}'s x", what),
            _number(y, "points", f"point {k}'s y", what))


def _timing(timing, count, what, slides=False):
    """The input's values at the points: as many as the points, finite, all moving one
    way, less than a turn (a whole turn at most for a closed curve) from first to last
    (unless they may be ``slides``)."""
    try:
        values = list(timing)
    except TypeError:
        raise DesignError(f"timing must be a list of angles, got {timing!r}", kind=what,
                          parameter="timing") from None
    out = tuple(_number(v, "timing", f"timing {k}", what) for k, v in enumerate(values, 1))
    if len(out) != count:
        raise DesignError(f"timing gives {len(out)} input values for {count} points (one per "
                          "point)", kind=what, parameter="timing")
    steps = np.diff(out)
    if not (np.all(steps > 0) or np.all(steps < 0)):
        raise DesignError("timing must move one way (every value above the one before, or "
                          f"every value below), got {'; '.join(f'{v:g}' for v in out)}",
                          kind=what, parameter="timing")
    if abs(out[-1] - out[0]) >= 360.0 and not slides:
        raise DesignError(f"timing spans {abs(out[-1] - out[0]):g} degrees: the points are "
                          "met within one turn of the input", kind=what, parameter="timing")
    return out
#: how many poses motion generation takes (two and three by the classical constructions,
#: four and five by Burmester theory)
POSE_COUNTS = (2, 3, 4, 5)


@dataclass(frozen=True)
class MotionTask:
    """A motion generator's task: a link passes through ``poses``, ``(x, y, degrees)``
    each (a point of it at x, y, the link turned by the angle), in order; ``seed`` makes
    a search through the atlas repeatable (None: no search, or one drawn)."""

    poses: tuple[tuple[float, float, float], ...]
    units: str = "mm"
    min_transmission: float = 30.0
    kind: str = "motion"
    seed: int | None = None
    mechanism: str = "four-bar or slider crank"

    @property
    def size(self) -> float:
        """The task's size: the largest distance between two poses' points."""
        p = np.asarray([(x, y) for x, y, _ in self.poses])
        return float(np.max(np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1))))

    def radians(self) -> tuple[tuple[float, float, float], ...]:
        """The poses with their angles in radians (:mod:`chaingraph.synthesis.poses`)."""
        return tuple((x, y, math.radians(a)) for x, y, a in self.poses)

    def to_dict(self) -> dict:
        """The JSON's ``"task"``."""
        out = {"kind": self.kind, "poses": [list(p) for p in self.poses],
               "units": self.units, "min_transmission": self.min_transmission}
        if self.seed is not None:
            out["seed"] = self.seed
        return out


def motion_task(*, poses: Iterable[Sequence[float]], units: str = "mm",
                min_transmission: float = 30.0, seed: int | None = None) -> MotionTask:
    """Check a motion generator's task (see :func:`chaingraph.synthesis.motion`): 2 to 5
    poses of three finite numbers (x, y, degrees), no two the same."""
    what = "motion"
    _check_seed(seed, what)
    mt = check_options(solutions=1, min_transmission=min_transmission, units=units,
                       kind=what)
    if isinstance(poses, (str, bytes)):
        raise DesignError(f"poses must be a sequence of (x, y, degrees), got {poses!r}",
                          kind=what, parameter="poses")
    try:
        given = list(poses)
    except TypeError:
        raise DesignError(f"poses must be a sequence of (x, y, degrees), got {poses!r}",
                          kind=what, parameter="poses") from None
    out: list[tuple[float, float, float]] = []
    for n, pose in enumerate(given, 1):
        try:
            x, y, a = pose
        except (TypeError, ValueError):
            raise DesignError(f"pose {n} must be three numbers (x, y, degrees), got "
                              f"{pose!r}", kind=what, parameter="poses") from None
        out.append((_number(x, "poses", f"pose {n}'s x", what),
                    _number(y, "poses", f"pose {n}'s y", what),
                    _number(a, "poses", f"pose {n}'s angle", what)))
    if len(out) not in POSE_COUNTS:
        raise DesignError(f"motion generation needs {POSE_COUNTS[0]} to {POSE_COUNTS[-1]} "
                          f"poses, got {len(out)}", kind=what, parameter="poses")
    checked_poses([(x, y, math.radians(a)) for x, y, a in out])
    return MotionTask(tuple(out), units, mt, seed=seed)
