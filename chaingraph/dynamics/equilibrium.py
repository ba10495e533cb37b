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
from dataclasses import dataclass, replace

import numpy as np

from chaingraph.errors import MechanismError
from chaingraph.geometry import Vec, cross, rotate, unit_deg
from chaingraph.kinematics.plan import InputJoint, Plan
from chaingraph.kinematics.pose import LinkState
from chaingraph.model.chain import Chain, Joint, mass_centre

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
    :class:`~chaingraph.kinematics.pose.LinkState` with arrays for fields (its frame
    origin about the plan's origin in m, its rotation from the drawn pose, their
    rates), and each input's rate ``rates[joint]`` (rad/s or m/s); ``rates_known``
    when the rates are the solver's own, NaN at its dead centres."""

    n: int
    links: dict[str, LinkState]       # by link, its fields arrays over the steps
    rates: dict[str, np.ndarray]
    rates_known: bool = False

    def direction(self, link: str, degrees: float) -> Vec:
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

    forces: dict[tuple[str, str], Vec]
    normal: dict[str, np.ndarray]
    couple: dict[str, np.ndarray]
    efforts: dict[str, np.ndarray]
    power: np.ndarray
    singular: np.ndarray
    at_rest: dict[str, np.ndarray]
    jammed: np.ndarray
    indeterminate: bool = False
    applied: tuple[tuple[str, str, Vec, Vec], ...] = ()
    couples: tuple[tuple[str, str, np.ndarray], ...] = ()
    points: dict[str, Vec] | None = None


def solve_equilibrium(chain: Chain, plan: Plan, state: KinematicState, *, static: bool = False,
                      metres: float = 1.0) -> Solution:
    """The reactions and efforts of ``chain`` (its masses, gravity, loads, friction) at
    the ``state``'s steps; ``plan`` gives the fixed link and the inputs; ``metres`` is
    the length unit in metres; drawn coordinates are taken about ``plan.origin``."""
    layout = _layout(chain, plan, state.n, metres)
    joints = _joint_geometry(chain, layout, state)
    known = _known_forces(chain, layout, state, joints, static=static)
    x, singular, settled, sigma = _solve_with_friction(layout, joints, -known.rhs,
                                                       _known_singular(layout, state))
    at_rest = _at_rest(joints, layout, state)
    jammed = ~settled & ~singular
    undetermined = singular | jammed
    for k in at_rest:
        undetermined = undetermined | at_rest[k]
    x[undetermined] = np.nan
    forces, normal, couple, efforts = _reactions(chain, layout, joints, x, sigma)
    power = _power_balance(plan, state, joints, known.power, efforts, normal)
    applied, couples = _with_efforts(plan, joints, efforts, known)
    return Solution(forces, normal, couple, efforts, power, singular,
                    {k: v & ~singular for k, v in at_rest.items()}, jammed,
                    layout.indeterminate, applied, couples, joints.where)


# -- the layout: which unknown is which column, which link's equations which rows ------------
@dataclass(frozen=True)
class _Layout:
    """The linear system's layout at ``n`` steps: ``cols`` one (kind, joint, extra) per
    unknown, ``row`` each moving link's first row (its x force, y force and moment
    equations); drawn points are taken in metres about ``origin`` (``drawn``), and
    moments are divided by ``size`` (m) so that every row is a force."""

    n: int
    fixed: str
    row: dict
    cols: tuple
    origin: tuple
    metres: float
    size: float

    @property
    def rows(self) -> int:
        return 3 * len(self.row)

    @property
    def indeterminate(self) -> bool:
        """More unknowns than equations: a redundant constraint (the locomotive's third
        wheel), statically indeterminate; the least-norm reactions are given."""
        return len(self.cols) > self.rows

    def drawn(self, p):
        """A drawn point in metres about the origin."""
        return ((p[0] - self.origin[0]) * self.metres, (p[1] - self.origin[1]) * self.metres)

    def put(self, a, link, col, f, q, sign=1.0):
        """Add the force f (Fx, Fy arrays) at q on ``link`` to column ``col`` of ``a``."""
        if link == self.fixed:
            return
        r = self.row[link]
        a[:, r, col] += sign * f[0]
        a[:, r + 1, col] += sign * f[1]
        a[:, r + 2, col] += sign * cross(q, f) / self.size    # moments over the size

    def put_couple(self, a, link, col, c, sign=1.0):
        """Add the couple c on ``link`` to column ``col`` of ``a``."""
        if link == self.fixed:
            return
        a[:, self.row[link] + 2, col] += sign * c / self.size


