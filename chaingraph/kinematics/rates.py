"""Velocities and accelerations: the constraint Jacobian times the rates equals the known
links' terms (and, for accelerations, the quadratic velocity terms).

Per step this is an exact linear solve: each link's constraint to a known link leaves it
one free rate (a null-space direction), and the dyad's own joint gives a 2 x 2 system in
those two rates; a group is solved whole. Where that system is singular (a dead centre)
the rates are NaN, never a finite wrong number.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from chaingraph.geometry import Scalar, turn_by
from chaingraph.kinematics.equations import (
    batched_inverse,
    constraint_gammas,
    constraint_geometry,
    constraint_rows,
    dot3,
    group_form,
    group_matrix,
    minus,
    plus,
    times,
)
from chaingraph.kinematics.equations import Pose, Rates
from chaingraph.kinematics.plan import Plan, Step

__all__ = ["rates"]


_SINGULAR = 1e-4          # velocities are NaN below this normalized determinant
_SINGULAR_ACC = 1e-3      # accelerations below this (their error grows as its cube)
_SINGULAR_GROUP = 1e-12   # a group's inverse Frobenius condition number
_POINT_DYADS = True      # RRR dyads in point coordinates (tests compare both ways)


def _column_free_det(p11, p12, p21, p22):
    """The 2 x 2 determinant over the product of its column lengths: the signed sine of
    the angle between the columns, 0 when singular whatever the units of the rates.
    (A tangency leaves positions accurate to about the square root of the rounding
    error, so rates are refused (NaN) below ``_SINGULAR``, not at zero only: near a
    tangency a position error e becomes about e / d in velocities and e / d**3 in
    accelerations, for the normalized determinant d.)"""
    return (p11 * p22 - p12 * p21) / ((np.sqrt(p11 * p11 + p21 * p21) + 1e-300) *
                                       (np.sqrt(p12 * p12 + p22 * p22) + 1e-300))


class _PointDyad:
    """An RRR dyad in the coordinates of its middle joint X: the constraints
    (X - W_a) . (dX - dW_a) = 0 and (X - W_b) . (dX - dW_b) = 0 make a 2 x 2 Jacobian
    [u_a; u_b], solved by Cramer's rule for velocities and again for accelerations; the
    links' rates follow from X's. The same answers as the general reduction in far fewer
    array operations, for the commonest dyad."""

    # X's velocity relative to each known joint, kept by the velocity solve for the
    # acceleration's centripetal terms (solve_velocity runs before solve_acceleration)
    _rel_a: tuple[Scalar, Scalar]
    _rel_b: tuple[Scalar, Scalar]

    def __init__(self, step, pose, n, size):
        self.step = step
        a, b = step.links
        ca, cb, cj = step.constraints
        self.ka, self.kb = ca.other(a), cb.other(b)
        self.pa, self.pb, self.q = ca.point, cb.point, cj.point
        self.ra_k = turn_by(pose[self.ka], self.pa)
        self.rb_k = turn_by(pose[self.kb], self.pb)
        wa = (self.ra_k[0] + pose[self.ka][0], self.ra_k[1] + pose[self.ka][1])
        wb = (self.rb_k[0] + pose[self.kb][0], self.rb_k[1] + pose[self.kb][1])
        self.rq = {a: turn_by(pose[a], self.q), b: turn_by(pose[b], self.q)}
        x = (self.rq[a][0] + pose[a][0], self.rq[a][1] + pose[a][1])
        self.wa, self.x = wa, x
        self.ua = (x[0] - wa[0], x[1] - wa[1])
        self.ub = (x[0] - wb[0], x[1] - wb[1])
        (ua0, ua1), (ub0, ub1) = self.ua, self.ub
        det = ua0 * ub1 - ua1 * ub0
        self.ra2 = ua0 * ua0 + ua1 * ua1
        self.rb2 = ub0 * ub0 + ub1 * ub1
        self.singular = det * det <= _SINGULAR ** 2 * self.ra2 * self.rb2
        # (np.where only where a pose is singular: most sweeps have none)
        self.any_singular = bool(np.any(self.singular))
        self.det = np.where(self.singular, 1.0, det) if self.any_singular else det
        self._det = det
        self._measure: Scalar | None = None

    @property
    def measure(self):
        if self._measure is None:
            self._measure = self._det / np.sqrt(self.ra2 * self.rb2)
        return self._measure

    @staticmethod
    def _known_point(table, link, r, second=None):
        v = table[link]
        if second is None:      # velocity of the point: v + w perp(R p)
            return minus(v[0], times(v[2], r[1])), plus(v[1], times(v[2], r[0]))
        w = second[link][2]     # acceleration: a + alpha perp(R p) - w^2 R p
        w2 = times(w, w)
        return (minus(minus(v[0], times(v[2], r[1])), times(w2, r[0])),
                minus(plus(v[1], times(v[2], r[0])), times(w2, r[1])))

    def solve_velocity(self, vel):
        dwa = self._known_point(vel, self.ka, self.ra_k)
        dwb = self._known_point(vel, self.kb, self.rb_k)
        self._at_wa = [dwa]                  # the known joint's rate, then acceleration
        self._at_x = []                      # the joint's own, the same
        return self._solve(dwa, dwb, 0.0, 0.0, second=False)

    def solve_acceleration(self, acc, vel):
        dwa = self._known_point(acc, self.ka, self.ra_k, vel)
        dwb = self._known_point(acc, self.kb, self.rb_k, vel)
        ga, gb = _sq(self._rel_a), _sq(self._rel_b)
        self._at_wa.append(dwa)
        return self._solve(dwa, dwb, ga, gb, second=True, vel=vel)

    def points(self, near: Scalar = False) -> dict:
        """The points the solve went through, after both solves (``near``: where the
        accelerations are refused): the joint between the two links, on each, and the
        first link's joint on its known link, by (link, point) as
        :class:`~chaingraph.kinematics.columns.LinkStates` holds them."""
        if any(c.point_b is not None for c in self.step.constraints):
            return {}           # (a link's point of a joint differs from the other's)
        (vwa, awa), (vx, ax) = self._at_wa, self._at_x
        if np.any(near):
            ax = tuple(np.where(near, np.nan, v) for v in ax)
        a, b = self.step.links
        at_x = (*self.x, *vx, *ax)
        return {(a, self.q): at_x, (b, self.q): at_x,
                (self.ka, self.pa): (*self.wa, *vwa, *awa)}

    def _solve(self, dwa, dwb, ga, gb, *, second, vel=None):
        # (``times``, ``plus`` and ``minus`` skip the terms of a known joint at rest)
        (ua0, ua1), (ub0, ub1) = self.ua, self.ub
        ca = minus(plus(times(ua0, dwa[0]), times(ua1, dwa[1])), ga)
        cb = minus(plus(times(ub0, dwb[0]), times(ub1, dwb[1])), gb)
        dx = minus(times(ca, ub1), times(ua1, cb)) / self.det
        dy = minus(times(ua0, cb), times(ca, ub0)) / self.det
        if self.any_singular:
            dx = np.where(self.singular, np.nan, dx)
            # (dy stays: it is what the links' rates are worked out from, as before;
            # the joint's own, as its links' rates give it, is NaN there too)
            self._at_x.append((dx, np.where(self.singular, np.nan, dy)))
        else:
            self._at_x.append((dx, dy))
        a, b = self.step.links
        out = {}
        for link, u, dw, r2 in ((a, self.ua, dwa, self.ra2), (b, self.ub, dwb, self.rb2)):
            rel = (minus(dx, dw[0]), minus(dy, dw[1]))
            w = (u[0] * rel[1] - u[1] * rel[0]) / r2
            rq = self.rq[link]
            if not second:
                setattr(self, "_rel_a" if link == a else "_rel_b", rel)
                out[link] = (dx + w * rq[1], dy - w * rq[0], w)
            else:
                w0 = vel[link][2]
                w02 = w0 * w0
                out[link] = (dx + w * rq[1] + w02 * rq[0],
                             dy - w * rq[0] + w02 * rq[1], w)
        return out


class _Weld:
    """A link welded to a known link by an input joint: its rates are the known link's
    carried to the joint, plus the input's own (a relative rotation about the joint,
    or a slide along the guide with its Coriolis term), in closed form."""

    measure = 1.0           # an input's weld always determines the link

    def __init__(self, step, pose):
        self.step = step
        self.u = step.links[0]
        self.c = c = step.constraints[0]
        self.k = c.other(self.u)
        self.sign = 1.0 if self.u == c.b else -1.0
        self.rk = turn_by(pose[self.k], c.point)       # the joint's point from each link
        self.ru = turn_by(pose[self.u], c.point)
        if c.kind == "P":
            self.delta = pose[c.drive][2]
            self.t = turn_by(pose[self.k], (math.cos(math.radians(c.axis)),
                                           math.sin(math.radians(c.axis))))

    def solve_velocity(self, vel):
        c, k, sg = self.c, self.k, self.sign
        vk, wk, rate = vel[k], vel[k][2], vel[c.drive][2]
        px = vk[0] - wk * self.rk[1]                  # the joint's point on k
        py = vk[1] + wk * self.rk[0]
        if c.kind == "R":
            w = wk + sg * rate
        else:
            w = wk
            t, d = self.t, self.delta
            px = px + sg * (rate * t[0] - d * wk * t[1])
            py = py + sg * (rate * t[1] + d * wk * t[0])
        return {self.u: (px + w * self.ru[1], py - w * self.ru[0], w)}

    def solve_acceleration(self, acc, vel):
        c, k, sg = self.c, self.k, self.sign
        ak, wk, alk = acc[k], vel[k][2], acc[k][2]
        rate, rate2 = vel[c.drive][2], acc[c.drive][2]
        rk, ru = self.rk, self.ru
        ax = ak[0] - alk * rk[1] - wk * wk * rk[0]
        ay = ak[1] + alk * rk[0] - wk * wk * rk[1]
        if c.kind == "R":
            w, al = wk + sg * rate, alk + sg * rate2
        else:
            w, al = wk, alk
            t, d = self.t, self.delta
            pt = (-t[1], t[0])
            ax = ax + sg * (rate2 * t[0] + 2 * rate * wk * pt[0] + d * (alk * pt[0] - wk * wk * t[0]))
            ay = ay + sg * (rate2 * t[1] + 2 * rate * wk * pt[1] + d * (alk * pt[1] - wk * wk * t[1]))
        return {self.u: (ax + al * ru[1] + w * w * ru[0], ay - al * ru[0] + w * w * ru[1], al)}


def _sq(v):
    return v[0] * v[0] + v[1] * v[1]


class Factor:
    """One step's constraint Jacobian, factored once for the velocity and acceleration
    solves (which differ only in their right-hand sides)."""

    def __init__(self, step: Step, pose: Pose, n: int, size: float) -> None:
        self.step = step
        self.n = n
        self.rows = []                       # (unknown coefficients, known coefficients)
        if step.kind == "group":
            self.form = group_form(step)
            unknowns = self.form.bodies
            coefs = self.form.rows(pose)
        else:
            self.geometry = [constraint_geometry(c, pose) for c in step.constraints]
            unknowns = step.links
            coefs = [coef for c, geom in zip(step.constraints, self.geometry)
                     for coef in constraint_rows(c, pose, geom)]
        for coef in coefs:
            unknown = {k: v for k, v in coef.items() if k in unknowns}
            known = {k: v for k, v in coef.items() if k not in unknowns}
            self.rows.append((unknown, known))
        if step.kind == "single":
            u = step.links[0]
            self.null = _NullSpace(self.rows[0][0][u], self.rows[1][0][u])
            self.extra = [dot3(r[0][u], self.null.e) for r in self.rows[2:]]
            den = sum(m * m for m in self.extra)
            # an input's weld always determines the link (its row and the null direction
            # are in different units, so no ratio of them means anything)
            self.singular = (np.abs(den) <= _SINGULAR ** 2 * (dot3(self.null.e, self.null.e))
                             if step.pattern[0] != "W" else np.zeros(n, dtype=bool))
            self.den = np.where(self.singular, 1.0, den)
        elif step.kind == "dyad":
            a, b = step.links
            self.null_a = _NullSpace(self.rows[0][0][a], self.rows[1][0][a])
            self.null_b = _NullSpace(self.rows[2][0][b], self.rows[3][0][b])
            p = []
            for unknown, _ in self.rows[4:6]:
                pa = dot3(unknown[a], self.null_a.e) if a in unknown else 0.0 * n
                pb = dot3(unknown[b], self.null_b.e) if b in unknown else 0.0 * n
                p.append((pa, pb))
            (p11, p12), (p21, p22) = p
            w = size if step.constraints[2].kind == "P" else 1.0  # angle row in lengths
            self._weighted = (w * p11, w * p12, p21, p22)
            det = p11 * p22 - p12 * p21
            wdet = w * det
            self.singular = wdet * wdet <= _SINGULAR ** 2 * (
                (w * w * p11 * p11 + p21 * p21) * (w * w * p12 * p12 + p22 * p22))
            self.p = (p11, p12, p21, p22, np.where(self.singular, 1.0, det))
        else:
            self.mat, _ = group_matrix(self.form.bodies, [(u, 0.0) for u, _ in self.rows], n)
            m = self.mat
            self.normal = m.shape[1] != m.shape[2]
            if self.normal:
                m = np.einsum("nij,nik->njk", self.mat, self.mat)
            inv = batched_inverse(m)
            # 1 / (Frobenius condition number): 0 when singular, whatever the scale
            measure = 1.0 / (np.sqrt((m * m).sum(axis=(1, 2)) *
                                     (inv * inv).sum(axis=(1, 2))) + 1e-300)
            self._measure = np.where(np.isfinite(measure), measure, 0.0)
            self.singular = self._measure <= _SINGULAR_GROUP
            self.inverse = inv
            if not self.normal:
                # signed, so that a dead centre is a change of sign: the determinant
                # over the product of the column lengths (the columns' units cancel)
                good = np.isfinite(self.mat).all(axis=(1, 2))
                signed = np.zeros(n)
                if good.any():
                    mg = self.mat[good]
                    signed[good] = np.linalg.det(mg) / (
                        np.prod(np.linalg.norm(mg, axis=1), axis=1) + 1e-300)
                self._measure = signed

    @property
    def measure(self) -> Scalar:
        """The step's normalized determinant along the sweep (0 at a dead centre;
        signed, except for a group with more equations than unknowns)."""
        if self.step.kind == "single":
            return np.where(self.singular, 0.0, 1.0)
        if self.step.kind == "dyad":
            return _column_free_det(*self._weighted)
        return self._measure

    def solve(self, rhs: Sequence[Scalar]) -> dict[str, tuple[Scalar, Scalar, Scalar]]:
        """Rates of the step's links for right-hand sides ``rhs`` (one per row)."""
        step = self.step
        if step.kind == "single":
            u = step.links[0]
            q0 = self.null.particular(rhs[0], rhs[1])
            num = 0.0
            for m, (unknown, _), r in zip(self.extra, self.rows[2:], rhs[2:]):
                num = num + m * (r - dot3(unknown[u], q0))
            z = np.where(self.singular, np.nan, num / self.den)
            e = self.null.e
            return {u: tuple(q0[i] + z * e[i] for i in range(3))}
        if step.kind == "dyad":
            a, b = step.links
            qa = self.null_a.particular(rhs[0], rhs[1])
            qb = self.null_b.particular(rhs[2], rhs[3])
            r = []
            for (unknown, _), value in zip(self.rows[4:6], rhs[4:6]):
                if a in unknown:
                    value = value - dot3(unknown[a], qa)
                if b in unknown:
                    value = value - dot3(unknown[b], qb)
                r.append(value)
            p11, p12, p21, p22, det = self.p
            za = np.where(self.singular, np.nan, (r[0] * p22 - p12 * r[1]) / det)
            zb = np.where(self.singular, np.nan, (p11 * r[1] - p21 * r[0]) / det)
            ea, eb = self.null_a.e, self.null_b.e
            return {a: tuple(qa[i] + za * ea[i] for i in range(3)),
                    b: tuple(qb[i] + zb * eb[i] for i in range(3))}
        vec = np.stack([np.broadcast_to(v, (self.n,)) for v in rhs], axis=-1)
        if self.normal:
            vec = np.einsum("nij,ni->nj", self.mat, vec)
        x = np.einsum("nij,nj->ni", self.inverse, vec)
        x[self.singular] = np.nan
        return {link: (x[:, 3 * k], x[:, 3 * k + 1], x[:, 3 * k + 2])
                for k, link in enumerate(self.form.bodies)}

    def right_hand_sides(self, rates_known: Rates,
                         gammas: Sequence[Scalar] | None = None) -> list[Scalar]:
        """Each row's right-hand side: its quadratic term ``gammas[i]`` (0 for the
        velocities) less the known links' terms from ``rates_known``."""
        out = []
        for i, (_, known) in enumerate(self.rows):
            value = gammas[i] if gammas is not None else 0.0
            for link, cf in known.items():
                value = value - dot3(cf, rates_known[link])
            out.append(value)
        return out


