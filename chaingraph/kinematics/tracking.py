"""Positions along a path of input values: the plan's steps one after another, each
dyad kept in its assembly mode, each group continued by Newton's method.

A dyad's two modes meet only where its discriminant reaches zero: every sampled local
minimum of the discriminant is refined, so that a narrow window where the dyad cannot be
assembled is found (the path stops there) and, where the modes touch (a parallelogram's
change point), the motion continues into the label that continues it smoothly. Poses at
an input value therefore do not depend on how finely the path is sampled.
"""

from __future__ import annotations

import math
from collections.abc import Container, Mapping

import numpy as np
from numpy.typing import ArrayLike

from chaingraph.geometry import DISC_TOL, FIXED, PoseEntry, Scalar
from chaingraph.kinematics.closed_form import dyad_roots, initial_sign, single_link
from chaingraph.kinematics.equations import group_form
from chaingraph.kinematics.groups import newton, newton_path
from chaingraph.kinematics.plan import Plan

__all__ = ["Evaluation", "Reference", "Start", "evaluate", "evaluate_at", "failing_step"]


# -- the sweep -----------------------------------------------------------------------
def _known_poses(plan, theta):
    """The fixed link, and each input's value (its delta, in the rotation's place) at
    the path parameters ``theta``: everything else is found from these (the joints
    higher pairs derive from them by :func:`_derive`, before each step)."""
    pose: dict[str, PoseEntry] = {plan.fixed: FIXED}
    for item, delta in zip(plan.inputs, plan.deltas(theta)):
        pose[item.key] = (0.0, 0.0, np.broadcast_to(delta, theta.shape), 1.0, 0.0)
    return pose


def _derive(plan, pose, theta, group_q, near):
    """Put in ``pose`` each higher pair's derived joint whose driving motion it now
    holds (a pair driven through the linkage: once the links it is read from are
    placed). Such a driving motion, the rotation of one link less another's, is known
    from the poses only to whole turns: it is followed and kept in ``group_q`` (key
    -1 - the pair's index, where a path or a reference continues it from). With
    ``near`` None, along the path (theta a path sampled finely enough to unwrap), from
    ``group_q``'s value at its first point if it holds one (a path continued from a
    :class:`Start`), else as found (a path from the drawn pose, where it is 0);
    otherwise point by point, the nearest to ``near(n)`` (a reference's values).
    Returns where every joint derived has a value (a follower drives its cam only over
    the rise or fall the cam is drawn in)."""
    ok = np.ones(theta.shape, dtype=bool)
    for n, d in enumerate(plan.derived):
        if d.key in pose or not d.ready(pose):
            continue
        x = d.driving(pose)
        if d.after is not None:
            x = np.array(np.broadcast_to(x, theta.shape), dtype=float)
            x = _followed(x, group_q.get(-1 - n) if near is None else None,
                          None if near is None else near(n))
            group_q[-1 - n] = x
        value = np.broadcast_to(d.value(x), theta.shape)
        if d.inverse:
            ok &= np.isfinite(value)
        pose[d.key] = (0.0, 0.0, value, 1.0, 0.0)
    return ok


def _followed(x, first, near):
    """Angles ``x`` (known to whole turns) made continuous: along a path from ``first``
    (its first point's value, else as found), or point by point nearest ``near``."""
    if near is not None:
        near = np.broadcast_to(np.asarray(near, dtype=float), x.shape)
        return near + np.remainder(x - near + math.pi, 2 * math.pi) - math.pi
    if not x.size:
        return x
    x = np.unwrap(x)
    if first is not None:
        x += 2 * math.pi * np.round((float(first) - x[0]) / (2 * math.pi))
    return x