def _layout(chain, plan, n, metres):
    """The unknowns (two reaction components per pair of an R joint's links; a P joint's
    normal force and couple; an effort per input) and the equations (three per moving
    link); refuses a joint other than R or P, and inputs that do not hold the
    mechanism."""
    cols: list[tuple[str, Joint | InputJoint, int | None]] = []   # (kind, joint, extra)
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
    moving = [x for x in chain.links if x != plan.fixed]
    layout = _Layout(n=n, fixed=plan.fixed, row={link: 3 * i for i, link in enumerate(moving)},
                     cols=tuple(cols), origin=plan.origin, metres=metres,
                     size=max(plan.size * metres, 1e-300))
    if layout.rows > len(cols):
        raise MechanismError(
            f"the inputs do not hold the mechanism: {len(cols)} unknown reactions and "
            f"efforts for {layout.rows} equations of equilibrium (give one input per degree "
            "of freedom)", mechanism=chain.source or chain.name)
    return layout


# -- where the joints are, how the slides move --------------------------------------------
@dataclass(frozen=True)
class _Joints:
    """The joints over the steps: ``where`` every joint's point (a P joint: its block's
    reference point), ``axis`` and ``slide_speed`` of each P joint (its guide's
    direction, the block's speed along it), ``friction`` the P joints with friction and
    ``normal_cols`` the column of each one's normal force."""

    where: dict
    axis: dict
    slide_speed: dict
    friction: tuple
    normal_cols: dict

    def friction_share(self, j, sigma, steps=slice(None)):
        """Friction's share of the guide's force per unit normal force, at ``steps``: on
        the guide it pulls along the block's sliding velocity, mu |N| sign(v) with
        |N| = sigma N (``sigma`` over those steps)."""
        return sigma[j.id] * np.sign(self.slide_speed[j.id][steps]) * j.friction


def _joint_geometry(chain, layout, state):
    """The joints' points, the P joints' axes and sliding speeds (see :class:`_Joints`)."""
    where, slide_speed, axis = {}, {}, {}
    for j in chain.joints:
        link = j.links[1] if j.kind == "P" else (layout.fixed if layout.fixed in j.links
                                                 else j.links[0])
        where[j.id] = state.links[link].moved(layout.drawn(j.at))
    for j in chain.joints:
        if j.kind == "P":
            t = state.direction(j.links[0], j.axis)
            axis[j.id] = t
            q = where[j.id]
            vb = state.links[j.links[1]].velocity_at(q)
            vg = state.links[j.links[0]].velocity_at(q)
            slide_speed[j.id] = (vb[0] - vg[0]) * t[0] + (vb[1] - vg[1]) * t[1]
    friction = tuple(j for j in chain.joints if j.kind == "P" and j.friction)
    normal_cols = {j.id: next(c for c, (kind, jj, _) in enumerate(layout.cols)
                              if kind == "N" and jj.id == j.id) for j in friction}
    return _Joints(where, axis, slide_speed, friction, normal_cols)


def _at_rest(joints, layout, state):
    """Per friction joint, the steps where its slide is at rest."""
    return {j.id: ~(np.abs(joints.slide_speed[j.id]) > 1e-12 * max(layout.size, 1e-12) *
                    _speed_scale(state)) for j in joints.friction}


# -- the matrix -------------------------------------------------------------------------------
def _base_matrix(layout, joints):
    """The equilibrium matrix without friction: one column per unknown."""
    n = layout.n
    one, zero = np.ones(n), np.zeros(n)
    a = np.zeros((n, layout.rows, len(layout.cols)))
    where, axis = joints.where, joints.axis
    for c, (kind, j, k) in enumerate(layout.cols):
        if kind in ("Fx", "Fy"):
            f = (one, zero) if kind == "Fx" else (zero, one)
            q = where[j.id]
            layout.put(a, j.links[k], c, f, q)
            layout.put(a, j.links[-1], c, f, q, -1.0)
        elif kind == "N":
            t = axis[j.id]
            layout.put(a, j.links[0], c, (-t[1], t[0]), where[j.id])
            layout.put(a, j.links[1], c, (-t[1], t[0]), where[j.id], -1.0)
        elif kind == "M":
            layout.put_couple(a, j.links[0], c, one * layout.size)
            layout.put_couple(a, j.links[1], c, one * layout.size, -1.0)
        elif j.kind == "R":                      # an R input's effort: a couple
            layout.put_couple(a, j.b, c, one)
            layout.put_couple(a, j.a, c, one, -1.0)
        else:                                    # a P input's effort: along the guide
            t = axis[j.joint]
            layout.put(a, j.b, c, t, where[j.joint])
            layout.put(a, j.a, c, t, where[j.joint], -1.0)
    return a


