"""The input's cycle and the sweep: where the inputs can go from the drawn pose, and
the poses at any input values, continued on one internal grid whatever was asked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ..errors import AssemblyError
from .tracking import Evaluation, evaluate

__all__ = ["Cycle", "cycle", "feasible_range"]


# -- the cycle and the sweep -----------------------------------------------------------
_GRID_DEG = 1.0         # the internal grid on which the assembly modes are tracked
_MAX_TURNS = 4          # how far a driver is followed each way before giving up


@dataclass(frozen=True)
class Cycle:
    """What the driver can do from the drawn pose: turn fully, returning to the drawn
    pose after ``period`` degrees (360 for an ordinary crank), or rock between the
    limits ``low`` and ``high`` (degrees, dead centres where the motion folds back)."""

    period: float | None
    low: float
    high: float
    limit_poses: tuple = field(default=(), compare=False, repr=False)

    @property
    def full_turn(self) -> bool:
        return self.period is not None


def _returns(plan, pose, k):
    """Whether every link is back in its drawn pose at point k (up to whole turns)."""
    for link in plan.moving:
        x, y, phi = (float(np.broadcast_to(v, (k + 1,))[k]) for v in pose[link][:3])
        if max(abs(x), abs(y)) > 1e-7 * plan.size or \
                abs(math.remainder(phi, 2 * math.pi)) > 1e-7:
            return False
    return True


def _walk(plan, direction):
    """Follow the driver from the drawn pose one way: (limit, None) where the motion
    stops, (None, period) where it returns to the drawn pose, (None, None) if neither
    within ``_MAX_TURNS`` turns."""
    t, start = plan.theta0, None
    steps = int(round(360.0 / _GRID_DEG))
    for m in range(1, _MAX_TURNS + 1):
        path = t + direction * np.linspace(0.0, 360.0, steps + 1)
        ev = evaluate(plan, path, start=start)
        if not ev.feasible.all():
            k = int(np.argmin(ev.feasible))
            if k == 0:
                return (float(path[0]), ev.take(np.array([0]))), None
            return _limit(plan, ev, k - 1, float(path[k])), None
        if _returns(plan, ev.pose, steps):
            return None, 360.0 * m
        t, start = float(path[-1]), ev.at(steps)
    return None, None


def _limit(plan, ev, k, bad):
    """The last angle that can be assembled past ev's point k, towards ``bad``,
    continued on ever finer paths from the last point that assembles: (angle, the
    evaluation at that angle)."""
    good, state, at = float(ev.theta[k]), ev.at(k), ev.take(np.array([k]))
    for _ in range(16):
        ts = np.linspace(good, bad, 17)
        trial = evaluate(plan, ts, start=state)
        if trial.feasible.all():
            return float(bad), trial.take(np.array([16]))
        j = int(np.argmin(trial.feasible)) - 1
        if j < 0:
            break
        good, state, bad = float(ts[j]), trial.at(j), float(ts[j + 1])
        at = trial.take(np.array([j]))
        if abs(bad - good) < 1e-10:
            break
    return good, at


def cycle(plan) -> Cycle:
    """The driver's :class:`Cycle` (cached per plan).

    Raises
    ------
    AssemblyError
        When the driver neither returns to the drawn pose nor reaches a limit within
        four turns either way.
    """
    return _cycle(plan)


@lru_cache(maxsize=256)
def _cycle(plan):
    t0 = plan.theta0
    high, period = _walk(plan, 1.0)
    if period is not None:
        return Cycle(period, t0, t0 + period)
    low, _ = _walk(plan, -1.0) if high is not None else (None, None)
    if high is None or low is None:
        raise AssemblyError(
            f"the driver {plan.driver!r} turns {_MAX_TURNS} times without returning to "
            "the drawn pose or reaching a limit", mechanism=plan.chain.source or plan.chain.name)
    # the poses at the limits as found there (at a fold the last digits depend on the
    # path, so the sweep takes them from here)
    return Cycle(None, low[0], high[0], (low[1], high[1]))


def feasible_range(plan):
    """The input angles that can be assembled from the drawn pose, or None for a crank.

    Returns
    -------
    (low, high) in degrees around the drawn pose's angle, or None when the driver makes
    full turns. A range may be wider than a turn.
    """
    c = cycle(plan)
    return None if c.full_turn else (c.low, c.high)


def _outside(plan, lo, hi):
    rng = feasible_range(plan)
    return AssemblyError(
        f"the sweep {lo:g} to {hi:g} degrees leaves the range that can be assembled: "
        f"the driver {plan.driver!r} can turn only from {rng[0]:.6f} to {rng[1]:.6f} "
        f"degrees", mechanism=plan.chain.source or plan.chain.name,
        feasible_range=rng)


def _along(plan, end, targets):
    """Poses at ``targets`` (all between the drawn pose's angle and ``end``), reached by
    continuation from the drawn pose on the internal grid to ``end`` with the targets
    inserted, so that they do not depend on which other targets were asked for."""
    t0 = plan.theta0
    span = end - t0
    n = max(1, int(math.ceil(abs(span) / _GRID_DEG)))
    grid = np.concatenate([t0 + span * np.arange(n + 1) / n, targets])
    sign = 1.0 if span >= 0 else -1.0
    grid = sign * np.unique(sign * grid)      # in path order
    ev = evaluate(plan, grid)
    idx = np.searchsorted(sign * grid, sign * targets)
    return ev.take(idx)


def _evaluate_sweep(plan, theta):
    """Poses at the angles ``theta`` (degrees): a crank's from its angle within one
    period of the drawn pose, a rocker's from the drawn pose outward, both continued on
    the same internal grid whatever the sweep."""
    theta = np.asarray(theta, dtype=float)
    c = cycle(plan)
    t0 = plan.theta0
    if c.full_turn:
        phase = t0 + np.mod(theta - t0, c.period)
        ev = _along(plan, t0 + c.period, phase)
        ev.theta = theta
        return ev
    lo, hi = float(theta.min()), float(theta.max())
    if lo < c.low - 1e-9 or hi > c.high + 1e-9:
        raise _outside(plan, lo, hi)
    clipped = np.clip(theta, c.low, c.high)
    # each side on its own path from the drawn pose; a limit itself (a fold, where
    # the last digits depend on the path) as the cycle found it
    parts = []
    for side, end in ((clipped > t0, c.high), (clipped <= t0, c.low)):
        inner = side & (clipped != end)
        if inner.any():
            parts.append((np.nonzero(inner)[0], _along(plan, end, clipped[inner])))
        limit = side & (clipped == end)
        if limit.any():
            found = c.limit_poses[0 if end == c.low else 1]
            parts.append((np.nonzero(limit)[0], found.take(np.zeros(limit.sum(), dtype=int))))
    ev = parts[0][1] if len(parts) == 1 else _merge(parts, theta.size)
    if not ev.feasible.all():
        raise _outside(plan, lo, hi)
    ev.theta = theta
    return ev


def _merge(parts, n):
    """One evaluation from parts, each (indices into the result, evaluation)."""
    first = parts[0][1]

    def put(values):
        out = None
        for (idx, _), v in zip(parts, values):
            v = np.asarray(v)
            if out is None:
                out = np.empty((n,) + v.shape[1:], dtype=v.dtype)
            out[idx] = np.broadcast_to(v, (idx.size,) + v.shape[1:])
        return out
    pose = {}
    for link, entry in first.pose.items():
        pose[link] = tuple(
            v if all(np.ndim(e.pose[link][i]) == 0 and e.pose[link][i] == v
                     for _, e in parts) else put([e.pose[link][i] for _, e in parts])
            for i, v in enumerate(entry))
    switches = {i: sorted(set().union(*(e.switches.get(i, ()) for _, e in parts)))
                for i in first.switches}
    return Evaluation(put([e.theta for _, e in parts]), pose,
                      put([e.feasible for _, e in parts]),
                      {i: put([e.signs[i] for _, e in parts]) for i in first.signs},
                      {i: put([e.group_q[i] for _, e in parts]) for i in first.group_q},
                      switches)

