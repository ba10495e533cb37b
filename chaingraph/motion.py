"""Solving a mechanism over an input sweep: the :class:`Motion` and its summary.

:func:`solve` is what ``chaingraph solve`` runs. The plan (structure) is built once per
inversion; the motion (arrays) is the result. The summary describes the mechanism's
whole cycle, whatever rows were asked for: one full turn of a crank, or a rocking
driver's whole feasible range.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from .errors import AssemblyError, MechanismError
from .plan import build_plan
from .solver import Evaluation, check_poses, evaluate, evaluate_at, rates, rotate

__all__ = ["Motion", "Cycle", "solve", "cycle", "feasible_range", "full_turns",
           "summary_rows"]



@lru_cache(maxsize=256)
def _plan(chain, fixed, driver):
    return build_plan(chain, fixed, driver)


@dataclass(frozen=True, eq=False)
class Motion:
    """A solved sweep: numpy arrays looked up by CSV column name, and the summary.

    ``motion["theta"]`` is the input angle (degrees); ``motion["angle:crank"]``,
    ``motion["omega:crank"]``, ``motion["alpha:crank"]`` a link's direction (degrees),
    angular velocity and acceleration; ``motion["x:B"]``, ``"vx:B"``, ``"ax:B"``... a
    joint's or point's position, velocity, acceleration; ``motion["s:S"]``, ``"v:S"``,
    ``"a:S"`` a P joint's slide. Rates are at the constant input speed ``omega``; NaN
    at a dead centre.
    """

    name: str
    fixed: str
    driver: str
    omega: float
    columns: dict
    summary: dict
    units: str | None = None
    plan: object = field(default=None, repr=False)

    def __getitem__(self, name) -> np.ndarray:
        return self.columns[name]

    @property
    def theta(self) -> np.ndarray:
        return self.columns["theta"]

    @property
    def steps(self) -> int:
        return self.theta.size - 1

    def to_csv(self, path=None) -> str | None:
        """Write the CSV (one row per step); returns the text when ``path`` is None."""
        names = list(self.columns)
        data = np.column_stack([self.columns[n] for n in names])
        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        writer.writerow(names)
        for row in data:
            writer.writerow(["nan" if not np.isfinite(v) else repr(float(v)) for v in row])
        if path is None:
            return buf.getvalue()
        with open(path, "w", encoding="utf-8", newline="") as f:
            f.write(buf.getvalue())
        return None

    def to_dict(self) -> dict:
        """The JSON of ``chaingraph solve --json``."""
        return {"name": self.name, "fixed": self.fixed, "driver": self.driver,
                "steps": self.steps, "summary": self.summary}


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


def solve(mechanism, *, fixed=None, driver=None, start=None, stop=None, steps=360,
          omega=None, summary=True) -> Motion:
    """Solve a mechanism's motion over an input sweep.

    Parameters
    ----------
    mechanism : Chain
        A chain with a drawn pose; its ``[mechanism]`` gives the fixed link, driver,
        output and input speed unless overridden here.
    fixed, driver : str, optional
        Choose the inversion and input link.
    start, stop : float, optional
        The sweep of input angles, degrees (the driver's direction from its fixed
        pivot, CCW from +x). By default one full turn from the drawn pose, or a rocking
        driver's whole feasible range.
    steps : int
        Equal intervals of the sweep: ``steps + 1`` rows.
    omega : float, optional
        Constant input speed, rad/s (default: the file's, else 1).
    summary : bool
        Also work out the summary (stroke, time ratio, extremes, dead centres...) over
        the whole cycle; without it ``Motion.summary`` is empty.

    Returns
    -------
    Motion

    Raises
    ------
    MechanismError
        A mechanism that cannot be solved as asked (bad input, exit status 2).
    AssemblyError
        A sweep past the range that can be assembled (exit status 1); the message and
        ``feasible_range`` give the range.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.catalog import catalog_path
    >>> shaper = chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))
    >>> motion = chaingraph.solve(shaper, steps=36)
    >>> round(motion.summary["time_ratio"], 5), len(motion["theta"])
    (1.70995, 37)
    """
    chain = mechanism
    if not isinstance(steps, int) or steps < 1:
        raise MechanismError(f"steps must be a positive whole number, got {steps!r}",
                             mechanism=chain.name)
    m = chain.mechanism
    plan = _plan(chain, fixed or (m.fixed if m else None), driver or (m.driver if m else None))
    if omega is None:
        omega = m.omega if m else 1.0
    output = m.output if m else None
    for value, flag in ((start, "--from"), (stop, "--to")):
        if value is not None and not math.isfinite(value):
            raise MechanismError(f"{flag} must be a finite angle", mechanism=chain.name)
    c = cycle(plan)
    if c.full_turn:
        lo = plan.theta0 if start is None else float(start)
        hi = lo + 360.0 if stop is None else float(stop)
    else:
        lo = c.low if start is None else float(start)
        hi = c.high if stop is None else float(stop)
    theta = np.linspace(lo, hi, steps + 1)    # both ends exact (a rocker's limits)
    ev = _evaluate_sweep(plan, theta)
    check_poses(plan, ev.pose, ev.feasible)
    vel, acc, _ = rates(plan, ev.pose, omega, theta.size, measure=False)
    columns = _columns(plan, theta, ev.pose, vel, acc)
    summary = _summary(plan, output, omega, c) if summary else {}
    return Motion(name=chain.name, fixed=plan.fixed, driver=plan.driver, omega=omega,
                  columns=columns, summary=summary, units=chain.units, plan=plan)


def full_turns(chain, fixed):
    """The links that make full turns relative to ``fixed``, from a solved cycle.

    The driver is the chain's own when its mechanism fixes ``fixed``, else each link
    pinned to ``fixed`` in turn until one turns fully (a rocking driver's range is used
    when none does). Returns (frozenset of links, driver) or None when the inversion
    cannot be solved (no pose, joints other than R and P, mobility other than 1).
    """
    m = chain.mechanism
    if m is not None and m.fixed == fixed and m.driver:
        drivers = [m.driver]
    else:
        drivers = [x for x in chain.links if x != fixed and any(
            j.kind == "R" and fixed in j.links and x in j.links for j in chain.joints)]
    fallback = None
    for driver in drivers:
        try:
            plan = _plan(chain, fixed, driver)
        except MechanismError:
            continue
        try:
            c = cycle(plan)
            ev = _evaluate_sweep(plan, _cycle_theta(plan, c, 720))
        except AssemblyError:
            continue
        turning = set()
        for link in chain.links:
            if link == fixed:
                continue
            phi = np.unwrap(np.broadcast_to(ev.pose[link][2], ev.theta.shape))
            if np.ptp(phi) >= 2 * math.pi - 1e-9:
                turning.add(link)
        if c.full_turn:
            return frozenset(turning), driver
        fallback = fallback or (frozenset(turning), driver)
    return fallback


def summary_rows(motion):
    """The summary as (label, text) rows, for the command line and the report.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=12)
    >>> dict(summary_rows(m))["time ratio"]
    '1.0466'
    """
    s = motion.summary

    def num(value, unit=""):
        if value is None or (isinstance(value, float) and not math.isfinite(value)):
            return "-"
        return f"{value:.6g}{unit}"
    unit = f" {s['stroke_unit']}" if s["stroke_unit"] else ""
    ta = s["transmission_angle"]
    rows = [
        ("fixed link", motion.fixed),
        ("driver", motion.driver + ("  (turns fully)" if s["full_turn"] else "  (rocks)")),
        ("input range", " to ".join(f"{t:.6g}" for t in s["input_range"]) + " degrees"),
        ("output", s["output"] or "-"),
        ("stroke", num(s["stroke"], unit)),
        ("time ratio", num(s["time_ratio"])),
        ("forward / return", f"{num(s['forward_deg'])} / {num(s['return_deg'])} degrees"),
        ("extremes at", ", ".join(f"{t:.6g}" for t in s["extremes"] or []) or "-"),
        ("every extreme", ", ".join(f"{e['kind']} {e['value']:.6g} at {e['input']:.6g}"
                                    for e in s.get("extreme_positions") or []) or "-"),
        ("transmission angle", "-" if ta is None else
         f"{ta['min']:.6g} to {ta['max']:.6g} degrees"),
        ("dead centres", ", ".join(f"{t:.6g}" for t in s["dead_centres"]) or "none"),
        ("mobility", f"{s['numeric_mobility']} at the drawn pose (Kutzbach: {s['mobility']})"),
    ]
    if s.get("note"):
        rows.append(("note", s["note"]))
    return rows


# -- columns -------------------------------------------------------------------------
def _point_motion(pose, vel, acc, link, p):
    x, y = pose[link][:2]
    vx, vy, w = vel[link]
    ax, ay, al = acc[link]
    rx, ry = rotate(pose[link], p)
    return (rx + x, ry + y, vx - w * ry, vy + w * rx,
            ax - al * ry - w * w * rx, ay + al * rx - w * w * ry)


def _link_direction(chain, link):
    """The drawn direction (degrees) of the line the CSV measures a link's angle by."""
    joints = chain.joints_of(link)
    if joints:
        first = joints[0].at
        for j in joints[1:]:
            if math.dist(j.at, first) > 0:
                return math.degrees(math.atan2(j.at[1] - first[1], j.at[0] - first[0]))
        for j in joints:
            if j.kind == "P":
                return j.axis
    return 0.0


