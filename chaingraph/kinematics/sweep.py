"""The input's cycle and the sweep: where the inputs can go from the drawn pose, and
the poses at any input values, continued on one internal grid whatever was asked.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from chaingraph.errors import AssemblyError, UnboundedRangeError
from chaingraph.kinematics import groups
from chaingraph.kinematics.closed_form import dyad_roots
from chaingraph.kinematics.higher import gear_cycle_turns
from chaingraph.kinematics.plan import Plan
from chaingraph.kinematics.roots import bracketed_roots
from chaingraph.kinematics.tracking import (
    Evaluation,
    Reference,
    Start,
    evaluate,
    evaluate_at,
    failing_step,
)

__all__ = ["Cycle", "Anchor", "cycle", "anchor", "feasible_range", "merged_path"]


# -- the cycle and the sweep -----------------------------------------------------------
_GRID_DEG = 1.0         # the internal grid on which the assembly modes are tracked
_MAX_TURNS = 4          # how far a driver is followed each way before giving up


@dataclass(frozen=True)
class Cycle:
    """What the inputs can do from the drawn pose: turn fully, returning to the drawn
    pose after ``period`` degrees (360 for an ordinary crank), or rock (or slide)
    between the limits ``low`` and ``high`` (dead centres where the motion folds back).
    All in the plan's path parameter ``tau`` (an R input's angle in degrees).

    ``ends`` is ``"limits"`` when ``low`` and ``high`` are where the motion folds back,
    ``"sweep"`` when they are the ends of a sweep of several inputs moving together
    (whose summary is of that sweep: its ends are no dead centres)."""

    period: float | None
    low: float
    high: float
    limit_poses: tuple[Evaluation, ...] = field(default=(), compare=False, repr=False)
    ends: str = "limits"

    @property
    def full_turn(self) -> bool:
        return self.period is not None


@dataclass(frozen=True)
class Anchor:
    """Where every path starts: the drawn pose (``state`` None), or, when the inputs'
    sweep line does not pass through the drawn pose, the sweep's first point, reached
    from the drawn pose along a straight path in the inputs' space. ``pose`` is each
    moving link's (x, y, phi) there."""

    tau: float
    state: Start | None
    pose: dict[str, tuple[float, ...]]      # (x, y, phi)


def anchor(plan: Plan) -> Anchor:
    """The plan's :class:`Anchor` (cached per plan).

    Raises
    ------
    AssemblyError
        When the sweep's first point cannot be reached from the drawn pose.
    """
    return _anchor(plan)


@lru_cache(maxsize=256)
def _anchor(plan):
    if plan.theta0 is not None:
        return Anchor(plan.theta0, None, {x: (0.0, 0.0, 0.0) for x in plan.moving})
    item = plan.inputs[plan.lead]
    tau = plan.tau(item.sweep[0])
    target = [float(d) for d in plan.deltas(tau)]
    span = max(math.degrees(abs(d) / (1.0 if i.kind == "R" else plan.size))
               for i, d in zip(plan.inputs, target))
    span = max(span, 1e-9)
    toward = replace(plan, line=tuple((0.0, d / span) for d in target), theta0=0.0)
    n = max(1, int(math.ceil(span / _GRID_DEG)))
    path = span * np.arange(n + 1) / n
    ev = evaluate(toward, path)
    if not ev.feasible.all():
        k = int(np.argmin(ev.feasible))
        at = ", ".join(f"{i.joint} = {v:.6g}" for i, v in
                       zip(plan.inputs, (float(x) for x in toward.values(path[k]))))
        raise AssemblyError(
            f"the sweep's first point cannot be reached from the drawn pose: moving the "
            f"inputs straight there, the mechanism cannot be assembled at {at}",
            mechanism=plan.chain.source or plan.chain.name)
    pose = {x: tuple(float(np.broadcast_to(v, path.shape)[-1]) for v in ev.pose[x][:3])
            for x in plan.moving}
    return Anchor(tau, ev.at(n), pose)


