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
from .solver import Evaluation, check_poses, evaluate, rates, rotate

__all__ = ["Motion", "solve", "feasible_range", "full_turns"]

_FULL_TURN_STEPS = 720


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


# -- the sweep -----------------------------------------------------------------------
def _path(a, b, max_step=1.0):
    n = max(1, int(math.ceil(abs(b - a) / max_step)))
    return np.linspace(a, b, n + 1)


def _bisect(plan, ev, k_good, t_bad, iterations=45):
    """The last feasible angle between ev.theta[k_good] and t_bad."""
    good = float(ev.theta[k_good])
    start = ev.at(k_good)
    bad = float(t_bad)
    for _ in range(iterations):
        mid = 0.5 * (good + bad)
        trial = evaluate(plan, np.array([good, mid]), start=start)
        if trial.feasible.all():
            good, start = mid, trial.at(1)
        else:
            bad = mid
        if abs(bad - good) < 1e-10:
            break
    return good


def feasible_range(plan):
    """The input angles that can be assembled from the drawn pose, or None for a crank.

    Returns
    -------
    (low, high) in degrees around the drawn pose's angle, or None when the driver makes
    full turns.
    """
    return _feasible(plan)


@lru_cache(maxsize=256)
def _feasible(plan):
    t0 = plan.theta0
    ends = []
    for direction in (1.0, -1.0):
        path = t0 + direction * np.linspace(0.0, 360.0, _FULL_TURN_STEPS + 1)
        ev = evaluate(plan, path)
        if ev.feasible.all():
            return None
        k = int(np.argmin(ev.feasible))
        ends.append(_bisect(plan, ev, k - 1, path[k]))
    return (ends[1], ends[0])


def _outside(plan, lo, hi):
    rng = feasible_range(plan)
    return AssemblyError(
        f"the sweep {lo:g} to {hi:g} degrees leaves the range that can be assembled: "
        f"the driver {plan.driver!r} can turn only from {rng[0]:.6f} to {rng[1]:.6f} "
        f"degrees", mechanism=plan.chain.source or plan.chain.name,
        feasible_range=rng)


def _evaluate_sweep(plan, theta):
    """Poses along ``theta`` (degrees), reached by continuation from the drawn pose."""
    t0 = plan.theta0
    rng = feasible_range(plan)
    lo, hi = float(theta.min()), float(theta.max())
    if rng is not None and (lo < rng[0] - 1e-9 or hi > rng[1] + 1e-9):
        raise _outside(plan, lo, hi)
    if theta[0] == t0:
        ev = evaluate(plan, theta)
    elif min(theta[0], theta[-1]) < t0 < max(theta[0], theta[-1]):
        # continue outward from the drawn pose both ways (never from a limit, where
        # the two assembly modes meet), then join the halves
        k = int(np.searchsorted(theta, t0)) if theta[-1] > theta[0] else \
            int(np.searchsorted(-theta, -t0))
        ahead = evaluate(plan, np.concatenate([[t0], theta[k:]]))
        behind = evaluate(plan, np.concatenate([[t0], theta[:k][::-1]]))
        ev = _join(behind, ahead, theta)
    else:
        walk = _path(t0, float(theta[0]))
        lead = evaluate(plan, walk)
        if not lead.feasible.all():
            raise _outside(plan, lo, hi)
        ev = evaluate(plan, theta, start=lead.at(walk.size - 1))
    if not ev.feasible.all():
        raise _outside(plan, lo, hi)
    return ev


