"""The path optimiser, generic over a mechanism family (:mod:`chaingraph.synthesis.family`).

Everything runs in the task's own frame (:class:`TaskFrame`: the targets' centroid at
the origin, the first target to the second along +x, the task's size 1), so that a task
moved, turned or scaled finds the same mechanisms moved, turned and scaled, from the same
random numbers.

* :func:`ordered_distance`: the distance from each target to a traced path (a polyline of
  samples over one turn of the input), the targets met *in order* along it: a dynamic
  programme over the samples (target i's segment at or after target i-1's, starting
  from the first target's nearest segment, either way round), vectorised over many
  mechanisms; :func:`objective` adds penalties (an input that does not turn fully, a
  transmission angle out of bounds, a link ratio over :data:`MAX_RATIO`).
* :func:`coarse_search`: many random mechanisms of the family (:meth:`Family.sample`),
  each turned, scaled to the task and moved so that its path runs near the targets,
  scored by :func:`objective`; the best kept.
* :func:`global_search`: scipy's differential evolution on :func:`objective`, its first
  population the coarse search's best (vectorised, repeatable from the generator).
* :func:`least_squares_fit`: scipy's least_squares (dogbox, a finite-difference
  Jacobian, its columns in one vectorised call) on the precision equations ``position(params, theta_i) - target_i`` with the
  input at each target unknown (or fixed by a timing): solved to rounding where the
  equations can be met (up to five points), the least squares of the distances otherwise.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal, overload

import numpy as np
import numpy.typing as npt
from scipy.optimize import (  # type: ignore[import-untyped]
    differential_evolution,
    least_squares,
    minimize_scalar,
)

from chaingraph.synthesis.family import Family

__all__ = ["TaskFrame", "MAX_RATIO", "curve", "sample_steps", "ordered_distance", "objective",
           "coarse_search", "global_search", "fit_start", "least_squares_fit", "Fit",
           "predicted_defect", "BETWEEN", "timed_guides"]

#: the longest link over the shortest, at most
MAX_RATIO = 20.0
_BIG = 1e3            # the objective of a mechanism that cannot be assembled over a turn


@dataclass(frozen=True)
class TaskFrame:
    """The similarity taking world points to the task's frame: subtract ``origin``, turn
    by ``-angle`` (radians), divide by ``scale``."""

    origin: tuple[float, float]
    angle: float
    scale: float

    @classmethod
    def of(cls, points: npt.ArrayLike) -> "TaskFrame":
        """The targets' frame: centroid, first-to-second direction, largest distance."""
        p = np.asarray(points, dtype=float)
        c = p.mean(axis=0)
        d = p[1] - p[0]
        size = float(np.max(np.hypot(*(p[:, None, :] - p[None, :, :]).transpose(2, 0, 1))))
        return cls((float(c[0]), float(c[1])), math.atan2(d[1], d[0]), size)

    def to_task(self, points: npt.ArrayLike) -> np.ndarray:
        p = np.asarray(points, dtype=float).reshape(-1, 2) - self.origin
        c, s = math.cos(self.angle), math.sin(self.angle)
        return np.stack([c * p[:, 0] + s * p[:, 1], -s * p[:, 0] + c * p[:, 1]],
                        axis=1) / self.scale

    def to_world(self, params: npt.ArrayLike) -> np.ndarray:
        """Parameters (x, y pairs) of the task's frame in the world."""
        p = np.asarray(params, dtype=float)
        pts = p.reshape(-1, 2) * self.scale
        c, s = math.cos(self.angle), math.sin(self.angle)
        out = np.stack([c * pts[:, 0] - s * pts[:, 1] + self.origin[0],
                        s * pts[:, 0] + c * pts[:, 1] + self.origin[1]], axis=1)
        return out.reshape(p.shape)

    def input_to_world(self, theta: npt.ArrayLike) -> np.ndarray:
        """An input angle (radians) of the task's frame in the world."""
        return np.asarray(theta) + self.angle


