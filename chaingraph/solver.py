"""Position, velocity and acceleration of a planned inversion over an input sweep.

Every link carries a rigid motion from its drawn pose (see :mod:`chaingraph.plan`):
position ``(x, y)`` and rotation ``phi``, so a drawn point p is at ``R(phi) p + (x, y)``.
All arrays run over the sweep at once (numpy), one step of the plan after another.

Positions: closed form for single links and dyads (intersections of circles and lines,
or a rotation angle from a cosine); each dyad's assembly mode is taken from the drawn
pose and kept, and where the two modes meet (a tangency, such as a parallelogram's change
point) the smoother continuation is chosen, so there are no flips. A group of higher
class is solved by Newton's method, continued from step to step along a coarse sweep with
a tangent predictor, then on the whole sweep at once from Hermite-interpolated guesses.

Velocities and accelerations: the constraint Jacobian times the rates equals the known
links' terms (and, for accelerations, the quadratic velocity terms). Per step this is an
exact linear solve: each link's constraint to a known link leaves it one free rate (a
null-space direction), and the dyad's own joint gives a 2 x 2 system in those two rates;
a group is solved whole. Where that system is singular (a dead centre) the rates are NaN,
never a finite wrong number.
"""

from __future__ import annotations

import math

import numpy as np

from .errors import AssemblyError

__all__ = ["Evaluation", "Reference", "evaluate", "evaluate_at", "rates", "residuals",
           "make_pose", "rotate"]

_DISC_TOL = 1e-13   # dimensionless discriminant: rounding is about 1e-16


# -- small geometry on arrays --------------------------------------------------------
# A pose is (x, y, phi, cos phi, sin phi): the trigonometry is done once per link.
# The fixed link's is constants, which numpy broadcasts.
_FIXED = (0.0, 0.0, 0.0, 1.0, 0.0)
def make_pose(x, y, phi, c=None, s=None):
    """A link's pose entry from its motion (x, y, phi)."""
    if c is None:
        c, s = np.cos(phi), np.sin(phi)
    return (x, y, phi, c, s)


def rotate(entry, p):
    """Rotate the drawn vector p by the pose entry's rotation."""
    c, s = entry[3], entry[4]
    return c * p[0] - s * p[1], s * p[0] + c * p[1]


def _world(pose, link, p):
    e = pose[link]
    rx, ry = rotate(e, p)
    return rx + e[0], ry + e[1]


def _fit_two_points(p1, w1, p2, w2):
    """The rigid motion taking drawn points p1, p2 to w1, w2 (rotation from the chord)."""
    dpx, dpy = p2[0] - p1[0], p2[1] - p1[1]
    dwx, dwy = w2[0] - w1[0], w2[1] - w1[1]
    c = dpx * dwx + dpy * dwy
    s = dpx * dwy - dpy * dwx
    norm = np.hypot(c, s)
    c, s = c / norm, s / norm
    e = (0.0, 0.0, None, c, s)
    rx, ry = rotate(e, p1)
    return make_pose(w1[0] - rx, w1[1] - ry, np.arctan2(s, c), c, s)


def _from_point(entry, p, w):
    """The pose with the rotation of ``entry`` that puts drawn point p at w."""
    rx, ry = rotate(entry, p)
    return make_pose(w[0] - rx, w[1] - ry, entry[2], entry[3], entry[4])


def _unit(deg):
    return math.cos(math.radians(deg)), math.sin(math.radians(deg))


def _line_of(pose, attach, unknown, through):
    """The line on which the unknown link's drawn point ``through`` must stay, for a P
    attachment to a known link: (base point, direction, the unknown link's rotation)."""
    known = pose[attach.other(unknown)]
    base = _world(pose, attach.other(unknown), attach.point)
    dx, dy = through[0] - attach.point[0], through[1] - attach.point[1]
    ox, oy = rotate(known, (dx, dy))
    u = rotate(known, _unit(attach.axis))
    return (base[0] + ox, base[1] + oy), u, known


def _clamp_disc(disc, scale):
    tol = _DISC_TOL * scale
    ok = disc >= -tol
    return np.where(ok, np.maximum(disc, 0.0), np.nan), ok


# -- closed-form steps ---------------------------------------------------------------
def _single(step, pose):
    u = step.links[0]
    c1, c2 = step.constraints[:2]
    if c1.kind == "R" and c2.kind == "R":
        w1 = _world(pose, c1.other(u), c1.point)
        w2 = _world(pose, c2.other(u), c2.point)
        return {u: _fit_two_points(c1.point, w1, c2.point, w2)}
    if c1.kind == "R":
        return {u: _from_point(pose[c2.other(u)], c1.point,
                               _world(pose, c1.other(u), c1.point))}
    return {u: _two_lines(pose, u, c1, c2)}


def _two_lines(pose, u, c1, c2):
    """Pose of link u with two P attachments to known links (its rotation from c1)."""
    turn = pose[c1.other(u)]
    rows, rhs = [], []
    for c in (c1, c2):
        base, dirn, _ = _line_of(pose, c, u, c.point)
        nx_, ny_ = -dirn[1], dirn[0]
        rx, ry = rotate(turn, c.point)
        rows.append((nx_, ny_))
        rhs.append(nx_ * (base[0] - rx) + ny_ * (base[1] - ry))
    (a, b), (c, d) = rows
    det = a * d - b * c
    x = (rhs[0] * d - b * rhs[1]) / det
    y = (a * rhs[1] - c * rhs[0]) / det
    return make_pose(x, y, turn[2], turn[3], turn[4])