def _join(behind, ahead, theta):
    """One evaluation from two that start at the drawn pose: ``behind`` reversed, then
    ``ahead`` (each without its first point, the drawn pose itself)."""
    def cat(a, b):
        a = np.broadcast_to(a, behind.theta.shape)
        b = np.broadcast_to(b, ahead.theta.shape)
        return np.concatenate([a[1:][::-1], b[1:]])
    pose = {link: tuple(cat(a, b) for a, b in zip(behind.pose[link], ahead.pose[link]))
            for link in ahead.pose}
    pose = {link: tuple(v if np.ptp(v) > 0 or not isinstance(ahead.pose[link][i], float)
                        else ahead.pose[link][i] for i, v in enumerate(p))
            for link, p in pose.items()}
    signs = {i: cat(behind.signs[i], ahead.signs[i]) for i in ahead.signs}
    group_q = {i: np.concatenate([behind.group_q[i][1:][::-1], ahead.group_q[i][1:]])
               for i in ahead.group_q}
    feasible = cat(behind.feasible, ahead.feasible)
    return Evaluation(theta, pose, feasible, signs, group_q)


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
    rng = feasible_range(plan)
    for value, flag in ((start, "--from"), (stop, "--to")):
        if value is not None and not math.isfinite(value):
            raise MechanismError(f"{flag} must be a finite angle", mechanism=chain.name)
    if rng is None:
        lo = plan.theta0 if start is None else float(start)
        hi = lo + 360.0 if stop is None else float(stop)
    else:
        lo = rng[0] if start is None else float(start)
        hi = rng[1] if stop is None else float(stop)
    theta = np.linspace(lo, hi, steps + 1)
    if start is None and stop is None and rng is not None:
        theta[0], theta[-1] = rng  # exactly the limits
    ev = _evaluate_sweep(plan, theta)
    check_poses(plan, ev.pose, ev.feasible)
    vel, acc, _ = rates(plan, ev.pose, omega, theta.size, measure=False)
    columns = _columns(plan, theta, ev.pose, vel, acc)
    summary = _summary(plan, output, omega, rng) if summary else {}
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
        # one turn each way from the drawn pose, a degree a step, as far as it assembles
        ahead = evaluate(plan, plan.theta0 + np.linspace(0.0, 360.0, 361))
        if ahead.feasible.all():
            parts = [ahead]
        else:
            parts = [ahead, evaluate(plan, plan.theta0 - np.linspace(0.0, 360.0, 361))]
        turning = set()
        for link in chain.links:
            if link == fixed:
                continue
            ranges = []
            for ev in parts:
                ok = ev.feasible
                phi = np.unwrap(np.broadcast_to(ev.pose[link][2], ev.theta.shape)[ok])
                ranges.append((phi.min(), phi.max()) if phi.size else (0.0, 0.0))
            lo = min(r[0] for r in ranges)
            hi = max(r[1] for r in ranges)
            if hi - lo >= 2 * math.pi - 1e-9:
                turning.add(link)
        if len(parts) == 1:
            return frozenset(turning), driver
        fallback = fallback or (frozenset(turning), driver)
    return fallback


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


def _slide(pose, vel, acc, joint):
    g, b = joint.links
    pg = _point_motion(pose, vel, acc, g, joint.at)
    pb = _point_motion(pose, vel, acc, b, joint.at)
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
    for name, link, at in items:
        if link == plan.fixed:
            values = (at[0], at[1], 0.0, 0.0, 0.0, 0.0)
        else:
            values = _point_motion(pose, vel, acc, link, at)
        for key, v in zip(("x", "y", "vx", "vy", "ax", "ay"), values):
            cols[f"{key}:{name}"] = _array(v, n)
    for j in chain.joints:
        if j.kind == "P":
            for key, v in zip(("s", "v", "a"), _slide(pose, vel, acc, j)):
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


def _cycle(plan, rng, steps=3600):
    if rng is None:
        return np.linspace(plan.theta0, plan.theta0 + 360.0, steps + 1)
    theta = np.linspace(rng[0], rng[1], steps + 1)
    theta[0], theta[-1] = rng
    return theta


def _at(plan, theta_from, start, theta, output_cols=True):
    """Columns at a single angle, continued from a known state at ``theta_from``."""
    ev = evaluate(plan, np.array([theta_from, theta]), start=start)
    if not ev.feasible.all():
        return None, None
    vel, acc, measure = rates(plan, ev.pose, 1.0, 2)
    cols = _columns(plan, ev.theta, ev.pose, vel, acc)
    return {k: v[1:] for k, v in cols.items()}, measure[:, 1]


def _refine_stationary(plan, ev, k, kind, name, direction):
    """Newton's method on du/dtheta = 0 near sweep point k (with d2u/dtheta2)."""
    start = ev.at(k)
    t_ref = float(ev.theta[k])
    t = t_ref
    for _ in range(12):
        cols, _ = _at(plan, t_ref, start, t)
        if cols is None:
            return None
        u, du, ddu = (v[0] for v in _signal_values(kind, name, cols, direction))
        if not np.isfinite(du) or not np.isfinite(ddu) or ddu == 0:
            return None
        step = math.degrees(du / ddu)
        t -= step
        if abs(step) < 1e-11:
            break
    cols, _ = _at(plan, t_ref, start, t)
    return t, float(_signal_values(kind, name, cols, direction)[0][0])