class Reference:
    """Where pointwise evaluations continue from: per point, an input angle, each
    dyad's mode sign there, each group's coordinates there, and the angles where each
    dyad's modes change label (``switches``: its two modes meet there and the motion
    continues smoothly into the other label)."""

    def __init__(self, theta: ArrayLike, signs: Mapping[int, Scalar],
                 group_q: Mapping[int, np.ndarray],
                 switches: Mapping[int, list[float]]) -> None:
        self.theta = np.asarray(theta, dtype=float)
        self.signs = signs
        self.group_q = group_q
        self.switches = switches

    def sign(self, i: int, theta: np.ndarray) -> np.ndarray:
        """Step i's mode sign at ``theta``, from the reference's across its switches."""
        s = np.broadcast_to(self.signs[i], self.theta.shape).astype(float)
        for t in self.switches.get(i, ()):
            s = np.where((t - self.theta) * (t - theta) < 0, -s, s)
        return s


def evaluate_at(plan: Plan, theta: ArrayLike, ref: Reference, *, upto: int | None = None,
                double: Container[int] = ()
                ) -> tuple[dict[str, PoseEntry], np.ndarray, dict[int, np.ndarray]]:
    """Poses at the angles ``theta`` (degrees, shape (M,)), each point continued from
    the same point of ``ref`` (a :class:`Reference` of M points, close by) without
    tracking: the modes are the reference's, across its switches; groups are solved by
    Newton's method from the reference's coordinates. Only the first ``upto`` steps of
    the plan when given; the dyads of the steps numbered in ``double`` at their double
    root (a fold, found as their discriminant's root).

    Returns (pose, feasible, group_q).
    """
    pose, feasible, group_q, _ = _evaluate_at(plan, theta, ref, upto, double)
    return pose, feasible, group_q


def failing_step(plan: Plan, theta: ArrayLike, ref: Reference) -> int | None:
    """The index of the first step of the plan that cannot be assembled at any of the
    angles ``theta`` (continued from ``ref`` as by :func:`evaluate_at`), or None."""
    return _evaluate_at(plan, theta, ref, None, ())[3]


def _evaluate_at(plan, theta, ref, upto, double):
    theta = np.asarray(theta, dtype=float)
    first_bad: int | None = None
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        pose = _known_poses(plan, theta)
        feasible = np.ones(theta.size, dtype=bool)
        group_q: dict[int, np.ndarray] = {}
        ok: bool | np.ndarray           # where each step assembles (a single link: all)
        for i, step in enumerate(plan.steps[:upto]):
            feasible &= _derive(plan, pose, theta, group_q, lambda n: ref.group_q[-1 - n])
            if step.kind == "single":
                pose.update(single_link(step, pose))
                ok = True
            elif step.kind == "dyad":
                keys, build, ok, _ = dyad_roots(step, pose, plan.size, double=i in double)
                pose.update(build(1.0 if keys is None else ref.sign(i, theta)))
            else:
                q0 = np.broadcast_to(ref.group_q[i], (theta.size, group_form(step).size))
                q, ok = newton(plan, step, pose, q0)
                group_q[i] = q
                pose.update(group_form(step).complete(group_form(step).set_bodies(pose, q)))
            if first_bad is None and not np.all(ok):
                first_bad = i
            feasible &= ok
    return pose, feasible, group_q, first_bad


