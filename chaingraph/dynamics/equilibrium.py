"""The force solve: every moving link's equilibrium (with its inertia force and couple
in kinetostatics, d'Alembert's principle), batched over the steps of a sweep.

The unknowns are the joints' reactions (two components for a turning pair of two
links; the forces on all but the last link for a multiple joint; the normal force and
the couple for a sliding pair, with Coulomb friction along its guide in proportion to
the normal force) and one effort per input (a couple between the input's two links for
an R input, a force along the guide for a P input). Three equations per moving link,
the forces and the moment about the drawing's origin, in SI units: one linear solve per
step, all steps at once. Friction's sign follows the normal force's sign, found by
iterating the signs per step until they agree (every combination tried where they do
not settle).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from chaingraph.errors import MechanismError
from chaingraph.geometry import cross, rotate, unit_deg
from chaingraph.model.chain import mass_centre

__all__ = ["UNIT_METRES", "KinematicState", "Solution", "solve_equilibrium"]

#: metres per length unit of a chain file
UNIT_METRES = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254}

#: a step's matrix (scaled) whose determinant over the product of its columns' lengths
#: (or, with more unknowns than equations, whose smallest singular value over its
#: largest) is below this is singular: a dead centre, where the effort is unbounded
_SINGULAR = 1e-10


@dataclass(frozen=True)
class KinematicState:
    """What the force solve needs of the motion at n steps, in SI units: each link's
    :class:`~chaingraph.kinematics.pose.LinkMotion` with arrays for fields (its frame
    origin about the plan's origin in m, its rotation from the drawn pose, their
    rates), and each input's rate ``rates[joint]`` (rad/s or m/s); ``rates_known``
    when the rates are the solver's own, NaN at its dead centres."""

    n: int
    links: dict
    rates: dict
    rates_known: bool = False

    def direction(self, link, degrees):
        """The unit vector drawn at ``degrees`` on the link, turned with it."""
        return rotate(unit_deg(degrees), self.links[link].angle)


@dataclass(frozen=True)
class Solution:
    """The solve's numbers at n steps (NaN where not determined): ``forces[(joint,
    link)]`` the (Fx, Fy) on ``link`` at the joint (for a two-link joint its first link,
    by the second), ``normal[joint]``, ``couple[joint]`` for P joints, ``efforts[joint]``
    per input, ``power`` the power balance (W), ``singular`` the dead-centre steps,
    ``at_rest`` per friction joint the steps where its slide is at rest (the friction
    is indeterminate within its cone), ``jammed`` the steps where no sign of the
    friction forces is consistent (the friction locks the mechanism);
    ``indeterminate`` when a redundant constraint leaves the reactions statically
    indeterminate (the least-norm reactions are given; the efforts are determined);
    ``applied`` the forces other than the reactions, as (link, what, point, force) in
    metres about the plan's origin and newtons (weights, inertia forces, loads, a P
    input's effort), ``couples`` as (link, what, N m) (inertia couples, loads' torques,
    an R input's effort), ``points`` every joint's point (m about the origin)."""

    forces: dict
    normal: dict
    couple: dict
    efforts: dict
    power: np.ndarray
    singular: np.ndarray
    at_rest: dict
    jammed: np.ndarray
    indeterminate: bool = False
    applied: tuple = ()
    couples: tuple = ()
    points: dict = None