def _with_friction(layout, joints, base, sigma, steps=slice(None)):
    """The matrix at ``steps`` with the friction forces for the signs ``sigma`` of the
    normal forces (per friction joint, arrays over those steps)."""
    if not joints.friction:
        return base[steps]
    a = base[steps].copy()
    for j in joints.friction:
        t, c, where = joints.axis[j.id], joints.normal_cols[j.id], joints.where[j.id]
        s = joints.friction_share(j, sigma, steps)
        f = (s * t[0][steps], s * t[1][steps])
        q = (where[0][steps], where[1][steps])
        layout.put(a, j.links[0], c, f, q)
        layout.put(a, j.links[1], c, f, q, -1.0)
    return a


# -- the known forces: gravity, loads, inertia (d'Alembert) ----------------------------------
@dataclass(frozen=True)
class _Known:
    """The known forces: ``rhs`` their share of each equation, ``power`` theirs (W),
    ``applied`` (link, what, point, force) and ``couples`` (link, what, value)."""

    rhs: np.ndarray
    power: np.ndarray
    applied: list
    couples: list


def _known_forces(chain, layout, state, joints, *, static):
    """Gravity, the loads and (unless ``static``) the inertia forces and couples."""
    known = _Known(np.zeros((layout.n, layout.rows, 1)), np.zeros(layout.n), [], [])
    _masses(chain, layout, state, known, static=static)
    _loads(chain, layout, state, joints, known)
    return replace(known, rhs=known.rhs[:, :, 0])


def _masses(chain, layout, state, known, *, static):
    """Each moving link's weight and, unless ``static``, its inertia force and couple."""
    one, zero = np.ones(layout.n), np.zeros(layout.n)
    g = chain.gravity or (0.0, 0.0)
    for mass in chain.masses:
        link = mass.link
        if link == layout.fixed:
            continue
        motion = state.links[link]
        q = motion.moved(layout.drawn(mass_centre(chain, mass)))
        v = motion.velocity_at(q)
        f = (mass.mass * g[0] * one, mass.mass * g[1] * one)
        if chain.gravity is not None and mass.mass:
            known.applied.append((link, "weight", q, f))
        couple = zero
        if not static:
            acc = motion.acceleration_at(q)
            inertia = (-mass.mass * acc[0], -mass.mass * acc[1])
            known.applied.append((link, "inertia force", q, inertia))
            f = (f[0] + inertia[0], f[1] + inertia[1])
            couple = -mass.inertia * motion.alpha
            if mass.inertia:
                known.couples.append((link, "inertia couple", couple))
        layout.put(known.rhs, link, 0, f, q)
        layout.put_couple(known.rhs, link, 0, couple)
        known.power[:] += f[0] * v[0] + f[1] * v[1] + couple * motion.omega


def _loads(chain, layout, state, joints, known):
    """The loads' forces and torques on the moving links."""
    one = np.ones(layout.n)
    for load in chain.loads:
        link = load.on
        if link == layout.fixed:
            continue
        if load.force is not None:
            if load.at in joints.where:
                q = joints.where[load.at]
            else:
                q = state.links[link].moved(layout.drawn(chain.point(load.at).at))
            f = (load.force[0] * one, load.force[1] * one)
            known.applied.append((link, "load", q, f))
            layout.put(known.rhs, link, 0, f, q)
            v = state.links[link].velocity_at(q)
            known.power[:] += f[0] * v[0] + f[1] * v[1]
        if load.torque:
            known.couples.append((link, "load", load.torque * one))
            layout.put_couple(known.rhs, link, 0, load.torque * one)
            known.power[:] += load.torque * state.links[link].omega


# -- the solve, iterating the friction signs ------------------------------------------------
def _known_singular(layout, state):
    """The steps the motion says are singular (its rates not finite there), when its
    rates are the solver's own; else None."""
    if not state.rates_known:
        return None
    known = np.zeros(layout.n, dtype=bool)
    for link in layout.row:
        motion = state.links[link]
        known |= ~np.isfinite(motion.omega) | ~np.isfinite(motion.velocity[0])
    return known


def _signs(x, col):
    """The sign (+1 or -1) of the unknown in column ``col`` at every step."""
    return np.where(x[:, col] < 0, -1.0, 1.0)