class Evaluation:
    """Poses of every link along a path of input angles, with what the next needs."""

    def __init__(self, theta: np.ndarray, pose: dict[str, PoseEntry], feasible: np.ndarray,
                 signs: Mapping[int, np.ndarray], group_q: Mapping[int, np.ndarray],
                 switches: Mapping[int, list[float]],
                 folds: dict[int, tuple[float, np.ndarray]] | None = None) -> None:
        self.theta = theta            # degrees, (N,)
        self.pose = pose              # link -> (x, y, phi) arrays
        self.feasible = feasible      # (N,) bool
        self.signs = signs            # step index -> (N,) branch signs
        self.group_q = group_q        # step index -> (N, 3k) group coordinates
        self.switches = switches      # step index -> angles where the mode label changes
        # step index -> (input degrees, q): a group's fold its trace found on the path
        self.folds = {} if folds is None else folds

    def at(self, k: int) -> Start:
        """The state at point k, to continue a new path from (its first angle)."""
        return Start({i: float(v[k]) for i, v in self.signs.items()},
                      {i: q[k] for i, q in self.group_q.items()})

    def poses_at(self, plan: Plan, theta: ArrayLike, k: int, *,
                 upto: int | None = None) -> dict[str, PoseEntry]:
        """The poses at the angles ``theta``, each continued from this evaluation's
        point ``k`` (the first ``upto`` steps of the plan): :func:`evaluate_at`."""
        return evaluate_at(plan, theta, self.reference(k), upto=upto)[0]

    def reference(self, k: ArrayLike) -> Reference:
        """A :class:`Reference` for pointwise evaluations near the points ``k`` (array)."""
        k = np.asarray(k)
        return Reference(self.theta[k], {i: v[k] for i, v in self.signs.items()},
                         {i: q[k] for i, q in self.group_q.items()}, self.switches)

    def take(self, k: np.ndarray) -> Evaluation:
        """The evaluation at the points ``k`` only (an index array)."""
        n = self.theta.size
        moved = np.flatnonzero(k != np.arange(n)) if k.size == n else None
        if moved is not None and moved.size <= n // 16:
            # nearly every point in place (a crank's last point, its first again):
            # copies patched where they differ, cheaper than indexing every array
            source = k[moved]

            def pick(v):
                if np.ndim(v) == 0:
                    return v
                out = v.copy()
                out[moved] = v[source]
                return out
        else:
            def pick(v):
                return v if np.ndim(v) == 0 else v[k]
        return Evaluation(pick(self.theta), {x: tuple(pick(v) for v in p)
                                             for x, p in self.pose.items()},
                          pick(self.feasible), {i: pick(v) for i, v in self.signs.items()},
                          {i: pick(q) for i, q in self.group_q.items()}, self.switches,
                          self.folds)

    def repeat_first(self, at: np.ndarray) -> Evaluation:
        """This evaluation with its first point's values also at the points ``at``
        (indices), in place: what :meth:`take` of its points, with those points
        pointing at the first, returns, without copying every array (an array that
        cannot be written, a broadcast input, is copied first)."""
        where = int(at[0]) if at.size == 1 else at     # (one point, as a crank's turn has)

        def patched(v):
            if not isinstance(v, np.ndarray) or v.ndim == 0:
                return v
            if not v.flags.writeable:
                v = v.copy()
            v[where] = v[0]
            return v
        self.theta = patched(self.theta)
        self.pose = {x: tuple(patched(v) for v in p) for x, p in self.pose.items()}
        self.feasible = patched(self.feasible)
        self.signs = {i: patched(v) for i, v in self.signs.items()}
        self.group_q = {i: patched(q) for i, q in self.group_q.items()}
        return self


class Start:
    """Where a path continues from: each dyad step's mode sign and each group step's
    coordinates at one point (:meth:`Evaluation.at`), by step index."""

    def __init__(self, signs: dict[int, float], group_q: dict[int, np.ndarray]) -> None:
        self.signs = signs
        self.group_q = group_q


def evaluate(plan: Plan, theta: ArrayLike, *, start: Start | None = None) -> Evaluation:
    """Poses along a path of input angles (degrees), continued from ``start`` (an
    Evaluation's state at the path's first point), else from the drawn pose, which
    must then be the path's first point.

    Each dyad keeps its assembly mode along the path. Its two modes meet only where
    its discriminant reaches zero; every sampled local minimum of the discriminant is
    refined between the neighbouring samples, so that a narrow window where the dyad
    cannot be assembled is found (the path stops there), and where the modes touch
    the motion continues into whichever label continues it smoothly (as a
    parallelogram passes its change points). The poses at an angle therefore do not
    depend on how finely the path is sampled.
    """
    # a degenerate step (two attachment points at one place) gives NaN, which counts as
    # "cannot be assembled", not as a warning
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return _evaluate(plan, np.asarray(theta, dtype=float), start)


_TOUCH_CANDIDATE = 0.05   # sampled discriminant minima below this are refined
_ZOOM_POINTS = 33
_SWITCH_STEP = 1e-4       # degrees either side of a touch, to see which label continues