def _slide(pose, vel, acc, joint, at):
    """A P joint's slide, its rate and acceleration; ``at`` its point in the plan's frame."""
    g, b = joint.links
    pg = _point_motion(pose, vel, acc, g, at)
    pb = _point_motion(pose, vel, acc, b, at)
    d = (pb[0] - pg[0], pb[1] - pg[1])
    dd = (pb[2] - pg[2], pb[3] - pg[3])
    ddd = (pb[4] - pg[4], pb[5] - pg[5])
    w, al = vel[g][2], acc[g][2]
    u = rotate(pose[g], (math.cos(math.radians(joint.axis)), math.sin(math.radians(joint.axis))))
    pu = (-u[1], u[0])
    du = (w * pu[0], w * pu[1])
    ddu = (al * pu[0] - w * w * u[0], al * pu[1] - w * w * u[1])
    s = d[0] * u[0] + d[1] * u[1]
    v = dd[0] * u[0] + dd[1] * u[1] + d[0] * du[0] + d[1] * du[1]
    a = (ddd[0] * u[0] + ddd[1] * u[1] + 2 * (dd[0] * du[0] + dd[1] * du[1])
         + d[0] * ddu[0] + d[1] * ddu[1])
    return s, v, a


def _continuous_degrees(phi, n):
    """Radians (possibly a constant) to degrees along the sweep, without jumps of a
    turn, the first value in (-180, 180]."""
    if np.ndim(phi) == 0:
        return np.full(n, math.degrees(math.remainder(float(phi), 2 * math.pi)))
    step = np.diff(phi)
    step -= 2 * math.pi * np.round(step / (2 * math.pi))
    out = np.empty(n)
    out[0] = math.remainder(float(phi[0]), 2 * math.pi)
    np.cumsum(step, out=out[1:])
    out[1:] += out[0]
    return np.degrees(out)