def _dyad_roots(step, pose, scale):
    """A dyad's assembly modes.

    Returns (keys, build, ok, disc): ``keys`` the two modes' joint point (or rotation as
    a unit vector), arrays of shape (N, 2) or None for a dyad with one mode;
    ``build(sign)`` the poses of the dyad's links for an array of mode signs (+1 or -1);
    ``ok`` where the dyad can be assembled; ``disc`` the discriminant over the size
    squared (dimensionless: negative where the dyad cannot be assembled, zero where its
    two modes meet), or None for a dyad with one mode.
    """
    a, b = step.links
    ca, cb, cj = step.constraints
    pattern = step.pattern
    if pattern in ("PRR", "PPR"):  # mirror to the R-first form
        a, b, ca, cb = b, a, cb, ca
        pattern = pattern[::-1]
    q = cj.point
    if pattern in ("RRR", "RRP"):
        wa = _world(pose, ca.other(a), ca.point)
        ra = math.dist(q, ca.point)
        if pattern == "RRR":
            wb = _world(pose, cb.other(b), cb.point)
            rb = math.dist(q, cb.point)
            dx, dy = wb[0] - wa[0], wb[1] - wa[1]
            d2 = dx * dx + dy * dy
            d = np.sqrt(d2)
            along = (ra * ra - rb * rb + d2) / (2 * d)
            raw = ra * ra - along * along
            h2, ok = _clamp_disc(raw, scale * scale)
            h = np.sqrt(h2)
            ux, uy = dx / d, dy / d
            mid = (wa[0] + along * ux, wa[1] + along * uy)
            off = (-h * uy, h * ux)
        else:
            base, dirn, turn_b = _line_of(pose, cb, b, q)
            ex, ey = base[0] - wa[0], base[1] - wa[1]
            beta = dirn[0] * ex + dirn[1] * ey
            raw = beta * beta - (ex * ex + ey * ey - ra * ra)
            disc, ok = _clamp_disc(raw, scale * scale)
            root_disc = np.sqrt(disc)
            mid = (base[0] - beta * dirn[0], base[1] - beta * dirn[1])
            off = (root_disc * dirn[0], root_disc * dirn[1])
        keys = (np.stack((mid[0] + off[0], mid[1] + off[1]), axis=-1),
                np.stack((mid[0] - off[0], mid[1] - off[1]), axis=-1))

        def build(sign):
            x, y = mid[0] + sign * off[0], mid[1] + sign * off[1]
            pa = _fit_two_points(ca.point, wa, q, (x, y))
            if pattern == "RRR":
                return {a: pa, b: _fit_two_points(cb.point, wb, q, (x, y))}
            return {a: pa, b: _from_point(turn_b, q, (x, y))}
        return keys, build, ok, raw / (scale * scale)
    if pattern == "RPR":
        wa = _world(pose, ca.other(a), ca.point)
        wb = _world(pose, cb.other(b), cb.point)
        nx_, ny_ = -_unit(cj.axis)[1], _unit(cj.axis)[0]
        dx, dy = wb[0] - wa[0], wb[1] - wa[1]
        dist = np.hypot(dx, dy)
        c = nx_ * (cb.point[0] - ca.point[0]) + ny_ * (cb.point[1] - ca.point[1])
        ratio = c / dist
        raw = 1.0 - ratio * ratio
        disc, ok = _clamp_disc(raw, 1.0)
        # rotation phi = start +- spread, with cos(spread) = ratio
        cs0, sn0 = dx / dist, dy / dist            # direction of the centre line
        cn, sn = nx_, ny_                           # drawn normal: rotate back by it
        cst, snt = cs0 * cn + sn0 * sn, sn0 * cn - cs0 * sn   # start = delta - nu
        root = np.sqrt(disc)

        def turn(sign):
            c1, s1 = cst * ratio - snt * sign * root, snt * ratio + cst * sign * root
            return c1, s1
        keys = tuple(np.stack(turn(sg), axis=-1) for sg in (1.0, -1.0))

        def build(sign):
            c1, s1 = turn(sign)
            e = make_pose(0.0, 0.0, np.arctan2(s1, c1), c1, s1)
            return {a: _from_point(e, ca.point, wa), b: _from_point(e, cb.point, wb)}
        return keys, build, ok, raw
    if pattern == "PRP":
        base_a, dir_a, turn_a = _line_of(pose, ca, a, q)
        base_b, dir_b, turn_b = _line_of(pose, cb, b, q)
        det = dir_a[0] * -dir_b[1] + dir_b[0] * dir_a[1]
        rx, ry = base_b[0] - base_a[0], base_b[1] - base_a[1]
        s_ = (rx * -dir_b[1] + dir_b[0] * ry) / det
        x, y = base_a[0] + s_ * dir_a[0], base_a[1] + s_ * dir_a[1]

        def build(sign):
            return {a: _from_point(turn_a, q, (x, y)), b: _from_point(turn_b, q, (x, y))}
        return None, build, np.isfinite(x), None
    if pattern == "RPP":
        wa = _world(pose, ca.other(a), ca.point)
        pa = _from_point(pose[cb.other(b)], ca.point, wa)

        def build(sign):
            known = dict(pose)
            known[a] = pa
            return {a: pa, b: _two_lines(known, b, cb, cj)}
        return None, build, np.isfinite(wa[0]), None
    raise ValueError(f"no closed form for a {pattern} dyad")


def _initial_sign(keys, drawn):
    """The mode of the drawn pose: the one whose first point is nearest the drawing."""
    kp, km = keys
    dp = np.hypot(kp[0, 0] - drawn[0], kp[0, 1] - drawn[1])
    dm = np.hypot(km[0, 0] - drawn[0], km[0, 1] - drawn[1])
    return 1.0 if dp <= dm else -1.0


# -- the sweep -----------------------------------------------------------------------
def _known_poses(plan, theta):
    n = theta.size
    zero = np.zeros(n)
    alpha = np.radians(theta - plan.theta0)
    turn = make_pose(zero, zero, alpha)
    ox, oy = plan.pivot_point
    rx, ry = rotate(turn, (ox, oy))
    return {plan.fixed: _FIXED,
            plan.driver: make_pose(ox - rx, oy - ry, alpha, turn[3], turn[4])}


class Reference:
    """Where pointwise evaluations continue from: per point, an input angle, each
    dyad's mode sign there, each group's coordinates there, and the angles where each
    dyad's modes change label (``switches``: its two modes meet there and the motion
    continues smoothly into the other label)."""

    def __init__(self, theta, signs, group_q, switches):
        self.theta = np.asarray(theta, dtype=float)
        self.signs = signs
        self.group_q = group_q
        self.switches = switches

    def sign(self, i, theta):
        """Step i's mode sign at ``theta``, from the reference's across its switches."""
        s = np.broadcast_to(self.signs[i], self.theta.shape).astype(float)
        for t in self.switches.get(i, ()):
            s = np.where((t - self.theta) * (t - theta) < 0, -s, s)
        return s


