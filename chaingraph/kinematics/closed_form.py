"""Closed-form position steps: a single link fixed by two attachments, and dyads.

A *single* link is joined to known links by two constraints (RR, RP, PP) or welded to
one by an input; a *dyad* of two links (RRR, RRP, PRR, RPR, PRP, RPP, PPR) is an
intersection of circles and lines, or a rotation angle from a cosine, with two assembly
modes where the discriminant is positive.
"""

from __future__ import annotations

import math

import numpy as np

from chaingraph.geometry import (
    DISC_TOL,
    circle_circle,
    circle_line,
    clamp_disc,
    fit_two_points,
    from_point,
    line_by_two_distances,
    make_pose,
    turn_by,
    unit_deg,
    world,
)


def line_of(pose, attach, unknown, through):
    """The line on which the unknown link's drawn point ``through`` must stay, for a P
    attachment to a known link: (base point, direction, the unknown link's rotation)."""
    known = pose[attach.other(unknown)]
    base = world(pose, attach.other(unknown), attach.point)
    dx, dy = through[0] - attach.point[0], through[1] - attach.point[1]
    ox, oy = turn_by(known, (dx, dy))
    u = turn_by(known, unit_deg(attach.axis))
    return (base[0] + ox, base[1] + oy), u, known


# -- closed-form steps ---------------------------------------------------------------
def single_link(step, pose):
    u = step.links[0]
    if step.pattern[0] == "W":
        return {u: _welded(pose, u, step.constraints[0])}
    c1, c2 = step.constraints[:2]
    if c1.kind == "R" and c2.kind == "R":
        w1 = world(pose, c1.other(u), c1.point)
        w2 = world(pose, c2.other(u), c2.point)
        return {u: fit_two_points(c1.point, w1, c2.point, w2)}
    if c1.kind == "R":
        return {u: from_point(pose[c2.other(u)], c1.point,
                               world(pose, c1.other(u), c1.point))}
    return {u: _two_lines(pose, u, c1, c2)}


def _welded(pose, u, c):
    """Pose of link u welded to a known link by input joint c at the input's value: an
    R joint turned by delta (the second link relative to the first), or a P joint's
    block slid by delta along the guide."""
    known = pose[c.other(u)]
    delta = pose[c.drive][2]
    sign = 1.0 if u == c.b else -1.0
    w = world(pose, c.other(u), c.point)
    if c.kind == "R":
        return from_point(make_pose(0.0, 0.0, known[2] + sign * delta), c.point, w)
    t = turn_by(known, unit_deg(c.axis))
    return from_point(known, c.point, (w[0] + sign * delta * t[0], w[1] + sign * delta * t[1]))


def _two_lines(pose, u, c1, c2):
    """Pose of link u with two P attachments to known links (its rotation from c1)."""
    turn = pose[c1.other(u)]
    rows, rhs = [], []
    for c in (c1, c2):
        base, dirn, _ = line_of(pose, c, u, c.point)
        nx_, ny_ = -dirn[1], dirn[0]
        rx, ry = turn_by(turn, c.point)
        rows.append((nx_, ny_))
        rhs.append(nx_ * (base[0] - rx) + ny_ * (base[1] - ry))
    (a, b), (c, d) = rows
    det = a * d - b * c
    x = (rhs[0] * d - b * rhs[1]) / det
    y = (a * rhs[1] - c * rhs[0]) / det
    return make_pose(x, y, turn[2], turn[3], turn[4])


