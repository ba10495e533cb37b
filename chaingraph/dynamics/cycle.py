"""The work of the lead input's effort over the mechanism's cycle, integrated exactly:
the mean effort, the steady torque of a ``torque = "mean"`` load, and the energy
fluctuation with its extremes where the effort crosses its mean.

The effort is smooth between the poses where a load switches (a table's knot, a slide
or a point reversing, where a stroke-limited load starts or stops) and where a
friction force turns; those poses are found as roots, and the effort is integrated on
every smooth piece by Gauss-Legendre quadrature at poses solved there (not read off the
sweep's grid), so the figures hold to rounding whatever the number of steps.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from chaingraph.dynamics.equilibrium import KinematicState, solve_equilibrium
from chaingraph.errors import MechanismError
from chaingraph.kinematics.columns import LinkStates, slide_of_states
from chaingraph.kinematics.plan import Plan
from chaingraph.kinematics.pose import LinkState
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.sweep import evaluate_sweep
from chaingraph.model.chain import Chain

__all__ = ["kinematic_state", "states_at", "CycleEfforts"]

#: Gauss-Legendre nodes and weights on [-1, 1] for each smooth piece of the cycle
_NODES, _WEIGHTS = np.polynomial.legendre.leggauss(8)


def kinematic_state(chain: Chain, plan: Plan, states: LinkStates, omega: float,
                    metres: float, *, rates_known: bool, angle: np.ndarray | None = None,
                    strokes: dict[int, tuple[float, float]] | None = None
                    ) -> KinematicState:
    """The :class:`KinematicState` of the solver's ``states`` at input speed ``omega``,
    in SI units: what the force solve needs, taken from the motion as it was solved;
    ``angle`` the lead R input's values (radians), ``strokes`` the stroke directions of
    the stroke-limited resisting loads."""
    n = states.tau.size
    w = 1.0 if float(omega) == states.speed else float(omega) / states.speed
    pose = states.pose
    vel = {k: tuple(np.asarray(c) * w for c in v) for k, v in states.velocity.items()}
    acc = {k: tuple(np.asarray(c) * w * w for c in v) for k, v in states.acceleration.items()}

    def arr(v, scale=1.0):
        return np.broadcast_to(np.asarray(v, dtype=float) * scale, (n,)).copy()
    links = {}
    for link in chain.links:
        p, v, a = pose[link], vel[link], acc[link]
        links[link] = LinkState(link, (arr(p[0], metres), arr(p[1], metres)), arr(p[2]),
                                (arr(v[0], metres), arr(v[1], metres)), arr(v[2]),
                                (arr(a[0], metres), arr(a[1], metres)), arr(a[2]))
    input_rates = {item.joint: arr(vel[item.key][2], 1.0 if item.kind == "R" else metres)
                   for item in plan.inputs}
    slides = {x.along: arr(slide_of_states(plan, states, x.along).s)
              for x in chain.loads if x.along is not None}
    return KinematicState(n, links, input_rates, rates_known=rates_known, slides=slides,
                          angle=None if angle is None else arr(angle),
                          strokes=dict(strokes or {}))


def states_at(plan: Plan, theta: np.ndarray) -> LinkStates:
    """The solver's states at the lead input's values ``theta`` (degrees), anywhere in
    its cycle, at unit input speed."""
    theta = np.asarray(theta, dtype=float)
    ev = evaluate_sweep(plan, theta)
    vel, acc, _ = rates(plan, ev.pose, 1.0, theta.size, measure=False)
    return LinkStates(theta, ev.pose, vel, acc)


@dataclass(frozen=True)
class CycleEfforts:
    """The lead input's effort at any pose of its cycle, with the loads as
    :func:`chaingraph.forces` applies them: ``strokes`` the stroke-limited resisting
    loads' directions, ``directions`` every resisting load's line of motion (where its
    point reverses, its force turns), ``mean_torque`` the steady load torque."""

    chain: Chain
    plan: Plan
    metres: float
    static: bool
    omega: float
    strokes: dict = field(default_factory=dict)
    directions: dict = field(default_factory=dict)
    mean_torque: float = 0.0
    #: the states already solved, by their angles (shared with :meth:`with_torque`'s),
    #: and what the caller keeps of its integrals
    solved: dict = field(default_factory=dict, repr=False, compare=False)

    def state(self, theta: np.ndarray) -> KinematicState:
        """The kinematic state at the lead input's values ``theta`` (degrees)."""
        theta = np.asarray(theta, dtype=float)
        key = theta.tobytes()
        if key not in self.solved:
            if len(self.solved) > 8:
                for k in [k for k in self.solved if isinstance(k, bytes)]:
                    del self.solved[k]
            self.solved[key] = kinematic_state(
                self.chain, self.plan, states_at(self.plan, theta), self.omega, self.metres,
                rates_known=False, angle=np.radians(theta), strokes=self.strokes)
        return self.solved[key]

    def effort(self, theta: np.ndarray, kin: KinematicState | None = None) -> np.ndarray:
        """The lead input's effort at ``theta`` (degrees)."""
        kin = self.state(theta) if kin is None else kin
        sol = solve_equilibrium(self.chain, self.plan, kin, static=self.static,
                                metres=self.metres, mean_torque=self.mean_torque)
        return sol.efforts[self.plan.inputs[self.plan.lead].joint]

    def with_torque(self, tau: float) -> CycleEfforts:
        return replace(self, mean_torque=tau)

    # -- where the effort is not smooth --------------------------------------------------
    def _switches(self) -> list[tuple]:
        """Where a load or a friction force switches (the effort has a kink there): the
        roots of :meth:`_switch` of each of these."""
        out: list[tuple] = []
        for i, load in enumerate(self.chain.loads):
            if load.on == self.plan.fixed:
                continue
            if load.follows and load.along is not None:
                if load.against == "slide":
                    out += [("slide", load.along, x) for x in load.values()[0]]
                if load.stroke or self.chain.joint(load.along).friction:
                    out.append(("slide speed", load.along, 0.0))
            if load.resist is not None and i in self.directions:
                out.append(("point speed", i, 0.0))
        out += [("slide speed", j.id, 0.0) for j in self.chain.joints
                if j.kind == "P" and j.friction]
        return out

    def _switch(self, kin: KinematicState, spec: tuple) -> np.ndarray:
        kind, what, x = spec
        if kind == "slide":
            return kin.slides[what] - x
        if kind == "slide speed":
            return self._slide_speed(kin, what)
        return self._point_speed(kin, what)

    def _slide_speed(self, kin, joint):
        j = self.chain.joint(joint)
        t = kin.direction(j.links[0], j.axis)
        guide, block = kin.links[j.links[0]], kin.links[j.links[1]]
        q = block.moved(self._drawn(j.at))
        vb, vg = block.velocity_at(q), guide.velocity_at(q)
        return (vb[0] - vg[0]) * t[0] + (vb[1] - vg[1]) * t[1]

    def _point_speed(self, kin, i):
        load = self.chain.loads[i]
        at = (self.chain.joint(load.at).at if load.at in {j.id for j in self.chain.joints}
              else self.chain.point(load.at).at)
        state = kin.links[load.on]
        v = state.velocity_at(state.moved(self._drawn(at)))
        d = self.directions[i]
        return v[0] * d[0] + v[1] * d[1]

    def _drawn(self, p):
        o = self.plan.origin
        return ((p[0] - o[0]) * self.metres, (p[1] - o[1]) * self.metres)

    def breaks(self, grid: np.ndarray) -> np.ndarray:
        """The grid (degrees) with every pose where the effort has a kink within it."""
        lo, hi = float(grid[0]), float(grid[-1])
        found = [grid]
        for load in self.chain.loads:
            if load.follows and load.against == "input" and load.on != self.plan.fixed:
                period = math.degrees(load.period)
                for x in np.degrees(np.asarray(load.values()[0])):
                    k = np.arange(math.floor((lo - x) / period), math.ceil((hi - x) / period) + 1)
                    found.append(x + k * period)
        switches = self._switches()
        if switches:
            kin = self.state(grid)
            for spec in switches:
                found.append(_roots(lambda t, spec=spec: self._switch(self.state(t), spec),
                                    grid, self._switch(kin, spec)))
        out = np.unique(np.concatenate(found))
        return out[(out >= lo) & (out <= hi)]

    # -- the integrals --------------------------------------------------------------------
    def integrals(self, a: np.ndarray, b: np.ndarray, *, power: int = 1) -> np.ndarray:
        """The integral of the effort (to ``power``) over the input's angle (radians)
        on each smooth piece [a, b] (degrees), by Gauss-Legendre quadrature."""
        a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
        mid, half = 0.5 * (a + b), 0.5 * (b - a)
        t = mid[:, None] + half[:, None] * _NODES[None, :]
        e = self.effort(t.ravel()).reshape(t.shape)
        return ((e ** power) @ _WEIGHTS) * np.radians(half)

    def mean(self, breaks: np.ndarray, *, power: int = 1) -> float:
        """The mean effort (to ``power``) over the span of ``breaks`` (degrees, every
        kink among them)."""
        total = float(np.sum(self.integrals(breaks[:-1], breaks[1:], power=power)))
        return total / math.radians(breaks[-1] - breaks[0])

    def energy_fluctuation(self, breaks: np.ndarray, mean: float) -> float:
        """The largest swing of the work of the effort about ``mean`` over the span of
        ``breaks``: the work W(u) = int (e - mean) du at the poses where the effort
        crosses the mean (found as roots, between the breaks) and at the ends."""
        work = np.concatenate([[0.0], np.cumsum(self.integrals(breaks[:-1], breaks[1:]))])
        swing = work - mean * np.radians(breaks - breaks[0])
        e = _filled(self.effort(breaks) - mean)
        roots = _roots(lambda t: self.effort(t) - mean, breaks, e)
        if roots.size:
            k = np.clip(np.searchsorted(breaks, roots, side="right") - 1, 0, breaks.size - 2)
            part = self.integrals(breaks[k], roots)
            swing = np.concatenate([swing, work[k] + part
                                    - mean * np.radians(roots - breaks[0])])
        if not np.isfinite(swing).all():
            raise MechanismError("the effort is not determined over the whole cycle",
                                 mechanism=self.chain.source or self.chain.name)
        return float(swing.max() - swing.min())