def _solve_with_friction(layout, joints, b, known):
    """x, the singular steps, the steps whose friction signs settled and the signs
    ``sigma`` (per friction joint): the signs iterated until they agree with the
    normal forces', then every combination tried at the steps that did not settle."""
    base = _base_matrix(layout, joints)
    sigma = {j.id: np.ones(layout.n) for j in joints.friction}
    x, singular = _solve(_with_friction(layout, joints, base, sigma), b, known)
    settled = np.ones(layout.n, dtype=bool)
    if not joints.friction:
        return x, singular, settled, sigma
    cols = joints.normal_cols
    for _ in range(8):
        new = {k: _signs(x, cols[k]) for k in sigma}
        if all((new[k] == sigma[k]).all() for k in sigma):
            break
        sigma = new
        x, singular = _solve(_with_friction(layout, joints, base, sigma), b, known)
    for k in sigma:
        settled &= (_signs(x, cols[k]) == sigma[k]) | (x[:, cols[k]] == 0)
    if not settled.all():
        _every_sign(layout, joints, base, b, known, (x, singular, settled, sigma))
    return x, singular, settled, sigma


def _every_sign(layout, joints, base, b, known, found):
    """Try every combination of friction signs at the steps that did not settle; where
    one agrees with its normal forces, take it (``found``: x, singular, settled and
    sigma, updated in place)."""
    x, singular, settled, sigma = found
    cols = joints.normal_cols
    bad = np.nonzero(~settled)[0]
    for combo in itertools.product((1.0, -1.0), repeat=len(sigma)):
        trial = {k: np.full(bad.size, s) for k, s in zip(sigma, combo)}
        xs, sing = _solve(_with_friction(layout, joints, base, trial, bad), b[bad],
                          None if known is None else known[bad])
        ok = np.ones(bad.size, dtype=bool)
        for k, s in zip(sigma, combo):
            ok &= _signs(xs, cols[k]) == s
        done = bad[ok]
        x[done], singular[done], settled[done] = xs[ok], sing[ok], True
        for k, s in zip(sigma, combo):
            sigma[k][done] = s
        if settled.all():
            break


# -- the results --------------------------------------------------------------------------
def _reactions(chain, layout, joints, x, sigma):
    """(forces, normal, couple, efforts) from the unknowns ``x`` (see :class:`Solution`)."""
    forces, normal, couple, efforts = {}, {}, {}, {}
    for c, (kind, j, k) in enumerate(layout.cols):
        if kind == "Fx":
            forces[(j.id, j.links[k])] = (x[:, c], x[:, c + 1])
        elif kind == "N":
            t = joints.axis[j.id]
            d = (-t[1], t[0])
            nn = x[:, c]
            f = (nn * d[0], nn * d[1])
            if j.friction:
                s = joints.friction_share(j, sigma)
                f = (f[0] + s * nn * t[0], f[1] + s * nn * t[1])
            forces[(j.id, j.links[0])] = f
            normal[j.id] = nn
            couple[j.id] = x[:, c + 1] * layout.size
        elif kind == "effort":                  # a couple (N m) or a force (N)
            efforts[j.joint] = x[:, c]
    for j in chain.joints:
        if j.kind == "R" and len(j.links) > 2:
            parts = [forces[(j.id, link)] for link in j.links[:-1]]
            forces[(j.id, j.links[-1])] = (-sum(p[0] for p in parts), -sum(p[1] for p in parts))
    return forces, normal, couple, efforts


def _power_balance(plan, state, joints, power, efforts, normal):
    """The efforts' power plus that of gravity, loads and inertia (``power``) and of
    friction (minus |friction| |slide speed|): zero where the solve holds."""
    total = power.copy()
    for item in plan.inputs:
        total = total + efforts[item.joint] * state.rates[item.joint]
    for j in joints.friction:
        fr = j.friction * np.abs(normal[j.id])
        total = total - fr * np.abs(joints.slide_speed[j.id])
    return total


def _with_efforts(plan, joints, efforts, known):
    """The applied forces and couples with the efforts, as applied to each input's
    link (a couple for an R input, a force along the guide for a P input)."""
    applied, couples = list(known.applied), list(known.couples)
    for item in plan.inputs:
        if item.kind == "R":
            couples.append((item.b, f"effort {item.joint}", efforts[item.joint]))
        else:
            t = joints.axis[item.joint]
            e = efforts[item.joint]
            applied.append((item.b, f"effort {item.joint}", joints.where[item.joint],
                            (e * t[0], e * t[1])))
    return tuple(applied), tuple(couples)


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