def _array(v, n):
    return np.full(n, float(v)) if np.ndim(v) == 0 else v


def _columns(plan, theta, pose, vel, acc):
    chain = plan.chain
    n = theta.size
    cols = {"theta": theta}
    for link in chain.links:
        direction = math.radians(_link_direction(chain, link)) + pose[link][2]
        cols[f"angle:{link}"] = _continuous_degrees(direction, n)
        cols[f"omega:{link}"] = _array(vel[link][2], n)
        cols[f"alpha:{link}"] = _array(acc[link][2], n)
    rank = {plan.fixed: 0, plan.driver: 1}
    items = [(j.id, j.block if j.kind == "P" else min(j.links, key=lambda x: rank.get(x, 2)),
              j.at) for j in chain.joints]
    items += [(p.id, p.link, p.at) for p in chain.points]
    ox, oy = plan.origin
    for name, link, at in items:
        if link == plan.fixed:
            values = (at[0], at[1], 0.0, 0.0, 0.0, 0.0)
        else:
            x, y, *rest = _point_motion(pose, vel, acc, link, plan.local(at))
            values = (x + ox, y + oy, *rest)
        for key, v in zip(("x", "y", "vx", "vy", "ax", "ay"), values):
            cols[f"{key}:{name}"] = _array(v, n)
    for j in chain.joints:
        if j.kind == "P":
            for key, v in zip(("s", "v", "a"), _slide(pose, vel, acc, j, plan.local(j.at))):
                cols[f"{key}:{j.id}"] = _array(v, n)
    return cols


# -- the summary -----------------------------------------------------------------------
def _output_signal(plan, output, cols):
    """How the output's position is measured: (kind, column name or vector, unit word)."""
    chain = plan.chain
    if output is None:
        return None
    if output in chain.links:
        for j in chain.joints:
            if j.kind == "P" and set(j.links) == {output, plan.fixed}:
                return ("slide", j.id)
        angle = cols[f"angle:{output}"]
        if np.ptp(angle) > 1e-9:
            return ("angle", output)
        output = chain.joints_of(output)[0].id
    return ("point", output)