def solve_equilibrium(chain, plan, state, *, static=False, metres=1.0):
    """The reactions and efforts of ``chain`` (its masses, gravity, loads, friction) at
    the ``state``'s steps; ``plan`` gives the fixed link and the inputs; ``metres`` is
    the length unit in metres; drawn coordinates are taken about ``plan.origin``."""
    n = state.n
    fixed = plan.fixed
    moving = [x for x in chain.links if x != fixed]
    row = {link: 3 * i for i, link in enumerate(moving)}
    ox, oy = plan.origin

    def drawn(p):                               # drawn point -> metres about the origin
        return ((p[0] - ox) * metres, (p[1] - oy) * metres)

    size = max(plan.size * metres, 1e-300)

    # ---- unknowns
    cols = []                                 # (kind, joint, extra)
    for j in chain.joints:
        if j.kind == "R":
            for k in range(len(j.links) - 1):
                cols += [("Fx", j, k), ("Fy", j, k)]
        elif j.kind == "P":
            cols += [("N", j, None), ("M", j, None)]
        else:
            raise MechanismError(f"forces are solved for R and P joints; joint {j.id!r} is "
                                 f"{j.kind}", mechanism=chain.source or chain.name)
    for item in plan.inputs:
        cols.append(("effort", item, None))
    m_rows, m_cols = 3 * len(moving), len(cols)
    if m_rows > m_cols:
        raise MechanismError(
            f"the inputs do not hold the mechanism: {m_cols} unknown reactions and efforts "
            f"for {m_rows} equations of equilibrium (give one input per degree of "
            "freedom)", mechanism=chain.source or chain.name)
    # more unknowns than equations: a redundant constraint (the locomotive's third
    # wheel), statically indeterminate; the least-norm reactions are given
    indeterminate = m_cols > m_rows

    # world points of the joints (a P joint: its block's reference point)
    where = {}
    for j in chain.joints:
        link = j.links[1] if j.kind == "P" else (fixed if fixed in j.links else j.links[0])
        where[j.id] = state.links[link].moved(drawn(j.at))
    friction = [j for j in chain.joints if j.kind == "P" and j.friction]
    slide_speed, axis = {}, {}
    for j in chain.joints:
        if j.kind == "P":
            t = state.direction(j.links[0], j.axis)
            axis[j.id] = t
            q = where[j.id]
            vb = state.links[j.links[1]].velocity_at(q)
            vg = state.links[j.links[0]].velocity_at(q)
            slide_speed[j.id] = (vb[0] - vg[0]) * t[0] + (vb[1] - vg[1]) * t[1]

    def put(a, link, col, f, q, sign=1.0):
        """Add the force f (Fx, Fy arrays) at q on ``link`` to column ``col``."""
        if link == fixed:
            return
        r = row[link]
        a[:, r, col] += sign * f[0]
        a[:, r + 1, col] += sign * f[1]
        a[:, r + 2, col] += sign * cross(q, f) / size    # moments over the size

    def put_couple(a, link, col, c, sign=1.0):
        if link == fixed:
            return
        a[:, row[link] + 2, col] += sign * c / size

    one, zero = np.ones(n), np.zeros(n)

    def matrix():
        """The equilibrium matrix without friction: one column per unknown."""
        a = np.zeros((n, m_rows, m_cols))
        for c, (kind, j, k) in enumerate(cols):
            if kind in ("Fx", "Fy"):
                f = (one, zero) if kind == "Fx" else (zero, one)
                q = where[j.id]
                put(a, j.links[k], c, f, q)
                put(a, j.links[-1], c, f, q, -1.0)
            elif kind == "N":
                t = axis[j.id]
                put(a, j.links[0], c, (-t[1], t[0]), where[j.id])
                put(a, j.links[1], c, (-t[1], t[0]), where[j.id], -1.0)
            elif kind == "M":
                put_couple(a, j.links[0], c, one * size)
                put_couple(a, j.links[1], c, one * size, -1.0)
            else:                                # an input's effort
                if j.kind == "R":
                    put_couple(a, j.b, c, one)
                    put_couple(a, j.a, c, one, -1.0)
                else:
                    t = axis[j.joint]
                    put(a, j.b, c, t, where[j.joint])
                    put(a, j.a, c, t, where[j.joint], -1.0)
        return a

    base = matrix()
    normal_cols = {j.id: next(c for c, (kind, jj, _) in enumerate(cols)
                              if kind == "N" and jj.id == j.id) for j in friction}

    def sliding_friction(j, sigma, steps=slice(None)):
        """Friction's share of the guide's force per unit normal force, at ``steps``: on
        the guide it pulls along the block's sliding velocity, mu |N| sign(v) with
        |N| = sigma N (``sigma`` over those steps)."""
        return sigma[j.id] * np.sign(slide_speed[j.id][steps]) * j.friction

    def with_friction(sigma, steps=slice(None)):
        """The matrix at ``steps`` with the friction forces for the signs ``sigma`` of
        the normal forces (per friction joint, arrays over those steps)."""
        if not friction:
            return base[steps]
        a = base[steps].copy()
        for j in friction:
            t, c = axis[j.id], normal_cols[j.id]
            s = sliding_friction(j, sigma, steps)
            f = (s * t[0][steps], s * t[1][steps])
            q = (where[j.id][0][steps], where[j.id][1][steps])
            put(a, j.links[0], c, f, q)
            put(a, j.links[1], c, f, q, -1.0)
        return a

    # ---- the known forces: gravity, loads, inertia (d'Alembert)
    rhs = np.zeros((n, m_rows, 1))           # the known forces, as one more column
    power = np.zeros(n)                       # of gravity, loads and inertia
    applied, couples = [], []                 # (link, what, point, force), (link, what, value)
    g = chain.gravity or (0.0, 0.0)
    for mass in chain.masses:
        link = mass.link
        if link == fixed:
            continue
        motion = state.links[link]
        q = motion.moved(drawn(mass_centre(chain, mass)))
        v = motion.velocity_at(q)
        f = (mass.mass * g[0] * one, mass.mass * g[1] * one)
        if chain.gravity is not None and mass.mass:
            applied.append((link, "weight", q, f))
        couple = zero
        if not static:
            acc = motion.acceleration_at(q)
            inertia = (-mass.mass * acc[0], -mass.mass * acc[1])
            applied.append((link, "inertia force", q, inertia))
            f = (f[0] + inertia[0], f[1] + inertia[1])
            couple = -mass.inertia * motion.alpha
            if mass.inertia:
                couples.append((link, "inertia couple", couple))
        put(rhs, link, 0, f, q)
        put_couple(rhs, link, 0, couple)
        power += f[0] * v[0] + f[1] * v[1] + couple * motion.omega
    for load in chain.loads:
        link = load.on
        if link == fixed:
            continue
        if load.force is not None:
            if load.at in where:
                q = where[load.at]
            else:
                q = state.links[link].moved(drawn(chain.point(load.at).at))
            f = (load.force[0] * one, load.force[1] * one)
            applied.append((link, "load", q, f))
            put(rhs, link, 0, f, q)
            v = state.links[link].velocity_at(q)
            power += f[0] * v[0] + f[1] * v[1]
        if load.torque:
            couples.append((link, "load", load.torque * one))
            put_couple(rhs, link, 0, load.torque * one)
            power += load.torque * state.links[link].omega

    # ---- solve, iterating the friction signs
    at_rest = {j.id: ~(np.abs(slide_speed[j.id]) > 1e-12 * max(size, 1e-12) *
                       _speed_scale(state)) for j in friction}
    sigma = {j.id: one.copy() for j in friction}
    known = np.zeros(n, dtype=bool)
    for link in moving:
        known |= ~np.isfinite(state.links[link].omega) | ~np.isfinite(state.links[link].velocity[0])
    known = known if state.rates_known else None
    rhs = rhs[:, :, 0]
    x, singular = _solve(with_friction(sigma), -rhs, known)
    settled = np.ones(n, dtype=bool)
    if friction:
        for _ in range(8):
            new = {k: np.where(x[:, normal_cols[k]] < 0, -1.0, 1.0) for k in sigma}
            if all((new[k] == sigma[k]).all() for k in sigma):
                break
            sigma = new
            x, singular = _solve(with_friction(sigma), -rhs, known)
        for k in sigma:
            settled &= (np.where(x[:, normal_cols[k]] < 0, -1.0, 1.0) == sigma[k]) | \
                (x[:, normal_cols[k]] == 0)
        if not settled.all():
            # every combination of signs at the steps that did not settle
            bad = np.nonzero(~settled)[0]
            for combo in itertools.product((1.0, -1.0), repeat=len(sigma)):
                trial = {k: np.full(bad.size, s) for k, s in zip(sigma, combo)}
                xs, sing = _solve(with_friction(trial, bad), -rhs[bad],
                                  None if known is None else known[bad])
                ok = np.ones(bad.size, dtype=bool)
                for k, s in zip(sigma, combo):
                    ok &= np.where(xs[:, normal_cols[k]] < 0, -1.0, 1.0) == s
                done = bad[ok]
                x[done], singular[done], settled[done] = xs[ok], sing[ok], True
                for k, s in zip(sigma, combo):
                    sigma[k][done] = s
                if settled.all():
                    break
    jammed = ~settled & ~singular
    undetermined = singular | jammed
    for k in at_rest:
        undetermined = undetermined | at_rest[k]
    x[undetermined] = np.nan

    # ---- results
    forces, normal, couple, efforts = {}, {}, {}, {}
    for c, (kind, j, k) in enumerate(cols):
        if kind == "Fx":
            fx, fy = x[:, c], x[:, c + 1]
            forces[(j.id, j.links[k])] = (fx, fy)
        elif kind == "N":
            t = axis[j.id]
            d = (-t[1], t[0])
            nn = x[:, c]
            f = (nn * d[0], nn * d[1])
            if j.friction:
                s = sliding_friction(j, sigma)
                f = (f[0] + s * nn * t[0], f[1] + s * nn * t[1])
            forces[(j.id, j.links[0])] = f
            normal[j.id] = nn
            couple[j.id] = x[:, c + 1] * size
        elif kind == "effort":                  # a couple (N m) or a force (N)
            efforts[j.joint] = x[:, c]
    for j in chain.joints:
        if j.kind == "R" and len(j.links) > 2:
            parts = [forces[(j.id, link)] for link in j.links[:-1]]
            forces[(j.id, j.links[-1])] = (-sum(p[0] for p in parts), -sum(p[1] for p in parts))
    # the power balance: the efforts' power plus that of gravity, loads, inertia and
    # friction (friction's power: minus |friction| |slide speed|)
    total = power.copy()
    for item in plan.inputs:
        total = total + efforts[item.joint] * state.rates[item.joint]
    for j in friction:
        fr = j.friction * np.abs(normal[j.id])
        total = total - fr * np.abs(slide_speed[j.id])
    for item in plan.inputs:                  # the efforts, as applied to the input's link
        if item.kind == "R":
            couples.append((item.b, f"effort {item.joint}", efforts[item.joint]))
        else:
            t = axis[item.joint]
            e = efforts[item.joint]
            applied.append((item.b, f"effort {item.joint}", where[item.joint],
                            (e * t[0], e * t[1])))
    return Solution(forces, normal, couple, efforts, total, singular,
                    {k: v & ~singular for k, v in at_rest.items()}, jammed, indeterminate,
                    tuple(applied), tuple(couples), where)