def _evaluate(plan, theta, start):
    pose = _known_poses(plan, theta)
    feasible = np.ones(theta.size, dtype=bool)
    signs: dict[int, np.ndarray] = {}
    group_q: dict[int, np.ndarray] = {}
    switches: dict[int, list[float]] = {}
    folds: dict[int, tuple[float, np.ndarray]] = {}
    # a path from the drawn pose has it, as drawn, at its own value: the closed forms
    # would give it only to rounding, and at a drawn dead centre to its square root
    at_drawn = None
    if start is None and plan.theta0 is not None:
        at_drawn = np.flatnonzero(theta == plan.theta0)
        if not at_drawn.size:
            at_drawn = None
    turns = {} if start is None else {k: q for k, q in start.group_q.items() if k < 0}
    for i, step in enumerate(plan.steps):
        if at_drawn is not None and i:
            _as_drawn(pose, plan.steps[i - 1].links, at_drawn, theta.shape,
                      group_q.get(i - 1))
        feasible &= _derive(plan, pose, theta, turns, None)
        group_q.update(turns)
        if step.kind == "single":
            pose.update(single_link(step, pose))
            continue
        if step.kind == "dyad":
            keys, build, ok, disc = dyad_roots(step, pose, plan.size)
            if keys is None:
                feasible &= ok
                pose.update(build(1.0))
                continue
            drawn = (1.0, 0.0) if step.pattern == "RPR" else step.constraints[2].point
            sign0 = start.signs[i] if start is not None else initial_sign(keys, drawn)
            ref = Evaluation(theta, pose, feasible, signs, group_q, switches)
            chosen, ok, found, touching, coincident = _track(
                plan, i, step, ref, disc if feasible.all() else np.where(feasible, disc, np.nan),
                sign0, off=keys.off if step.pattern == "RRR" else None)
            feasible &= ok
            signs[i] = chosen
            switches[i] = found
            if touching.any():       # samples at a touch: the double root, not the
                build = dyad_roots(step, pose, plan.size, double=touching)[1]   # sqrt
            pose.update(build(chosen))
            if coincident.size:
                _limits_at(plan, i, step, ref, pose, coincident, chosen, found)
            continue
        q0 = start.group_q[i] if start is not None else np.zeros(group_form(step).size)
        head = Evaluation(theta, pose, feasible, signs, group_q, switches)
        q, ok, fold = newton_path(plan, step, pose, theta, q0, head=head)
        if fold is not None:
            folds[i] = fold
        feasible &= ok
        group_q[i] = q
        pose.update(group_form(step).complete(group_form(step).set_bodies(pose, q)))
    if at_drawn is not None and plan.steps:
        _as_drawn(pose, plan.steps[-1].links, at_drawn, theta.shape,
                  group_q.get(len(plan.steps) - 1))
    if not feasible.all():
        first_bad = int(np.argmin(feasible))
        feasible[first_bad:] = False
    return Evaluation(theta, pose, feasible, signs, group_q, switches, folds)


_LIMIT_STEP = 1e-6        # degrees either side of a sampled turn, to take its limit


def _limits_at(plan, i, step, head, pose, samples, signs, switches):
    """Put dyad step i's links, at the ``samples`` where its two known points coincide
    (:func:`_flips`), in their pose's limit: the mean of the poses just either side,
    each in its own label (the pose there, to the square of ``_LIMIT_STEP``)."""
    theta = head.theta
    direction = 1.0 if theta[-1] >= theta[0] else -1.0
    for k in map(int, samples):
        h = _LIMIT_STEP * direction * max(1.0, abs(float(theta[k])))
        ts = np.array([theta[k] - h, theta[k] + h])
        side = np.full(2, float(signs[k - 1]))    # the labels either side of the switch
        for t in switches:
            if direction * (t - theta[k - 1]) > 0:
                side = np.where(direction * (ts - t) > 0, -side, side)
        ref = head.reference(np.full(2, k - 1))
        near, feasible, _ = evaluate_at(plan, ts, ref, upto=i)
        keys, build, ok, _ = dyad_roots(step, near, plan.size)
        if not (np.all(feasible) and np.all(ok)):
            continue
        for link, entry in build(side).items():
            values = [np.array(v, dtype=float) if np.ndim(v) else v for v in pose[link]]
            mean = [0.5 * (np.ravel(e)[0] + np.ravel(e)[-1]) for e in entry]
            norm = math.hypot(mean[3], mean[4])
            mean[3], mean[4] = mean[3] / norm, mean[4] / norm
            mean[2] = math.atan2(mean[4], mean[3]) + 2 * math.pi * round(
                (float(np.ravel(entry[2])[0]) - math.atan2(mean[4], mean[3])) / (2 * math.pi))
            for v, m in zip(values, mean):
                if np.ndim(v):
                    v[k] = m
            pose[link] = tuple(values)