def _summary(plan, output, omega, rng):
    theta = _cycle(plan, rng)
    ev = evaluate(plan, _path(plan.theta0, theta[0]))
    ev = evaluate(plan, theta, start=ev.at(ev.theta.size - 1))
    vel, acc, measure = rates(plan, ev.pose, 1.0, theta.size)
    cols = _columns(plan, theta, ev.pose, vel, acc)
    summary = {"output": output, "stroke": None, "stroke_unit": None, "time_ratio": None,
               "forward_deg": None, "return_deg": None, "extremes": None,
               "transmission_angle": _transmission(plan, ev, theta),
               "dead_centres": _dead_centres(plan, ev, measure, rng),
               "input_range": [float(theta[0]), float(theta[-1])],
               "full_turn": rng is None,
               "mobility": plan.mobility, "numeric_mobility": plan.numeric_mobility,
               "omega": omega}
    signal = _output_signal(plan, output, cols)
    if signal is None:
        return summary
    kind, name = signal
    direction = None
    if kind == "point":
        xy = np.column_stack([cols[f"x:{name}"], cols[f"y:{name}"]])
        _, _, vt = np.linalg.svd(xy - xy.mean(axis=0), full_matrices=False)
        direction = tuple(vt[0])
    u, du, _ = _signal_values(kind, name, cols, direction)
    summary["stroke_unit"] = "deg" if kind == "angle" else plan.chain.units
    if kind == "angle" and rng is None and abs(u[-1] - u[0]) > 180.0:
        summary["output_turns_fully"] = True
        return summary
    candidates = [(float(theta[0]), float(u[0])), (float(theta[-1]), float(u[-1]))]
    # the sweep's own extremes, and where the rate is exactly zero on the grid
    flips, zeros = _crossings(du)
    for k in (int(np.nanargmax(u)), int(np.nanargmin(u)), *zeros):
        candidates.append((float(theta[k]), float(u[k])))
    for k in flips:
        found = _refine_stationary(plan, ev, int(k), kind, name, direction)
        if found is not None:
            candidates.append(found)
    t_max, u_max = max(candidates, key=lambda c: c[1])
    t_min, u_min = min(candidates, key=lambda c: c[1])
    summary["stroke"] = u_max - u_min
    summary["extremes"] = [_turn(plan, t_min, rng), _turn(plan, t_max, rng)]
    if rng is None:
        a = (t_max - t_min) % 360.0
        b = 360.0 - a
        forward, back = max(a, b), min(a, b)
        summary.update(forward_deg=forward, return_deg=back,
                       time_ratio=forward / back if back > 0 else None)
    return summary


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


def _crossings(values):
    """Where sampled values meet zero: the points k with a sign change between k and
    k + 1 (to be refined), and the points that are zero exactly (a grid point can fall
    on the root itself, and then neither neighbour pair changes sign)."""
    sign = np.sign(values)
    return np.nonzero(sign[:-1] * sign[1:] < 0)[0], np.nonzero(sign == 0)[0]


def _dead_centres(plan, ev, measure, rng):
    """Input angles where the driven mechanism is singular: where a step's normalized
    determinant changes sign (bisection), or touches zero without changing sign, as at a
    parallelogram's change point (golden-section search on its size)."""
    found = []
    for i, m in enumerate(measure):
        sign = np.sign(m)
        changes, zeros = _crossings(m)
        for k in changes:
            start, t_ref = ev.at(int(k)), float(ev.theta[k])
            good, bad = t_ref, float(ev.theta[k + 1])
            for _ in range(60):
                mid = 0.5 * (good + bad)
                _, mm = _at(plan, t_ref, start, mid)
                if mm is None or np.sign(mm[i]) == sign[k]:
                    good = mid
                else:
                    bad = mid
                if abs(bad - good) < 1e-11:
                    break
            found.append(0.5 * (good + bad))
        found += [float(ev.theta[k]) for k in zeros]
        size = np.abs(m)
        for k in range(1, size.size - 1):
            if size[k] <= size[k - 1] and size[k] <= size[k + 1] and size[k] < 0.05 \
                    and sign[k - 1] * sign[k + 1] > 0:
                t = _golden_minimum(plan, ev, k, i)
                if t is not None:
                    found.append(t)
    if rng is not None:
        found += list(rng)
    found = sorted(found)
    merged = [t for i, t in enumerate(found) if i == 0 or t - found[i - 1] > 1e-6]
    return sorted(_turn(plan, t, rng) for t in merged)


def _golden_minimum(plan, ev, k, i):
    """Where step i's |determinant| reaches zero between sweep points k - 1 and k + 1."""
    start, t_ref = ev.at(k - 1), float(ev.theta[k - 1])
    lo, hi = t_ref, float(ev.theta[k + 1])
    ratio = (math.sqrt(5) - 1) / 2

    def f(t):
        _, m = _at(plan, t_ref, start, t)
        return math.inf if m is None else abs(float(m[i]))
    a, b = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
    fa, fb = f(a), f(b)
    for _ in range(80):
        if fa < fb:
            hi, b, fb = b, a, fa
            a = hi - ratio * (hi - lo)
            fa = f(a)
        else:
            lo, a, fa = a, b, fb
            b = lo + ratio * (hi - lo)
            fb = f(b)
        if hi - lo < 1e-10:
            break
    t = 0.5 * (lo + hi)
    return t if f(t) < 1e-5 else None


def _turn(plan, t, rng):
    """An angle of a full-turn cycle in [0, 360); a rocker's as it is."""
    return float(t % 360.0) if rng is None else float(t)