def _returns(plan, pose, k):
    """Whether every link is back in its pose at the anchor at point k (up to whole
    turns)."""
    home = anchor(plan).pose
    for link in plan.moving:
        x, y, phi = (float(np.broadcast_to(v, (k + 1,))[k]) for v in pose[link][:3])
        x0, y0, phi0 = home[link]
        if max(abs(x - x0), abs(y - y0)) > 1e-7 * plan.size or \
                abs(math.remainder(phi - phi0, 2 * math.pi)) > 1e-7:
            return False
    return True


def _turns_searched(plan):
    """How many turns the driver is followed each way: ``_MAX_TURNS``, or a gear
    train's cycle known from its teeth (``gear_cycle_turns``; times ``_MAX_TURNS``
    where the linkage drives a pair: the linkage's own cycle may be several turns)."""
    lead = plan.inputs[plan.lead]
    known = gear_cycle_turns(plan.derived) if lead.kind == "R" and \
        plan.moving_inputs == 1 else None
    if known is None:
        return _MAX_TURNS
    late = any(d.after is not None for d in plan.derived)
    return max(_MAX_TURNS, known * (_MAX_TURNS if late else 1))


def _walk(plan, direction):
    """Follow the inputs from the anchor one way: (limit, None) where the motion
    stops, (None, period) where it returns to the anchor's pose, (None, None) if
    neither within :func:`_turns_searched` turns."""
    home = anchor(plan)
    t, start = home.tau, home.state
    steps = int(round(360.0 / _GRID_DEG))
    for m in range(1, _turns_searched(plan) + 1):
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


#: how near the paths close in on a limit before the fold is solved for: near enough for
#: a fold's Newton's method; closer only where no fold is found (the limit then is the
#: last point assembled, to ``_FINEST``)
_NEAR, _FINEST = 1e-7, 1e-10


def _limit(plan, ev, k, bad):
    """The last angle that can be assembled past ev's point k, towards ``bad``,
    continued on ever finer paths from the last point that assembles: (angle, the
    evaluation at that angle)."""
    good, state, at = float(ev.theta[k]), ev.at(k), ev.take(np.array([k]))
    far = bad
    traced = _traced_fold(ev, good, bad)
    if traced is not None:
        # a group's fold that the path's trace found: solved from there, once, not
        # traced again on ever shorter paths
        limit = _fold(plan, at, good, bad, far, traced=traced)
        if limit[0] != good:
            return limit
    for tolerance in (_NEAR, _FINEST):
        for _ in range(16):
            if abs(bad - good) < tolerance:
                break
            ts = np.linspace(good, bad, 17)
            trial = evaluate(plan, ts, start=state)
            if trial.feasible.all():
                # reached from nearer (Newton's method near a group's fold depends on
                # where it starts): the fold is past it, before ``far``
                good, at, bad = float(bad), trial.take(np.array([16])), far
                return _fold(plan, at, good, bad, far)
            j = int(np.argmin(trial.feasible)) - 1
            if j < 0:
                return _fold(plan, at, good, bad, far)
            good, state, bad = float(ts[j]), trial.at(j), float(ts[j + 1])
            at = trial.take(np.array([j]))
        limit = _fold(plan, at, good, bad, far)
        if limit[0] != good:                  # a fold: solved exactly
            return limit
    return limit


def _traced_fold(ev, good, bad):
    """(step index, input degrees, q) of the first group whose fold the evaluation's
    trace found between ``good`` and ``bad``, or None."""
    for i in sorted(ev.folds):
        t, q = ev.folds[i]
        if (t - good) * (t - bad) <= 0:
            return i, t, q
    return None


_AT_FOLD = 1e-12     # a dyad's discriminant (dimensionless) this small: a fold


