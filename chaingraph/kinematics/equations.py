"""The constraint equations: residuals, Jacobian rows and the quadratic velocity terms
of every joint, and a group's equations in reduced coordinates.

Constraints (see :mod:`chaingraph.kinematics.plan`): an R pair keeps two links' points
together; a P joint keeps the block's rotation equal to the guide's and its point on the
guide's line; an input joint adds the prescribed relative rotation (R) or slide (P).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any, TypeAlias

import numpy as np

from chaingraph.errors import AssemblyError
from chaingraph.geometry import (
    PoseEntry,
    Scalar,
    Vec,
    fit_two_points,
    make_pose,
    perp,
    turn_by,
    unit_deg,
    world,
)
from chaingraph.kinematics.plan import Constraint, Plan, Step

__all__ = ["residuals", "check_poses", "newton_step", "constraint_residuals",
           "place_translations"]

#: a pose: each link's entry (x, y, phi, cos phi, sin phi), one point or a batch
Pose: TypeAlias = Mapping[str, PoseEntry]
#: each link's rates (vx, vy, omega), or accelerations (ax, ay, alpha)
Rates: TypeAlias = Mapping[str, tuple[Scalar, Scalar, Scalar]]
#: a row of the constraint Jacobian: link -> (cx, cy, cphi)
Row: TypeAlias = dict[str, tuple[Scalar, Scalar, Scalar]]
#: what a constraint's rows share: the arms on both links, and for a P joint the
#: guide's (normal, direction) and the block's offset from the guide's point
Geometry: TypeAlias = tuple[Vec, Vec, "tuple[Vec, Vec] | None", "Vec | None"]


# -- constraint rows (Jacobian and quadratic velocity terms) ------------------------
def constraint_geometry(c: Constraint, pose: Pose) -> Geometry:
    """What a constraint's rows and acceleration terms share, computed once: the
    constraint point's arms on both links and, for a P joint, the guide's normal and
    the block's offset from the guide's point (and the guide's direction when the
    joint is an input)."""
    ra = turn_by(pose[c.a], c.point)
    rb = turn_by(pose[c.b], c.at(c.b))
    if c.kind == "R":
        return ra, rb, None, None
    u = turn_by(pose[c.a], unit_deg(c.axis))
    d = (rb[0] + pose[c.b][0] - ra[0] - pose[c.a][0], rb[1] + pose[c.b][1] - ra[1] - pose[c.a][1])
    return ra, rb, (perp(u), u), d


def _along_row(g: str, b: str, n: Vec, ra: Vec, rb: Vec, d: Vec) -> Row:
    """The row of n . d (d the block's offset from the guide's point, n turning with the
    guide): the guide's normal keeps the block on its line; its direction, for a P
    input, measures the slide."""
    pn = perp(n)
    prb, prg = perp(rb), perp(ra)
    return {b: (n[0], n[1], n[0] * prb[0] + n[1] * prb[1]),
            g: (-n[0], -n[1], pn[0] * d[0] + pn[1] * d[1] - (n[0] * prg[0] + n[1] * prg[1]))}


def _along_gamma(g: str, b: str, n: Vec, ra: Vec, rb: Vec, d: Vec, vel: Rates) -> Scalar:
    """The acceleration equation's velocity terms for the row of n . d."""
    rg = ra
    pn = perp(n)
    prb, prg = perp(rb), perp(rg)
    (vbx, vby, wb_), (vgx, vgy, wg_) = vel[b], vel[g]
    dd = (vbx + wb_ * prb[0] - vgx - wg_ * prg[0], vby + wb_ * prb[1] - vgy - wg_ * prg[1])
    return (-2 * wg_ * (pn[0] * dd[0] + pn[1] * dd[1])
            + wg_ ** 2 * (n[0] * d[0] + n[1] * d[1])
            + n[0] * (wb_ ** 2 * rb[0] - wg_ ** 2 * rg[0])
            + n[1] * (wb_ ** 2 * rb[1] - wg_ ** 2 * rg[1]))