def path_direction(cols, name):
    """The main direction of point ``name``'s path (a unit vector), along which its
    stroke is measured: its sign points towards the path's point farthest from the
    path's mean, so that it turns with the drawing and does not depend on its frame."""
    xy = np.column_stack([cols[f"x:{name}"], cols[f"y:{name}"]])
    centred = xy - xy.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    far = centred[int(np.argmax(np.hypot(centred[:, 0], centred[:, 1])))]
    d = vt[0] if far @ vt[0] >= 0 else -vt[0]
    return float(d[0]), float(d[1])


def _signal_values(kind, name, cols, direction=None):
    """(u, du/dt, d2u/dt2) of the output along the sweep."""
    if kind == "slide":
        return cols[f"s:{name}"], cols[f"v:{name}"], cols[f"a:{name}"]
    if kind == "angle":
        return cols[f"angle:{name}"], np.degrees(cols[f"omega:{name}"]), \
            np.degrees(cols[f"alpha:{name}"])
    ux, uy = direction
    return (cols[f"x:{name}"] * ux + cols[f"y:{name}"] * uy,
            cols[f"vx:{name}"] * ux + cols[f"vy:{name}"] * uy,
            cols[f"ax:{name}"] * ux + cols[f"ay:{name}"] * uy)


def _cycle_theta(plan, c, steps_per_turn=3600):
    """The summary's grid: one period of a crank from the drawn pose, or a rocker's
    whole range, limits included exactly."""
    if c.full_turn:
        n = int(round(steps_per_turn * c.period / 360.0))
        return plan.theta0 + c.period * np.arange(n + 1) / n
    theta = np.linspace(c.low, c.high, steps_per_turn + 1)
    theta[0], theta[-1] = c.low, c.high
    return theta


def _pointwise(plan, ev, k, t):
    """Columns and step measures at angles ``t``, each continued from ev's point k."""
    pose, feasible, _ = evaluate_at(plan, t, ev.reference(k))
    vel, acc, measure = rates(plan, pose, 1.0, t.size)
    return _columns(plan, t, pose, vel, acc), measure, feasible


def _bracketed_roots(f, a, b, fa, fb, *, newton=False, tol=1e-10, iterations=60):
    """Roots of f between a and b (arrays of brackets with fa, fb of opposite signs),
    all at once: Newton's step (``newton``: f returns the value and its derivative
    per degree) or the secant, kept inside the bracket, with a bisection every other
    step so that the bracket at least halves. Returns the roots."""
    a, b, fa, fb = (np.array(v, dtype=float) for v in (a, b, fa, fb))
    t = 0.5 * (a + b)
    for it in range(iterations):
        with np.errstate(divide="ignore", invalid="ignore"):   # a zero slope: bisect
            if newton and it > 0:
                trial = t - value / slope
            else:
                trial = b - fb * (b - a) / (fb - fa)
        inside = np.isfinite(trial) & ((trial - a) * (trial - b) < 0)
        t = np.where(inside & (it % 2 == 0 or newton), trial, 0.5 * (a + b))
        out = f(t)
        value, slope = out if newton else (out, None)
        left = np.sign(value) == np.sign(fa)
        a, fa = np.where(left, t, a), np.where(left, value, fa)
        b, fb = np.where(left, b, t), np.where(left, fb, value)
        done = (np.abs(b - a) < tol) | (value == 0) | ~np.isfinite(value)
        if done.all():
            break
    return np.where(np.isfinite(t), t, 0.5 * (a + b))


