"""Disc cams (issue 39): the laws against their closed forms, continuity where promised,
the pressure angle against the textbook's formula, the profile touching the follower at
every angle, the smallest base circle against a search, undercutting."""

import math

import numpy as np
import pytest

from chaingraph.errors import DesignError
from chaingraph.kinematics.cams import (
    analyse_cam,
    cam_summary,
    follower_motion,
    law,
    smallest_base,
    turn_angles,
)
from chaingraph.model.cams import Cam, Segment

PI = math.pi
# (f, f', f'', f''') at u = 0, 1/2 and 1, worked by hand from each law's formula
ENDS = {
    "uniform": [(0, 1, 0, 0), (0.5, 1, 0, 0), (1, 1, 0, 0)],
    "shm": [(0, 0, PI**2 / 2, 0), (0.5, PI / 2, 0, -PI**3 / 2), (1, 0, -PI**2 / 2, 0)],
    "parabolic": [(0, 0, 4, 0), (0.5, 2, -4, 0), (1, 0, -4, 0)],
    "cycloidal": [(0, 0, 0, 4 * PI**2), (0.5, 2, 0, -4 * PI**2), (1, 0, 0, 4 * PI**2)],
    "poly345": [(0, 0, 0, 60), (0.5, 15 / 8, 0, -30), (1, 0, 0, 60)],
    "poly4567": [(0, 0, 0, 0), (0.5, 35 / 16, 0, -105 / 2), (1, 0, 0, 0)],
}
# how many derivatives stay continuous where the law meets a dwell (0: s only)
CONTINUOUS = {"uniform": 0, "shm": 1, "parabolic": 1, "cycloidal": 2, "poly345": 2,
              "poly4567": 3}


@pytest.mark.parametrize("name", sorted(ENDS))
def test_each_law_at_its_ends_and_middle(name):
    values = np.array(law(name, np.array([0.0, 0.5, 1.0]))).T
    assert values == pytest.approx(np.array(ENDS[name], dtype=float), abs=1e-12)


@pytest.mark.parametrize("name", sorted(ENDS))
def test_each_law_derivatives_are_its_derivatives(name):
    u = np.linspace(0.01, 0.99, 99)
    u = u[np.abs(u - 0.5) > 0.011]               # (the parabolic law's seam)
    h = 1e-5
    for k in range(3):
        up, down = law(name, u + h)[k], law(name, u - h)[k]
        assert (up - down) / (2 * h) == pytest.approx(law(name, u)[k + 1], abs=1e-5)


def _cam(rise_law="cycloidal", fall_law="shm", *, contact="roller", base=40.0, roller=10.0,
         offset=0.0, lift=30.0, moves="translating", arm=None, pivot=None):
    d = math.radians
    motion = (Segment("rise", lift, d(120), rise_law), Segment("dwell", 0.0, d(60)),
              Segment("fall", lift, d(120), fall_law), Segment("dwell", 0.0, d(60)))
    return Cam("K", "cam", "follower", contact, base, motion, moves=moves, roller=roller,
               offset=offset, arm=arm, pivot=pivot)


@pytest.mark.parametrize("name", sorted(ENDS))
def test_continuity_where_the_law_promises_it(name):
    cam = _cam(name, name)
    eps = 1e-7
    for edge in (0.0, 120.0, 180.0, 300.0):
        a = np.radians(edge)
        left = np.array(follower_motion(cam, np.array([a - eps])))[:, 0]
        right = np.array(follower_motion(cam, np.array([a])))[:, 0]
        jumps = np.abs(left - right)
        assert np.all(jumps[:CONTINUOUS[name] + 1] < 1e-3), (name, edge, jumps)
        if name != "poly4567" and edge in (0.0, 120.0):
            assert jumps[CONTINUOUS[name] + 1] > 1e-2, (name, edge, jumps)