def _fold(plan, at, good, bad, far, *, traced=None):
    """The limit between ``good`` (assembled; ``at`` its evaluation) and ``bad`` (not)
    exactly, as a fold of the step that fails there: a dyad's at its discriminant's root,
    where it takes its double root; a group's by Newton's method on the extended system
    (:func:`groups.fold_point`). Found by bisection alone, a limit's pose would carry
    the square root of the bisection's tolerance. ``far`` is where the path first
    failed (a group's Newton's method near its fold depends on where it starts: ``bad``
    may assemble from ``good`` where the path found it did not). A dyad that
    degenerates there (no sign change of its discriminant) is no fold: the limit stays
    at ``good``. ``traced``: (step index, input degrees, q), a group's fold as its
    trace found it, where that group's Newton's method starts. Returns (angle, the
    evaluation there)."""
    ref = at.reference(np.array([0]))
    if traced is not None:
        i = traced[0]
    else:
        i = failing_step(plan, np.array([bad]), ref)
        if i is None:
            i = failing_step(plan, np.array([far]), ref)
    if i is None:
        return good, at
    step = plan.steps[i]
    double: tuple[int, ...] = ()
    group_q = dict(ref.group_q)
    if step.kind == "dyad":
        def disc(t):
            t = np.atleast_1d(np.asarray(t, dtype=float))
            pose, _, _ = evaluate_at(plan, t, _repeat(ref, t.size), upto=i)
            with np.errstate(divide="ignore", invalid="ignore"):
                return np.asarray(dyad_roots(step, pose, plan.size)[3], dtype=float) \
                    * np.ones(t.size)
        d_good, d_bad = disc(good)[0], disc(bad)[0]
        if d_good > 0 and np.isfinite(d_bad) and d_bad < 0:
            t = float(bracketed_roots(disc, [good], [bad], [d_good], [d_bad],
                                      tol=4e-16 * max(1.0, abs(good)), iterations=200)[0])
        elif abs(d_good) <= _AT_FOLD:
            t = good
        else:
            # no fold: the dyad degenerates there (its two known joints meet)
            return good, at
        double = (i,)
    else:
        start = (at.group_q[i][0], good) if traced is None else traced[2:0:-1]
        found = groups.fold_point(plan, step, at, *start)
        # the fold lies between the last point assembled and ``bad`` (a point a
        # hair past the fold may count as assembled: Newton's method stalls there)
        if found is None or (found[0] - good) * (found[0] - far) > 0 and \
                abs(found[0] - good) > 1e-6:
            return good, at
        t, q = found
        group_q[i] = q[None]
    ref = Reference(ref.theta, ref.signs, group_q, ref.switches)
    pose, feasible, group_q = evaluate_at(plan, np.array([t]), ref, double=double)
    if not feasible.all():
        return good, at
    return t, Evaluation(np.array([t]), pose, feasible, ref.signs, group_q, ref.switches)


def _repeat(ref, n):
    """The one-point reference ``ref`` for n points."""
    return Reference(np.repeat(ref.theta, n), {i: np.repeat(v, n) for i, v in ref.signs.items()},
                     {i: np.repeat(q, n, axis=0) for i, q in ref.group_q.items()}, ref.switches)


def cycle(plan: Plan) -> Cycle:
    """The driver's :class:`Cycle` (cached per plan).

    Raises
    ------
    AssemblyError
        When the driver neither returns to the drawn pose nor reaches a limit within
        four turns either way (a gear train's cycle known from its teeth when longer:
        :func:`~chaingraph.kinematics.higher.gear_cycle_turns`).
    """
    return _cycle(plan)


