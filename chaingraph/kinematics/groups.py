"""Groups of higher class (Assur groups that no closed form solves, such as the triad
of Stephenson's third inversion): Newton's method, and continuation along the path.

A coarse trace of the group's branch by pseudo-arclength continuation follows the
assembly mode and finds a fold (the input turns back: the path cannot go on); every point
is then corrected at once by batched Newton from Hermite-interpolated guesses.
"""

from __future__ import annotations

import math
import weakref
from typing import TYPE_CHECKING, Protocol

import numpy as np
from numpy.typing import ArrayLike

from chaingraph.kinematics.equations import (
    Pose,
    batched_inverse,
    dot3,
    group_form,
    group_jacobian,
    group_residual,
    group_rows_at,
    newton_step,
    pose_at_point,
    slice,
    with_group,
)
from chaingraph.kinematics.plan import Plan, Step
from chaingraph.kinematics.rates import rates

if TYPE_CHECKING:                       # tracking imports this module
    from chaingraph.kinematics.tracking import Evaluation


class Scaled(Protocol):
    """What Newton's method reads of a plan: the size its tolerances are relative to
    (a :class:`Plan`, or the assembly's stand-in for one)."""

    @property
    def size(self) -> float: ...


def _chord(plan, step, known, q, iterations=8):
    """Newton's method with the Jacobian inverted once at the guesses (the chord
    method): cheap for many points near their solutions. Returns (q, converged:
    residual <= 1e-11 of the size)."""
    tol = 1e-12 * plan.size
    full = with_group(known, step, q)
    mat = group_jacobian(step, full, q.shape[0])
    if mat.shape[1] != mat.shape[2]:
        return q, np.zeros(q.shape[0], dtype=bool)
    inv = batched_inverse(mat)
    q = q.copy()
    for _ in range(iterations):
        r = group_residual(step, with_group(known, step, q))
        q -= np.einsum("nij,nj->ni", inv, r)   # one more step after tol: to the rounding
        if np.all(np.abs(r).max(axis=1) <= tol):
            break
    err = np.abs(group_residual(step, with_group(known, step, q))).max(axis=1)
    # converged to near the rounding, as Newton's method takes a point: the chord's
    # convergence is linear, and a point it left at 1e-9 of the size (near a fold) is
    # finished by Newton's method, not taken as it is (its joints would close only to
    # about that, and the check of the poses asks 1e-9 of their distance)
    return q, err <= 1e-11 * plan.size


def newton(plan: Scaled, step: Step, known: Pose, q: np.ndarray, iterations: int = 40,
           tol_rel: float = 1e-12) -> tuple[np.ndarray, np.ndarray]:
    """Batched Newton's method on the group's loop-closure equations; each point
    iterates until its residual is below 1e-12 of the size (linear convergence at a
    fold needs more iterations than elsewhere, so only unconverged points go on).
    Returns (q, converged: residual <= 1e-9 of the size)."""
    n = q.shape[0]
    q = q.copy()
    tol = tol_rel * plan.size
    active = np.arange(n)
    last = np.full(n, np.inf)
    for it in range(iterations):
        sub = slice(known, active) if active.size < n else known
        full = with_group(sub, step, q[active])
        r = group_residual(step, full)
        err = np.abs(r).max(axis=1)
        # go on where not converged and still improving (a fold converges linearly)
        todo = (err > tol) & np.isfinite(err) & ((it < 4) | (err < 0.9 * last[active]))
        last[active] = err
        if not todo.any():
            break
        active, r = active[todo], r[todo]
        full = slice(full, np.nonzero(todo)[0])
        q[active] += newton_step(group_jacobian(step, full, active.size), r)
    full = with_group(known, step, q)
    err = np.abs(group_residual(step, full)).max(axis=1)
    return q, err <= 1e-9 * plan.size



