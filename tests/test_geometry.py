"""The 2-D kit against closed forms and invariants."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from chaingraph import geometry as g

coord = st.floats(-100.0, 100.0, allow_nan=False)
length = st.floats(0.5, 80.0)
angle = st.floats(-math.pi, math.pi)


@given(coord, coord, length, coord, coord, length)
def test_two_circles_meet_where_both_radii_hold(x1, y1, r1, x2, y2, r2):
    d = math.hypot(x2 - x1, y2 - y1)
    if not (abs(r1 - r2) + 1e-6 < d < r1 + r2 - 1e-6):
        return
    mid, across, raw = g.circle_circle((x1, y1), r1, (x2, y2), r2)
    assert raw > 0
    for sign in (1.0, -1.0):
        p = (mid[0] + sign * math.sqrt(raw) * across[0], mid[1] + sign * math.sqrt(raw) * across[1])
        assert math.dist(p, (x1, y1)) == pytest.approx(r1, abs=1e-9 * (1 + d))
        assert math.dist(p, (x2, y2)) == pytest.approx(r2, abs=1e-9 * (1 + d))
        # +: left of the line from the first centre to the second
        side = g.cross(g.sub((x2, y2), (x1, y1)), g.sub(p, (x1, y1)))
        assert math.copysign(1.0, side) == sign


def test_circles_apart_or_nested_do_not_meet():
    assert g.circle_circle((0.0, 0.0), 1.0, (5.0, 0.0), 1.0)[2] < 0
    assert g.circle_circle((0.0, 0.0), 5.0, (1.0, 0.0), 1.0)[2] < 0


@given(coord, coord, length, coord, coord, angle)
def test_a_circle_and_a_line_meet_on_both(cx, cy, r, bx, by, a):
    u = g.unit(a)
    foot, direction, raw = g.circle_line((cx, cy), r, (bx, by), u)
    if raw <= 1e-9:
        return
    n = g.normal(a)
    for sign in (1.0, -1.0):
        p = (foot[0] + sign * math.sqrt(raw) * u[0], foot[1] + sign * math.sqrt(raw) * u[1])
        assert math.dist(p, (cx, cy)) == pytest.approx(r, abs=1e-9 * (1 + r + abs(bx) + abs(by)))
        assert g.dot(n, g.sub(p, (bx, by))) == pytest.approx(0.0, abs=1e-9 * (1 + abs(bx) + abs(by)))
        assert g.dot(g.sub(p, foot), u) * sign >= 0


@given(coord, coord, coord, coord, st.floats(-1.0, 1.0))
def test_a_line_at_two_distances(ax, ay, bx, by, share):
    d = math.hypot(bx - ax, by - ay)
    if d < 1e-3:
        return
    c = share * d
    u, ratio, raw = g.line_by_two_distances((ax, ay), (bx, by), c)
    assert raw == pytest.approx(1 - share * share, abs=1e-12)
    spread = math.atan2(math.sqrt(max(raw, 0.0)), ratio)
    for turn in (spread, -spread):
        n = g.rotate(u, turn)
        assert g.dot(n, g.sub((bx, by), (ax, ay))) == pytest.approx(c, abs=1e-9 * (1 + d))


@given(angle, coord, coord, angle, coord, coord, coord, coord)
def test_frames_compose_and_invert(p1, x1, y1, p2, x2, y2, px, py):
    a, b = (p1, x1, y1), (p2, x2, y2)
    both = g.apply(g.compose(a, b), (px, py))
    step = g.apply(a, g.apply(b, (px, py)))
    assert math.dist(both, step) <= 1e-9 * (1 + abs(x1) + abs(x2) + abs(px) + abs(py))
    back = g.apply(g.inverse(a), g.apply(a, (px, py)))
    assert math.dist(back, (px, py)) <= 1e-9 * (1 + abs(x1) + abs(px) + abs(py))


@given(angle, coord, coord)
def test_a_frame_fitted_to_moved_points_is_the_motion(phi, x, y):
    body = [(0.0, 0.0), (3.0, 1.0), (-2.0, 4.0)]
    placed = [g.apply((phi, x, y), p) for p in body]
    fit = g.fit_frame(list(zip(body, placed)))
    assert math.remainder(fit[0] - phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)
    assert fit[1:] == pytest.approx((x, y), abs=1e-9 * (1 + abs(x) + abs(y)))
    two = g.frame_from_two(body[0], placed[0], body[1], placed[1])
    assert math.dist(g.apply(two, body[2]), placed[2]) <= 1e-9 * (1 + abs(x) + abs(y))


def test_pose_entries_over_a_sweep_match_the_scalar_frames():
    phi = np.linspace(-3.0, 3.0, 7)
    entry = g.make_pose(np.full(7, 2.0), np.full(7, -1.0), phi)
    xs, ys = g.world({"link": entry}, "link", (1.5, 0.5))
    for k, a in enumerate(phi):
        assert (xs[k], ys[k]) == pytest.approx(g.apply((a, 2.0, -1.0), (1.5, 0.5)), abs=1e-12)


def test_angles_in_degrees_only_by_name():
    assert g.unit_deg(90.0) == pytest.approx((0.0, 1.0), abs=1e-15)
    assert g.direction_deg((-1.0, 0.0)) == 180.0 and g.direction_deg((0.0, 0.0)) is None
    assert g.rotate((1.0, 0.0), math.pi / 2) == pytest.approx((0.0, 1.0), abs=1e-15)


@given(st.lists(st.tuples(st.integers(-9, 9), st.integers(-9, 9)), min_size=3, max_size=30))
def test_the_hull_holds_every_point(points):
    hull = g.convex_hull(points)
    if len(hull) < 3:
        return
    for p in points:      # every point on the inner side of every edge (counter-clockwise)
        for a, b in zip(hull, hull[1:] + hull[:1]):
            assert g.cross(g.sub(b, a), g.sub(p, a)) >= 0
    assert g.polygon_area(hull) > 0