def _as_drawn(pose, links, drawn, shape, q=None):
    """Put ``links`` in their drawn pose (no motion) at the points ``drawn`` (indices
    into a path of ``shape``), and a group's coordinates ``q`` (its bodies' motions)
    to zero there."""
    for link in links:
        entry = []
        for v, rest in zip(pose[link], (0.0, 0.0, 0.0, 1.0, 0.0)):
            if not (isinstance(v, np.ndarray) and v.shape == shape and v.dtype == float):
                v = np.array(np.broadcast_to(v, shape), dtype=float)
            elif not v.flags.writeable or v.base is not None:
                v = v.copy()                      # an input's, or a view: not this one's
            # (an array of this path's own may be another link's too, a rotation
            # carried across a sliding pair: that link is drawn there as well, its
            # values there the same drawn ones)
            v[drawn] = rest
            entry.append(v)
        pose[link] = tuple(entry)
    if q is not None:
        q[drawn] = 0.0


def _track(plan, i, step, head, disc, sign0, off=None):
    """Mode signs of dyad step i along the path, where it can be assembled, and the
    angles where its label switches.

    ``head`` is the path's evaluation so far (the steps before i); ``disc`` the dyad's
    sampled discriminant (NaN where an earlier step failed); ``off`` an RRR dyad's
    offset from the middle of its two modes' points (None for other dyads). Returns
    (signs, ok, switches, touching, coincident): ``touching`` the samples that lie on a
    touch of the two modes (their discriminant zero to rounding): there the pose is the
    double root, where the computed discriminant's rounding, of either sign, would put
    the joint off by its square root (a parallelogram at its change point, sampled
    there); ``coincident`` the samples (indices) where an RRR dyad's two known points
    coincide (:func:`_flips`), whose pose is its limit either side.
    """
    theta = head.theta
    n = theta.size
    ok = disc >= -DISC_TOL
    direction = 1.0 if n < 2 or theta[-1] >= theta[0] else -1.0
    flips: dict[int, float] = {}
    coincident = np.zeros(0, dtype=np.intp)
    if off is not None and n >= 3:
        flips, coincident = _flips(plan, i, step, head, disc, off, bool(ok.all()))
        ok[coincident] = True
    last = n if ok.all() else int(np.argmin(ok))
    found: list[float] = []
    touching = np.zeros(n, dtype=bool)
    if last >= 2:
        d = disc[:last]
        # the path stops at ``last`` for an earlier step (NaN) or for this dyad: only
        # then is its last sample on the way down to where it cannot be assembled
        ends = last == n or bool(np.isnan(disc[last]))
        events = sorted([(int(k), "touch") for k in _touch_candidates(theta[:last], d, ends)]
                        + [(int(k), "flip") for k in flips if k < last])
        for k, kind in events:
            sign = sign0 * (-1.0) ** len(found)
            if kind == "flip":
                tstar = flips[k]
            else:
                lo, hi = theta[max(k - 1, 0)], theta[min(k + 1, last - 1)]
                tstar, dmin = _zoom_minimum(plan, i, step, head, k, lo, hi)
                if dmin < -DISC_TOL:          # a window where it cannot be assembled
                    last = min(last, int(np.argmax(direction * (theta - tstar) >= 0)))
                    break
                if dmin > DISC_TOL:
                    continue
                touching[k] = abs(d[k]) <= DISC_TOL
                tstar = _touch_vertex(plan, i, step, head, k, tstar)
            if _switches_label(plan, i, step, head, k, tstar, direction, sign):
                if not found or abs(tstar - found[-1]) > 1e-7:
                    found.append(float(tstar))
    signs = np.full(n, float(sign0))
    for t in found:
        signs = np.where(direction * (theta - t) > 0, -signs, signs)
    ok = np.zeros(n, dtype=bool)
    ok[:last] = True
    return signs, ok, found, touching & ok, coincident[coincident < last]