def _summary(plan, output, omega, c):
    theta = _cycle_theta(plan, c)
    ev = _evaluate_sweep(plan, theta)
    vel, acc, measure = rates(plan, ev.pose, 1.0, theta.size)
    cols = _columns(plan, theta, ev.pose, vel, acc)
    summary = {"output": output, "stroke": None, "stroke_unit": None, "time_ratio": None,
               "forward_deg": None, "return_deg": None, "extremes": None,
               "extreme_positions": None,
               "transmission_angle": _transmission(plan, ev, theta),
               "dead_centres": _dead_centres(plan, ev, measure, c),
               "input_range": [float(theta[0]), float(theta[-1])],
               "full_turn": c.full_turn,
               "mobility": plan.mobility, "numeric_mobility": plan.numeric_mobility,
               "omega": omega, "note": None}
    signal = _output_signal(plan, output, cols)
    if signal is None:
        summary["note"] = "no output is named, so there is no stroke or time ratio"
        return summary
    kind, name = signal
    direction = path_direction(cols, name) if kind == "point" else None
    u, du, _ = _signal_values(kind, name, cols, direction)
    summary["stroke_unit"] = "deg" if kind == "angle" else plan.chain.units
    if kind == "angle" and c.full_turn and abs(u[-1] - u[0]) > 180.0:
        summary["output_turns_fully"] = True
        summary["note"] = "the output turns fully, so it has no stroke or time ratio"
        return summary
    scale = np.nanmax(np.abs(du))
    if not np.isfinite(scale) or np.nanmax(u) - np.nanmin(u) <= 1e-12 * max(
            plan.size if kind != "angle" else 360.0, 1e-300):
        summary.update(stroke=0.0, note="the output does not move")
        return summary
    extremes = _output_extremes(plan, ev, kind, name, direction, u, du, scale, c)
    values = [e["value"] for e in extremes]
    hi_e = extremes[int(np.argmax(values))]
    lo_e = extremes[int(np.argmin(values))]
    summary["stroke"] = hi_e["value"] - lo_e["value"]
    summary["extremes"] = [_turn(lo_e["input"], c), _turn(hi_e["input"], c)]
    summary["extreme_positions"] = [dict(e, input=_turn(e["input"], c)) for e in extremes]
    if not c.full_turn:
        summary["note"] = "the input rocks, so there is no time ratio"
        return summary
    maxima = sum(e["kind"] == "max" for e in extremes)
    if maxima != 1:
        summary["note"] = (f"the output reaches {maxima} maxima and {len(extremes) - maxima} "
                           "minima in a cycle, so no single forward and return stroke "
                           "(and no time ratio) is defined")
        return summary
    a = (hi_e["input"] - lo_e["input"]) % c.period
    b = c.period - a
    forward, back = max(a, b), min(a, b)
    summary.update(forward_deg=forward, return_deg=back,
                   time_ratio=forward / back if back > 0 else None)
    return summary


def _output_extremes(plan, ev, kind, name, direction, u, du, scale, c):
    """Every extreme of the output over the cycle, in input order: stationary points
    refined by Newton's method on its rate (safeguarded by bisection), and for a rocker
    the values at the input's limits. Each {"input", "value", "kind"}."""
    theta = ev.theta
    sign = np.where(np.abs(du) > 1e-9 * scale, np.sign(du), 0.0)
    # the rate's sign changes between significant samples (a dwell's rounding noise and
    # exact zeros on the grid are skipped over, not counted); a crank's cycle closes on
    # itself, so a change across its seam counts too, one period on
    idx = np.nonzero(sign)[0]
    ka, kb = idx[:-1], idx[1:]
    tb = theta[kb]
    if c.full_turn and idx.size and sign[idx[-1]] != sign[idx[0]]:
        ka, kb = np.append(ka, idx[-1]), np.append(kb, idx[0])
        tb = np.append(tb, theta[idx[0]] + c.period)
    change = sign[ka] != sign[kb]
    ka, kb, tb = ka[change], kb[change], tb[change]
    found = []
    if ka.size:
        t = _bracketed_roots(lambda t: _rate_and_slope(plan, ev, ka, t, kind, name, direction),
                             theta[ka], tb, du[ka], du[kb], newton=True)
        cols, _, _ = _pointwise(plan, ev, ka, t)
        value = _signal_values(kind, name, cols, direction)[0]
        if kind == "angle":      # the same turn as the sweep's own values
            value = u[ka] + np.remainder(value - u[ka] + 180.0, 360.0) - 180.0
        found = [{"input": float(ti), "value": float(vi), "kind": "max" if sign[k] > 0 else "min"}
                 for ti, vi, k in sorted(zip(t, value, ka))]
    if not c.full_turn and idx.size:
        found.insert(0, {"input": float(theta[0]), "value": float(u[0]),
                         "kind": "min" if sign[idx[0]] > 0 else "max"})
        found.append({"input": float(theta[-1]), "value": float(u[-1]),
                      "kind": "max" if sign[idx[-1]] > 0 else "min"})
    return found or [{"input": float(theta[int(np.argmax(u))]), "value": float(np.max(u)),
                      "kind": "max"},
                     {"input": float(theta[int(np.argmin(u))]), "value": float(np.min(u)),
                      "kind": "min"}]