class _NullSpace:
    """Two rows on one link's three rates: their null direction and a particular solution.

    The particular solution is solved on the two columns whose 2 x 2 minor is largest
    (those minors are the null direction's components), not through the rows' Gram
    matrix, which squares the conditioning: a rotation column carries the drawing's
    absolute coordinates, so far from the origin the Gram determinant cancels to 0.
    """

    def __init__(self, m1, m2):
        self.m1, self.m2 = m1, m2
        self.e = (minus(times(m1[1], m2[2]), times(m1[2], m2[1])),
                  minus(times(m1[2], m2[0]), times(m1[0], m2[2])),
                  minus(times(m1[0], m2[1]), times(m1[1], m2[0])))
        self.drop = np.argmax(np.abs(np.array(np.broadcast_arrays(*self.e), dtype=float)),
                              axis=0)

    def particular(self, c1, c2):
        m1, m2 = self.m1, self.m2
        y: list[Scalar] = [0.0, 0.0, 0.0]
        with np.errstate(divide="ignore", invalid="ignore"):
            for i in range(3):
                use = self.drop == i
                if not np.any(use):
                    continue
                j, k = (i + 1) % 3, (i + 2) % 3
                det = np.asarray(self.e[i], dtype=float)        # m1[j] m2[k] - m1[k] m2[j]
                yj = (c1 * m2[k] - c2 * m1[k]) / det
                yk = (m1[j] * c2 - m2[j] * c1) / det
                y[j] = np.where(use, yj, y[j])
                y[k] = np.where(use, yk, y[k])
        return tuple(y)