def _speed_scale(state):
    """A typical angular speed of the state (for what counts as a slide at rest)."""
    w = [np.abs(np.asarray(m.omega)) for m in state.links.values()]
    r = [abs(np.asarray(v)) for v in state.rates.values()]
    vals = [float(np.nanmax(a)) for a in w + r if np.size(a)]
    return max([v for v in vals if math.isfinite(v)] + [1e-300])


def _solve(a, b, known=None):
    """x with a x = b per step (with more unknowns than equations, the least-norm x),
    and which steps are singular (x NaN there). ``known``: the steps already known to
    be singular (the motion's dead centres, where its rates are not finite), so that
    the others need no test of their own."""
    n = a.shape[0]
    x = np.full((n, a.shape[2]), np.nan)
    good = np.isfinite(a).all(axis=(1, 2)) & np.isfinite(b).all(axis=1)
    singular = ~good
    if known is not None and a.shape[1] == a.shape[2]:
        use = good & ~known
        singular |= known
        if use.any():
            try:
                if use.all():
                    x = np.linalg.solve(a, b[:, :, None])[:, :, 0]
                else:
                    x[use] = np.linalg.solve(a[use], b[use][:, :, None])[:, :, 0]
                return x, singular
            except np.linalg.LinAlgError:     # a singular step the motion did not flag
                pass
        else:
            return x, singular
    if good.any():
        ag, bg = a[good], b[good]
        if ag.shape[1] == ag.shape[2]:
            # the determinant over the product of the columns' lengths (Hadamard's
            # ratio, 1 for orthogonal columns, 0 when singular): one LU per step
            ratio = np.abs(np.linalg.det(ag)) / (np.prod(np.linalg.norm(ag, axis=1), axis=1)
                                                 + 1e-300)
            ok = ratio > _SINGULAR
        else:
            s = np.linalg.svd(ag, compute_uv=False)
            ok = s[:, -1] > _SINGULAR * s[:, 0]
        idx = np.nonzero(good)[0]
        singular[idx[~ok]] = True
        if ok.any():
            if ag.shape[1] == ag.shape[2]:
                x[idx[ok]] = np.linalg.solve(ag[ok], bg[ok][:, :, None])[:, :, 0]
            else:
                x[idx[ok]] = (np.linalg.pinv(ag[ok]) @ bg[ok][:, :, None])[:, :, 0]
    return x, singular