def _rate_and_slope(plan, ev, k, t, kind, name, direction):
    """The output's rate and its derivative per degree of input at angles t."""
    cols, _, _ = _pointwise(plan, ev, k, t)
    _, d1, d2 = _signal_values(kind, name, cols, direction)
    return d1, d2 * (math.pi / 180.0)      # d2 is per radian of input, t in degrees


def _transmission(plan, ev, theta):
    """Transmission angle range of the four-bar loop (RRR dyad) at the output, if any."""
    dyads = [s for s in plan.steps if s.kind == "dyad" and s.pattern == "RRR"]
    if not dyads:
        return None
    out = plan.chain.mechanism.output if plan.chain.mechanism else None
    step = next((s for s in dyads if out in s.links), dyads[0])
    a, b = step.links
    ca, cb, cj = step.constraints
    pose = ev.pose

    def world(link, p):
        rx, ry = rotate(pose[link], p)
        return rx + pose[link][0], ry + pose[link][1]
    x = world(a, cj.point)
    pa = world(a, ca.point)
    pb = world(b, cb.point)
    v1 = (pa[0] - x[0], pa[1] - x[1])
    v2 = (pb[0] - x[0], pb[1] - x[1])
    mu = np.degrees(np.arctan2(np.abs(v1[0] * v2[1] - v1[1] * v2[0]),
                               v1[0] * v2[0] + v1[1] * v2[1]))
    return {"min": _refined_extreme(mu, np.argmin(mu)),
            "max": _refined_extreme(mu, np.argmax(mu))}


def _refined_extreme(y, k):
    """A sampled extreme refined by the parabola through its neighbours."""
    k = int(k)
    if 0 < k < y.size - 1:
        y0, y1, y2 = y[k - 1], y[k], y[k + 1]
        den = y0 - 2 * y1 + y2
        if den != 0:
            return float(y1 - 0.125 * (y2 - y0) ** 2 / den)
    return float(y[k])


def _dead_centres(plan, ev, measure, c):
    """Input angles where the driven mechanism is singular: where a step's signed,
    normalized determinant changes sign (refined all at once), where a dyad's two
    modes touch (a change point), and a rocker's limits."""
    theta = ev.theta
    # where a dyad's modes touch, and a rocker's limits, are known precisely; a root of
    # a determinant near one (where positions carry the square root of the rounding
    # error) is the same dead centre
    exact = [t for ts in ev.switches.values() for t in ts]
    if not c.full_turn:
        exact += [c.low, c.high]
    # a rocker's limits are folds, where a determinant is zero with no meaningful
    # sign: the samples there are left out of the search
    inner = np.ones(theta.size, dtype=bool)
    if not c.full_turn:
        inner[[0, -1]] = False
    roots = []
    for i, m in enumerate(measure):
        m = np.asarray(m, dtype=float)
        idx = np.nonzero(inner & np.isfinite(m) & (m != 0))[0]
        change = np.sign(m[idx[:-1]]) != np.sign(m[idx[1:]])
        ka, kb = idx[:-1][change], idx[1:][change]
        roots += [float(theta[k]) for k in np.nonzero(inner & (m == 0))[0]]
        if ka.size:
            def f(t, ka=ka, i=i):
                _, mm, _ = _pointwise(plan, ev, ka, t)
                return mm[i]
            roots += list(_bracketed_roots(f, theta[ka], theta[kb], m[ka], m[kb]))
    found = exact + [t for t in roots if all(abs(t - x) > 1e-5 for x in exact)]
    found = sorted(_turn(t, c) for t in found)
    merged = [t for i, t in enumerate(found) if i == 0 or t - found[i - 1] > _SAME_ANGLE]
    if c.full_turn and len(merged) > 1 and merged[0] + 360.0 - merged[-1] <= _SAME_ANGLE:
        merged.pop()
    return merged


_SAME_ANGLE = 1e-7     # degrees: how precisely change points and limits are found


def _turn(t, c):
    """An angle of a full-turn cycle in [0, 360) (within ``_SAME_ANGLE`` of 360 is 0);
    a rocker's as it is."""
    if not c.full_turn:
        return float(t)
    t = float(t % 360.0)
    return 0.0 if t > 360.0 - _SAME_ANGLE else t