def _filled(v):
    """``v`` with its undetermined entries (a slide with friction at rest) filled in
    linearly from their neighbours."""
    good = np.isfinite(v)
    if good.all() or good.sum() < 2:
        return v
    k = np.arange(v.size)
    return np.interp(k, k[good], v[good])


def _roots(f, grid, values, iterations: int = 60) -> np.ndarray:
    """The roots of ``f`` (a function of arrays of degrees) in each interval of ``grid``
    where ``values`` (f on the grid) changes sign, by the Illinois method, all at
    once."""
    values = np.asarray(values, dtype=float)
    ok = np.isfinite(values[:-1]) & np.isfinite(values[1:])
    k = np.nonzero(ok & (np.sign(values[:-1]) * np.sign(values[1:]) < 0))[0]
    if k.size == 0:
        return np.zeros(0)
    a, b = grid[k].astype(float), grid[k + 1].astype(float)
    fa, fb = values[k], values[k + 1]
    side = np.zeros(k.size)
    scale = max(float(np.max(np.abs(grid))), 1.0)
    for _ in range(iterations):
        c = np.where(fb != fa, b - fb * (b - a) / np.where(fb != fa, fb - fa, 1.0), 0.5 * (a + b))
        c = np.clip(c, np.minimum(a, b), np.maximum(a, b))
        fc = np.asarray(f(c), dtype=float)
        left = np.sign(fc) == np.sign(fa)       # the root lies between c and b
        # Illinois: the end kept twice running has its value halved
        fb = np.where(left, np.where(side == -1, fb * 0.5, fb), fc)
        fa = np.where(left, fc, np.where(side == 1, fa * 0.5, fa))
        a, b = np.where(left, c, a), np.where(left, b, c)
        side = np.where(left, -1, 1)
        done = (np.abs(b - a) < 1e-12 * scale) | (fc == 0)
        if done.all():
            break
    return np.where(np.abs(fa) < np.abs(fb), a, b)