def _flips(plan, i, step, head, disc, off, assembled):
    """Where an RRR dyad's two known points pass over each other (a chain's two joints
    meeting, as a symmetric chain's multiple joints do): there the line through them,
    and with it the side each mode's label names, turns over, and the motion goes on
    smoothly only in the other label (a label switch, as at a touch of the modes).
    Found as a turn of the modes' offset (more than a right angle) between two samples,
    placed by bisection (``assembled``: the dyad assembles at every sample, so that
    none is undefined). Returns ({sample before the turn: its angle}, the samples at
    the turn itself: where the points coincide to rounding, the offset's direction
    undefined or noise)."""
    theta = head.theta
    ox, oy = off
    if np.ndim(ox) == 0 or np.ndim(oy) == 0:            # (an offset along an axis)
        ox, oy = np.broadcast_to(ox, theta.shape), np.broadcast_to(oy, theta.shape)
    turned = ox[:-1] * ox[1:] + oy[:-1] * oy[1:] < 0
    at: dict[int, float] = {}
    coincident: set[int] = set()
    if not assembled:
        finite = np.isfinite(disc)
        undefined = ~finite[1:-1] & finite[:-2] & finite[2:]
        for k in map(int, np.flatnonzero(undefined) + 1):   # a sample exactly on the turn
            if ox[k - 1] * ox[k + 1] + oy[k - 1] * oy[k + 1] < 0:
                at[k - 1] = float(theta[k])
                coincident.add(k)
    if not at and not turned.any():
        return {}, np.zeros(0, dtype=np.intp)
    for k in map(int, np.flatnonzero(turned)):
        if k in coincident or k - 1 in at or k in at:
            continue
        t = _turn_point(plan, i, step, head, k, (float(ox[k]), float(oy[k])))
        near = 1e-9 * max(1.0, abs(t))
        for j in (k, k + 1):
            if j and abs(theta[j] - t) <= near:    # the sample on the turn: noise there
                coincident.add(j)                  # (not the path's first: its start)
        at[k] = t
    return at, np.array(sorted(coincident), dtype=np.intp)


def _turn_point(plan, i, step, head, k, ref_off):
    """Where the RRR dyad's offset turns over between samples k and k + 1 (its side of
    ``ref_off``, the offset at sample k, changes), by bisection to rounding."""
    lo, hi = float(head.theta[k]), float(head.theta[k + 1])
    for _ in range(10):
        ts = np.linspace(lo, hi, _ZOOM_POINTS)
        keys, _ = _head_roots(plan, i, step, head, k, ts)
        ox, oy = keys.off
        same = ~(ox * ref_off[0] + oy * ref_off[1] < 0)
        j = int(np.argmin(same)) if not same.all() else ts.size - 1
        lo, hi = float(ts[max(j - 1, 0)]), float(ts[j])
        if hi == lo or abs(hi - lo) <= 1e-13 * max(1.0, abs(hi)):
            break
    return hi


def _touch_candidates(theta: np.ndarray, d: np.ndarray, whole: bool) -> list[int]:
    """The samples of a dyad's discriminant ``d`` along a path (at ``theta``) where its
    two modes may touch between samples: each local minimum below
    ``_TOUCH_CANDIDATE``, or whose V through it and its neighbours dips below it (the
    V with the slope of the steeper side, through the other neighbour: a touch's
    discriminant falls to zero at least as steeply as that, and on a coarse path its
    samples can all lie well above zero). Only a sample within the largest step of
    ``d`` from ``_TOUCH_CANDIDATE`` can be one (most dyads stay far from a touch: a
    few array operations). ``whole``: ``d`` is the whole path, or stops where an earlier
    step cannot be assembled (else it stops where this dyad cannot be, and its last
    sample, on the way down to that, is no minimum)."""
    if d.size < 2:
        return []
    low = d < _TOUCH_CANDIDATE + np.fmax.reduce(np.abs(np.diff(d)))
    if not low.any():
        return []
    left = np.concatenate(([np.inf], d[:-1]))
    right = np.concatenate((d[1:], [np.inf if whole else -np.inf]))
    out = []
    for k in map(int, np.flatnonzero((d <= left) & (d <= right) & low)):
        if d[k] < _TOUCH_CANDIDATE or (0 < k < d.size - 1 and _v_vertex(
                theta[k - 1:k + 2], d[k - 1:k + 2]) < _TOUCH_CANDIDATE):
            out.append(k)
    return out