def evaluate_at(plan, theta, ref, *, upto=None):
    """Poses at the angles ``theta`` (degrees, shape (M,)), each point continued from
    the same point of ``ref`` (a :class:`Reference` of M points, close by) without
    tracking: the modes are the reference's, across its switches; groups are solved by
    Newton's method from the reference's coordinates. Only the first ``upto`` steps of
    the plan when given.

    Returns (pose, feasible, group_q).
    """
    theta = np.asarray(theta, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        pose = _known_poses(plan, theta)
        feasible = np.ones(theta.size, dtype=bool)
        group_q = {}
        for i, step in enumerate(plan.steps[:upto]):
            if step.kind == "single":
                pose.update(_single(step, pose))
            elif step.kind == "dyad":
                keys, build, ok, _ = _dyad_roots(step, pose, plan.size)
                feasible &= ok
                pose.update(build(1.0 if keys is None else ref.sign(i, theta)))
            else:
                q0 = np.broadcast_to(ref.group_q[i], (theta.size, _form(step).size))
                q, ok = _newton(plan, step, pose, q0)
                feasible &= ok
                group_q[i] = q
                pose.update(_form(step).complete(_form(step).set_bodies(pose, q)))
    return pose, feasible, group_q


class Evaluation:
    """Poses of every link along a path of input angles, with what the next needs."""

    def __init__(self, theta, pose, feasible, signs, group_q, switches):
        self.theta = theta            # degrees, (N,)
        self.pose = pose              # link -> (x, y, phi) arrays
        self.feasible = feasible      # (N,) bool
        self.signs = signs            # step index -> (N,) branch signs
        self.group_q = group_q        # step index -> (N, 3k) group coordinates
        self.switches = switches      # step index -> angles where the mode label changes

    def at(self, k):
        """The state at point k, to continue a new path from (its first angle)."""
        return _Start({i: float(v[k]) for i, v in self.signs.items()},
                      {i: q[k] for i, q in self.group_q.items()})

    def reference(self, k):
        """A :class:`Reference` for pointwise evaluations near the points ``k`` (array)."""
        k = np.asarray(k)
        return Reference(self.theta[k], {i: v[k] for i, v in self.signs.items()},
                         {i: q[k] for i, q in self.group_q.items()}, self.switches)

    def take(self, k):
        """The evaluation at the points ``k`` only (an index array)."""
        def pick(v):
            return v if np.ndim(v) == 0 else v[k]
        return Evaluation(self.theta[k], {x: tuple(pick(v) for v in p)
                                          for x, p in self.pose.items()},
                          self.feasible[k], {i: v[k] for i, v in self.signs.items()},
                          {i: q[k] for i, q in self.group_q.items()}, self.switches)


class _Start:
    def __init__(self, signs, group_q):
        self.signs = signs
        self.group_q = group_q


def evaluate(plan, theta, *, start=None) -> Evaluation:
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
    signs, group_q, switches = {}, {}, {}
    for i, step in enumerate(plan.steps):
        if step.kind == "single":
            pose.update(_single(step, pose))
            continue
        if step.kind == "dyad":
            keys, build, ok, disc = _dyad_roots(step, pose, plan.size)
            if keys is None:
                feasible &= ok
                pose.update(build(1.0))
                continue
            drawn = (1.0, 0.0) if step.pattern == "RPR" else step.constraints[2].point
            sign0 = start.signs[i] if start is not None else _initial_sign(keys, drawn)
            ref = Evaluation(theta, pose, feasible, signs, group_q, switches)
            chosen, ok, found = _track(plan, i, step, ref, np.where(feasible, disc, np.nan),
                                       sign0)
            feasible &= ok
            signs[i] = chosen
            switches[i] = found
            pose.update(build(chosen))
            continue
        q0 = start.group_q[i] if start is not None else np.zeros(_form(step).size)
        head = Evaluation(theta, pose, feasible, signs, group_q, switches)
        q, ok = _newton_path(plan, step, pose, theta, q0, head=head)
        feasible &= ok
        group_q[i] = q
        pose.update(_form(step).complete(_form(step).set_bodies(pose, q)))
    if not feasible.all():
        first_bad = int(np.argmin(feasible))
        feasible[first_bad:] = False
    return Evaluation(theta, pose, feasible, signs, group_q, switches)


def _track(plan, i, step, head, disc, sign0):
    """Mode signs of dyad step i along the path, where it can be assembled, and the
    angles where its label switches.

    ``head`` is the path's evaluation so far (the steps before i); ``disc`` the dyad's
    sampled discriminant (NaN where an earlier step failed).
    """
    theta = head.theta
    n = theta.size
    ok = disc >= -_DISC_TOL
    last = n if ok.all() else int(np.argmin(ok))
    direction = 1.0 if n < 2 or theta[-1] >= theta[0] else -1.0
    found = []
    if last >= 2:
        d = disc[:last]
        left = np.r_[np.inf, d[:-1]]
        right = np.r_[d[1:], np.inf if last == n else -np.inf]
        candidates = np.nonzero((d <= left) & (d <= right) & (d < _TOUCH_CANDIDATE))[0]
        for k in candidates:
            lo, hi = theta[max(k - 1, 0)], theta[min(k + 1, last - 1)]
            tstar, dmin = _zoom_minimum(plan, i, step, head, int(k), lo, hi)
            if dmin < -_DISC_TOL:          # a window where it cannot be assembled
                last = min(last, int(np.argmax(direction * (theta - tstar) >= 0)))
                break
            if dmin <= _DISC_TOL:
                tstar = _touch_vertex(plan, i, step, head, int(k), tstar)
                sign = sign0 * (-1.0) ** len(found)
                if _switches_label(plan, i, step, head, int(k), tstar, direction, sign):
                    if not found or abs(tstar - found[-1]) > 1e-7:
                        found.append(float(tstar))
    signs = np.full(n, float(sign0))
    for t in found:
        signs = np.where(direction * (theta - t) > 0, -signs, signs)
    ok = np.zeros(n, dtype=bool)
    ok[:last] = True
    return signs, ok, found


def _head_roots(plan, i, step, head, k, ts):
    ref = head.reference(np.full(ts.size, k))
    pose, feasible, _ = evaluate_at(plan, ts, ref, upto=i)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        keys, _, _, disc = _dyad_roots(step, pose, plan.size)
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
        if dmin < -_DISC_TOL:
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
    if not np.all(disc[1:] >= -_DISC_TOL):
        return False             # a fold: the path cannot pass, nothing to continue
    cur = keys[0] if sign > 0 else keys[1]
    alt = keys[1] if sign > 0 else keys[0]
    pred = cur[1] + 2 * (cur[1] - cur[0])
    return bool(np.linalg.norm(alt[2] - pred) < np.linalg.norm(cur[2] - pred))


# -- constraint rows (Jacobian and quadratic velocity terms) ------------------------
def _perp(v):
    return -v[1], v[0]


def _geometry(c, pose):
    """What a constraint's rows and acceleration terms share, computed once."""
    ra = rotate(pose[c.a], c.point)
    rb = rotate(pose[c.b], c.point)
    if c.kind == "R":
        return ra, rb, None, None
    n = rotate(pose[c.a], _perp(_unit(c.axis)))
    d = (rb[0] + pose[c.b][0] - ra[0] - pose[c.a][0], rb[1] + pose[c.b][1] - ra[1] - pose[c.a][1])
    return ra, rb, n, d


def _rows(c, pose, geom=None):
    """Rows of the constraint Jacobian, each {link: (cx, cy, cphi)} (constant entries as
    Python floats)."""
    ra, rb, n, d = geom or _geometry(c, pose)
    if c.kind == "R":
        return [{c.a: (1.0, 0.0, -ra[1]), c.b: (-1.0, 0.0, rb[1])},
                {c.a: (0.0, 1.0, ra[0]), c.b: (0.0, -1.0, -rb[0])}]
    g, b = c.a, c.b
    pn = _perp(n)
    prb, prg = _perp(rb), _perp(ra)
    return [{b: (0.0, 0.0, 1.0), g: (0.0, 0.0, -1.0)},
            {b: (n[0], n[1], n[0] * prb[0] + n[1] * prb[1]),
             g: (-n[0], -n[1], pn[0] * d[0] + pn[1] * d[1] - (n[0] * prg[0] + n[1] * prg[1]))}]


def _gammas(c, pose, vel, geom=None):
    """Right-hand sides of the acceleration equations from the velocities alone."""
    ra, rb, n, d = geom or _geometry(c, pose)
    if c.kind == "R":
        wa2, wb2 = vel[c.a][2] ** 2, vel[c.b][2] ** 2
        return [wa2 * ra[0] - wb2 * rb[0], wa2 * ra[1] - wb2 * rb[1]]
    g, b = c.a, c.b
    rg = ra
    pn = _perp(n)
    prb, prg = _perp(rb), _perp(rg)
    (vbx, vby, wb_), (vgx, vgy, wg_) = vel[b], vel[g]
    dd = (vbx + wb_ * prb[0] - vgx - wg_ * prg[0], vby + wb_ * prb[1] - vgy - wg_ * prg[1])
    return [0.0, (-2 * wg_ * (pn[0] * dd[0] + pn[1] * dd[1])
                  + wg_ ** 2 * (n[0] * d[0] + n[1] * d[1])
                  + n[0] * (wb_ ** 2 * rb[0] - wg_ ** 2 * rg[0])
                  + n[1] * (wb_ ** 2 * rb[1] - wg_ ** 2 * rg[1]))]


def residuals(plan, pose):
    """Largest constraint residual at every point (lengths; rotations times the size)."""
    worst = None
    for c in plan.constraints:
        if c.kind == "R":
            wa, wb = _world(pose, c.a, c.point), _world(pose, c.b, c.point)
            r = np.hypot(wa[0] - wb[0], wa[1] - wb[1])
        else:
            dphi = np.abs(np.remainder(pose[c.b][2] - pose[c.a][2] + np.pi, 2 * np.pi) - np.pi)
            n = rotate(pose[c.a], _perp(_unit(c.axis)))
            wg, wb = _world(pose, c.a, c.point), _world(pose, c.b, c.point)
            r = np.maximum(np.abs(n[0] * (wb[0] - wg[0]) + n[1] * (wb[1] - wg[1])),
                           dphi * plan.size)
        worst = r if worst is None else np.maximum(worst, r)
    return worst


def _dot3(c, v):
    """c . v for three-vectors whose entries may be constant Python floats."""
    total = 0.0
    for ci, vi in zip(c, v):
        if isinstance(vi, float) and vi == 0.0:
            continue
        if isinstance(ci, float):
            if ci == 0.0:
                continue
            total = total + (vi if ci == 1.0 else -vi if ci == -1.0 else ci * vi)
        else:
            total = total + ci * vi
    return total


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
    return (p11 * p22 - p12 * p21) / ((np.hypot(p11, p21) + 1e-300) *
                                       (np.hypot(p12, p22) + 1e-300))


class _PointDyad:
    """An RRR dyad in the coordinates of its middle joint X: the constraints
    (X - W_a) . (dX - dW_a) = 0 and (X - W_b) . (dX - dW_b) = 0 make a 2 x 2 Jacobian
    [u_a; u_b], solved by Cramer's rule for velocities and again for accelerations; the
    links' rates follow from X's. The same answers as the general reduction in far fewer
    array operations, for the commonest dyad."""

    def __init__(self, step, pose, n, size):
        self.step = step
        a, b = step.links
        ca, cb, cj = step.constraints
        self.ka, self.kb = ca.other(a), cb.other(b)
        self.pa, self.pb, self.q = ca.point, cb.point, cj.point
        self.ra_k = rotate(pose[self.ka], self.pa)
        self.rb_k = rotate(pose[self.kb], self.pb)
        wa = (self.ra_k[0] + pose[self.ka][0], self.ra_k[1] + pose[self.ka][1])
        wb = (self.rb_k[0] + pose[self.kb][0], self.rb_k[1] + pose[self.kb][1])
        self.rq = {a: rotate(pose[a], self.q), b: rotate(pose[b], self.q)}
        x = (self.rq[a][0] + pose[a][0], self.rq[a][1] + pose[a][1])
        self.ua = (x[0] - wa[0], x[1] - wa[1])
        self.ub = (x[0] - wb[0], x[1] - wb[1])
        det = self.ua[0] * self.ub[1] - self.ua[1] * self.ub[0]
        self.ra2 = self.ua[0] ** 2 + self.ua[1] ** 2
        self.rb2 = self.ub[0] ** 2 + self.ub[1] ** 2
        self.singular = det * det <= _SINGULAR ** 2 * self.ra2 * self.rb2
        self.det = np.where(self.singular, 1.0, det)
        self._det = det

    @property
    def measure(self):
        return self._det / np.sqrt(self.ra2 * self.rb2)

    def _known_point(self, table, link, r, second=None):
        v = table[link]
        if second is None:      # velocity of the point: v + w perp(R p)
            return _add(v[0], _mul(-1.0, _mul(v[2], r[1]))), _add(v[1], _mul(v[2], r[0]))
        w = second[link][2]     # acceleration: a + alpha perp(R p) - w^2 R p
        w2 = _mul(w, w)
        return (_add(_add(v[0], _mul(-1.0, _mul(v[2], r[1]))), _mul(-1.0, _mul(w2, r[0]))),
                _add(_add(v[1], _mul(v[2], r[0])), _mul(-1.0, _mul(w2, r[1]))))

    def solve_velocity(self, vel):
        dwa = self._known_point(vel, self.ka, self.ra_k)
        dwb = self._known_point(vel, self.kb, self.rb_k)
        return self._solve(dwa, dwb, 0.0, 0.0, second=False)

    def solve_acceleration(self, acc, vel):
        dwa = self._known_point(acc, self.ka, self.ra_k, vel)
        dwb = self._known_point(acc, self.kb, self.rb_k, vel)
        ga, gb = _sq(self._rel_a), _sq(self._rel_b)
        return self._solve(dwa, dwb, ga, gb, second=True, vel=vel)

    def _solve(self, dwa, dwb, ga, gb, *, second, vel=None):
        ua, ub = self.ua, self.ub
        ca = ua[0] * dwa[0] + ua[1] * dwa[1] - ga
        cb = ub[0] * dwb[0] + ub[1] * dwb[1] - gb
        dx = (ca * ub[1] - ua[1] * cb) / self.det
        dy = (ua[0] * cb - ca * ub[0]) / self.det
        dx = np.where(self.singular, np.nan, dx)
        a, b = self.step.links
        out = {}
        for link, u, dw, r2 in ((a, ua, dwa, self.ra2), (b, ub, dwb, self.rb2)):
            rel = (dx - dw[0], dy - dw[1])
            w = (u[0] * rel[1] - u[1] * rel[0]) / r2
            rq = self.rq[link]
            if not second:
                setattr(self, "_rel_a" if link == a else "_rel_b", rel)
                out[link] = (dx + w * rq[1], dy - w * rq[0], w)
            else:
                w0 = vel[link][2]
                out[link] = (dx + w * rq[1] + w0 * w0 * rq[0],
                             dy - w * rq[0] + w0 * w0 * rq[1], w)
        return out


def _sq(v):
    return v[0] * v[0] + v[1] * v[1]


class _Factor:
    """One step's constraint Jacobian, factored once for the velocity and acceleration
    solves (which differ only in their right-hand sides)."""

    def __init__(self, step, pose, n, size):
        self.step = step
        self.n = n
        self.rows = []                       # (unknown coefficients, known coefficients)
        if step.kind == "group":
            self.form = _form(step)
            unknowns = self.form.bodies
            coefs = self.form.rows(pose)
        else:
            self.geometry = [_geometry(c, pose) for c in step.constraints]
            unknowns = step.links
            coefs = [coef for c, geom in zip(step.constraints, self.geometry)
                     for coef in _rows(c, pose, geom)]
        for coef in coefs:
            unknown = {k: v for k, v in coef.items() if k in unknowns}
            known = {k: v for k, v in coef.items() if k not in unknowns}
            self.rows.append((unknown, known))
        if step.kind == "single":
            u = step.links[0]
            self.null = _NullSpace(self.rows[0][0][u], self.rows[1][0][u])
            self.extra = [_dot3(r[0][u], self.null.e) for r in self.rows[2:]]
            den = sum(m * m for m in self.extra)
            self.singular = np.abs(den) <= _SINGULAR ** 2 * (_dot3(self.null.e, self.null.e))
            self.den = np.where(self.singular, 1.0, den)
        elif step.kind == "dyad":
            a, b = step.links
            self.null_a = _NullSpace(self.rows[0][0][a], self.rows[1][0][a])
            self.null_b = _NullSpace(self.rows[2][0][b], self.rows[3][0][b])
            p = []
            for unknown, _ in self.rows[4:6]:
                pa = _dot3(unknown[a], self.null_a.e) if a in unknown else 0.0 * n
                pb = _dot3(unknown[b], self.null_b.e) if b in unknown else 0.0 * n
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
            self.mat, _ = _group_matrix(self.form.bodies, [(u, 0.0) for u, _ in self.rows], n)
            m = self.mat
            self.normal = m.shape[1] != m.shape[2]
            if self.normal:
                m = np.einsum("nij,nik->njk", self.mat, self.mat)
            inv = _batched_inverse(m)
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
    def measure(self):
        """The step's normalized determinant along the sweep (0 at a dead centre;
        signed, except for a group with more equations than unknowns)."""
        if self.step.kind == "single":
            return np.where(self.singular, 0.0, 1.0)
        if self.step.kind == "dyad":
            return _column_free_det(*self._weighted)
        return self._measure

    def solve(self, rhs):
        """Rates of the step's links for right-hand sides ``rhs`` (one per row)."""
        step = self.step
        if step.kind == "single":
            u = step.links[0]
            q0 = self.null.particular(rhs[0], rhs[1])
            num = 0.0
            for m, (unknown, _), r in zip(self.extra, self.rows[2:], rhs[2:]):
                num = num + m * (r - _dot3(unknown[u], q0))
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
                    value = value - _dot3(unknown[a], qa)
                if b in unknown:
                    value = value - _dot3(unknown[b], qb)
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

    def right_hand_sides(self, rates_known, gammas=None):
        out = []
        for i, (_, known) in enumerate(self.rows):
            value = gammas[i] if gammas is not None else 0.0
            for link, cf in known.items():
                value = value - _dot3(cf, rates_known[link])
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
        self.e = (_sub(_mul(m1[1], m2[2]), _mul(m1[2], m2[1])),
                  _sub(_mul(m1[2], m2[0]), _mul(m1[0], m2[2])),
                  _sub(_mul(m1[0], m2[1]), _mul(m1[1], m2[0])))
        self.drop = np.argmax(np.abs(np.array(np.broadcast_arrays(*self.e), dtype=float)),
                              axis=0)

    def particular(self, c1, c2):
        m1, m2 = self.m1, self.m2
        y = [0.0, 0.0, 0.0]
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


def _mul(a, b):
    if isinstance(a, float) and a == 0.0 or isinstance(b, float) and b == 0.0:
        return 0.0
    if isinstance(a, float) and a == 1.0:
        return b
    if isinstance(b, float) and b == 1.0:
        return a
    return a * b


def _add(a, b):
    if isinstance(a, float) and a == 0.0:
        return b
    if isinstance(b, float) and b == 0.0:
        return a
    return a + b


def _sub(a, b):
    if isinstance(b, float) and b == 0.0:
        return a
    return a - b


def _group_matrix(links, rows, n):
    col = {link: 3 * k for k, link in enumerate(links)}
    size = 3 * len(links)
    entries = [[0.0] * size for _ in rows]
    for i, (coef, _) in enumerate(rows):
        for link, cf in coef.items():
            for k in range(3):
                entries[i][col[link] + k] = cf[k]
    mat = np.empty((n, len(rows), size))
    for i, row in enumerate(entries):
        for j, v in enumerate(row):
            mat[:, i, j] = v
    rhs = np.empty((n, len(rows)))
    for i, (_, r) in enumerate(rows):
        rhs[:, i] = r
    return mat, rhs


def rates(plan, pose, omega, n, *, steps=None, measure=True, accelerations=True):
    """Velocities and accelerations of every link at constant input speed ``omega``.

    Returns
    -------
    vel, acc : dict link -> (vx, vy, omega) and (ax, ay, alpha) arrays (the fixed
        link's as zeros)
    singularity : (S, N) array, each step's normalized determinant (0 at a dead
        centre); None unless ``measure``

    With ``accelerations=False`` the accelerations are left out (zeros for the fixed
    link and the driver only).
    """
    zero = np.zeros(n)
    ox, oy = plan.pivot_point
    rx, ry = rotate(pose[plan.driver], (ox, oy))
    vel = {plan.fixed: (0.0, 0.0, 0.0),
           plan.driver: (omega * ry, -omega * rx, omega + zero)}
    acc = {plan.fixed: (0.0, 0.0, 0.0),
           plan.driver: (omega ** 2 * rx, omega ** 2 * ry, 0.0)}
    measures = [] if measure else None
    factors = []
    for step in (plan.steps if steps is None else steps):
        if step.kind == "dyad" and step.pattern == "RRR" and _POINT_DYADS:
            f = _PointDyad(step, pose, n, plan.size)
            vel.update(f.solve_velocity(vel))
        else:
            f = _Factor(step, pose, n, plan.size)
            vel.update(f.solve(f.right_hand_sides(vel)))
            if step.kind == "group":
                vel.update(f.form.bar_rates(pose, vel))
        factors.append(f)
        if measure:
            measures.append(np.broadcast_to(f.measure, (n,)))
    for f in (factors if accelerations else []):
        if isinstance(f, _PointDyad):
            acc.update(_refuse_near_singular(f, f.solve_acceleration(acc, vel)))
            continue
        if f.step.kind == "group":
            acc.update(f.solve(f.right_hand_sides(acc, f.form.gammas(pose, vel))))
            acc.update(f.form.bar_rates(pose, vel, acc))
            continue
        gammas = [g for c, geom in zip(f.step.constraints, f.geometry)
                  for g in _gammas(c, pose, vel, geom)]
        acc.update(_refuse_near_singular(f, f.solve(f.right_hand_sides(acc, gammas))))
    for table in (vel, acc):
        table[plan.fixed] = (zero, zero, zero)
        table[plan.driver] = tuple(v + zero for v in table[plan.driver])
    return vel, acc, (np.array(measures) if measure else None)


def _refuse_near_singular(factor, found):
    """NaN accelerations where a dyad is too near a singular pose for them to be exact."""
    if factor.step.kind != "dyad":
        return found
    near = np.abs(factor.measure) < _SINGULAR_ACC
    if not np.any(near):
        return found
    return {link: tuple(np.where(near, np.nan, v) for v in values)
            for link, values in found.items()}


# -- groups: reduced coordinates ------------------------------------------------------
class _GroupForm:
    """A group's equations in reduced coordinates.

    A binary link of the group pinned by R joints to two links that are not such bars
    says only that its two pins keep their distance: its three coordinates and four
    equations become one distance equation between the links it joins. The unknowns are
    the other links (``bodies``); the bars' poses and rates follow from their pins. (In
    Stephenson's third inversion this turns 12 unknowns into 3.)
    """

    def __init__(self, step):
        links = set(step.links)
        touching = {x: [c for c in step.constraints if x in (c.a, c.b)] for x in links}
        candidates = {x for x, cs in touching.items()
                      if len(cs) == 2 and all(c.kind == "R" for c in cs)
                      and cs[0].other(x) != cs[1].other(x)}
        bars = {x for x in candidates
                if not any(c.other(x) in candidates for c in touching[x])}
        self.bodies = tuple(x for x in step.links if x not in bars)
        if not self.bodies:                        # nothing to reduce onto
            bars, self.bodies = set(), tuple(step.links)
        self.bars = []
        for x in step.links:
            if x in bars:
                c1, c2 = touching[x]
                self.bars.append((x, c1.other(x), c1.point, c2.other(x), c2.point,
                                  math.dist(c1.point, c2.point)))
        self.others = tuple(c for c in step.constraints if c.a not in bars and c.b not in bars)
        self.size = 3 * len(self.bodies)

    def residual(self, pose):
        out = list(_group_residual_of(self.others, pose).T) if self.others else []
        for _, x, px, y, py, length in self.bars:
            wx, wy = _world(pose, x, px), _world(pose, y, py)
            d2 = (wx[0] - wy[0]) ** 2 + (wx[1] - wy[1]) ** 2
            out.append((d2 - length * length) / (2 * length))
        return np.stack(np.broadcast_arrays(*out), axis=-1)

    def rows(self, pose):
        rows = [coef for c in self.others for coef in _rows(c, pose)]
        for _, x, px, y, py, length in self.bars:
            rx, ry_ = rotate(pose[x], px), rotate(pose[y], py)
            d = (rx[0] + pose[x][0] - ry_[0] - pose[y][0], rx[1] + pose[x][1] - ry_[1] - pose[y][1])
            px_, py_ = _perp(rx), _perp(ry_)
            row = {x: (d[0] / length, d[1] / length, (d[0] * px_[0] + d[1] * px_[1]) / length)}
            other = (-d[0] / length, -d[1] / length, -(d[0] * py_[0] + d[1] * py_[1]) / length)
            if y in row:
                row[y] = tuple(a + b for a, b in zip(row[y], other))
            else:
                row[y] = other
            rows.append(row)
        return rows

    def gammas(self, pose, vel):
        out = [g for c in self.others for g in _gammas(c, pose, vel)]
        for _, x, px, y, py, length in self.bars:
            rx, ry_ = rotate(pose[x], px), rotate(pose[y], py)
            d = (rx[0] + pose[x][0] - ry_[0] - pose[y][0], rx[1] + pose[x][1] - ry_[1] - pose[y][1])
            vx_, vy_ = _point_rate(vel[x], rx), _point_rate(vel[y], ry_)
            dd = (vx_[0] - vy_[0], vx_[1] - vy_[1])
            wx2, wy2 = vel[x][2] ** 2, vel[y][2] ** 2
            acc_terms = (wx2 * rx[0] - wy2 * ry_[0], wx2 * rx[1] - wy2 * ry_[1])
            out.append((d[0] * acc_terms[0] + d[1] * acc_terms[1]
                        - dd[0] * dd[0] - dd[1] * dd[1]) / length)
        return out

    def set_bodies(self, pose, q):
        full = dict(pose)
        for k, link in enumerate(self.bodies):
            full[link] = make_pose(q[:, 3 * k], q[:, 3 * k + 1], q[:, 3 * k + 2])
        return full

    def complete(self, pose):
        """Add the bars' poses (each fitted to its two pins)."""
        for bar, x, px, y, py, _ in self.bars:
            pose[bar] = _fit_two_points(px, _world(pose, x, px), py, _world(pose, y, py))
        return pose

    def bar_rates(self, pose, vel, acc=None):
        """The bars' velocities (or, with ``acc``, accelerations) from their pins'."""
        out = {}
        for bar, x, px, y, py, _ in self.bars:
            r1, r2 = rotate(pose[bar], px), rotate(pose[bar], py)
            d = (r2[0] - r1[0], r2[1] - r1[1])
            d2 = d[0] * d[0] + d[1] * d[1]
            if acc is None:
                v1 = _point_rate(vel[x], rotate(pose[x], px))
                v2 = _point_rate(vel[y], rotate(pose[y], py))
                w = (d[0] * (v2[1] - v1[1]) - d[1] * (v2[0] - v1[0])) / d2
                out[bar] = (v1[0] + w * r1[1], v1[1] - w * r1[0], w)
            else:
                a1 = _point_accel(acc[x], vel[x], rotate(pose[x], px))
                a2 = _point_accel(acc[y], vel[y], rotate(pose[y], py))
                al = (d[0] * (a2[1] - a1[1]) - d[1] * (a2[0] - a1[0])) / d2
                w = vel[bar][2]
                out[bar] = (a1[0] + al * r1[1] + w * w * r1[0], a1[1] - al * r1[0] + w * w * r1[1], al)
        return out


def _point_rate(rate, r):
    return rate[0] - rate[2] * r[1], rate[1] + rate[2] * r[0]


def _point_accel(acc, vel, r):
    w2 = vel[2] * vel[2]
    return acc[0] - acc[2] * r[1] - w2 * r[0], acc[1] + acc[2] * r[0] - w2 * r[1]


_FORMS = {}


def _form(step):
    form = _FORMS.get(step)
    if form is None:
        form = _FORMS[step] = _GroupForm(step)
    return form


# -- Newton's method for groups ------------------------------------------------------
def _group_residual_of(constraints, pose):
    out = []
    for c in constraints:
        if c.kind == "R":
            wa, wb = _world(pose, c.a, c.point), _world(pose, c.b, c.point)
            out += [wa[0] - wb[0], wa[1] - wb[1]]
        else:
            dphi = np.remainder(pose[c.b][2] - pose[c.a][2] + np.pi, 2 * np.pi) - np.pi
            n = rotate(pose[c.a], _perp(_unit(c.axis)))
            wg, wb = _world(pose, c.a, c.point), _world(pose, c.b, c.point)
            out += [dphi, n[0] * (wb[0] - wg[0]) + n[1] * (wb[1] - wg[1])]
    return np.stack(out, axis=-1)


def _with_group(pose, step, q):
    return _form(step).set_bodies(pose, q)


def _group_residual(step, pose):
    return _form(step).residual(pose)


def _group_jacobian(step, pose, n):
    form = _form(step)
    rows = [({k: v for k, v in coef.items() if k in form.bodies}, 0.0)
            for coef in form.rows(pose)]
    return _group_matrix(form.bodies, rows, n)[0]


def _chord(plan, step, known, q, iterations=8):
    """Newton's method with the Jacobian inverted once at the guesses (the chord
    method): cheap for many points near their solutions. Returns (q, converged)."""
    tol = 1e-12 * plan.size
    full = _with_group(known, step, q)
    mat = _group_jacobian(step, full, q.shape[0])
    if mat.shape[1] != mat.shape[2]:
        return q, np.zeros(q.shape[0], dtype=bool)
    inv = _batched_inverse(mat)
    q = q.copy()
    for _ in range(iterations):
        r = _group_residual(step, _with_group(known, step, q))
        q -= np.einsum("nij,nj->ni", inv, r)   # one more step after tol: to the rounding
        if np.all(np.abs(r).max(axis=1) <= tol):
            break
    err = np.abs(_group_residual(step, _with_group(known, step, q))).max(axis=1)
    return q, err <= 1e-9 * plan.size


def _newton(plan, step, known, q, iterations=40, tol_rel=1e-12):
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
        sub = _slice(known, active) if active.size < n else known
        full = _with_group(sub, step, q[active])
        r = _group_residual(step, full)
        err = np.abs(r).max(axis=1)
        # go on where not converged and still improving (a fold converges linearly)
        todo = (err > tol) & np.isfinite(err) & ((it < 4) | (err < 0.9 * last[active]))
        last[active] = err
        if not todo.any():
            break
        active, r = active[todo], r[todo]
        full = _slice(full, np.nonzero(todo)[0])
        mat = _group_jacobian(step, full, active.size)
        if mat.shape[1] != mat.shape[2]:
            rhs = np.einsum("nij,ni->nj", mat, -r)
            mat = np.einsum("nij,nik->njk", mat, mat)
        else:
            rhs = -r
        q[active] += _batched_solve(mat, rhs)
    full = _with_group(known, step, q)
    err = np.abs(_group_residual(step, full)).max(axis=1)
    return q, err <= 1e-9 * plan.size


def _batched_inverse(mat):
    """Stacked inverses; a singular matrix gets its pseudo-inverse, a matrix with
    non-finite entries (an earlier step that failed) NaN."""
    out = np.full(mat.shape[:1] + mat.shape[:0:-1], np.nan)
    good = np.isfinite(mat).all(axis=(1, 2))
    if good.any():
        m = mat[good]
        try:
            out[good] = np.linalg.inv(m)
        except np.linalg.LinAlgError:
            out[good] = np.linalg.pinv(m)
    return out


def _batched_solve(mat, rhs):
    """Solve stacked systems; a singular one (at a fold) gets its least-squares step,
    one with non-finite entries NaN."""
    out = np.full(rhs.shape, np.nan)
    good = np.isfinite(mat).all(axis=(1, 2)) & np.isfinite(rhs).all(axis=1)
    if good.any():
        m, r = mat[good], rhs[good]
        try:
            out[good] = np.linalg.solve(m, r[..., None])[..., 0]
        except np.linalg.LinAlgError:
            out[good] = np.einsum("nij,nj->ni", np.linalg.pinv(m), r)
    return out


def _slice(pose, idx):
    return {k: tuple(v if isinstance(v, float) else np.asarray(v)[idx] for v in p)
            for k, p in pose.items()}


def _newton_path(plan, step, pose, theta, q0, coarse_deg=10.0, *, head):
    """Group coordinates along the path, from q0 at its first point.

    A coarse trace of the group's branch by pseudo-arclength continuation (steps of
    at most ``coarse_deg`` in scaled coordinates) follows the assembly mode through
    places where the input angle alone would be a poor parameter, and finds a fold
    (the input turns back: the path cannot go on); every point is then corrected at
    once by batched Newton from Hermite-interpolated guesses. Points past where the
    trace ends are infeasible.
    """
    n = theta.size
    q0 = np.asarray(q0, dtype=float)
    if n == 1:
        q, ok = _newton(plan, step, pose, q0[None])
        return q, ok
    span = theta[-1] - theta[0]
    direction = 1.0 if span >= 0 else -1.0
    h = min(coarse_deg, max(abs(span) / 8.0, 1e-9))
    t = float(theta[0])
    known = _known_along(plan, step, pose, theta, np.array([t]), head)
    qi, ok = _newton(plan, step, known, q0[None])
    if not ok[0]:
        return np.zeros((n, q0.size)), np.zeros(n, dtype=bool)
    ts, qs, dqs, fold = _trace(plan, step, pose, theta, head, qi[0], t, float(theta[-1]),
                               direction, h)
    tc, qc, dqc = np.array(ts), np.array(qs), np.array(dqs)
    reached = direction * (theta - tc[-1]) <= 1e-9
    guess = _hermite(tc, qc, dqc, theta)
    if fold is not None:
        # between the trace's last point and the fold, q moves as the square root of
        # the input's distance from the fold: predict it so, on this side
        t_f, q_f = fold
        near = ~reached & (direction * (theta - t_f) <= 1e-12)
        with np.errstate(invalid="ignore", divide="ignore"):
            frac = np.sqrt(np.clip((t_f - theta[near]) / (t_f - tc[-1]), 0.0, 1.0))
        guess[near] = q_f + (qc[-1] - q_f) * frac[:, None]
        reached = reached | near
    guess = np.where(np.isfinite(guess), guess, 0.0)
    q, ok = _chord(plan, step, pose, guess)
    if not ok.all():
        redo = np.nonzero(~ok)[0]
        q2, ok2 = _newton(plan, step, _slice(pose, redo), guess[redo])
        q[redo], ok[redo] = q2, ok2
    ok &= np.linalg.norm(q - guess, axis=1) <= 0.05 * plan.size
    ok &= reached
    # near a fold the tangent blows up and guesses are poor: continue point by point,
    # approaching each point through ever finer substeps (a limit of the range is a
    # fold, where Newton's method converges only linearly)
    for i in range(1, n):
        if ok[i]:
            continue
        if not ok[i - 1]:
            break
        qi = _approach(plan, step, pose, theta, head, float(theta[i - 1]), q[i - 1],
                       float(theta[i]))
        if qi is None:
            break
        q[i], ok[i] = qi, True
    return q, ok


class _Branch:
    """A group's equations in the scaled unknowns z = (q / scale, input in radians),
    for continuation along its branch."""

    def __init__(self, plan, step, pose, theta, head):
        self.plan, self.step, self.pose, self.theta, self.head = plan, step, pose, theta, head
        m = _form(step).size
        self.scale = np.tile([plan.size, plan.size, 1.0], m // 3)
        self.head_steps = plan.steps[:plan.steps.index(step)]

    def _full(self, z):
        known = _known_along(self.plan, self.step, self.pose, self.theta,
                             np.array([math.degrees(z[-1])]), self.head)
        return _with_group(known, self.step, (self.scale * z[:-1])[None])

    def residual(self, z):
        return _group_residual(self.step, self._full(z))[0] / self.plan.size

    def jacobian(self, z):
        """d(residual)/dz: the group's Jacobian in its unknowns, and its derivative in
        the input, which is minus the velocity equations' right-hand side at unit
        input rate."""
        full = self._full(z)
        vel, _, _ = rates(self.plan, full, 1.0, 1, steps=self.head_steps, measure=False,
                          accelerations=False)
        f = _Factor(self.step, full, 1, self.plan.size)
        ft = -np.array([float(np.broadcast_to(v, (1,))[0])
                        for v in f.right_hand_sides(vel)])
        return np.column_stack([f.mat[0] * self.scale, ft]) / self.plan.size

    def tangent(self, z, like=None, direction=1.0):
        jac = self.jacobian(z)
        if not np.isfinite(jac).all():
            return None
        _, _, vt = np.linalg.svd(jac)
        tau = vt[-1]
        if like is not None:
            return tau if tau @ like >= 0 else -tau
        return tau if tau[-1] * direction >= 0 else -tau

    def correct(self, zp, tau, tol=1e-11):
        """Newton's method from the predicted zp on the branch and the hyperplane
        through zp normal to tau; None if it does not converge."""
        x = zp.copy()
        for _ in range(12):
            r = np.append(self.residual(x), tau @ (x - zp))
            if not np.all(np.isfinite(r)):
                return None
            if np.abs(r).max() <= tol:
                return x
            a = np.vstack([self.jacobian(x), tau])
            if not np.isfinite(a).all():
                return None
            x = x + np.linalg.lstsq(a, -r, rcond=None)[0]
        return None

    def dq(self, tau):
        """dq / d(input) per radian along the branch (infinite at a fold)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.scale * tau[:-1] / tau[-1]


def _trace(plan, step, pose, theta, head, q, t, end, direction, h_deg):
    """Points (input degrees, q, dq/dinput) along the group's branch from (t, q)
    towards ``end``, by pseudo-arclength continuation; stops at ``end`` or a fold."""
    branch = _Branch(plan, step, pose, theta, head)
    z = np.append(q / branch.scale, math.radians(t))
    tau = branch.tangent(z, direction=direction)
    if tau is None:
        return [t], [q], [np.zeros_like(q)], None
    ts, qs, dqs = [t], [q], [branch.dq(tau)]
    fold = None
    h = math.radians(h_deg)
    ds = h
    while direction * (math.degrees(z[-1]) - end) < -1e-12 and ds > 1e-6 * h:
        # no further along the arc than reaching the end needs (far, near a fold)
        remaining = math.radians(abs(end - math.degrees(z[-1])))
        reach = 1.05 * remaining / max(abs(tau[-1]), 1e-300)
        ds = min(ds, reach) if reach > 1e-6 * h else ds
        h_here = max(h, min(reach, math.radians(10.0)))
        zp = z + ds * tau
        x = branch.correct(zp, tau)
        if x is None or np.linalg.norm(x - zp) > 0.25 * ds:
            ds /= 2
            continue
        tau_new = branch.tangent(x, like=tau)
        if tau_new is None or tau_new @ tau < 0.9:
            ds /= 2
            continue
        if tau_new[-1] * direction <= 0 and tau[-1] * direction > 0:
            # the input turned back between z and x: a fold, where the path ends
            fold = _fold(branch, z, tau, ds, direction)
            break
        z, tau = x, tau_new
        ts.append(math.degrees(z[-1])), qs.append(branch.scale * z[:-1])
        dqs.append(branch.dq(tau))
        ds = min(h_here, 1.5 * ds)
    return ts, qs, dqs, fold


def _fold(branch, z, tau, ds, direction):
    """The fold between z and z + ds tau along the arc (where the input turns back),
    by bisection on the sign of the tangent's input component: (input degrees, q)."""
    lo, hi, best = 0.0, ds, None
    for _ in range(40):
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


def _approach(plan, step, pose, theta, head, t_from, q_from, t_to):
    """Group coordinates at ``t_to`` continued from ``q_from`` at ``t_from`` through
    substeps that shrink geometrically towards ``t_to``; None if it cannot be reached."""
    ts = t_to - (t_to - t_from) * 4.0 ** -np.arange(1, 9)
    q = q_from
    for t in list(ts) + [t_to]:
        known = _known_along(plan, step, pose, theta, np.array([t]), head)
        qi, good = _newton(plan, step, known, q[None], iterations=100)
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
    return evaluate_at(plan, at, head.reference(k), upto=plan.steps.index(step))[0]


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


def check_poses(plan, pose, feasible):
    """Raise AssemblyError where a returned pose does not close its loops."""
    res = residuals(plan, pose)
    bad = feasible & ~(res <= 1e-9 * plan.size)
    if bad.any():
        i = int(np.argmax(bad))
        raise AssemblyError(f"loop closure fails at step {i} (residual {res[i]:.3g}, "
                            f"more than 1e-9 of the mechanism's size {plan.size:g})",
                            mechanism=plan.chain.name)
    return res