def constraint_rows(c: Constraint, pose: Pose, geom: Geometry | None = None) -> list[Row]:
    """Rows of the constraint Jacobian, each {link: (cx, cy, cphi)} (constant entries as
    Python floats). An input joint's prescribed value is one more row, whose known
    part is the input's rate (its table entry, the rate in the rotation's place)."""
    ra, rb, frame, d = geom or constraint_geometry(c, pose)
    if c.kind == "R":
        rows = [{c.a: (1.0, 0.0, -ra[1]), c.b: (-1.0, 0.0, rb[1])},
                {c.a: (0.0, 1.0, ra[0]), c.b: (0.0, -1.0, -rb[0])}]
        if c.drive is not None:          # phi_b - phi_a = delta
            rows.append({c.b: (0.0, 0.0, 1.0), c.a: (0.0, 0.0, -1.0), c.drive: (0.0, 0.0, -1.0)})
        return rows
    g, b = c.a, c.b
    assert frame is not None and d is not None          # a P joint's
    n, u = frame
    rows = [{b: (0.0, 0.0, 1.0), g: (0.0, 0.0, -1.0)}, _along_row(g, b, n, ra, rb, d)]
    if c.drive is not None:              # u . d = delta
        rows.append(dict(_along_row(g, b, u, ra, rb, d), **{c.drive: (0.0, 0.0, -1.0)}))
    return rows


def constraint_gammas(c: Constraint, pose: Pose, vel: Rates, geom: Geometry | None = None,
                      ) -> list[Scalar]:
    """Right-hand sides of the acceleration equations from the velocities alone (the
    inputs' accelerations are zero: they move at constant rates)."""
    ra, rb, frame, d = geom or constraint_geometry(c, pose)
    if c.kind == "R":
        wa2, wb2 = vel[c.a][2] ** 2, vel[c.b][2] ** 2
        return [wa2 * ra[0] - wb2 * rb[0], wa2 * ra[1] - wb2 * rb[1]] + \
            ([0.0] if c.drive is not None else [])
    assert frame is not None and d is not None          # a P joint's
    n, u = frame
    out = [0.0, _along_gamma(c.a, c.b, n, ra, rb, d, vel)]
    if c.drive is not None:
        out.append(_along_gamma(c.a, c.b, u, ra, rb, d, vel))
    return out


def constraint_residuals(c: Constraint, pose: Pose) -> list[Scalar]:
    """The constraint's equations at the pose: lengths, and rotations in radians."""
    wa, wb = world(pose, c.a, c.point), world(pose, c.b, c.at(c.b))
    if c.kind == "R" and c.drive is None:     # (no rotation to compare: np.remainder is dear)
        return [wa[0] - wb[0], wa[1] - wb[1]]
    dphi = np.remainder(pose[c.b][2] - pose[c.a][2] - c.turn + np.pi, 2 * np.pi) - np.pi
    if c.kind == "R":
        assert c.drive is not None            # (an R pair without an input returned above)
        return [wa[0] - wb[0], wa[1] - wb[1],
                np.remainder(dphi - pose[c.drive][2] + np.pi, 2 * np.pi) - np.pi]
    n = turn_by(pose[c.a], perp(unit_deg(c.axis)))
    out = [dphi, n[0] * (wb[0] - wa[0]) + n[1] * (wb[1] - wa[1])]
    if c.drive is not None:
        u = turn_by(pose[c.a], unit_deg(c.axis))
        out.append(u[0] * (wb[0] - wa[0]) + u[1] * (wb[1] - wa[1]) - pose[c.drive][2])
    return out


def residuals(plan: Plan, pose: Pose) -> Scalar:
    """Largest constraint residual at every point (lengths; rotations times the size)."""
    worst = None
    for c in plan.constraints:
        eqs = constraint_residuals(c, pose)
        if c.kind == "R":
            r = np.hypot(eqs[0], eqs[1])
            if c.drive is not None:
                r = np.maximum(r, np.abs(eqs[2]) * plan.size)
        else:
            r = np.maximum(np.abs(eqs[1]), np.abs(eqs[0]) * plan.size)
            if c.drive is not None:
                r = np.maximum(r, np.abs(eqs[2]))
        worst = r if worst is None else np.maximum(worst, r)
    return worst


def dot3(c: Sequence[Scalar], v: Sequence[Scalar]) -> Scalar:
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



def times(a: Scalar, b: Scalar) -> Scalar:
    """a * b, skipping the product where a constant factor is 0 or 1."""
    if isinstance(a, float) and a == 0.0 or isinstance(b, float) and b == 0.0:
        return 0.0
    if isinstance(a, float) and a == 1.0:
        return b
    if isinstance(b, float) and b == 1.0:
        return a
    return a * b