def test_the_program_over_a_turn():
    cam = _cam("poly345", "cycloidal")
    s, ds, _, _ = follower_motion(cam, np.radians([0.0, 60.0, 120.0, 150.0, 240.0, 300.0, 330.0]))
    assert s == pytest.approx([0.0, 15.0, 30.0, 30.0, 15.0, 0.0, 0.0], abs=1e-12)
    assert ds[1] == pytest.approx(30.0 * 15 / 8 / math.radians(120.0))
    assert ds[4] == pytest.approx(-30.0 * 2 / math.radians(120.0))


@pytest.mark.parametrize("offset", [0.0, 8.0, -12.0])
def test_pressure_angle_of_a_translating_roller(offset):
    cam = _cam(offset=offset)
    theta = turn_angles(cam, 720)
    r = analyse_cam(cam, theta)
    prime = cam.base + cam.roller
    s, ds, _, _ = follower_motion(cam, theta)
    expected = np.arctan((ds - offset) / (s + math.sqrt(prime**2 - offset**2)))
    assert r.pressure == pytest.approx(expected, abs=1e-12)


def _world(points, theta):
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c * points[:, 0] - s * points[:, 1], s * points[:, 0] + c * points[:, 1]], 1)


@pytest.mark.parametrize("cam", [
    _cam(offset=6.0), _cam("poly4567", "parabolic", roller=4.0, offset=-10.0),
    _cam(contact="knife", roller=0.0, offset=5.0),
    _cam(moves="oscillating", lift=math.radians(20), arm=60.0, pivot=(70.0, 10.0)),
    _cam("shm", "poly345", moves="oscillating", lift=math.radians(15), arm=50.0,
         pivot=(-20.0, 75.0), roller=6.0)], ids=["roller", "roller2", "knife", "rocker", "rocker2"])
def test_the_follower_touches_the_profile_at_every_angle(cam):
    theta = turn_angles(cam, 720)
    r = analyse_cam(cam, theta)
    gap = np.hypot(*(r.profile - r.pitch).T)
    assert gap == pytest.approx(np.full(len(theta), cam.roller), abs=1e-9)
    # the roller (or the knife) at each angle touches the cam and nowhere cuts into it:
    # its distance to the whole profile is the roller's radius, at its own point
    distance = np.hypot(r.pitch[:, None, 0] - r.profile[None, :, 0],
                        r.pitch[:, None, 1] - r.profile[None, :, 1])
    assert distance.min(axis=1) == pytest.approx(np.full(len(theta), cam.roller), abs=1e-9)
    # the contact is where the roller's circle is tangent to the pitch curve
    h = 1e-6
    tangent = (analyse_cam(cam, theta + h).pitch - analyse_cam(cam, theta - h).pitch) / (2 * h)
    if cam.roller:
        dot = np.einsum("ij,ij->i", tangent, r.profile - r.pitch)
        assert np.all(np.abs(dot) / (np.hypot(*tangent.T) * cam.roller) < 1e-6)


def test_a_flat_face_touches_the_profile_at_every_angle():
    cam = _cam("cycloidal", "poly345", contact="flat", roller=0.0)
    theta = turn_angles(cam, 720)
    r = analyse_cam(cam, theta)
    s, ds, _, _ = follower_motion(cam, theta)
    for k, t in enumerate(theta):
        world = _world(r.profile, t)
        face = cam.base + s[k]
        assert world[k, 1] == pytest.approx(face, abs=1e-9)      # the contact is on the face
        assert world[k, 0] == pytest.approx(ds[k], abs=1e-9)     # at s' from the stem
        assert world[:, 1].max() <= face + 1e-9                  # the cam is under the face
    assert np.all(r.pressure == 0)


def _three_point_radius(points):
    """The radius of the circle through each point and its neighbours (positive where
    the curve turns clockwise, as a pitch curve does seen on the cam)."""
    a, b, c = np.roll(points, 1, 0), points, np.roll(points, -1, 0)
    ab, bc, ca = (np.hypot(*(b - a).T), np.hypot(*(c - b).T), np.hypot(*(a - c).T))
    cross = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    return -ab * bc * ca / (2 * cross)