def curve(family: Family, params: npt.ArrayLike,
          steps: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The tracing point's path over one turn of the input from the drawn pose (a
    sliding input's: over the slides that assemble, :meth:`Family.sweep`):
    ``theta`` (M, steps), ``x``, ``y`` (NaN where unassembled)."""
    params = np.atleast_2d(params)
    theta = family.sweep(params, steps)
    x, y = family.positions(params, theta)
    return theta, x, y


def sample_steps(family: Family, theta: np.ndarray, turns: npt.ArrayLike) -> np.ndarray:
    """Input steps ``turns`` (radians; a sliding input's: slides) as steps of the
    samples ``theta`` (M, K) of :func:`curve`: (N,) for a turn, (M, N) for a slide."""
    turns = np.asarray(turns, dtype=float)
    k = theta.shape[1]
    if not family.sliding:
        return (turns / (2 * math.pi) * k) % k
    with np.errstate(all="ignore"):
        return turns[None, :] / (theta[:, 1:2] - theta[:, :1])


def _segment_distances(x, y, targets, open_path=False):
    """(M, N, K) squared distances from each target to each segment k (sample k to k+1,
    the last closing the turn; on an ``open_path``, none: infinity), and where along it
    the nearest point is (0..1)."""
    ax, ay = x[:, None, :], y[:, None, :]
    bx, by = np.roll(x, -1, axis=1)[:, None, :], np.roll(y, -1, axis=1)[:, None, :]
    tx, ty = targets[None, :, 0, None], targets[None, :, 1, None]
    vx, vy = bx - ax, by - ay
    length2 = vx * vx + vy * vy
    with np.errstate(all="ignore"):
        u = np.clip(((tx - ax) * vx + (ty - ay) * vy) / length2, 0.0, 1.0)
    u = np.where(length2 > 0, u, 0.0)
    dx, dy = ax + u * vx - tx, ay + u * vy - ty
    d2 = dx * dx + dy * dy
    if open_path:
        d2[..., -1] = np.inf
    return d2, u


@overload
def ordered_distance(x: np.ndarray, y: np.ndarray, targets: np.ndarray, *,
                     assign: Literal[False] = False,
                     timed: npt.ArrayLike | None = None,
                     open_path: bool = False) -> np.ndarray: ...


@overload
def ordered_distance(x: np.ndarray, y: np.ndarray, targets: np.ndarray, *,
                     assign: Literal[True], timed: npt.ArrayLike | None = None,
                     open_path: bool = False,
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]: ...


def ordered_distance(x: np.ndarray, y: np.ndarray, targets: np.ndarray, *,
                     assign: bool = False, timed: npt.ArrayLike | None = None,
                     open_path: bool = False,
                     ) -> np.ndarray | tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The in-order distance from the targets to each traced path (module docstring).

    Parameters
    ----------
    x, y : (M, K) arrays
        Samples over one turn of the input (NaN: unassembled; such a path scores
        infinity).
    targets : (N, 2) array
    assign : bool
        Also return, per mechanism and target, the sample step (a float: segment plus
        the place along it) where the target is met.
    timed : (N,) or (M, N) array, optional
        Targets met at these sample steps after the first target's nearest (a timing):
        the distances there, no search.
    open_path : bool
        The samples are a path from end to end (a sliding input's), not a closed turn:
        no segment joins the last sample to the first, and the targets are met along it
        without wrapping round.

    Returns
    -------
    cost : (M,) the mean squared distance; (cost, steps (M, N)) with ``assign``; and
    the direction (+1, -1) the path is run.
    """
    m, k = x.shape
    n = len(targets)
    d2, u = _segment_distances(x, y, targets, open_path)
    d2 = np.where(np.isfinite(d2), d2, np.inf)
    first = np.argmin(d2[:, 0, :], axis=1)
    if timed is not None:     # target i at the first's sample plus its turn
        step = first[:, None] + np.atleast_2d(np.asarray(timed, dtype=float))
        outside = ~np.isfinite(step) | (step < 0) | (step > k - 1) if open_path else False
        step = np.where(np.isfinite(step), step, 0.0) % k
        at = np.floor(step).astype(int) % k
        near = np.take_along_axis(d2, at[:, :, None], 2)[..., 0]
        total = np.where(outside, np.inf, near).mean(axis=1)
        return (total, step, np.ones(m)) if assign else total
    best_cost, best_steps, best_way = np.full(m, np.inf), np.zeros((m, n)), np.ones(m)
    for way in (1, -1):
        ahead = first[:, None] + way * np.arange(k)[None, :]
        order = ahead % k      # (M, K)
        dd = np.take_along_axis(d2, np.broadcast_to(order[:, None, :], (m, n, k)), 2)
        if open_path:          # no wrapping round an open path's ends
            dd = np.where(((ahead < 0) | (ahead > k - 1))[:, None, :], np.inf, dd)
        cost = np.full((m, k), np.inf)
        cost[:, 0] = dd[:, 0, 0]
        args = []
        for i in range(1, n):
            run = np.minimum.accumulate(cost, axis=1)
            if assign:
                args.append(_running_argmin(cost))
            cost = dd[:, i, :] + run
        end = np.argmin(cost, axis=1)
        total = cost[np.arange(m), end] / n
        if assign:
            steps = np.empty((m, n))
            at = end.copy()
            for i in range(n - 1, -1, -1):
                seg = order[np.arange(m), at]
                along = u[np.arange(m), i, seg]
                steps[:, i] = seg + along
                if i > 0:
                    at = args[i - 1][np.arange(m), at]
        take = total < best_cost
        best_way = np.where(take, way, best_way)
        if assign:
            best_steps = np.where(take[:, None], steps, best_steps)
        best_cost = np.where(take, total, best_cost)
    return (best_cost, best_steps, best_way) if assign else best_cost


def _running_argmin(cost):
    """Where the running minimum along axis 1 is attained."""
    m, k = cost.shape
    idx = np.broadcast_to(np.arange(k), (m, k)).copy()
    run = cost.copy()
    for j in range(1, k):       # k is small (the samples); a plain scan, vectorised over M
        keep = run[:, j - 1] <= run[:, j]
        run[:, j] = np.where(keep, run[:, j - 1], run[:, j])
        idx[:, j] = np.where(keep, idx[:, j - 1], j)
    return idx


def objective(family: Family, params: npt.ArrayLike, targets: np.ndarray, *, steps: int,
              min_transmission: float, timing: npt.ArrayLike | None = None,
              turns: npt.ArrayLike | None = None) -> np.ndarray:
    """The in-order rms distance from the targets to each mechanism's path (task units),
    plus penalties: an input that cannot turn fully (:data:`_BIG` and the share of the
    turn unassembled), a transmission angle out of ``[min, 180 - min]`` over the turn
    (a sliding input's: between the first target and the last; its excess in degrees
    over 90), a link ratio over :data:`MAX_RATIO`. ``timing``: the input's turn
    (radians; a sliding input's slide) from the first target to each. ``turns``
    (poses): the carrier's turn (radians) from the first target to each, its rms miss
    (where the path comes nearest each target) added."""
    params = np.atleast_2d(params)
    theta, x, y = curve(family, params, steps)
    unassembled = np.mean(~np.isfinite(x), axis=1)
    timed = None if timing is None else sample_steps(family, theta, timing)
    with np.errstate(all="ignore"):
        mu = family.transmission(params, theta)
        if family.sliding:      # its ends are limits: bounds between the targets only
            cost, at, _ = ordered_distance(np.nan_to_num(x), np.nan_to_num(y), targets,
                                           timed=timed, open_path=True, assign=True)
            cost = np.sqrt(cost)
            k = np.arange(theta.shape[1])[None, :]
            lo, hi = np.floor(at.min(axis=1))[:, None], np.ceil(at.max(axis=1))[:, None]
            mu = np.where((k >= lo) & (k <= hi), mu, 90.0)
        else:
            cost = np.sqrt(ordered_distance(np.nan_to_num(x), np.nan_to_num(y), targets,
                                            timed=timed))
        excess = np.nanmax(np.maximum(min_transmission - mu, mu - (180.0 - min_transmission)),
                           axis=1)
        if turns is not None:
            cost = cost + _turn_miss(family, params, theta, x, y, targets, turns)
    ratio = family.link_ratio(params)
    out = cost + np.maximum(excess, 0.0) / 90.0 + np.maximum(ratio / MAX_RATIO - 1.0, 0.0)
    out = np.where(unassembled > 0, _BIG * (1 + unassembled), out)
    return np.where(np.isfinite(out), out, 2 * _BIG)


def _turn_miss(family, params, theta, x, y, targets, turns):
    """The rms of the carrier's turn, where its path comes nearest each target, from
    its turn at the first target, less ``turns`` (radians)."""
    d2 = (x[:, None, :] - targets[None, :, 0, None]) ** 2 + \
        (y[:, None, :] - targets[None, :, 1, None]) ** 2
    near = np.argmin(np.where(np.isfinite(d2), d2, np.inf), axis=2)       # (M, N)
    turned = np.take_along_axis(family.rotation(params, theta), near, axis=1)
    miss = _wrapped(turned - turned[:, :1] - np.asarray(turns)[None, :])
    return np.sqrt(np.mean(miss * miss, axis=1))


def _wrapped(angle: np.ndarray | float) -> np.ndarray:
    """Angles (radians) wrapped to [-pi, pi)."""
    return (np.asarray(angle) + math.pi) % (2 * math.pi) - math.pi


def coarse_search(family: Family, targets: np.ndarray, rng: np.random.Generator, *,
                  count: int, keep: int, steps: int, min_transmission: float,
                  timing: npt.ArrayLike | None = None,
                  turns: npt.ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
    """``count`` random mechanisms of the family placed on the task (turned at random,
    scaled to 0.7 to 1.5 times its size, moved so that their path's centre is near the
    targets'), the ``keep`` best by :func:`objective`: (params (keep, size), scores)."""
    batches, scores = [], []
    for start in range(0, count, 2000):
        n = min(2000, count - start)
        p = family.sample(rng, n)
        turn = rng.uniform(0.0, 2 * math.pi, n)
        scale = rng.uniform(0.7, 1.5, n)
        shift = rng.normal(0.0, 0.15, (n, 2))
        c, s = np.cos(turn)[:, None], np.sin(turn)[:, None]
        pts = p.reshape(n, -1, 2)
        moved = np.stack([c * pts[..., 0] - s * pts[..., 1],
                          s * pts[..., 0] + c * pts[..., 1]], axis=2)
        moved = moved * scale[:, None, None] + shift[:, None, :]
        p = moved.reshape(n, -1)
        batches.append(p)
        scores.append(objective(family, p, targets, steps=steps,
                                min_transmission=min_transmission, timing=timing,
                                turns=turns))
    params, score = np.concatenate(batches), np.concatenate(scores)
    best = np.argsort(score, kind="stable")[:keep]
    return params[best], score[best]


def global_search(family: Family, targets: np.ndarray, seeds: npt.ArrayLike,
                  rng: np.random.Generator, *, steps: int, min_transmission: float,
                  timing: npt.ArrayLike | None = None,
                  generations: int = 100) -> tuple[np.ndarray, float]:
    """Differential evolution on :func:`objective` from the population ``seeds`` (rows of
    parameters; at least five), within a box about them; the best parameters found."""
    seeds = np.asarray(seeds, dtype=float)
    lo, hi = seeds.min(axis=0), seeds.max(axis=0)
    pad = 0.25 * np.maximum(hi - lo, 0.1)
    bounds = list(zip(lo - pad, hi + pad))

    def f(x):
        return objective(family, np.atleast_2d(x.T), targets, steps=steps,
                         min_transmission=min_transmission, timing=timing)
    found = differential_evolution(f, bounds, init=seeds, rng=rng, maxiter=generations,
                                   polish=False, vectorized=True, updating="deferred",
                                   tol=1e-8)
    return np.asarray(found.x), float(found.fun)


@dataclass(frozen=True, eq=False)
class Fit:
    """A least-squares fit: ``params``, the input at each target (radians, ``inputs``),
    the largest distance from a target to its point (task units, ``residual``)."""

    params: np.ndarray
    inputs: np.ndarray
    residual: float


def least_squares_fit(family: Family, targets: npt.ArrayLike, params: np.ndarray,
                      inputs: npt.ArrayLike, *, timing: npt.ArrayLike | None = None,
                      exact: bool, min_transmission: float | None = None,
                      closed: bool = False,
                      turns: npt.ArrayLike | None = None,
                      evaluations: int | None = None, bounded: bool = False) -> Fit | None:
    """Solve ``position(params, theta_i) = target_i`` by least squares from ``params``
    and ``inputs`` (radians at each target, running one way; the first is the drawn
    pose's); to rounding when ``exact`` (else the least squares of the distances). The
    inputs' steps from target to target are unknowns kept positive the way they run
    (their logarithms are solved for, so the targets stay in order), or with ``timing``
    the given turns from the first. A fit that is not exact also keeps (softly, by
    further residuals) its link ratio within :data:`MAX_RATIO` and, with
    ``min_transmission``, its transmission angle within bounds from the first target to
    the last (over the whole turn when ``closed``). None when the fit leaves the family
    (a mechanism that cannot be assembled at a target). ``turns`` (poses): the carrier
    also turns by these (radians) from the first target to each (the residual in
    radians, as a distance of the task's unit size). ``evaluations``: the most
    evaluations of the residuals least squares makes (by default 50 when ``exact``, else
    100). ``bounded``: an exact fit keeps the link ratio and the transmission angle
    within bounds too, by the same further residuals (for a family with more unknowns
    than equations, whose solutions are a set: they are then sought on it where the
    bounds hold)."""
    targets = np.asarray(targets, dtype=float)
    size = family.size
    free_inputs = timing is None
    inputs = np.asarray(inputs, dtype=float)
    way = 1.0 if len(inputs) < 2 or inputs[-1] >= inputs[0] else -1.0

    def residuals(z):
        """Rows of unknowns (R, n) to rows of residuals (R, 2N), and the inputs."""
        p = z[:, :size]
        first = family.first_input(p)[:, None]
        if free_inputs:
            ahead = way * np.cumsum(np.exp(np.clip(z[:, size:], -30.0, 3.0)), axis=1)
        else:
            ahead = np.asarray(timing)[None, 1:]
        th = np.concatenate([first, first + ahead], axis=1)
        x, y = family.positions(p, th)
        r = np.stack([x - targets[:, 0], y - targets[:, 1]], axis=2).reshape(len(z), -1)
        if turns is not None:
            r = np.concatenate([r, _wrapped(family.rotation(p, th[:, 1:])
                                           - np.asarray(turns)[None, 1:])], axis=1)
        if not exact:
            r = np.concatenate([r, _penalties(family, p, th, min_transmission, closed),
                                _between(family, p, th, targets, closed)], axis=1)
        elif bounded:
            r = np.concatenate([r, _penalties(family, p, th, min_transmission, closed)],
                               axis=1)
        return np.where(np.isfinite(r), r, 10.0), th

    def jacobian(z):            # central differences, every column in one call
        h = 1e-6 * np.maximum(1.0, np.abs(z))
        steps = np.diag(h)
        r, _ = residuals(np.concatenate([z + steps, z - steps]))
        return ((r[:len(z)] - r[len(z):]) / (2 * h)[:, None]).T
    if free_inputs:
        gaps = np.maximum(np.abs(np.diff(inputs)), 1e-3)
        z0 = np.concatenate([params, np.log(gaps)])
    else:
        z0 = np.asarray(params, dtype=float)
    tol = 1e-15 if exact else 1e-9
    found = least_squares(lambda z: residuals(z[None, :])[0][0], z0, jac=jacobian,
                          method="dogbox", x_scale="jac", xtol=tol, ftol=tol, gtol=tol,
                          max_nfev=evaluations or (50 if exact else 100))
    r, th = residuals(found.x[None, :])
    n = len(targets)
    r = r[:, :2 * n + (0 if turns is None else n - 1)]
    if np.any(np.abs(r) >= 10.0):
        return None
    dist = np.hypot(r[0, 0:2 * n:2], r[0, 1:2 * n:2])
    return Fit(found.x[:size], th[0], float(np.max(np.concatenate([dist, np.abs(r[0, 2 * n:])]))))


#: the weight of the path's distance from the chords between targets, in a fit
BETWEEN = 0.1


def _between(family, params, inputs, targets, closed, samples: int = 3):
    """Residuals (R, gaps * samples): the path's distance, at inputs between each
    target's and the next's, from the chord joining the two targets, times
    :data:`BETWEEN` (so that a fit does not loop away between its targets)."""
    first, last = inputs, np.roll(inputs, -1, axis=1)
    a, b = targets, np.roll(targets, -1, axis=0)
    if closed:
        turn = 2 * math.pi * np.sign(inputs[:, -1] - inputs[:, 0])
        last = last.copy()
        last[:, -1] = inputs[:, 0] + turn
    else:
        first, last, a, b = first[:, :-1], last[:, :-1], a[:-1], b[:-1]
    u = np.linspace(0.0, 1.0, samples + 2)[1:-1]
    theta = first[:, :, None] + (last - first)[:, :, None] * u
    x, y = family.positions(params, theta.reshape(len(params), -1))
    x, y = x.reshape(theta.shape), y.reshape(theta.shape)
    vx, vy = (b - a)[:, 0][None, :, None], (b - a)[:, 1][None, :, None]
    ax, ay = a[:, 0][None, :, None], a[:, 1][None, :, None]
    t = np.clip(((x - ax) * vx + (y - ay) * vy) / (vx * vx + vy * vy), 0.0, 1.0)
    d = np.hypot(ax + t * vx - x, ay + t * vy - y)
    return BETWEEN * d.reshape(len(params), -1)


def _penalties(family, params, inputs, min_transmission, closed, samples: int = 24):
    """Residuals (R, samples + 1) that are 0 within bounds: the link ratio's excess over
    0.95 :data:`MAX_RATIO` (the fit then stays inside the hard bound), and the transmission angle's excess (over 90 degrees) beyond
    ``[min, 180 - min]`` at samples from the first target's input to the last's (a
    whole turn when ``closed``)."""
    ratio = np.maximum(family.link_ratio(params) / (0.95 * MAX_RATIO) - 1.0, 0.0)[:, None]
    if min_transmission is None:
        return ratio
    end = inputs[:, :1] + 2 * math.pi * np.sign(inputs[:, -1:] - inputs[:, :1]) \
        if closed else inputs[:, -1:]
    theta = inputs[:, :1] + (end - inputs[:, :1]) * np.linspace(0.0, 1.0, samples)
    with np.errstate(all="ignore"):
        mu = family.transmission(params, theta)
    excess = np.maximum(np.maximum(min_transmission - mu, mu - 180.0 + min_transmission),
                        0.0) / 90.0
    return np.concatenate([ratio, np.where(np.isfinite(excess), excess, 1.0)], axis=1)


def fit_start(family: Family, params: npt.ArrayLike, targets: np.ndarray, *, steps: int,
              timing: npt.ArrayLike | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Where least squares starts from each mechanism (rows of ``params``): the
    mechanism drawn where its path meets the first target (in order, by
    :func:`ordered_distance`), and the input there and at every other target (radians,
    unwrapped the way the path is run): ``(params (M, size), inputs (M, N))``."""
    params = np.atleast_2d(params)
    theta, x, y = curve(family, params, steps)
    timed = None if timing is None else sample_steps(family, theta, timing)
    with np.errstate(all="ignore"):
        _, at, way = ordered_distance(np.nan_to_num(x), np.nan_to_num(y), targets,
                                      assign=True, timed=timed, open_path=family.sliding)
    if family.sliding:          # a step of the samples, per mechanism; no wrapping round
        turn = (theta[:, 1:2] - theta[:, :1])
        ahead = at - at[:, :1]
    else:
        turn = np.full((len(params), 1), 2 * math.pi / steps)
        ahead = ((at - at[:, :1]) * way[:, None]) % steps * way[:, None]
    if timing is not None:
        ahead = np.broadcast_to(np.asarray(timing), at.shape) / turn
    first = theta[:, 0] + at[:, 0] * turn[:, 0]
    return family.posed(params, first), first[:, None] + ahead * turn


def predicted_defect(family: Family, fit: Fit, *, steps: int = 720) -> str | None:
    """What the family's own kinematics says is wrong with a fit before it is written
    and certified: ``"order defect"`` when its inputs at the targets do not run one way
    within a turn, ``"branch defect"`` when the drawn assembly is lost between the first
    target and the last; None when it looks right."""
    d = np.asarray(fit.inputs) - fit.inputs[0]
    if family.sliding:          # a slide does not come round: one way, no wrapping
        steps_between = np.diff(d)
        if not (np.all(steps_between > 0) or np.all(steps_between < 0)):
            return "order defect"
        theta = np.linspace(fit.inputs[0], fit.inputs[-1], steps)
        x, _ = family.positions(fit.params[None, :], theta[None, :])
        return None if np.all(np.isfinite(x)) else "branch defect"
    for way in (1.0, -1.0):
        ahead = (way * d) % (2 * math.pi)
        ahead[0] = 0.0
        if np.all(np.diff(ahead) > 0):
            theta = fit.inputs[0] + way * np.linspace(0.0, ahead[-1], steps)
            x, _ = family.positions(fit.params[None, :], theta[None, :])
            return None if np.all(np.isfinite(x)) else "branch defect"
    return "order defect"


def timed_guides(targets: np.ndarray, slides: npt.ArrayLike, *, count: int = 4,
                 samples: int = 720) -> np.ndarray:
    """Directions (radians) a guide may have for a point carried by a link pinned to a
    block that slides by ``slides`` (from the first target) to reach ``targets``: seen
    from the block, the point moves on a circle about the pin, so the targets less
    the block's slides along the guide are concyclic. The ``count`` directions where
    they come nearest to a circle (the least squares circle's largest miss: local
    minima over ``samples`` directions, each refined, best first), rows (direction,
    the circle's centre x, y: the pin at the first target, its radius). Five timed targets
    give two conditions on the one direction: a slider crank driven by its slider is
    then over-determined by one (its solutions exist only for a consistent task,
    isolated), which random seeds rarely find."""
    pts = np.asarray(targets, dtype=float)
    s = np.asarray(slides, dtype=float)

    def miss(phi):
        phi = np.atleast_1d(phi)
        u = np.stack([np.cos(phi), np.sin(phi)], axis=1)
        q = pts[None, :, :] - s[None, :, None] * u[:, None, :]
        # the least squares circle x^2 + y^2 = 2 cx x + 2 cy y + k of each one's points
        a = np.concatenate([2 * q, np.ones(q.shape[:2] + (1,))], axis=2)
        b = np.sum(q * q, axis=2)
        c = np.array([np.linalg.lstsq(a[k], b[k], rcond=None)[0] for k in range(len(q))])
        r = np.sqrt(np.maximum(c[:, 2] + c[:, 0] ** 2 + c[:, 1] ** 2, 0.0))
        return (np.abs(np.hypot(q[..., 0] - c[:, None, 0], q[..., 1] - c[:, None, 1])
                       - r[:, None]).max(axis=1), c[:, :2], r)
    phi = np.linspace(0.0, 2 * math.pi, samples, endpoint=False)
    dist = miss(phi)[0]
    local = np.flatnonzero((dist <= np.roll(dist, 1)) & (dist <= np.roll(dist, -1)))
    step = 2 * math.pi / samples
    refined = [minimize_scalar(lambda v: float(miss(v)[0][0]), bounds=(phi[k] - step, phi[k] + step),
                               method="bounded", options={"xatol": 1e-10}) for k in local]
    order = np.argsort([r.fun for r in refined], kind="stable")[:count]
    best = np.array([refined[k].x for k in order])
    _, centre, radius = miss(best)
    return np.column_stack([best, centre, radius])