def rates(plan: Plan, pose: Pose, omega: float, n: int, *,
          steps: Sequence[Step] | None = None, measure: bool = True,
          accelerations: bool = True, points: dict | None = None
          ) -> tuple[dict[str, tuple[Scalar, Scalar, Scalar]],
                     dict[str, tuple[Scalar, Scalar, Scalar]], np.ndarray | None]:
    """Velocities and accelerations of every link with the inputs at constant rates,
    the lead input's ``omega`` (rad/s for an R input, length units/s for a P input;
    the other inputs in proportion, as they move together along the sweep).

    Returns
    -------
    vel, acc : dict link -> (vx, vy, omega) and (ax, ay, alpha) arrays (the fixed
        link's as zeros), plus each input's entry (its rate in the rotation's place)
    singularity : (S, N) array, each step's normalized determinant (0 at a dead
        centre); None unless ``measure``

    With ``accelerations=False`` the accelerations are left out. ``points``, a dict,
    gets the points the solve goes through (an RRR dyad's joints), by (link, point in
    the plan's frame): (x, y, vx, vy, ax, ay) (see
    :class:`~chaingraph.kinematics.columns.LinkStates`).
    """
    zero = np.zeros(n)
    tau_rate = omega / plan.rate_scale          # d(tau)/dt, "degrees" per second
    vel: dict[str, tuple[Scalar, Scalar, Scalar]] = {plan.fixed: (0.0, 0.0, 0.0)}
    acc: dict[str, tuple[Scalar, Scalar, Scalar]] = {plan.fixed: (0.0, 0.0, 0.0)}
    for item, (_, k) in zip(plan.inputs, plan.line):
        vel[item.key] = (0.0, 0.0, k * tau_rate)
        acc[item.key] = (0.0, 0.0, 0.0)
    late = [d for d in plan.derived if not d.ready(vel)]    # driven through the linkage
    early = [d for d in plan.derived if d.key not in {x.key for x in late}]
    for d in early:                # a higher pair's joint: by the chain rule
        vel[d.key], acc[d.key] = d.rates(pose, vel, acc)
    measures: list[np.ndarray] = []           # left empty unless ``measure``
    factors: list[_PointDyad | _Weld | Factor] = []
    f: _PointDyad | _Weld | Factor
    for step in (plan.steps if steps is None else steps):
        for d in late:             # its rate once its links' are known
            if d.key not in vel and d.ready(vel):
                vel[d.key] = d.velocity(pose, vel)
        if step.kind == "dyad" and step.pattern == "RRR" and _POINT_DYADS:
            f = _PointDyad(step, pose, n, plan.size)
            vel.update(f.solve_velocity(vel))
        elif step.pattern[0] == "W" and _POINT_DYADS:
            f = _Weld(step, pose)
            vel.update(f.solve_velocity(vel))
        else:
            f = Factor(step, pose, n, plan.size)
            vel.update(f.solve(f.right_hand_sides(vel)))
            if step.kind == "group":
                vel.update(f.form.bar_rates(pose, vel))
        factors.append(f)
        if measure:
            measures.append(np.broadcast_to(f.measure, (n,)))
    for f in (factors if accelerations else []):
        for d in late:             # its acceleration once its links' are known
            if d.key not in acc and d.ready(acc):
                acc[d.key] = d.rates(pose, vel, acc)[1]
        if isinstance(f, _Weld):
            acc.update(f.solve_acceleration(acc, vel))
            continue
        if isinstance(f, _PointDyad):
            found = f.solve_acceleration(acc, vel)
            near = _near_singular(f)
            acc.update(_refused(near, found))
            if points is not None:
                points.update(f.points(near))
            continue
        if f.step.kind == "group":
            acc.update(f.solve(f.right_hand_sides(acc, f.form.gammas(pose, vel))))
            acc.update(f.form.bar_rates(pose, vel, acc))
            continue
        gammas = [g for c, geom in zip(f.step.constraints, f.geometry)
                  for g in constraint_gammas(c, pose, vel, geom)]
        acc.update(_refuse_near_singular(f, f.solve(f.right_hand_sides(acc, gammas))))
    for table in (vel, acc):
        table[plan.fixed] = (zero, zero, zero)
    return vel, acc, (np.array(measures) if measure else None)


def _refuse_near_singular(factor, found):
    """NaN accelerations where a dyad is too near a singular pose for them to be exact."""
    if factor.step.kind != "dyad":
        return found
    return _refused(_near_singular(factor), found)


def _near_singular(factor):
    """Where a dyad is too near a singular pose for its accelerations to be exact."""
    return np.abs(factor.measure) < _SINGULAR_ACC


def _refused(near, found):
    """``found`` (link -> rates) with NaN where ``near``."""
    if not np.any(near):
        return found
    return {link: tuple(np.where(near, np.nan, v) for v in values)
            for link, values in found.items()}

