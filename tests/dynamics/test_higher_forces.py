"""Forces in linkages with higher pairs: a cam's contact force along the common normal
(the pair unclosed: a note where it would pull), a gear pair's tooth force along the
line of action (20 degrees from the common tangent), both checked by virtual work: the
input's effort times its speed balances the power of every load and inertia force,
worked out in the test from the motion alone."""

from __future__ import annotations

import math

import numpy as np
import pytest

import chaingraph
from chaingraph.kinematics.higher import cam_contact

from ..conftest import run_cli
from ..kinematics.test_higher import drawn_into_its_program

CAM_ROCKER = "catalog/cam-rocker.toml"
FIVE_BAR = "catalog/geared-five-bar.toml"


def _load_power(chain, motion):
    """The power (W) of the chain's constant loads, each at its joint or point."""
    total = np.zeros(motion.theta.size)
    for load in chain.loads:
        p = motion.point(load.at)
        total += (load.force[0] * p.vx + load.force[1] * p.vy) * 1e-3
    return total


def _inertia_power(chain, motion):
    """The power (W) of the links' d'Alembert forces and couples: -m a_G . v_G -
    I alpha omega, the centre G's motion carried from one of the link's joints."""
    total = np.zeros(motion.theta.size)
    for mass in chain.masses:
        link = motion.link(mass.link)
        joint = next(j for j in chain.joints if mass.link in j.links and j.kind == "R")
        p = motion.joint(joint.id)
        turn = link.angle - math.radians(chain.reference_direction(mass.link))  # from drawn
        dx, dy = mass.centre[0] - joint.at[0], mass.centre[1] - joint.at[1]
        rx = (np.cos(turn) * dx - np.sin(turn) * dy) * 1e-3       # from the joint, in m
        ry = (np.sin(turn) * dx + np.cos(turn) * dy) * 1e-3
        w, al = link.omega, link.alpha
        vx, vy = p.vx * 1e-3 - w * ry, p.vy * 1e-3 + w * rx
        ax = p.ax * 1e-3 - al * ry - w * w * rx
        ay = p.ay * 1e-3 + al * rx - w * w * ry
        total -= mass.mass * (ax * vx + ay * vy) + mass.inertia * al * w
    return total


@pytest.mark.parametrize("static", [True, False])
def test_cam_rocker_effort_by_virtual_work(static):
    chain = chaingraph.load(CAM_ROCKER)
    f = chaingraph.forces(chain, static=static, steps=180)
    m = f.motion
    effort = f.solution.efforts["O"]
    others = _load_power(chain, m) + (0.0 if static else _inertia_power(chain, m))
    np.testing.assert_allclose(effort * m.omega, -others, atol=1e-9 * np.abs(others).max())


def test_cam_contact_force_lies_along_the_common_normal():
    chain = chaingraph.load(CAM_ROCKER)
    f = chaingraph.forces(chain, steps=72)
    m = f.motion
    cam = chain.cams[0]
    point, normal, centre = cam_contact(chain, cam, np.radians(m.theta - m.theta[0]))
    fx, fy = f.solution.forces[("K", "follower")]
    n = f.solution.normal["K"]
    np.testing.assert_allclose(fx, n * normal[:, 0], atol=1e-12 * np.abs(n).max())
    np.testing.assert_allclose(fy, n * normal[:, 1], atol=1e-12 * np.abs(n).max())
    # a roller's common normal passes through the roller's centre, a roller away
    np.testing.assert_allclose(np.hypot(*(centre - point).T), cam.roller, atol=1e-9)
    np.testing.assert_allclose(centre - point, cam.roller * normal, atol=1e-9)
    # and the roller's centre is the follower's own point, moved with it
    np.testing.assert_allclose(centre[:, 1], 40.0 + m.slide("S").s, atol=1e-9)
    assert np.all(n > 0)          # at 10 rad/s the load keeps the roller on the cam
    assert not any("leaves the cam" in note for note in f.notes)


def test_where_the_follower_would_leave_the_cam_is_noted():
    chain = chaingraph.load(CAM_ROCKER)
    f = chaingraph.forces(chain, omega=60.0, steps=360)
    n = f.solution.normal["K"]
    theta = f.motion.theta
    pulls = theta[n < 0]
    (note,) = [x for x in f.notes if "leaves the cam" in x]
    assert note.startswith("the contact force of cam 'K' would have to pull its follower")
    # the runs the note gives are the steps where the force is negative
    runs = [tuple(float(v) for v in run.split(" to "))
            for run in note.split(" at ")[1].split(" degrees")[0].split(", ")]
    inside = np.zeros(theta.size, dtype=bool)
    for a, b in runs:
        inside |= (theta >= a) & (theta <= b)
    np.testing.assert_array_equal(inside, n < 0)
    # where the follower decelerates at the end of the rise (cam 60-120 degrees from
    # the drawing: input 150-210) and the start of the fall (270-330)
    assert pulls.size and np.all(((pulls > 150) & (pulls < 210)) | ((pulls > 270) & (pulls < 330)))
    one = chaingraph.forces(chain, omega=60.0, at=180.0)
    assert any("leaves the cam" in x for x in one.notes)
    assert not any("leaves the cam" in x for x in chaingraph.forces(chain, at=180.0).notes)