def newton_path(plan: Plan, step: Step, pose: Pose, theta: np.ndarray, q0: ArrayLike,
                coarse_deg: float = 10.0, *, head: Evaluation
                ) -> tuple[np.ndarray, np.ndarray, tuple[float, np.ndarray] | None]:
    """Group coordinates along the path, from q0 at its first point.

    A coarse trace of the group's branch by pseudo-arclength continuation (steps of
    at most ``coarse_deg`` in scaled coordinates) follows the assembly mode through
    places where the input angle alone would be a poor parameter, and finds a fold
    (the input turns back: the path cannot go on); every point is then corrected at
    once by batched Newton from Hermite-interpolated guesses. Points past where the
    trace ends are infeasible.

    Returns (q, ok, fold): ``fold`` is the fold the trace found, (input degrees, q) on
    the arc to the bisection's precision, or None; a limit of the range is solved
    from it (:func:`fold_point`), not traced again on ever shorter paths.
    """
    n = theta.size
    q0 = np.asarray(q0, dtype=float)
    if n == 1:
        q, ok = newton(plan, step, pose, q0[None])
        return q, ok, None
    span = theta[-1] - theta[0]
    direction = 1.0 if span >= 0 else -1.0
    h = min(coarse_deg, max(abs(span) / 8.0, 1e-9))
    t = float(theta[0])
    known = _known_along(plan, step, pose, theta, np.array([t]), head)
    qi, ok = newton(plan, step, known, q0[None])
    if not ok[0]:
        return np.zeros((n, q0.size)), np.zeros(n, dtype=bool), None
    path = _Path(plan, step, pose, theta, head, direction, h)
    q, ok, fold = path.traced(0, qi[0])
    # past a fold the trace found, the branch does not go on: Newton's method from the
    # fold may land on another branch (a small group's, a quaternary joint chain's)
    past = (direction * (theta - fold[0]) > 1e-12 if fold is not None
            else np.zeros(n, dtype=bool))
    # near a fold the tangent blows up and guesses are poor: continue point by point,
    # approaching each point through ever finer substeps (a limit of the range is a
    # fold, where Newton's method converges only linearly). Where the trace ended
    # with no fold (a slide far out, a step that collapsed), the branch is traced
    # again from each point so reached, a few times, instead of approaching every
    # point left one by one (a trace that ended far out, where this point was
    # reached, goes on from here as far as the branch does)
    retraces = _RETRACES if fold is None else 0
    i = 1
    while i < n:
        if ok[i]:
            i += 1
            continue
        if not ok[i - 1] or past[i]:
            break
        if _filled_back(plan, step, pose, theta, head, q, ok, i, past):
            continue
        qi = _approach(plan, step, pose, theta, head, float(theta[i - 1]), q[i - 1],
                       float(theta[i]))
        if qi is None:
            break
        q[i], ok[i] = qi, True
        if retraces and i + 1 < n:
            retraces -= 1
            more_q, more_ok, more_fold = path.traced(i, qi, runaway=math.inf)
            run = _leading_run(more_ok[i + 1:])
            q[i + 1:i + 1 + run], ok[i + 1:i + 1 + run] = more_q[i + 1:i + 1 + run], True
            if more_fold is not None:
                fold, retraces = more_fold, 0
                past = direction * (theta - fold[0]) > 1e-12
        i += 1
    return q, ok, fold


#: how many times a path whose trace ended with no fold is traced again from a point
#: approached past its end
_RETRACES = 8


def _filled_back(plan, step, pose, theta, head, q, ok, i, past):
    """Fill the run of points from ``i`` that the trace's correction missed, when the
    trace's points go on after it: each approached from the next, back along the
    branch the trace followed (in place; True if the whole run was filled). From the
    point before the run instead, a path that starts next to a fold (a drawn pose a
    hair from its limit) would step out onto either of the two branches that meet
    there; the trace went along one."""
    j = i
    while j < theta.size and not ok[j] and not past[j]:
        j += 1
    if j == theta.size or not ok[j]:
        return False
    for m in range(j - 1, i - 1, -1):
        qm = _approach(plan, step, pose, theta, head, float(theta[m + 1]), q[m + 1],
                       float(theta[m]))
        if qm is None:
            return False
        q[m], ok[m] = qm, True
    return True


def _leading_run(ok):
    """How many of ``ok`` are True before the first False."""
    return ok.size if ok.all() else int(np.argmin(ok))