def plus(a: Scalar, b: Scalar) -> Scalar:
    """a + b, skipping the sum where a constant term is 0."""
    if isinstance(a, float) and a == 0.0:
        return b
    if isinstance(b, float) and b == 0.0:
        return a
    return a + b


def minus(a: Scalar, b: Scalar) -> Scalar:
    """a - b, skipping the difference where the constant ``b`` is 0."""
    if isinstance(b, float) and b == 0.0:
        return a
    return a - b


def group_matrix(links: Sequence[str], rows: Sequence[tuple[Row, Scalar]], n: int,
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The stacked matrices (n, rows, 3 links) of Jacobian ``rows`` over ``links``
    and their right-hand sides (n, rows)."""
    col = {link: 3 * k for k, link in enumerate(links)}
    size = 3 * len(links)
    # only a row's own links' entries are set: a group's rows are sparse (a joint
    # touches two links), and setting every entry made a large group's matrix slow
    mat = np.zeros((n, len(rows), size))
    for i, (coef, _) in enumerate(rows):
        for link, cf in coef.items():
            for k in range(3):
                mat[:, i, col[link] + k] = cf[k]
    rhs = np.empty((n, len(rows)))
    for i, (_, r) in enumerate(rows):
        rhs[:, i] = r
    return mat, rhs



# -- groups: reduced coordinates ------------------------------------------------------
class _GroupForm:
    """A group's equations in reduced coordinates.

    A binary link of the group pinned by R joints to two links that are not such bars
    says only that its two pins keep their distance: its three coordinates and four
    equations become one distance equation between the links it joins. The unknowns are
    the other links (``bodies``); the bars' poses and rates follow from their pins. (In
    Stephenson's third inversion this turns 12 unknowns into 3.)
    """

    def __init__(self, step: Step) -> None:
        links = set(step.links)
        touching = {x: [c for c in step.constraints if x in (c.a, c.b)] for x in links}
        candidates = {x for x, cs in touching.items()
                      if len(cs) == 2 and all(c.kind == "R" and c.drive is None for c in cs)
                      and cs[0].other(x) != cs[1].other(x)}
        bars = {x for x in candidates
                if not any(c.other(x) in candidates for c in touching[x])}
        self.bodies = tuple(x for x in step.links if x not in bars)
        if not self.bodies:                        # nothing to reduce onto
            bars, self.bodies = set(), tuple(step.links)
        self.bars: list[tuple[str, str, tuple[float, float], str, tuple[float, float], float,
                              tuple[float, float], tuple[float, float]]] = []
        for x in step.links:
            if x in bars:
                c1, c2 = touching[x]
                # (the bar, each link it joins with the pin's point on that link,
                # the pins' distance, and the pins' points on the bar)
                y1, y2 = c1.other(x), c2.other(x)
                self.bars.append((x, y1, c1.at(y1), y2, c2.at(y2),
                                  math.dist(c1.at(x), c2.at(x)), c1.at(x), c2.at(x)))
        self.others = tuple(c for c in step.constraints if c.a not in bars and c.b not in bars)
        self.size = 3 * len(self.bodies)

    def residual(self, pose: Pose) -> np.ndarray:
        out = [e for c in self.others for e in constraint_residuals(c, pose)]
        for _, x, px, y, py, length, _, _ in self.bars:
            wx, wy = world(pose, x, px), world(pose, y, py)
            d2 = (wx[0] - wy[0]) ** 2 + (wx[1] - wy[1]) ** 2
            out.append((d2 - length * length) / (2 * length))
        if not any(isinstance(e, np.ndarray) and e.ndim for e in out):
            return np.array(out, dtype=float)           # one point, in numbers
        return np.stack(np.broadcast_arrays(*out), axis=-1)

    def rows(self, pose: Pose) -> list[Row]:
        rows = [coef for c in self.others for coef in constraint_rows(c, pose)]
        for _, x, px, y, py, length, _, _ in self.bars:
            rx, ry_ = turn_by(pose[x], px), turn_by(pose[y], py)
            d = (rx[0] + pose[x][0] - ry_[0] - pose[y][0], rx[1] + pose[x][1] - ry_[1] - pose[y][1])
            px_, py_ = perp(rx), perp(ry_)
            row = {x: (d[0] / length, d[1] / length, (d[0] * px_[0] + d[1] * px_[1]) / length)}
            other = (-d[0] / length, -d[1] / length, -(d[0] * py_[0] + d[1] * py_[1]) / length)
            if y in row:
                row[y] = tuple(a + b for a, b in zip(row[y], other))
            else:
                row[y] = other
            rows.append(row)
        return rows

    def gammas(self, pose: Pose, vel: Rates) -> list[Scalar]:
        out = [g for c in self.others for g in constraint_gammas(c, pose, vel)]
        for _, x, px, y, py, length, _, _ in self.bars:
            rx, ry_ = turn_by(pose[x], px), turn_by(pose[y], py)
            d = (rx[0] + pose[x][0] - ry_[0] - pose[y][0], rx[1] + pose[x][1] - ry_[1] - pose[y][1])
            vx_, vy_ = _point_rate(vel[x], rx), _point_rate(vel[y], ry_)
            dd = (vx_[0] - vy_[0], vx_[1] - vy_[1])
            wx2, wy2 = vel[x][2] ** 2, vel[y][2] ** 2
            acc_terms = (wx2 * rx[0] - wy2 * ry_[0], wx2 * rx[1] - wy2 * ry_[1])
            out.append((d[0] * acc_terms[0] + d[1] * acc_terms[1]
                        - dd[0] * dd[0] - dd[1] * dd[1]) / length)
        return out

    def set_bodies(self, pose: Pose, q: np.ndarray) -> dict[str, PoseEntry]:
        full = dict(pose)
        for k, link in enumerate(self.bodies):
            full[link] = make_pose(q[:, 3 * k], q[:, 3 * k + 1], q[:, 3 * k + 2])
        return full

    def set_bodies_at(self, pose: Pose, q: Sequence[float]) -> dict[str, PoseEntry]:
        """:meth:`set_bodies` at one point: ``pose`` in numbers (:func:`pose_at_point`)
        and ``q`` one point's reduced coordinates."""
        full = dict(pose)
        for k, link in enumerate(self.bodies):
            phi = float(q[3 * k + 2])
            full[link] = (float(q[3 * k]), float(q[3 * k + 1]), phi, math.cos(phi),
                          math.sin(phi))
        return full

    def complete(self, pose: dict[str, PoseEntry]) -> dict[str, PoseEntry]:
        """Add the bars' poses (each fitted to its two pins)."""
        for bar, x, px, y, py, _, bx, by in self.bars:
            pose[bar] = fit_two_points(bx, world(pose, x, px), by, world(pose, y, py))
        return pose

    def bar_rates(self, pose: Pose, vel: Rates, acc: Rates | None = None,
                  ) -> dict[str, tuple[Scalar, Scalar, Scalar]]:
        """The bars' velocities (or, with ``acc``, accelerations) from their pins'."""
        out: dict[str, tuple[Scalar, Scalar, Scalar]] = {}
        for bar, x, px, y, py, _, bx, by in self.bars:
            r1, r2 = turn_by(pose[bar], bx), turn_by(pose[bar], by)
            d = (r2[0] - r1[0], r2[1] - r1[1])
            d2 = d[0] * d[0] + d[1] * d[1]
            if acc is None:
                v1 = _point_rate(vel[x], turn_by(pose[x], px))
                v2 = _point_rate(vel[y], turn_by(pose[y], py))
                w = (d[0] * (v2[1] - v1[1]) - d[1] * (v2[0] - v1[0])) / d2
                out[bar] = (v1[0] + w * r1[1], v1[1] - w * r1[0], w)
            else:
                a1 = _point_accel(acc[x], vel[x], turn_by(pose[x], px))
                a2 = _point_accel(acc[y], vel[y], turn_by(pose[y], py))
                al = (d[0] * (a2[1] - a1[1]) - d[1] * (a2[0] - a1[0])) / d2
                w = vel[bar][2]
                out[bar] = (a1[0] + al * r1[1] + w * w * r1[0], a1[1] - al * r1[0] + w * w * r1[1], al)
        return out


def _point_rate(rate: tuple[Scalar, Scalar, Scalar], r: Vec) -> tuple[Scalar, Scalar]:
    return rate[0] - rate[2] * r[1], rate[1] + rate[2] * r[0]


def _point_accel(acc: tuple[Scalar, Scalar, Scalar], vel: tuple[Scalar, Scalar, Scalar],
                 r: Vec) -> tuple[Scalar, Scalar]:
    w2 = vel[2] * vel[2]
    return acc[0] - acc[2] * r[1] - w2 * r[0], acc[1] + acc[2] * r[0] - w2 * r[1]


_FORMS: dict[Step, _GroupForm] = {}


def group_form(step: Step) -> _GroupForm:
    """A group's equations in reduced coordinates (cached by step)."""
    form = _FORMS.get(step)
    if form is None:
        if len(_FORMS) >= 4096:     # every assembly from lengths has its own steps
            _FORMS.clear()
        form = _FORMS[step] = _GroupForm(step)
    return form


# -- Newton's method for groups ------------------------------------------------------
def with_group(pose: Pose, step: Step, q: np.ndarray) -> dict[str, PoseEntry]:
    """The pose with the group's bodies at the reduced coordinates ``q`` (n, 3 bodies)."""
    return group_form(step).set_bodies(pose, q)


def group_residual(step: Step, pose: Pose) -> np.ndarray:
    """The group's equations at the pose (n, equations)."""
    return group_form(step).residual(pose)


def pose_at_point(pose: Mapping[str, Sequence[Any]]) -> dict[str, Any]:
    """A pose (or rates) of one point, each entry a number or an array of one, in
    Python numbers: the equations then cost a few microseconds of arithmetic instead of
    a numpy call per term (a group's continuation evaluates them one point at a time)."""
    def number(v):
        if v is None or isinstance(v, float):
            return v
        return float(v[0]) if isinstance(v, np.ndarray) and v.ndim else float(v)
    return {link: tuple(number(v) for v in entry) for link, entry in pose.items()}


def group_rows_at(step: Step, pose: Pose) -> tuple[np.ndarray, list[Row]]:
    """The group's Jacobian in its reduced coordinates at one point (equations, 3
    bodies) and each row's entries on the links it does not solve (the known links and
    the inputs), from a pose in numbers (:func:`pose_at_point`)."""
    form = group_form(step)
    col = {link: 3 * k for k, link in enumerate(form.bodies)}
    rows = form.rows(pose)
    mat = np.zeros((len(rows), form.size))
    known: list[Row] = []
    for i, coef in enumerate(rows):
        other: Row = {}
        for link, cf in coef.items():
            k = col.get(link)
            if k is None:
                other[link] = cf
            else:
                mat[i, k:k + 3] = cf
        known.append(other)
    return mat, known


def group_jacobian(step: Step, pose: Pose, n: int) -> np.ndarray:
    """The group's Jacobian in its reduced coordinates (n, equations, 3 bodies)."""
    form = group_form(step)
    rows = [({k: v for k, v in coef.items() if k in form.bodies}, 0.0)
            for coef in form.rows(pose)]
    return group_matrix(form.bodies, rows, n)[0]



def batched_inverse(mat: np.ndarray) -> np.ndarray:
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


def newton_step(mat: np.ndarray, r: np.ndarray) -> np.ndarray:
    """Newton's step ``dx`` for stacked systems ``J dx = -r``: a square ``J`` solved
    (at a fold, the least-squares step), more equations than unknowns by the normal
    equations. The one Newton step: the solver's groups and the assembly use it.

    >>> mat = np.array([[[2.0, 0.0], [0.0, 4.0], [0.0, 0.0]]])
    >>> [float(v) for v in newton_step(mat, np.array([[2.0, -4.0, 0.0]]))[0]]
    [-1.0, 1.0]
    """
    if mat.shape[1] != mat.shape[2]:
        return batched_solve(np.einsum("nij,nik->njk", mat, mat),
                             np.einsum("nij,ni->nj", mat, -r))
    return batched_solve(mat, -r)


def place_translations(links: Sequence[str], constraints: Sequence[Constraint], pose: Pose,
                       ) -> dict[str, PoseEntry] | None:
    """Links whose rotations are known, placed by their translations.

    ``pose`` holds each of ``links`` at its rotation (at any translation) beside the
    links already placed; ``constraints`` join them to each other and to placed links.
    The equations are linear in the translations, so one Newton step in them is exact
    (least squares where there are more equations than unknowns). Returns the links'
    pose entries, or None where the equations do not fix the translations. One pose
    (the assembly from lengths), not a batch.
    """
    col = {link: 3 * k for k, link in enumerate(links)}
    rows = [({x: v for x, v in coef.items() if x in col}, 0.0)
            for c in constraints for coef in constraint_rows(c, pose)]
    mat = group_matrix(links, rows, 1)[0][0]
    moves = [col[link] + k for link in links for k in (0, 1)]
    mat = mat[:, moves]
    if len(rows) < len(moves) or np.linalg.matrix_rank(
            mat, tol=1e-9 * max(1.0, float(np.abs(mat).max()))) < len(moves):
        return None
    r = np.array([float(e) for c in constraints for e in constraint_residuals(c, pose)])
    step = newton_step(mat[None], r[None])[0]
    return {link: make_pose(pose[link][0] + step[2 * k], pose[link][1] + step[2 * k + 1],
                            pose[link][2], pose[link][3], pose[link][4])
            for k, link in enumerate(links)}


def batched_solve(mat: np.ndarray, rhs: np.ndarray) -> np.ndarray:
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


def slice(pose: Pose, idx: int | np.ndarray) -> dict[str, PoseEntry]:
    """The pose at the points ``idx`` of a batch (its constant entries kept)."""
    def pick(v: Scalar) -> Scalar:
        return v if isinstance(v, float) else np.asarray(v)[idx]
    return {k: (pick(p[0]), pick(p[1]), pick(p[2]), pick(p[3]), pick(p[4]))
            for k, p in pose.items()}



def _closes(plan: Plan, pose: Pose, tol: float,
            constraints: Sequence[Constraint]) -> np.ndarray:
    """Where every one of ``constraints`` has a residual of at most ``tol`` (as
    :func:`residuals` measures it, compared without its square roots and remainders,
    which cost more than the rest of the check): False where one is larger or not a
    number."""
    ok = np.ones(np.shape(pose[plan.fixed][0]) or (), dtype=bool)
    for c in constraints:
        if c.kind != "R":
            eqs = constraint_residuals(c, pose)
            ok = ok & (np.abs(eqs[1]) <= tol) & (np.abs(eqs[0]) * plan.size <= tol)
            if c.drive is not None:
                ok = ok & (np.abs(eqs[2]) <= tol)
            continue
        wa, wb = world(pose, c.a, c.point), world(pose, c.b, c.at(c.b))
        dx, dy = wa[0] - wb[0], wa[1] - wb[1]
        ok = ok & (dx * dx + dy * dy <= tol * tol)
        if c.drive is not None:        # the relative rotation, to whole turns
            d = pose[c.b][2] - pose[c.a][2] - c.turn - pose[c.drive][2]
            d = d - (2 * np.pi) * np.round(d / (2 * np.pi))
            ok = ok & (np.abs(d) * plan.size <= tol)
    return ok


def check_poses(plan: Plan, pose: Pose, feasible: np.ndarray, *,
                constraints: Sequence[Constraint] | None = None) -> None:
    """Raise AssemblyError where a returned pose does not close its loops (a residual,
    as :func:`residuals` measures it, over 1e-9 of the size). ``constraints``: only
    these pairs (by default every one; the pose's builder knows which it met by
    construction: :func:`~chaingraph.kinematics.closed_form.closure_checks`)."""
    pairs = plan.constraints if constraints is None else constraints
    bad = feasible & ~_closes(plan, pose, 1e-9 * plan.size, pairs)
    if bad.any():
        res = residuals(plan, pose)
        i = int(np.argmax(bad))
        if not np.isfinite(res[i]):
            raise AssemblyError(f"the pose at step {i} cannot be computed: "
                                f"{_undefined_at(plan, pose, i)}",
                                mechanism=plan.chain.name)
        raise AssemblyError(f"loop closure fails at step {i} (residual {res[i]:.3g}, "
                            f"more than 1e-9 of the mechanism's size {plan.size:g})",
                            mechanism=plan.chain.name)


def _undefined_at(plan: Plan, pose: Pose, i: int) -> str:
    """What is undefined at point i of a pose whose residual there is not a number: the
    first joint whose equations are not (a link placed from two joints that meet, a
    sliding pair whose line or direction is undefined)."""
    for c in plan.constraints:
        with np.errstate(invalid="ignore"):
            eqs = [np.asarray(e, dtype=float) for e in constraint_residuals(c, pose)]
        if not all(np.isfinite(e.reshape(-1)[i if e.size > 1 else 0]) for e in eqs):
            pair = "sliding pair" if c.kind == "P" else "joint"
            return (f"the {pair} {c.joint!r} of links {c.a!r} and {c.b!r} has no defined "
                    "place there (a link placed from two joints that meet, or a sliding "
                    "pair whose line is undefined)")
    return "a link's place is undefined there (two joints that place it meet)"