def test_geared_five_bar_effort_by_virtual_work_and_tooth_force_on_its_line():
    chain = chaingraph.load(FIVE_BAR)
    for static in (True, False):
        f = chaingraph.forces(chain, static=static, start=-100.0, stop=100.0, steps=100)
        m = f.motion
        others = _load_power(chain, m) + (0.0 if static else _inertia_power(chain, m))
        np.testing.assert_allclose(f.solution.efforts["A"] * m.omega, -others,
                                   atol=1e-9 * np.abs(others).max())
    # the cranks' centres lie on the x axis: the common tangent at the pitch point
    # (50, 0) is vertical, and the line of action is 20 degrees from it
    fx, fy = f.solution.forces[("G", "right crank")]
    moving = np.abs(fy) > 1e-9
    np.testing.assert_allclose(np.abs(fx[moving]) / np.abs(fy[moving]),
                               math.tan(math.radians(20.0)), rtol=1e-9)
    # pushing the gears apart: on the right gear, away from the left one (+x)
    assert np.all(fx[moving] > 0)
    np.testing.assert_allclose(np.abs(f.solution.normal["G"]), np.hypot(fx, fy), rtol=1e-12)


def test_a_gear_pairs_pressure_angle_tilts_its_tooth_force_and_leaves_the_effort(tmp_path):
    text = open(FIVE_BAR, encoding="utf-8").read()
    steeper = chaingraph.loads(text.replace('carrier = "frame"',
                                            'carrier = "frame"\npressure_angle = 25.0'))
    assert steeper.gears[0].pressure_angle == 25.0
    assert chaingraph.loads(chaingraph.dumps(steeper)).gears[0].pressure_angle == 25.0
    a = chaingraph.forces(chaingraph.load(FIVE_BAR), at=60.0, static=True)
    b = chaingraph.forces(steeper, at=60.0, static=True)
    assert b.effort() == pytest.approx(a.effort(), rel=1e-12)     # the tangential part
    fx, fy = b.reaction("G", "left crank").force
    assert abs(fx / fy) == pytest.approx(math.tan(math.radians(25.0)), rel=1e-9)
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace('carrier = "frame"', 'carrier = "frame"\npressure_angle = 50'),
                   encoding="utf-8")
    code, out, err = run_cli("solve", bad)
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "key 'pressure_angle' must be a number of degrees from 0 to less than 45" in err


@pytest.mark.parametrize("static", [True, False])
def test_sun_and_planet_effort_by_virtual_work(static):
    """Watt's sun and planet: the arm's effort balances the power of the load on the
    sun's rim and of the rod's and the sun's inertia, the sun turned by the gear pair
    that the linkage drives (the planet fixed to the rod, the arm its carrier)."""
    chain = chaingraph.load("examples/sun-and-planet.toml")
    f = chaingraph.forces(chain, static=static, steps=72)
    m = f.motion
    others = _load_power(chain, m) + (0.0 if static else _inertia_power(chain, m))
    assert np.abs(others).max() > 0.1
    np.testing.assert_allclose(f.solution.efforts["O"] * m.omega, -others,
                               atol=1e-9 * np.abs(others).max())


def test_a_cam_drawn_into_its_program_bears_the_same_forces():
    """The cam-driven rocker drawn 60 degrees into its program (kinematics'
    test_higher) balances its loads with the same effort and contact force as the one
    drawn at the start, 60 degrees on (statically: its masses' centres stay where the
    original's are drawn)."""
    a = chaingraph.forces(chaingraph.load(CAM_ROCKER), start=150.0, stop=510.0, steps=36,
                          static=True)
    b = chaingraph.forces(drawn_into_its_program(CAM_ROCKER, 60.0), steps=36, static=True)
    for got, want in ((b.solution.efforts["O"], a.solution.efforts["O"]),
                      (b.solution.normal["K"], a.solution.normal["K"])):
        np.testing.assert_allclose(got, want, atol=1e-9 * np.abs(want).max())
    assert np.ptp(a.solution.normal["K"]) > 1.0