@lru_cache(maxsize=256)
def _cycle(plan):
    t0 = anchor(plan).tau
    high, period = _walk(plan, 1.0)
    if period is not None:
        return Cycle(period, t0, t0 + period)
    low, _ = _walk(plan, -1.0) if high is not None else (None, None)
    if high is None or low is None:
        lead = plan.inputs[plan.lead]
        how = (f"turns {_turns_searched(plan)} times" if lead.kind == "R" else
               f"slides {_MAX_TURNS * 2 * math.pi:.4g} times the mechanism's size")
        raise UnboundedRangeError(
            f"{plan.describe()} {how} without returning to the drawn pose or reaching a "
            "limit (give its sweep's ends)", mechanism=plan.chain.source or plan.chain.name)
    # the poses at the limits as found there (at a fold the last digits depend on the
    # path, so the sweep takes them from here)
    return Cycle(None, low[0], high[0], (low[1], high[1]))


def feasible_range(plan: Plan) -> tuple[float, float] | None:
    """The input values that can be assembled from the drawn pose, or None for a crank.

    Returns
    -------
    (low, high) of the lead input (degrees for an R input, slide for a P input) around
    its drawn value, or None when it makes full turns. A range may be wider than a turn.
    """
    c = cycle(plan)
    if c.full_turn:
        return None
    low, high = sorted(float(plan.value(t)) for t in (c.low, c.high))
    return (low, high)


def _outside(plan, lo, hi):
    """The error for a sweep from ``lo`` to ``hi`` (values of the lead input) that leaves
    the range that can be assembled."""
    rng = feasible_range(plan)
    # only a rocker's sweep can leave its range: a crank assembles at every angle
    assert rng is not None, "a sweep leaves the assembled range only of a rocker"
    unit = plan.lead_unit
    verb = "turn" if plan.inputs[plan.lead].kind == "R" else "slide"
    return AssemblyError(
        f"the sweep {lo:g} to {hi:g} {unit} leaves the range that can be assembled: "
        f"{plan.describe()} can {verb} only from {rng[0]:.6f} to {rng[1]:.6f} {unit}",
        mechanism=plan.chain.source or plan.chain.name, feasible_range=rng)


def _along(plan, end, targets, *, home=None):
    """Poses at ``targets`` (all between the anchor's tau and ``end``), reached by
    continuation from the anchor on the internal grid to ``end`` with the targets
    inserted, so that they do not depend on which other targets were asked for.
    ``home``: a mask of the targets that are ``end`` a whole period on from the
    anchor, whose poses are the anchor's (the path's first) exactly."""
    start = anchor(plan)
    t0 = start.tau
    span = end - t0
    n = max(1, int(math.ceil(abs(span) / _GRID_DEG)))
    sign = 1.0 if span >= 0 else -1.0
    grid = sign * (t0 + span * np.arange(n + 1) / n)
    if home is not None and home.any():
        if grid[-1] != sign * end:
            # the period's end off the grid: the anchor's own value instead
            return _along(plan, end, np.where(home, t0, targets))
        targets = np.where(home, end, targets)
    path, idx = merged_path(grid, sign * targets)
    ev = evaluate(plan, sign * path, start=start.state)    # in path order
    if home is not None and home.any():
        # the grid's first point is the anchor (every target is past it)
        if idx is None:                 # the path is the targets: ev is this call's own
            return ev.repeat_first(np.flatnonzero(home))
        idx = np.where(home, 0, idx)
    return ev if idx is None else ev.take(idx)