def _v_vertex(t: np.ndarray, v: np.ndarray) -> float:
    """The least value of the V through three samples (the middle one least) with the
    slope of its steeper side: where it meets the gentler side's sample."""
    (t0, t1, t2), (a, b, c) = (float(x) for x in t), (float(x) for x in v)
    h_l, h_r, rise_l, rise_r = abs(t1 - t0), abs(t2 - t1), a - b, c - b
    if not (h_l > 0 and h_r > 0):
        return b
    if rise_l * h_r >= rise_r * h_l:         # the left side the steeper
        slope, h, rise = rise_l / h_l, h_r, rise_r
    else:
        slope, h, rise = rise_r / h_r, h_l, rise_l
    if not slope > 0:
        return b
    return b - slope * 0.5 * (h - rise / slope)


def _head_roots(plan, i, step, head, k, ts):
    ref = head.reference(np.full(ts.size, k))
    pose, feasible, _ = evaluate_at(plan, ts, ref, upto=i)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        keys, _, _, disc = dyad_roots(step, pose, plan.size)
    return keys, np.where(feasible, disc, np.nan)


def _zoom_minimum(plan, i, step, head, k, lo, hi):
    """The least discriminant of dyad i between angles lo and hi (sampled ever more
    finely around the least sample), stopping early once it is negative."""
    tstar, dmin = float(head.theta[k]), math.inf
    for _ in range(12):
        ts = np.linspace(lo, hi, _ZOOM_POINTS)
        _, d = _head_roots(plan, i, step, head, k, ts)
        if np.all(np.isnan(d)):
            break
        j = int(np.nanargmin(d))
        tstar, dmin = float(ts[j]), float(d[j])
        if dmin < -DISC_TOL:
            break
        lo, hi = ts[max(j - 1, 0)], ts[min(j + 1, ts.size - 1)]
        if abs(hi - lo) < 1e-9:
            break
    return tstar, dmin


def _touch_vertex(plan, i, step, head, k, tstar, width=1e-3):
    """Where the two modes touch, more precisely than the least sample: near a touch
    the discriminant is a (t - t*)**2, so the vertex of the parabola through it at
    tstar and tstar -+ ``width`` degrees (far enough out to dwarf the rounding)."""
    ts = np.array([tstar - width, tstar, tstar + width])
    _, d = _head_roots(plan, i, step, head, k, ts)
    curve = d[0] - 2 * d[1] + d[2]
    if not (np.all(np.isfinite(d)) and curve > 0):
        return tstar
    shift = 0.5 * width * (d[0] - d[2]) / curve
    return tstar + shift if abs(shift) < width else tstar


def _switches_label(plan, i, step, head, k, tstar, direction, sign):
    """At a touch of the two modes, whether the motion continues in the other label:
    the label whose point is nearer the straight continuation of the last two."""
    h = _SWITCH_STEP * direction
    ts = np.array([tstar - 2 * h, tstar - h, tstar + h])
    keys, disc = _head_roots(plan, i, step, head, k, ts)
    if not np.all(disc[1:] >= -DISC_TOL):
        return False             # a fold: the path cannot pass, nothing to continue
    cur = keys[0] if sign > 0 else keys[1]
    alt = keys[1] if sign > 0 else keys[0]
    pred = cur[1] + 2 * (cur[1] - cur[0])
    return bool(np.linalg.norm(alt[2] - pred) < np.linalg.norm(cur[2] - pred))

