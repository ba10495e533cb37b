"""Closed-form position steps: a single link fixed by two attachments, and dyads.

A *single* link is joined to known links by two constraints (RR, RP, PP) or welded to
one by an input; a *dyad* of two links (RRR, RRP, PRR, RPR, PRP, RPP, PPR) is an
intersection of circles and lines, or a rotation angle from a cosine, with two assembly
modes where the discriminant is positive.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TypeAlias, overload

import numpy as np

from chaingraph.geometry import (
    DISC_TOL,
    PoseEntry,
    Scalar,
    Vec,
    circle_circle,
    circle_line,
    clamp_disc,
    dot,
    fit_two_points,
    from_point,
    line_by_two_distances,
    make_pose,
    rotate,
    sub,
    turn_by,
    unit_deg,
    world,
)
from chaingraph.kinematics.equations import Pose
from chaingraph.kinematics.plan import Constraint, Plan, Step


class ModeKeys(Sequence[np.ndarray]):
    """A dyad's two modes' keys (each an (N, 2) array: a joint's point, or a rotation as
    a unit vector), ``mid + off`` and ``mid - off``, stacked only when first read (a
    sweep reads them at its first point alone, to choose the drawn mode)."""

    def __init__(self, mid: Vec, off: Vec) -> None:
        self._parts = (mid, off)
        self._keys: tuple[np.ndarray, np.ndarray] | None = None

    def _stacked(self) -> tuple[np.ndarray, np.ndarray]:
        if self._keys is None:
            (mx, my), (ox, oy) = self._parts
            self._keys = (np.stack((mx + ox, my + oy), axis=-1),
                          np.stack((mx - ox, my - oy), axis=-1))
        return self._keys

    def __len__(self) -> int:
        return 2

    @property
    def off(self) -> Vec:
        """The offset of the first mode's key from the middle of the two (the second's
        is its negative)."""
        return self._parts[1]

    def first(self) -> tuple[Vec, Vec]:
        """The two keys at the first point only (``self[0][0]``, ``self[1][0]``)."""
        (mx, my), (ox, oy) = (tuple(float(np.ravel(v)[0]) for v in part)
                              for part in self._parts)
        return (mx + ox, my + oy), (mx - ox, my - oy)

    @overload
    def __getitem__(self, i: int) -> np.ndarray: ...

    @overload
    def __getitem__(self, i: slice) -> Sequence[np.ndarray]: ...

    def __getitem__(self, i: int | slice) -> np.ndarray | Sequence[np.ndarray]:
        return self._stacked()[i]


#: a dyad's modes: (keys, build, ok, disc), as :func:`dyad_roots` returns them
Roots: TypeAlias = tuple["ModeKeys | None",
                         Callable[[Scalar], dict[str, PoseEntry]], Scalar, Scalar]


def carried(c: Constraint, entry: PoseEntry, link: str) -> PoseEntry:
    """The rotation of ``link`` across the P joint ``c`` from the other link's pose
    entry: the same (a drawn chain's links turn together), or turned by ``c.turn``
    (links drawn each in its own frame, as the assembly from lengths places them)."""
    if not c.turn:
        return entry
    return make_pose(entry[0], entry[1], entry[2] + (c.turn if link == c.b else -c.turn))


def _known_point(pose: Pose, c: Constraint, unknown: str) -> Vec:
    """Where the known link of constraint ``c`` puts the joint's point."""
    other = c.other(unknown)
    return world(pose, other, c.at(other))


def line_of(pose: Pose, attach: Constraint, unknown: str, through: Vec,
            ) -> tuple[Vec, Vec, PoseEntry]:
    """The line on which the unknown link's drawn point ``through`` must stay, for a P
    attachment to a known link: (base point, direction, the unknown link's rotation)."""
    other = attach.other(unknown)
    known = pose[other]
    turn = carried(attach, known, unknown)
    base = world(pose, other, attach.at(other))
    p = attach.at(unknown)
    ox, oy = turn_by(turn, (through[0] - p[0], through[1] - p[1]))
    u = turn_by(known if other == attach.a else turn, unit_deg(attach.axis))
    return (base[0] + ox, base[1] + oy), u, turn


# -- closed-form steps ---------------------------------------------------------------
def single_link(step: Step, pose: Pose) -> dict[str, PoseEntry]:
    """The pose of a single link's step: welded by an input, or placed from two
    attachments to known links (RR, RP, PP)."""
    u = step.links[0]
    if step.pattern[0] == "W":
        return {u: _welded(pose, u, step.constraints[0])}
    c1, c2 = step.constraints[:2]
    if c1.kind == "R" and c2.kind == "R":
        return {u: fit_two_points(c1.at(u), _known_point(pose, c1, u),
                                  c2.at(u), _known_point(pose, c2, u))}
    if c1.kind == "R":
        return {u: from_point(carried(c2, pose[c2.other(u)], u), c1.at(u),
                              _known_point(pose, c1, u))}
    return {u: _two_lines(pose, u, c1, c2)}


def _welded(pose: Pose, u: str, c: Constraint) -> PoseEntry:
    """Pose of link u welded to a known link by input joint c at the input's value: an
    R joint turned by delta (the second link relative to the first), or a P joint's
    block slid by delta along the guide."""
    known = pose[c.other(u)]
    assert c.drive is not None                    # an input's joint
    delta = pose[c.drive][2]
    sign = 1.0 if u == c.b else -1.0
    w = _known_point(pose, c, u)
    if c.kind == "R":
        return from_point(make_pose(0.0, 0.0, known[2] + sign * delta), c.at(u), w)
    t = turn_by(known if c.other(u) == c.a else carried(c, known, u), unit_deg(c.axis))
    return from_point(carried(c, known, u), c.at(u),
                      (w[0] + sign * delta * t[0], w[1] + sign * delta * t[1]))


def _two_lines(pose: Pose, u: str, c1: Constraint, c2: Constraint) -> PoseEntry:
    """Pose of link u with two P attachments to known links (its rotation from c1)."""
    turn = carried(c1, pose[c1.other(u)], u)
    rows: list[tuple[Scalar, Scalar]] = []
    rhs: list[Scalar] = []
    for c in (c1, c2):
        base, dirn, _ = line_of(pose, c, u, c.at(u))
        nx_, ny_ = -dirn[1], dirn[0]
        rx, ry = turn_by(turn, c.at(u))
        rows.append((nx_, ny_))
        rhs.append(nx_ * (base[0] - rx) + ny_ * (base[1] - ry))
    (a, b), (c, d) = rows
    det = a * d - b * c
    x = (rhs[0] * d - b * rhs[1]) / det
    y = (a * rhs[1] - c * rhs[0]) / det
    return make_pose(x, y, turn[2], turn[3], turn[4])


def dyad_roots(step: Step, pose: Pose, scale: float, *, double: Scalar = False) -> Roots:
    """A dyad's assembly modes.

    ``double`` (a bool, or a bool per point) takes the discriminant as exactly zero:
    the double root where the two modes meet, at a fold found as the discriminant's
    root (there the computed discriminant is zero only to rounding, and the pose would
    carry the square root of that rounding).

    Returns (keys, build, ok, disc): ``keys`` the two modes' joint point (or rotation as
    a unit vector), arrays of shape (N, 2) or None for a dyad with one mode;
    ``build(sign)`` the poses of the dyad's links for an array of mode signs (+1 or -1);
    ``ok`` where the dyad can be assembled; ``disc`` the discriminant made
    dimensionless by the dyad's own lengths (negative where the dyad cannot be
    assembled, zero where its two modes meet), or None for a dyad with one mode.
    ``scale`` is the mechanism's size. The discriminant of two circles (the squared
    half-chord, at most the smaller radius squared) is taken over the smaller radius
    times the sum of the radii, that of a circle and a line over the radius times
    (radius + ``scale``): its cut at rounding (``DISC_TOL``) then moves a fold's joint
    by about ``DISC_TOL`` of the lengths involved, however short the shorter link
    (over ``scale`` squared, a crank of 1e-5 of the size would be off by 1e-8 of it).
    The single pose, the sweep and the assembly from lengths all place their dyads
    here (pose entries, one point or a batch of them).
    """
    a, b = step.links
    ca, cb, cj = step.constraints
    pattern = step.pattern
    if pattern in ("PRR", "PPR"):  # mirror to the R-first form
        a, b, ca, cb = b, a, cb, ca
        pattern = pattern[::-1]
    if pattern in ("RRR", "RRP"):
        return _circle_roots(pattern, (a, b), (ca, cb, cj), pose, scale, double)
    if pattern == "RPR":
        return _rpr_roots((a, b), (ca, cb, cj), pose, double)
    if pattern == "PRP":
        return _prp_roots((a, b), (ca, cb, cj), pose)
    if pattern == "RPP":
        return _rpp_roots((a, b), (ca, cb, cj), pose)
    raise ValueError(f"no closed form for a {pattern} dyad")


def _circle_roots(pattern: str, links: tuple[str, str],
                  constraints: tuple[Constraint, Constraint, Constraint], pose: Pose,
                  scale: float, double: Scalar) -> Roots:
    """An RRR dyad (two circles) or an RRP dyad (a circle and the line the second link
    slides on): the joint between the links at their crossing."""
    (a, b), (ca, cb, cj) = links, constraints
    qa, qb = cj.at(a), cj.at(b)
    wa = _known_point(pose, ca, a)
    ra = math.dist(qa, ca.at(a))
    if pattern == "RRR":
        wb = _known_point(pose, cb, b)
        rb = math.dist(qb, cb.at(b))
        mid, across, raw = circle_circle(wa, ra, wb, rb)
        norm = min(ra, rb) * (ra + rb)
    else:
        base, dirn, turn_b = line_of(pose, cb, b, qb)
        mid, across, raw = circle_line(wa, ra, base, dirn)
        norm = ra * (ra + scale)
    norm = max(norm, (DISC_TOL * scale) ** 2)      # a link of zero length
    disc, ok = clamp_disc(raw, norm, double)
    h = np.sqrt(disc)
    off = (h * across[0], h * across[1])
    keys = ModeKeys(mid, off)

    def build(sign: Scalar) -> dict[str, PoseEntry]:
        x, y = mid[0] + sign * off[0], mid[1] + sign * off[1]
        pa = fit_two_points(ca.at(a), wa, qa, (x, y))
        if pattern == "RRR":
            return {a: pa, b: fit_two_points(cb.at(b), wb, qb, (x, y))}
        return {a: pa, b: from_point(turn_b, qb, (x, y))}
    return keys, build, ok, raw / norm


def _rpr_offset(links: tuple[str, str],
                constraints: tuple[Constraint, Constraint, Constraint], n: Vec) -> Scalar:
    """``c`` such that the sliding line's normal in the world, ``n_w``, has
    ``n_w . (wb - wa) = c`` (``wa``, ``wb`` where the links turn, ``n`` the line's
    normal on the guide): the line passes through both links' points on it."""
    (a, b), (ca, cb, cj) = links, constraints
    if cj.point_b is None and not cj.turn:          # a drawn chain: one point
        pa, pb = ca.at(a), cb.at(b)
        return n[0] * (pb[0] - pa[0]) + n[1] * (pb[1] - pa[1])
    g, k = cj.a, cj.b
    turns_about = {a: ca.at(a), b: cb.at(b)}
    on_guide = sub(cj.at(g), turns_about[g])
    on_block = rotate(sub(cj.at(k), turns_about[k]), cj.turn)
    c = dot(n, on_guide) - dot(n, on_block)
    return c if g == a else -c


def _rpr_roots(links: tuple[str, str], constraints: tuple[Constraint, Constraint, Constraint],
               pose: Pose, double: Scalar) -> Roots:
    """An RPR dyad: two links turning about known points, one sliding on the other;
    the sliding line at the distances from both points (its two tangents)."""
    (a, b), (ca, cb, cj) = links, constraints
    wa, wb = _known_point(pose, ca, a), _known_point(pose, cb, b)
    nx_, ny_ = -unit_deg(cj.axis)[1], unit_deg(cj.axis)[0]
    c = _rpr_offset(links, constraints, (nx_, ny_))
    (cs0, sn0), ratio, raw = line_by_two_distances(wa, wb, c)
    disc, ok = clamp_disc(raw, 1.0, double)
    # the guide's rotation phi = start +- spread, with cos(spread) = ratio: the centre
    # line's direction turned back by the drawn normal
    cn, sn = nx_, ny_
    cst, snt = cs0 * cn + sn0 * sn, sn0 * cn - cs0 * sn   # start = delta - nu
    root = np.sqrt(disc)

    def turn(sign: Scalar) -> tuple[Scalar, Scalar]:
        c1, s1 = cst * ratio - snt * sign * root, snt * ratio + cst * sign * root
        return c1, s1
    keys = ModeKeys((cst * ratio, snt * ratio), (-snt * root, cst * root))

    def build(sign: Scalar) -> dict[str, PoseEntry]:
        c1, s1 = turn(sign)
        guide = make_pose(0.0, 0.0, np.arctan2(s1, c1), c1, s1)
        rotation = {cj.a: guide, cj.b: carried(cj, guide, cj.b)}
        return {a: from_point(rotation[a], ca.at(a), wa),
                b: from_point(rotation[b], cb.at(b), wb)}
    return keys, build, ok, raw


def _prp_roots(links: tuple[str, str], constraints: tuple[Constraint, Constraint, Constraint],
               pose: Pose) -> Roots:
    """A PRP dyad: two links sliding on known lines, pinned where the lines cross."""
    (a, b), (ca, cb, cj) = links, constraints
    qa, qb = cj.at(a), cj.at(b)
    base_a, dir_a, turn_a = line_of(pose, ca, a, qa)
    base_b, dir_b, turn_b = line_of(pose, cb, b, qb)
    det = dir_a[0] * -dir_b[1] + dir_b[0] * dir_a[1]
    rx, ry = base_b[0] - base_a[0], base_b[1] - base_a[1]
    s_ = (rx * -dir_b[1] + dir_b[0] * ry) / det
    x, y = base_a[0] + s_ * dir_a[0], base_a[1] + s_ * dir_a[1]

    def build(sign: Scalar) -> dict[str, PoseEntry]:
        return {a: from_point(turn_a, qa, (x, y)), b: from_point(turn_b, qb, (x, y))}
    return None, build, np.isfinite(x), None


def _rpp_roots(links: tuple[str, str], constraints: tuple[Constraint, Constraint, Constraint],
               pose: Pose) -> Roots:
    """An RPP dyad: a link turning about a known point slides on a link that slides on
    a known line: both turn with that line."""
    (a, b), (ca, cb, cj) = links, constraints
    wa = _known_point(pose, ca, a)
    turn_b = carried(cb, pose[cb.other(b)], b)
    pa = from_point(carried(cj, turn_b, a), ca.at(a), wa)

    def build(sign: Scalar) -> dict[str, PoseEntry]:
        known = dict(pose)
        known[a] = pa
        return {a: pa, b: _two_lines(known, b, cb, cj)}
    return None, build, np.isfinite(wa[0]), None


def met_by_construction(step: Step) -> tuple[Constraint, ...]:
    """The turning pairs that a closed-form step's poses meet by construction: each
    link the step places is put with one of its points on a known point (by
    ``from_point``, or as the first point of ``fit_two_points``: :func:`single_link`,
    :func:`dyad_roots`), so that pair's residual is rounding alone at any pose the step
    builds (and NaN only where the link's other points are NaN too: a pair the step
    does not meet by construction then says so). A welded input's turning pair, its
    relative rotation included; the first pair of a link placed by two turning pairs;
    a dyad's turning pairs with known links (both of an RRR or RPR dyad, the turning
    one of RRP, PRR, RPP, PPR). Never a pair that an input drives, except in its weld,
    and nothing of a group (solved by Newton's method).
    """
    cons = step.constraints
    if step.kind == "single" and step.pattern[0] == "W":
        return (cons[0],) if cons[0].kind == "R" and not cons[0].turn else ()
    if step.kind == "single":
        return (cons[0],) if step.pattern == "RR" and cons[0].drive is None else ()
    if step.kind != "dyad":
        return ()
    return tuple(c for c in cons[:2] if c.kind == "R" and c.drive is None)


def closure_checks(plan: Plan) -> tuple[Constraint, ...]:
    """The pairs whose closure a pose the plan's steps build must be checked for
    (:func:`~chaingraph.kinematics.equations.check_poses`): every pair but those a
    closed-form step meets by construction (:func:`met_by_construction`). For a
    four-bar driven by its crank, the coupler-rocker pin alone.

    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> from chaingraph.kinematics.inputs import plan_of
    >>> plan = plan_of(chaingraph.load(catalog_path("log10-function-generator")), None, None)
    >>> [c.joint for c in plan.constraints], [c.joint for c in closure_checks(plan)]
    (['A', 'B', 'C', 'D'], ['C'])
    """
    met = {c for step in plan.steps for c in met_by_construction(step)}
    return tuple(c for c in plan.constraints if c not in met)


def initial_sign(keys: Sequence[np.ndarray], drawn: Vec) -> float:
    """The mode of the drawn pose: the one whose first point is nearest the drawing."""
    if isinstance(keys, ModeKeys):
        kp, km = keys.first()
    else:
        kp, km = tuple(keys[0][0]), tuple(keys[1][0])
    dp = np.hypot(kp[0] - drawn[0], kp[1] - drawn[1])
    dm = np.hypot(km[0] - drawn[0], km[1] - drawn[1])
    return 1.0 if dp <= dm else -1.0