def dyad_roots(step, pose, scale, *, double=False):
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
    """
    a, b = step.links
    ca, cb, cj = step.constraints
    pattern = step.pattern
    if pattern in ("PRR", "PPR"):  # mirror to the R-first form
        a, b, ca, cb = b, a, cb, ca
        pattern = pattern[::-1]
    q = cj.point
    if pattern in ("RRR", "RRP"):
        wa = world(pose, ca.other(a), ca.point)
        ra = math.dist(q, ca.point)
        if pattern == "RRR":
            wb = world(pose, cb.other(b), cb.point)
            rb = math.dist(q, cb.point)
            mid, across, raw = circle_circle(wa, ra, wb, rb)
            norm = min(ra, rb) * (ra + rb)
        else:
            base, dirn, turn_b = line_of(pose, cb, b, q)
            mid, across, raw = circle_line(wa, ra, base, dirn)
            norm = ra * (ra + scale)
        norm = max(norm, (DISC_TOL * scale) ** 2)      # a link of zero length
        disc, ok = clamp_disc(raw, norm, double)
        h = np.sqrt(disc)
        off = (h * across[0], h * across[1])
        keys = (np.stack((mid[0] + off[0], mid[1] + off[1]), axis=-1),
                np.stack((mid[0] - off[0], mid[1] - off[1]), axis=-1))

        def build(sign):
            x, y = mid[0] + sign * off[0], mid[1] + sign * off[1]
            pa = fit_two_points(ca.point, wa, q, (x, y))
            if pattern == "RRR":
                return {a: pa, b: fit_two_points(cb.point, wb, q, (x, y))}
            return {a: pa, b: from_point(turn_b, q, (x, y))}
        return keys, build, ok, raw / norm
    if pattern == "RPR":
        wa = world(pose, ca.other(a), ca.point)
        wb = world(pose, cb.other(b), cb.point)
        nx_, ny_ = -unit_deg(cj.axis)[1], unit_deg(cj.axis)[0]
        c = nx_ * (cb.point[0] - ca.point[0]) + ny_ * (cb.point[1] - ca.point[1])
        (cs0, sn0), ratio, raw = line_by_two_distances(wa, wb, c)
        disc, ok = clamp_disc(raw, 1.0, double)
        # rotation phi = start +- spread, with cos(spread) = ratio: the centre line's
        # direction turned back by the drawn normal
        cn, sn = nx_, ny_
        cst, snt = cs0 * cn + sn0 * sn, sn0 * cn - cs0 * sn   # start = delta - nu
        root = np.sqrt(disc)

        def turn(sign):
            c1, s1 = cst * ratio - snt * sign * root, snt * ratio + cst * sign * root
            return c1, s1
        keys = tuple(np.stack(turn(sg), axis=-1) for sg in (1.0, -1.0))

        def build(sign):
            c1, s1 = turn(sign)
            e = make_pose(0.0, 0.0, np.arctan2(s1, c1), c1, s1)
            return {a: from_point(e, ca.point, wa), b: from_point(e, cb.point, wb)}
        return keys, build, ok, raw
    if pattern == "PRP":
        base_a, dir_a, turn_a = line_of(pose, ca, a, q)
        base_b, dir_b, turn_b = line_of(pose, cb, b, q)
        det = dir_a[0] * -dir_b[1] + dir_b[0] * dir_a[1]
        rx, ry = base_b[0] - base_a[0], base_b[1] - base_a[1]
        s_ = (rx * -dir_b[1] + dir_b[0] * ry) / det
        x, y = base_a[0] + s_ * dir_a[0], base_a[1] + s_ * dir_a[1]

        def build(sign):
            return {a: from_point(turn_a, q, (x, y)), b: from_point(turn_b, q, (x, y))}
        return None, build, np.isfinite(x), None
    if pattern == "RPP":
        wa = world(pose, ca.other(a), ca.point)
        pa = from_point(pose[cb.other(b)], ca.point, wa)

        def build(sign):
            known = dict(pose)
            known[a] = pa
            return {a: pa, b: _two_lines(known, b, cb, cj)}
        return None, build, np.isfinite(wa[0]), None
    raise ValueError(f"no closed form for a {pattern} dyad")


def initial_sign(keys, drawn):
    """The mode of the drawn pose: the one whose first point is nearest the drawing."""
    kp, km = keys
    dp = np.hypot(kp[0, 0] - drawn[0], kp[0, 1] - drawn[1])
    dm = np.hypot(km[0, 0] - drawn[0], km[0, 1] - drawn[1])
    return 1.0 if dp <= dm else -1.0