def test_curvature_of_the_pitch_curve_against_three_points():
    cam = _cam("poly345", "cycloidal", offset=7.0)
    theta = np.linspace(0, 2 * PI, 7200, endpoint=False)
    r = analyse_cam(cam, theta)
    fd = _three_point_radius(r.pitch)
    # (where the jerk jumps, at the segments' ends, three points are only first order)
    edges = np.isin(np.arange(7200) % 600, [0]) & np.isin(np.arange(7200) // 600, [0, 4, 6, 10])
    ok = (np.abs(r.curvature) < 1e3) & ~edges
    assert fd[ok] == pytest.approx(r.curvature[ok], rel=1e-4)


def test_undercut_where_the_pitch_curve_is_sharper_than_the_roller():
    sharp = Cam("K", "cam", "follower", "roller", 20.0,
                (Segment("rise", 40.0, math.radians(30), "cycloidal"),
                 Segment("fall", 40.0, math.radians(30), "cycloidal"),
                 Segment("dwell", 0.0, math.radians(300))), roller=15.0)
    for cam, undercut in ((sharp, True), (_cam(), False)):
        theta = np.linspace(0, 2 * PI, 7200, endpoint=False)
        fd = _three_point_radius(analyse_cam(cam, theta).pitch)
        sharpest = fd[fd > 0].min()
        assert bool(sharpest < cam.roller) is undercut
        summary = cam_summary(cam)
        assert summary["undercut"] is undercut
        assert summary["curvature"]["min"] == pytest.approx(sharpest - cam.roller, rel=1e-3)


@pytest.mark.parametrize("offset", [0.0, 10.0])
def test_smallest_base_circle_against_a_search(offset):
    cam = _cam(offset=offset)
    limit = math.radians(30.0)
    found = smallest_base(cam, limit)
    theta = turn_angles(cam, 3600)
    s, ds, _, _ = follower_motion(cam, theta)

    def worst(base):
        y = math.sqrt((base + cam.roller) ** 2 - offset**2)
        return np.max(np.abs(np.arctan((ds - offset) / (s + y))))
    grid = np.arange(abs(offset) - cam.roller + 0.01, 200.0, 0.01)
    first = next(b for b in grid if worst(b) <= limit)
    assert found == pytest.approx(first, abs=0.011)
    assert worst(found + 1e-9) <= limit + 1e-12


def test_smallest_base_circle_of_a_rocker_against_a_search():
    cam = _cam(moves="oscillating", lift=math.radians(20), arm=60.0, pivot=(70.0, 0.0))
    limit = math.radians(35.0)
    found = smallest_base(cam, limit, steps=720)
    theta = turn_angles(cam, 720)

    def worst(base):
        return np.max(np.abs(analyse_cam(cam, theta, base=base).pressure))
    grid = np.arange(0.5, 120.0, 0.25)
    first = next(b for b in grid if worst(b) <= limit)
    assert first - 0.25 < found <= first + 1e-9
    assert worst(found) <= limit + 1e-9


def test_a_limit_out_of_range_is_refused():
    with pytest.raises(DesignError, match="between 0 and 90"):
        smallest_base(_cam(), math.radians(90.0))


@pytest.mark.parametrize("rise, fall, lift", [("uniform", "uniform", 30.0),
                                              ("cycloidal", "shm", 60.0)])
def test_a_flat_face_base_circle_keeps_the_profile_convex(rise, fall, lift):
    """The base circle found leaves the profile nowhere concave (its radius of curvature
    base + s + s'' at least 0), and one 1 % smaller makes it concave somewhere."""
    cam = _cam(rise, fall, contact="flat", roller=0.0, lift=lift)
    base = smallest_base(cam, math.radians(30.0))
    theta = turn_angles(cam, 3600)
    s, _, dds, _ = follower_motion(cam, theta)
    assert base == pytest.approx(max(0.0, float(np.max(-(s + dds)))))
    assert analyse_cam(cam, theta, base=base).curvature.min() >= -1e-9
    if base > 0:
        assert analyse_cam(cam, theta, base=0.99 * base).curvature.min() < 0