def merged_path(grid: ArrayLike, targets: ArrayLike) -> tuple[np.ndarray, np.ndarray | None]:
    """The sorted union of ``grid`` (increasing) and ``targets``, and where each target
    is in it (None when the union is the targets themselves, in their order).

    The same as ``np.unique`` of both and ``np.searchsorted`` of the targets in it, in
    far fewer operations when the targets are already in order (a sweep's are) and
    hold most of the grid: the grid's points are merged in, not sorted with them.

    >>> path, idx = merged_path(np.array([0.0, 1.0, 2.0]), np.array([2.0, 0.5, 0.5, 1.0]))
    >>> path.tolist(), idx.tolist()
    ([0.0, 0.5, 1.0, 2.0], [3, 1, 1, 2])
    """
    grid = np.asarray(grid, dtype=float)
    targets = np.asarray(targets, dtype=float)
    if targets.size == 0 or not (np.isfinite(targets).all() and np.all(grid[1:] > grid[:-1])):
        path = np.unique(np.concatenate([grid, targets]))
        return path, np.searchsorted(path, targets)
    order = None
    if not np.all(targets[1:] >= targets[:-1]):
        order = np.argsort(targets, kind="stable")
    ordered = targets if order is None else targets[order]
    first = np.empty(ordered.size, dtype=bool)                # each value's first
    first[:1] = True
    np.not_equal(ordered[1:], ordered[:-1], out=first[1:])
    distinct = ordered if first.all() else ordered[first]
    at = np.searchsorted(distinct, grid)
    found = distinct[np.minimum(at, distinct.size - 1)] == grid
    if found.all():
        path, where = distinct, None
    else:
        # the grid's points not among the targets, each before the targets' point it
        # was found before (after the grid's points inserted before it)
        extra = at[~found] + np.arange(np.count_nonzero(~found))
        kept = np.ones(distinct.size + extra.size, dtype=bool)
        kept[extra] = False
        path = np.empty(kept.size)
        path[kept] = distinct
        path[extra] = grid[~found]
        where = np.flatnonzero(kept)
    if order is None and where is None and distinct is ordered:
        return path, None
    if where is None:
        where = np.arange(distinct.size)
    if distinct is not ordered:
        where = where[np.cumsum(first) - 1]
    if order is None:
        return path, where
    idx = np.empty(targets.size, dtype=np.intp)
    idx[order] = where
    return path, idx


def evaluate_near(plan: Plan, theta: ArrayLike) -> Evaluation:
    """Poses at ``theta`` continued from the anchor on each side, without working out
    the cycle first (for an explicit sweep without summary); the cycle is worked out
    only to say the range when the sweep leaves it."""
    theta = np.asarray(theta, dtype=float)
    t0 = anchor(plan).tau
    if np.max(np.abs(theta - t0)) > 720.0:
        # far from the drawn pose: work out the cycle, so that a crank's angles are
        # taken within one turn instead of walking the whole span on the grid
        return evaluate_sweep(plan, theta)
    parts = []
    for side, farthest in ((theta > t0, np.max), (theta <= t0, np.min)):
        if side.any():
            parts.append((np.nonzero(side)[0],
                          _along(plan, float(farthest(theta[side])), theta[side])))
    ev = parts[0][1] if len(parts) == 1 else _merge(parts, theta.size)
    if not ev.feasible.all():
        return evaluate_sweep(plan, theta)      # says the range
    ev.theta = theta
    return ev


def evaluate_sweep(plan: Plan, theta: ArrayLike) -> Evaluation:
    """Poses at the path parameters ``theta`` (a driver's angles, degrees): a crank's
    from its angle within one period of the anchor, a rocker's from the anchor
    outward, both continued on the same internal grid whatever the sweep."""
    theta = np.asarray(theta, dtype=float)
    c = cycle(plan)
    t0 = anchor(plan).tau
    if c.period is not None:                   # a full turn
        turned = theta - t0
        if turned.size and turned.min() >= 0.0 and turned.max() <= c.period:
            # within one period from the anchor (a sweep from it): np.mod's result
            # without its cost; a whole period on is the anchor's pose again
            ev = _along(plan, t0 + c.period, t0 + turned, home=turned >= c.period)
        else:
            ev = _along(plan, t0 + c.period, t0 + np.mod(turned, c.period))
        ev.theta = theta
        return ev
    lo, hi = float(theta.min()), float(theta.max())
    if lo < c.low - 1e-9 or hi > c.high + 1e-9:
        raise _outside(plan, float(plan.value(lo)), float(plan.value(hi)))
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
        raise _outside(plan, float(plan.value(lo)), float(plan.value(hi)))
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