class _Path:
    """A group's path of input values ``theta``: its branch traced from a point and
    every point past it corrected at once (:meth:`traced`)."""

    def __init__(self, plan, step, pose, theta, head, direction, h):
        self.plan, self.step, self.pose, self.theta = plan, step, pose, theta
        self.head, self.direction, self.h = head, direction, h

    def traced(self, k, qk, runaway=None):
        """(q, ok, fold) along the whole path from ``qk`` at its point ``k``: the trace
        from there (ending ``runaway`` sizes out), and every point after it corrected
        from Hermite guesses (ok only there, up to where the trace reached, or to its
        fold)."""
        plan, step, pose, theta, direction = (self.plan, self.step, self.pose, self.theta,
                                              self.direction)
        ts, qs, dqs, fold = _traced_once(plan, step, pose, theta, self.head, qk,
                                         float(theta[k]), float(theta[-1]), direction,
                                         self.h, runaway)
        tc, qc, dqc = np.array(ts), np.array(qs), np.array(dqs)
        reached = direction * (theta - tc[-1]) <= 1e-9
        reached[:k] = False
        guess = _hermite(tc, qc, dqc, theta)
        if fold is not None:
            # between the trace's last point and the fold, q moves as the square root
            # of the input's distance from the fold: predict it so, on this side
            t_f, q_f = fold
            near = ~reached & (direction * (theta - t_f) <= 1e-12)
            near[:k] = False
            with np.errstate(invalid="ignore", divide="ignore"):
                frac = np.sqrt(np.clip((t_f - theta[near]) / (t_f - tc[-1]), 0.0, 1.0))
            guess[near] = q_f + (qc[-1] - q_f) * frac[:, None]
            reached = reached | near
        guess = np.where(np.isfinite(guess), guess, 0.0)
        if k == 0:
            q, ok = _chord(plan, step, pose, guess)
        else:
            q, ok = np.zeros_like(guess), np.zeros(theta.size, dtype=bool)
            at = np.arange(k, theta.size)
            q[at], ok[at] = _chord(plan, step, slice(pose, at), guess[at])
        if not ok[k:].all():
            redo = k + np.nonzero(~ok[k:])[0]
            q2, ok2 = newton(plan, step, slice(pose, redo), guess[redo])
            q[redo], ok[redo] = q2, ok2
        ok &= np.linalg.norm(q - guess, axis=1) <= 0.05 * plan.size
        ok &= reached
        return q, ok, fold


#: the traces of a plan's groups, by their start: the walk that finds a driver's cycle
#: and the sweep over the same turn (or to the limit the walk found) from the same pose
#: trace the same branch with the same steps (a trace depends only on where it starts,
#: its step and the head's modes, and on its end only within a step of it); the points
#: asked for are corrected from the trace, each to the rounding, whatever was traced
_TRACES: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()
_TRACES_KEPT = 32


def _traced_once(plan, step, pose, theta, head, q, t, end, direction, h, runaway):
    """:func:`_trace` from (t, q) to ``end``, kept per plan: a trace asked again, or
    one that went at least as far from the same start with the same step, is not
    traced again (only the first trace of a path is kept, not those to other runaway
    bounds)."""
    if runaway is not None:
        return _trace(plan, step, pose, theta, head, q, t, end, direction, h, runaway)
    key = (plan.steps.index(step), q.tobytes(), t, direction, h)
    kept = _TRACES.setdefault(plan, {})
    for (k, far), found in kept.items():
        if k == key and direction * (far - end) >= 0.0:
            return found
    found = _trace(plan, step, pose, theta, head, q, t, end, direction, h)
    if len(kept) >= _TRACES_KEPT:
        kept.pop(next(iter(kept)))
    kept[(key, end)] = found
    return found


