"""The force solve: every moving link's equilibrium (with its inertia force and couple
in kinetostatics, d'Alembert's principle), batched over the steps of a sweep.

The unknowns are the joints' reactions (two components for a turning pair of two
links; the forces on all but the last link for a multiple joint; the normal force and
the couple for a sliding pair, with Coulomb friction along its guide in proportion to
the normal force; one force for a higher pair: a cam's along the common normal at the
contact, a gear pair's along the common tangent at the pitch point, whose radial part
along the line of action, |tangential| tan(pressure angle) (the pair's
``pressure_angle``, 20 degrees by default), is then added as a known force) and one effort per input (a couple between the input's two links for an R
input, a force along the guide for a P input). Three equations per moving link,
the forces and the moment about the drawing's origin, in SI units: one linear solve per
step, all steps at once; over a sweep, group by group as the textbook solves it (the
last dyad placed first, back to the input: a dyad's six equations at a time), where
the plan's groups split the system so. Friction's sign follows the normal force's sign, found by
iterating the signs per step until they agree (every combination tried where they do
not settle).
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace

import numpy as np

from chaingraph.errors import MechanismError
from chaingraph.geometry import Vec, cross, rotate, unit_deg
from chaingraph.kinematics.equations import dot3
from chaingraph.kinematics.higher import HIGHER_KINDS, cam_contact, cam_frame
from chaingraph.kinematics.plan import InputJoint, Plan
from chaingraph.kinematics.pose import LinkState
from chaingraph.model.chain import Chain, Joint, Load, mass_centre

__all__ = ["UNIT_METRES", "KinematicState", "Solution", "solve_equilibrium", "load_table_value",
           "solve_block_triangular"]

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
    #: what the loads that follow the motion read: each P joint's slide from the drawn
    #: pose (file units), the lead R input's value (radians), and per load (by its
    #: index) limited to the input's forward or return stroke, the direction its point
    #: moves in during that stroke (unit vector)
    slides: dict[str, np.ndarray] = field(default_factory=dict)
    angle: np.ndarray | None = None
    strokes: dict[int, tuple[float, float]] = field(default_factory=dict)

    def direction(self, link: str, degrees: float) -> Vec:
        """The unit vector drawn at ``degrees`` on the link, turned with it."""
        return rotate(unit_deg(degrees), self.links[link].angle)


@dataclass(frozen=True)
class Solution:
    """The solve's numbers at n steps (NaN where not determined): ``forces[(joint,
    link)]`` the (Fx, Fy) on ``link`` at the joint (for a two-link joint its first link,
    by the second), ``normal[joint]``, ``couple[joint]`` for P joints (``normal`` also
    for a higher pair: a cam's contact force along the common normal, positive where it
    pushes the follower off the cam; a gear pair's tooth force along the line of
    action), ``efforts[joint]`` per input, ``power`` the power balance (W), ``singular`` the dead-centre steps,
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
                      metres: float = 1.0, mean_torque: float = 0.0,
                      by_groups: bool = True) -> Solution:
    """The reactions and efforts of ``chain`` (its masses, gravity, loads, friction) at
    the ``state``'s steps; ``plan`` gives the fixed link and the inputs; ``metres`` is
    the length unit in metres; drawn coordinates are taken about ``plan.origin``;
    ``mean_torque`` (N m) is the torque of a ``torque = "mean"`` load.

    With ``by_groups`` (the default), the steps whose dead centres the motion gives
    (``state.rates_known``) are solved as the textbook does, group by group from the
    last the plan places back to the input (a dyad's six equations, then the next),
    each group's reactions at the links placed after it being known by then; the
    whole system at once where the equations do not split so, and with ``by_groups``
    false (the same answers, to rounding)."""
    layout = _layout(chain, plan, state.n, metres, by_groups=by_groups and state.rates_known)
    joints = _joint_geometry(chain, layout, state)
    known = _known_forces(chain, layout, state, joints, static=static,
                          mean_torque=mean_torque)
    dead = _known_singular(layout, state)
    x, singular, settled, sigma = _solve_with_friction(layout, joints, -known.rhs, dead)
    parting = _parting_forces(layout, joints, x)
    if parting is not None:     # the gears' radial forces: the reactions at their axes
        x, singular, settled, sigma = _solve_with_friction(
            layout, joints, -known.rhs - parting, dead)
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
    moments are divided by ``size`` (m) so that every row is a force.

    ``groups``, when the system splits as the plan places the links (see
    :func:`_split`): the equations and the unknowns laid out group by group in the
    order they are solved, from the last group placed back to the input, and where
    each group's ends (its rows and its columns alike: as many unknowns as equations);
    ``dyads`` whether each group is a dyad laid out as :func:`solve_block_triangular`
    solves it in closed form."""

    n: int
    fixed: str
    row: dict
    cols: tuple
    origin: tuple
    metres: float
    size: float
    groups: tuple[int, ...] | None = None
    dyads: tuple[bool, ...] = ()

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

    def put(self, a, link, col, f, q):
        """Add the force f (Fx, Fy arrays) at q on ``link`` to column ``col`` of ``a``."""
        if link == self.fixed:
            return
        r = self.row[link]
        m = cross(q, f) / self.size                          # moments over the size
        a[:, r, col] += f[0]
        a[:, r + 1, col] += f[1]
        a[:, r + 2, col] += m

    def put_pair(self, a, on, by, col, f, q):
        """Add the force f at q on ``on`` and its reaction on ``by`` (the moment worked
        out once; no entry on the fixed link)."""
        m = cross(q, f) / self.size
        for link, add in ((on, np.add), (by, np.subtract)):
            if link == self.fixed:
                continue
            r = self.row[link]
            for k, v in enumerate((f[0], f[1], m)):
                if not (isinstance(v, float) and v == 0.0):     # (a unit force's zero)
                    add(a[:, r + k, col], v, out=a[:, r + k, col])

    def put_couple(self, a, link, col, c, sign=1.0):
        """Add the couple c on ``link`` to column ``col`` of ``a``."""
        if link == self.fixed:
            return
        a[:, self.row[link] + 2, col] += sign * c / self.size


def _layout(chain, plan, n, metres, *, by_groups=False):
    """The unknowns (two reaction components per pair of an R joint's links; a P joint's
    normal force and couple; a higher pair's force; an effort per input) and the
    equations (three per moving link), laid out group by group with ``by_groups`` where
    the system splits so (:func:`_split`); refuses another joint (a rolling pair), and
    inputs that do not hold the mechanism."""
    cols: list[tuple[str, Joint | InputJoint, int | None]] = []   # (kind, joint, extra)
    for j in chain.joints:
        if j.kind == "R":
            for k in range(len(j.links) - 1):
                cols += [("Fx", j, k), ("Fy", j, k)]
        elif j.kind == "P":
            cols += [("N", j, None), ("M", j, None)]
        elif j.kind in HIGHER_KINDS:    # one force: along the common normal, or the tangent
            cols.append(("contact", j, None))
        else:
            raise MechanismError(f"forces are solved for R and P joints; joint {j.id!r} is "
                                 f"{j.kind}", mechanism=chain.source or chain.name)
    for item in plan.inputs:
        cols.append(("effort", item, None))
    moving = [x for x in chain.links if x != plan.fixed]
    split = _split(plan, moving, cols) if by_groups else None
    if split is not None:
        moving, cols = split[0], split[1]
    layout = _Layout(n=n, fixed=plan.fixed, row={link: 3 * i for i, link in enumerate(moving)},
                     cols=tuple(cols), origin=plan.origin, metres=metres,
                     size=max(plan.size * metres, 1e-300),
                     groups=None if split is None else split[2],
                     dyads=() if split is None else split[3])
    if layout.rows > len(cols):
        raise MechanismError(
            f"the inputs do not hold the mechanism: {len(cols)} unknown reactions and "
            f"efforts for {layout.rows} equations of equilibrium (give one input per degree "
            "of freedom)", mechanism=chain.source or chain.name)
    return layout


def _split(plan, moving, cols):
    """The system in the textbook's order, group by group from the last the plan places
    back to the input: each group's equations (three per link) with the unknowns they
    alone leave once the groups placed after it are solved (its own joints' reactions,
    those joining it to the links placed before it, its input's effort). As (the moving
    links, the unknowns, each group's end, whether it is a dyad) so ordered, the matrix
    is block triangular: a small system per group (a dyad's six equations) gives the
    whole system's answer. A dyad whose links each keep two unknowns of their own (a
    pair's, to the links placed before) and share two (their own pair's) has them in
    that order (the first link's, the second's, the shared), as
    :func:`solve_block_triangular` solves it. None where the system does not split so
    (a group leaving more or fewer unknowns than its equations, links no step places, a
    statically indeterminate chain)."""
    if len(cols) != 3 * len(moving):
        return None
    touches = [_column_links(kind, j, k) - {plan.fixed} for kind, j, k in cols]
    links: list[str] = []
    order: list[int] = []
    ends, dyads = [], []
    for step in reversed(plan.steps):
        group = [x for x in step.links if x != plan.fixed]
        # (in the layout's order: a reaction's two components stay side by side, as
        # :func:`_reactions` reads them)
        mine = [c for c, t in enumerate(touches) if t.intersection(group) and c not in order]
        if not group or len(mine) != 3 * len(group) or set(group) & set(links):
            return None
        if len(group) == 2:         # the first link's own, the second's, the shared
            parts = [[c for c in mine if touches[c] & set(group) == want]
                     for want in ({group[0]}, {group[1]}, set(group))]
            dyads.append([len(part) for part in parts] == [2, 2, 2])
            if dyads[-1]:
                mine = [c for part in parts for c in part]
        else:
            dyads.append(False)
        links += group
        order += mine
        ends.append(len(order))
    if set(links) != set(moving):
        return None
    return links, [cols[c] for c in order], tuple(ends), tuple(dyads)


def _column_links(kind, j, k):
    """The links whose equations the unknown (kind, joint, extra) enters."""
    if kind in ("Fx", "Fy"):                    # on j.links[k], by the last
        return {j.links[k], j.links[-1]}
    if kind == "effort":                        # between the input's two links
        return {j.a, j.b}
    return set(j.links)                         # a sliding or a higher pair's


def solve_block_triangular(a: np.ndarray, b: np.ndarray, ends: tuple[int, ...], *,
                           dyads: tuple[bool, ...] = ()) -> np.ndarray:
    """x with a x = b per step, as :func:`numpy.linalg.solve` (a of shape (n, m, m), b
    (n, m, 1)), for a block lower triangular a whose diagonal blocks end at ``ends``:
    one small system per block, forward. A block of three (a single link's) by Cramer's
    rule; a block that ``dyads`` marks, [[E1, 0, I1], [0, E2, I2]] in blocks of 3 x 2
    (two links' equations, each link's own two unknowns, then the two they share), in
    closed form as :func:`_dyad` says; another by LU. Raises
    :class:`numpy.linalg.LinAlgError` where a block is singular."""
    x = np.empty(b.shape)
    lo = 0
    for g, hi in enumerate(ends):
        rhs = b[:, lo:hi]
        if lo:
            rhs = rhs - a[:, lo:hi, :lo] @ x[:, :lo]
        block = a[:, lo:hi, lo:hi]
        if hi - lo == 3:
            x[:, lo:hi] = _cramer3(block, rhs)
        elif g < len(dyads) and dyads[g]:
            x[:, lo:hi] = _dyad(block, rhs)
        else:
            x[:, lo:hi] = np.linalg.solve(block, rhs)
        lo = hi
    return x


def _dyad(d, r):
    """x with d x = r per step for a dyad's six equations (d (n, 6, 6) laid out as
    :func:`solve_block_triangular` says, r (n, 6, 1)), as the textbook does: each link's
    equations taken about the line its own two unknowns leave free (the cross product of
    their columns, n1 and n2: the moment about the pair they act at, for a turning pair)
    give the two shared unknowns (2 x 2, by Cramer's rule); then each link's own two from
    what remains of its equations. A quarter of a batched LU's time (3,601 steps). Raises
    :class:`numpy.linalg.LinAlgError` where the 2 x 2 determinant is nil (a singular
    dyad)."""
    def col(row, c):
        return (d[:, row, c], d[:, row + 1, c], d[:, row + 2, c])
    e1, f1, e2, f2 = col(0, 0), col(0, 1), col(3, 2), col(3, 3)
    s1, t1, s2, t2 = col(0, 4), col(0, 5), col(3, 4), col(3, 5)
    r1 = (r[:, 0, 0], r[:, 1, 0], r[:, 2, 0])
    r2 = (r[:, 3, 0], r[:, 4, 0], r[:, 5, 0])
    n1, n2 = _cross3(e1, f1), _cross3(e2, f2)
    m00, m01, m10, m11 = dot3(n1, s1), dot3(n1, t1), dot3(n2, s2), dot3(n2, t2)
    q0, q1 = dot3(n1, r1), dot3(n2, r2)
    det = m00 * m11 - m01 * m10
    if not det.all():
        raise np.linalg.LinAlgError("Singular matrix")
    x = np.empty(r.shape)
    g = x[:, 4, 0], x[:, 5, 0]
    np.divide(q0 * m11 - m01 * q1, det, out=g[0])
    np.divide(m00 * q1 - m10 * q0, det, out=g[1])
    for c, e, f, s, t, rr, nn in ((0, e1, f1, s1, t1, r1, n1), (2, e2, f2, s2, t2, r2, n2)):
        rest = tuple(rr[k] - s[k] * g[0] - t[k] * g[1] for k in range(3))
        size = dot3(nn, nn)        # rest = u e + v f: rest x f = u n, e x rest = v n
        x[:, c, 0] = dot3(_cross3(rest, f), nn) / size
        x[:, c + 1, 0] = dot3(_cross3(e, rest), nn) / size
    return x


def _cross3(u, v):
    """The cross product of two 3-vectors given as their components' arrays."""
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def _cramer3(a, b):
    """x with a x = b per step for 3 x 3 systems (a (n, 3, 3), b (n, 3, 1)) by Cramer's
    rule (the adjugate over the determinant): a seventh of a batched LU's time (3,601
    steps). Raises :class:`numpy.linalg.LinAlgError` where a determinant is nil."""
    (a00, a01, a02), (a10, a11, a12), (a20, a21, a22) = (
        [a[:, i, j] for j in range(3)] for i in range(3))
    c00, c01, c02 = a11 * a22 - a12 * a21, a12 * a20 - a10 * a22, a10 * a21 - a11 * a20
    det = a00 * c00 + a01 * c01 + a02 * c02
    if not det.all():
        raise np.linalg.LinAlgError("Singular matrix")
    b0, b1, b2 = b[:, 0, 0], b[:, 1, 0], b[:, 2, 0]
    x = np.empty(b.shape)
    x[:, 0, 0] = b0 * c00 + b1 * (a02 * a21 - a01 * a22) + b2 * (a01 * a12 - a02 * a11)
    x[:, 1, 0] = b0 * c01 + b1 * (a00 * a22 - a02 * a20) + b2 * (a02 * a10 - a00 * a12)
    x[:, 2, 0] = b0 * c02 + b1 * (a01 * a20 - a00 * a21) + b2 * (a00 * a11 - a01 * a10)
    x /= det[:, None, None]
    return x


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
    higher: dict = field(default_factory=dict)

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
    higher = _higher_lines(chain, layout, state)
    where.update({k: h.point for k, h in higher.items()})
    return _Joints(where, axis, slide_speed, friction, normal_cols, higher)


@dataclass(frozen=True)
class _Line:
    """A higher pair's force over the steps: ``by`` pushes ``on`` at ``point`` (m about
    the origin) along ``direction`` (unit) per unit of its unknown; a gear pair's
    ``radial`` is the direction that parts ``on`` from ``by`` (else None), and its tooth
    force's line of action leans ``pressure`` (radians) from the common tangent."""

    point: Vec
    direction: Vec
    on: str
    by: str
    radial: Vec | None = None
    pressure: float = 0.0


def _higher_lines(chain, layout, state):
    """Each cam's contact point and common normal (from the cam to the follower), each
    gear pair's pitch point, common tangent and line of centres, as the links move."""
    n = state.n
    out = {}
    for cam in chain.cams:
        frame = cam_frame(chain, cam)
        on = state.links[frame.on]
        turn = np.broadcast_to(np.asarray(state.links[cam.cam].angle, dtype=float)
                               - np.asarray(on.angle, dtype=float), (n,))
        point, normal, _ = cam_contact(chain, cam, turn, frame=frame)
        where = on.moved(layout.drawn((point[:, 0], point[:, 1])))
        out[cam.id] = _Line(where, rotate((normal[:, 0], normal[:, 1]), on.angle),
                            cam.follower, cam.cam)
    for g in chain.gears:
        carrier = state.links[g.carrier]
        axes = [next(j.at for j in chain.joints if j.kind == "R" and link in j.links
                     and g.carrier in j.links) for link in g.links]
        a, b = (carrier.moved(layout.drawn(p)) for p in axes)
        pitch = carrier.moved(layout.drawn(chain.joint(g.id).at))
        # the common tangent, square to the line of centres; the radial direction from
        # the driving gear's axis through the pitch point (away from it on the other)
        centres = np.arctan2(b[1] - a[1], b[0] - a[0])
        radial = np.arctan2(pitch[1] - a[1], pitch[0] - a[0])
        out[g.id] = _Line(pitch, rotate((0.0, 1.0), centres), g.links[1], g.links[0],
                          rotate((1.0, 0.0), radial), math.radians(g.pressure_angle))
    return out


def _at_rest(joints, layout, state):
    """Per friction joint, the steps where its slide is at rest."""
    return {j.id: ~(np.abs(joints.slide_speed[j.id]) > 1e-12 * max(layout.size, 1e-12) *
                    _speed_scale(state)) for j in joints.friction}


# -- the matrix -------------------------------------------------------------------------------
def _base_matrix(layout, joints):
    """The equilibrium matrix without friction: one column per unknown."""
    n = layout.n
    one = np.ones(n)
    # laid out step-last, so that each entry's steps are contiguous (every write below
    # is one entry over the steps), and seen step-first as the solve takes it
    a = np.zeros((layout.rows, len(layout.cols), n)).transpose(2, 0, 1)
    where, axis = joints.where, joints.axis
    for c, (kind, j, k) in enumerate(layout.cols):
        if kind in ("Fx", "Fy"):
            f = (1.0, 0.0) if kind == "Fx" else (0.0, 1.0)
            q = where[j.id]
            layout.put_pair(a, j.links[k], j.links[-1], c, f, q)
        elif kind == "N":
            t = axis[j.id]
            layout.put_pair(a, j.links[0], j.links[1], c, (-t[1], t[0]), where[j.id])
        elif kind == "M":
            layout.put_couple(a, j.links[0], c, one * layout.size)
            layout.put_couple(a, j.links[1], c, one * layout.size, -1.0)
        elif kind == "contact":
            h = joints.higher[j.id]
            layout.put_pair(a, h.on, h.by, c, h.direction, h.point)
        elif j.kind == "R":                      # an R input's effort: a couple
            layout.put_couple(a, j.b, c, one)
            layout.put_couple(a, j.a, c, one, -1.0)
        else:                                    # a P input's effort: along the guide
            t = axis[j.joint]
            layout.put_pair(a, j.b, j.a, c, t, where[j.joint])
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
        layout.put_pair(a, j.links[0], j.links[1], c, f, q)
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


def _known_forces(chain, layout, state, joints, *, static, mean_torque=0.0):
    """Gravity, the loads and (unless ``static``) the inertia forces and couples."""
    # step-last, as the matrix (each entry's steps contiguous)
    rhs = np.zeros((layout.rows, 1, layout.n)).transpose(2, 0, 1)
    known = _Known(rhs, np.zeros(layout.n), [], [])
    _masses(chain, layout, state, known, static=static)
    _loads(chain, layout, state, joints, known, mean_torque)
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


def _loads(chain, layout, state, joints, known, mean_torque):
    """The loads' forces and torques on the moving links, at each step as the motion
    has them (a table's force read off at the slide or the input's value, a resisting
    force against its point's velocity)."""
    one = np.ones(layout.n)
    for i, load in enumerate(chain.loads):
        link = load.on
        if link == layout.fixed:
            continue
        f = _load_force(chain, layout, state, joints, i)
        if f is not None:
            q = (joints.where[load.at] if load.at in joints.where
                 else state.links[link].moved(layout.drawn(chain.point(load.at).at)))
            f = f(q)
            known.applied.append((link, "load", q, f))
            layout.put(known.rhs, link, 0, f, q)
            v = state.links[link].velocity_at(q)
            known.power[:] += f[0] * v[0] + f[1] * v[1]
        torque = mean_torque if load.mean_torque else float(load.torque)
        if torque:
            known.couples.append((link, "load", torque * one))
            layout.put_couple(known.rhs, link, 0, torque * one)
            known.power[:] += torque * state.links[link].omega


def _load_force(chain, layout, state, joints, i):
    """The force of load ``i`` as a function of its point q (arrays over the steps),
    or None for a load without a force."""
    load = chain.loads[i]
    one = np.ones(layout.n)
    if load.force is not None:
        return lambda q: (load.force[0] * one, load.force[1] * one)
    if load.follows:
        size = load_table_value(load, state)
        speed = joints.slide_speed[load.along]
        if load.stroke == "out":
            size = np.where(speed > 0, size, 0.0)
        elif load.stroke == "in":
            size = np.where(speed < 0, size, 0.0)
        t = joints.axis[load.along]
        return lambda q: (size * t[0], size * t[1])
    if load.resist is not None:
        def resist(q):
            v = state.links[load.on].velocity_at(q)
            speed = np.hypot(v[0], v[1])
            moving = speed > 0
            size = np.where(moving, -load.resist / np.where(moving, speed, 1.0), 0.0)
            if i in state.strokes:
                d = state.strokes[i]
                size = np.where(v[0] * d[0] + v[1] * d[1] > 0, size, 0.0)
            return (size * v[0], size * v[1])
        return resist
    return None


def load_table_value(load: Load, state: KinematicState) -> np.ndarray:
    """A table load's force (N, along its P joint's axis) at the state's steps: its
    table (or indicator diagram times area) interpolated linearly at the slide of
    ``along`` (held at its ends beyond them) or, periodic over its cycle, at the
    input's value."""
    xs, fs = (np.asarray(v, dtype=float) for v in load.values())
    if load.against == "slide":
        assert load.along is not None               # (the chain checks a table's P joint)
        return np.interp(state.slides[load.along], xs, fs)
    if state.angle is None:
        raise MechanismError(f"the load on {load.on!r} is tabulated against the input's "
                             "value: it needs an R input (a crank's angle)")
    period = load.period
    xs = np.concatenate([[xs[-1] - period], xs, [xs[0] + period]])
    fs = np.concatenate([[fs[-1]], fs, [fs[0]]])
    return np.interp(np.mod(state.angle - xs[1], period) + xs[1], xs, fs)


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
    x, singular = _solve(_with_friction(layout, joints, base, sigma), b, known, layout)
    settled = np.ones(layout.n, dtype=bool)
    if not joints.friction:
        return x, singular, settled, sigma
    cols = joints.normal_cols
    for _ in range(8):
        new = {k: _signs(x, cols[k]) for k in sigma}
        if all((new[k] == sigma[k]).all() for k in sigma):
            break
        sigma = new
        x, singular = _solve(_with_friction(layout, joints, base, sigma), b, known, layout)
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
                          None if known is None else known[bad], layout)
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
def _parting_forces(layout, joints, x):
    """The gear pairs' radial forces (|tangential force| tan(pressure angle), parting
    the gears) as known forces' shares of the equations, from a first solve ``x``; None
    without gears. They pass through the gears' axes on the carrier and balance there,
    so the tangential forces (and the efforts) do not change."""
    gears = [(c, joints.higher[j.id]) for c, (kind, j, _) in enumerate(layout.cols)
             if kind == "contact" and joints.higher[j.id].radial is not None]
    if not gears:
        return None
    share = np.zeros((layout.rows, 1, layout.n)).transpose(2, 0, 1)
    for c, h in gears:
        r = np.nan_to_num(np.abs(x[:, c])) * math.tan(h.pressure)
        assert h.radial is not None
        f = (r * h.radial[0], r * h.radial[1])
        layout.put_pair(share, h.on, h.by, 0, f, h.point)
    return share[:, :, 0]


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
        elif kind == "contact":
            h = joints.higher[j.id]
            t = x[:, c]
            f = (t * h.direction[0], t * h.direction[1])
            if h.radial is not None:            # a gear's: along the line of action
                r = np.abs(t) * math.tan(h.pressure)
                f = (f[0] + r * h.radial[0], f[1] + r * h.radial[1])
                t = t / math.cos(h.pressure)
            forces[(j.id, h.on)] = f
            forces[(j.id, h.by)] = (-f[0], -f[1])
            normal[j.id] = t
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


def _solve(a, b, known=None, layout=None):
    """x with a x = b per step (with more unknowns than equations, the least-norm x),
    and which steps are singular (x NaN there). ``known``: the steps already known to
    be singular (the motion's dead centres, where its rates are not finite), so that
    the others need no test of their own; there, a ``layout`` whose ``groups`` split the
    system (see :func:`_split`) has it solved group by group (the whole system where a
    group's is exactly singular, then as without)."""
    n = a.shape[0]
    x = np.full((n, a.shape[2]), np.nan)
    good = np.isfinite(a).all(axis=(1, 2)) & np.isfinite(b).all(axis=1)
    singular = ~good
    if known is not None and a.shape[1] == a.shape[2]:
        use = good & ~known
        singular |= known
        if use.any():
            au, bu = (a, b[:, :, None]) if use.all() else (a[use], b[use][:, :, None])
            if layout is not None and layout.groups is not None:
                try:
                    x[use] = solve_block_triangular(au, bu, layout.groups,
                                                    dyads=layout.dyads)[:, :, 0]
                    return x, singular
                except np.linalg.LinAlgError:     # a group's system singular: the whole
                    pass
            try:
                x[use] = np.linalg.solve(au, bu)[:, :, 0]
                return x, singular
            except np.linalg.LinAlgError:         # a singular step the motion did not flag
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