class _Branch:
    """A group's equations in the scaled unknowns z = (q / scale, input in radians),
    for continuation along its branch."""

    def __init__(self, plan, step, pose, theta, head):
        self.plan, self.step, self.pose, self.theta, self.head = plan, step, pose, theta, head
        self.form = group_form(step)
        m = self.form.size
        self.scale = np.tile([plan.size, plan.size, 1.0], m // 3)
        self.head_steps = plan.steps[:plan.steps.index(step)]
        self._last = None

    def _at(self, z):
        """(the head's poses, the group's pose in numbers) at z: the last point's kept,
        as Newton's method asks the residual and the Jacobian at the same point."""
        key = z.tobytes()
        if self._last is not None and self._last[0] == key:
            return self._last[1]
        known = _known_along(self.plan, self.step, self.pose, self.theta,
                             np.array([math.degrees(z[-1])]), self.head)
        at = (known, self.form.set_bodies_at(pose_at_point(known), self.scale * z[:-1]))
        self._last = (key, at)
        return at

    def residual(self, z):
        return self.form.residual(self._at(z)[1]) / self.plan.size

    def in_unknowns(self, z):
        """d(residual)/d(q / scale): the group's Jacobian in its own unknowns."""
        return group_rows_at(self.step, self._at(z)[1])[0] * self.scale / self.plan.size

    def jacobian(self, z):
        """d(residual)/dz: the group's Jacobian in its unknowns, and its derivative in
        the input: the known links' terms of the velocity equations at unit input rate
        (the head's velocities)."""
        known, point = self._at(z)
        # the input's rate that moves tau by one radian per second
        vel, _, _ = rates(self.plan, known, self.plan.rate_scale * 180.0 / math.pi, 1,
                          steps=self.head_steps, measure=False, accelerations=False)
        rate = pose_at_point(vel)
        mat, others = group_rows_at(self.step, point)
        ft = np.array([float(sum(dot3(cf, rate[link]) for link, cf in row.items()))
                       for row in others])
        return np.column_stack([mat * self.scale, ft]) / self.plan.size

    def tangent(self, z, like=None, direction=1.0):
        found = self.oriented_tangent(z, like, direction)
        return None if found is None else found[0]

    def oriented_tangent(self, z, like=None, direction=1.0):
        """(the branch's unit tangent at z, oriented like ``like`` or along the input's
        ``direction``; the sign of det [J; tangent]), or None: the sign stays along a
        branch, folds included, and changes where the path crosses onto another
        branch (at a bifurcation, or through the narrow gap where two pass close)."""
        jac = self.jacobian(z)
        if not np.isfinite(jac).all():
            return None
        _, _, vt = np.linalg.svd(jac)
        tau = vt[-1]
        if like is not None:
            tau = tau if tau @ like >= 0 else -tau
        else:
            tau = tau if tau[-1] * direction >= 0 else -tau
        augmented = np.vstack([jac, tau])
        if augmented.shape[0] != augmented.shape[1]:      # (more equations than unknowns)
            return tau, 0.0
        return tau, float(np.sign(np.linalg.det(augmented)))

    def correct(self, zp, tau, tol=1e-11):
        """Newton's method from the predicted zp on the branch and the hyperplane
        through zp normal to tau; None if it does not converge. The Jacobian's column
        in the input (the head's velocities, the costly part) is taken once, at zp:
        the corrections keep the input within a small step of it, and the answer is
        the residual's zero whatever the column (only the rate of convergence
        depends on it)."""
        x = zp.copy()
        column = None
        for _ in range(12):
            r = np.append(self.residual(x), tau @ (x - zp))
            if not np.all(np.isfinite(r)):
                return None
            if np.abs(r).max() <= tol:
                return x
            if column is None:
                jac = self.jacobian(x)
                column = jac[:, -1]
            else:
                jac = np.column_stack([self.in_unknowns(x), column])
            a = np.vstack([jac, tau])
            if not np.isfinite(a).all():
                return None
            x = x + newton_step(a[None], r[None])[0]
        return None

    def dq(self, tau):
        """dq / d(input) per radian along the branch (infinite at a fold)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.scale * tau[:-1] / tau[-1]


#: arc-length steps a trace may take (a full turn takes a few hundred at most): a
#: backstop; a slide running off to infinity, what walked thousands of steps, ends at
#: RUNAWAY_SIZES instead
MAX_ARC_STEPS = 2000

#: how far (in sizes of the mechanism) from the drawing's centre a group's link may
#: move before a trace ends there: the input is then near a value where a slide runs off
#: to infinity (its guides turn parallel), a limit of the range with no fold before it
#: (the same on every path, as the plan's coordinates are about the drawing's centre)
RUNAWAY_SIZES = 25.0


def _trace(plan, step, pose, theta, head, q, t, end, direction, h_deg,
           runaway=RUNAWAY_SIZES):
    """Points (input degrees, q, dq/dinput) along the group's branch from (t, q)
    towards ``end``, by pseudo-arclength continuation; stops at ``end``, a fold, or a
    link ``runaway`` sizes from the drawing's centre."""
    branch = _Branch(plan, step, pose, theta, head)
    z = np.append(q / branch.scale, math.radians(t))
    found = branch.oriented_tangent(z, direction=direction)
    if found is None:
        return [t], [q], [np.zeros_like(q)], None
    tau, side = found
    ts, qs, dqs = [t], [q], [branch.dq(tau)]
    fold = None
    h = math.radians(h_deg)
    ds = h
    taken = 0
    lengths = branch.scale != 1.0           # the coordinates that are positions
    while direction * (math.degrees(z[-1]) - end) < -1e-12 and ds > 1e-6 * h:
        taken += 1
        if taken > MAX_ARC_STEPS:
            # the branch goes on while the input hardly moves: end the trace, as at a
            # limit, rather than walk forever (the catalog and the 6-link R/P atlas take
            # 95 steps at most now)
            break
        # no further along the arc than reaching the end needs (far, near a fold)
        remaining = math.radians(abs(end - math.degrees(z[-1])))
        reach = 1.05 * remaining / max(abs(tau[-1]), 1e-300)
        ds = min(ds, reach) if reach > 1e-6 * h else ds
        # far out (running off along a slide), steps grow with the distance, so that
        # reaching RUNAWAY_SIZES takes tens of steps, not thousands
        away = float(np.abs(z[:-1][lengths]).max(initial=0.0))
        h_here = max(h, min(reach, math.radians(10.0)), 0.2 * away)
        zp = z + ds * tau
        x = branch.correct(zp, tau)
        if x is None or np.linalg.norm(x - zp) > 0.25 * ds or \
                np.abs(x[:-1][lengths]).max(initial=0.0) > runaway:
            # (past RUNAWAY_SIZES: halving the step ends the trace where it is reached,
            # on any path, within the smallest step)
            ds /= 2
            continue
        found = branch.oriented_tangent(x, like=tau)
        if found is None or found[0] @ tau < 0.9:
            ds /= 2
            continue
        tau_new, side_new = found
        if side_new != side and ds > _CROSSING_STEP * h:
            # onto another branch: through the gap where two pass close (or across a
            # bifurcation, passed at the smallest step): a shorter step keeps this one
            ds /= 2
            continue
        if tau_new[-1] * direction <= 0 and tau[-1] * direction > 0:
            # the input turned back between z and x: a fold, where the path ends
            fold = _fold(branch, z, tau, ds, direction)
            break
        z, tau, side = x, tau_new, side_new
        ts.append(math.degrees(z[-1]))
        qs.append(branch.scale * z[:-1])
        dqs.append(branch.dq(tau))
        ds = min(h_here, 1.5 * ds)
    return ts, qs, dqs, fold


#: the step along the arc, of the trace's own, below which a crossing onto another
#: branch is taken as a bifurcation the branch goes through (a change point), not a gap
_CROSSING_STEP = 1e-4


#: the halvings of the arc that bracket a fold: to about 1e-8 of the step along the arc,
#: where :func:`fold_point` (Newton's method on the extended system, regular at the
#: fold) takes over and converges in a step or two
_FOLD_HALVINGS = 26


def _fold(branch, z, tau, ds, direction):
    """The fold between z and z + ds tau along the arc (where the input turns back),
    by bisection on the sign of the tangent's input component: (input degrees, q)."""
    lo, hi, best = 0.0, ds, None
    for _ in range(_FOLD_HALVINGS):
        mid = 0.5 * (lo + hi)
        x = branch.correct(z + mid * tau, tau, tol=1e-12)
        here = None if x is None else branch.tangent(x, like=tau)
        if here is None:
            return best
        if here[-1] * direction > 0:
            lo, best = mid, (math.degrees(x[-1]), branch.scale * x[:-1])
        else:
            hi = mid
    return best


def fold_point(plan: Plan, step: Step, head: Evaluation, q: ArrayLike, t: float,
               iterations: int = 25) -> tuple[float, np.ndarray] | None:
    """The fold of the group's branch near (``t``, ``q``): where the input turns back,
    the loop-closure equations R(q, t) = 0 together with the Jacobian's null vector,
    R_q v = 0 with c . v = 1, solved by Newton's method on that extended system, which
    is regular at a simple fold (so converges quadratically, and the fold is exact to
    the rounding, where Newton's method on R alone stalls at the square root of it).
    The second derivatives d(R_q v)/d(q, t) are central differences.

    ``head`` is the evaluation at ``t`` (a single point) of the steps before the group.
    Returns (input degrees, q), or None where the iteration does not settle.
    """
    branch = _Branch(plan, step, head.pose, head.theta, head)
    z = np.append(np.asarray(q, dtype=float) / branch.scale, math.radians(t))
    m = z.size - 1
    jac = branch.jacobian(z)
    if not np.isfinite(jac).all():
        return None
    v = np.linalg.svd(jac[:, :m])[2][-1]
    c = v.copy()
    h = 1e-6
    for _ in range(iterations):
        jac = branch.jacobian(z)
        a = jac[:, :m]
        g = np.concatenate([branch.residual(z), a @ v, [c @ v - 1.0]])
        if not (np.isfinite(g).all() and np.isfinite(jac).all()):
            return None
        d = np.empty((m, m + 1))
        for k in range(m + 1):
            e = np.zeros(m + 1)
            e[k] = h
            d[:, k] = (branch.in_unknowns(z + e) @ v - branch.in_unknowns(z - e) @ v) / (2 * h)
        big = np.zeros((2 * m + 1, 2 * m + 1))
        big[:m, :m + 1] = jac
        big[m:2 * m, :m + 1] = d
        big[m:2 * m, m + 1:] = a
        big[2 * m, m + 1:] = c
        dx = newton_step(big[None], g[None])[0]
        if not np.isfinite(dx).all():
            return None
        z, v = z + dx[:m + 1], v + dx[m + 1:]
        if np.abs(dx[:m + 1]).max() <= 1e-15:
            break
    if not (np.isfinite(z).all() and np.abs(branch.residual(z)).max() <= 1e-12):
        return None
    return math.degrees(z[-1]), branch.scale * z[:-1]


def _approach(plan, step, pose, theta, head, t_from, q_from, t_to):
    """Group coordinates at ``t_to`` continued from ``q_from`` at ``t_from`` through
    substeps that shrink geometrically towards ``t_to``; None if it cannot be reached."""
    ts = t_to - (t_to - t_from) * 4.0 ** -np.arange(1, 9)
    q = q_from
    for t in list(ts) + [t_to]:
        known = _known_along(plan, step, pose, theta, np.array([t]), head)
        qi, good = newton(plan, step, known, q[None], iterations=100)
        if good[0] and np.linalg.norm(qi[0] - q) <= 0.1 * plan.size:
            q = qi[0]
        elif t == t_to:
            return None
    return q


def _known_along(plan, step, pose, theta, at, head):
    """Poses of the fixed link, the driver and the links solved before ``step`` at the
    angles ``at`` (the path's own poses when ``at`` is the path), in the path's modes
    (continued from its nearest point of ``head``, the path's evaluation so far)."""
    if np.array_equal(at, theta):
        return pose
    k = np.abs(theta[:, None] - at[None, :]).argmin(axis=0)
    return head.poses_at(plan, at, k, upto=plan.steps.index(step))


def _hermite(tc, qc, dqc, t):
    """Cubic Hermite interpolation of q(theta) (degrees) with dq/dtheta per radian."""
    if tc.size == 0:
        return np.full((t.size, qc.shape[1]), np.nan)
    if tc.size == 1:
        return np.repeat(qc[:1], t.size, axis=0)
    order = np.argsort(tc)
    tc, qc, dqc = tc[order], qc[order], dqc[order]
    dqc = np.where(np.isfinite(dqc), dqc, 0.0)
    idx = np.clip(np.searchsorted(tc, t) - 1, 0, tc.size - 2)
    t0, t1 = tc[idx], tc[idx + 1]
    h = t1 - t0
    s = ((t - t0) / h)[:, None]
    hr = np.radians(h)[:, None]
    h00, h10 = 2 * s ** 3 - 3 * s ** 2 + 1, s ** 3 - 2 * s ** 2 + s
    h01, h11 = -2 * s ** 3 + 3 * s ** 2, s ** 3 - s ** 2
    return h00 * qc[idx] + h10 * hr * dqc[idx] + h01 * qc[idx + 1] + h11 * hr * dqc[idx + 1]

