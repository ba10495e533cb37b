"""Linkages with higher pairs: a geared five-bar and a cam driving a rocker, solved by
the ordinary solver with the pairs as derived inputs (kinematics/higher.py).

Checked against closed forms (the 1:1 geared five-bar is symmetric about the line
between its pivots, its coupler's joint on that line), kinematics/cams.py's program
(the follower's slide is s(theta) exactly), finite differences of the positions, and
relabelling."""

import math
import tomllib

import numpy as np
import pytest

import chaingraph
from chaingraph.errors import MechanismError
from chaingraph.kinematics.cams import follower_motion
from chaingraph.kinematics.higher import cam_contact
from chaingraph.kinematics.plan import build_plan
from chaingraph.kinematics.sweep import cycle
from chaingraph.model.chainfile import toml_text

from ..conftest import catalog_path, run_cli
from .newton_check import assert_newton_agrees_with_closed_forms

FIVE_BAR = "catalog/geared-five-bar.toml"
CAM_ROCKER = "catalog/cam-rocker.toml"


def _text(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def test_geared_five_bar_is_symmetric_and_matches_its_closed_form():
    chain = chaingraph.load(FIVE_BAR)
    m = chaingraph.solve(chain, steps=48)
    theta = np.radians(m.theta)                      # the left crank's direction
    b = m.joint("B")
    np.testing.assert_allclose(b.x, 40 * np.cos(theta), atol=1e-9)
    np.testing.assert_allclose(b.y, 40 * np.sin(theta), atol=1e-9)
    # the right crank turns the other way at the same speed: D mirrors B about x = 50
    d = m.joint("D")
    np.testing.assert_allclose(d.x, 100 - b.x, atol=1e-9)
    np.testing.assert_allclose(d.y, b.y, atol=1e-9)
    c = m.joint("C")
    np.testing.assert_allclose(c.x, 50.0, atol=1e-9)
    np.testing.assert_allclose(
        c.y, 40 * np.sin(theta) + np.sqrt(70.0 ** 2 - (50 - 40 * np.cos(theta)) ** 2),
        atol=1e-9)
    right = m.link("right crank").omega
    np.testing.assert_allclose(right, -m.link("left crank").omega, atol=1e-12)
    # the arms straighten (a dead centre) where 50 - 40 cos(theta) = 70
    assert m.summary["input_range"] == pytest.approx([-120.0, 120.0], abs=1e-6)
    assert m.plan.mobility == 1 and m.plan.numeric_mobility == 1


def _check_finite_differences(m, names, h_deg, *, rtol_a):
    """Each point's velocity and acceleration against central differences of its
    positions over the sweep's uniform grid of input angles (``h_deg`` apart), to a
    share of the point's largest velocity and acceleration."""
    h = math.radians(h_deg) / m.omega
    for name in names:
        p = m.point(name)
        v_scale = max(np.abs(p.vx).max(), np.abs(p.vy).max())
        a_scale = max(np.abs(p.ax).max(), np.abs(p.ay).max())
        for coord in ("x", "y"):
            q = getattr(p, coord)
            np.testing.assert_allclose((q[2:] - q[:-2]) / (2 * h),
                                       getattr(p, "v" + coord)[1:-1], atol=1e-5 * v_scale)
            np.testing.assert_allclose((q[2:] - 2 * q[1:-1] + q[:-2]) / h ** 2,
                                       getattr(p, "a" + coord)[1:-1], atol=rtol_a * a_scale)


@pytest.mark.parametrize("teeth", [(25, 25), (20, 30)])
def test_geared_five_bar_rates_are_the_derivatives_of_its_positions(teeth):
    text = _text(FIVE_BAR).replace("teeth = [25, 25]", f"teeth = [{teeth[0]}, {teeth[1]}]")
    chain = chaingraph.loads(text)
    m = chaingraph.solve(chain, start=20.0, stop=80.0, steps=600)
    assert np.all(np.diff(m.theta) == pytest.approx(0.1))
    ratio = -teeth[0] / teeth[1]
    np.testing.assert_allclose(m.link("right crank").omega, ratio * m.link("left crank").omega,
                               rtol=1e-12)
    turned = (m.link("right crank").angle - m.link("right crank").angle[0])
    np.testing.assert_allclose(turned, ratio * np.radians(m.theta - m.theta[0]), atol=1e-12)
    _check_finite_differences(m, ("C", "P"), 0.1, rtol_a=1e-4)


def test_cam_follower_slides_by_the_program():
    chain = chaingraph.load(CAM_ROCKER)
    m = chaingraph.solve(chain, steps=720)
    cam = chain.cams[0]
    turn = np.radians(m.theta - m.theta[0])           # the cam's turn from the drawing
    s, ds, dds, _ = follower_motion(cam, turn)
    slide = m.slide("S")
    np.testing.assert_allclose(slide.s, s, atol=1e-12)
    np.testing.assert_allclose(slide.v, ds * m.omega, atol=1e-9)
    np.testing.assert_allclose(slide.a, dds * m.omega ** 2, atol=1e-7)
    np.testing.assert_allclose(m.joint("F").y, 100.0 + s, atol=1e-9)
    np.testing.assert_allclose(m.joint("F").x, 0.0, atol=1e-12)
    assert m.plan.mobility == 1


def test_cam_rocker_rates_are_the_derivatives_of_its_positions():
    chain = chaingraph.load(CAM_ROCKER)
    m = chaingraph.solve(chain, start=100.0, stop=200.0, steps=1000)  # inside the rise
    _check_finite_differences(m, ("G",), 0.1, rtol_a=1e-3)


def test_oscillating_follower_swings_by_the_program(write):
    """A cam swinging a rocker follower (the oscillating example's cam, drawn with its
    pivot at the table's place) turns the rocker by the program exactly."""
    text = _text("examples/cam-oscillating-roller.toml")
    text = text.replace('links = ["frame", "cam"]', 'links = ["frame", "cam"]\nat = [0.0, 0.0]')
    text = text.replace('links = ["frame", "rocker"]',
                        'links = ["frame", "rocker"]\nat = [70.0, 20.0]')
    text = text.replace('links = ["cam", "rocker"]', 'links = ["cam", "rocker"]\nat = [0.0, 30.0]')
    text += '\n[mechanism]\nfixed = "frame"\ndriver = "cam"\noutput = "rocker"\n'
    chain = chaingraph.load(write(text))
    m = chaingraph.solve(chain, steps=360)
    s = follower_motion(chain.cams[0], np.radians(m.theta - m.theta[0]))[0]
    rocker = m.link("rocker").angle
    np.testing.assert_allclose(rocker - rocker[0], s, atol=1e-12)


def test_an_oscillating_follower_drives_its_cam_through_the_rise(write):
    """The oscillating example drawn 75 degrees into its program (halfway up its rise
    of 20 degrees over 150), the rocker's pivot Q the input: the rocker swings from -10
    to 10 degrees of its drawing, turning the cam by the program's inverse, -75 to 75."""
    text = _text("examples/cam-oscillating-roller.toml")
    text = text.replace('links = ["frame", "cam"]', 'links = ["frame", "cam"]\nat = [0.0, 0.0]')
    text = text.replace('links = ["frame", "rocker"]',
                        'links = ["frame", "rocker"]\nat = [70.0, 20.0]')
    first = chaingraph.loads(text.replace('links = ["cam", "rocker"]',
                                          'links = ["cam", "rocker"]\nat = [0.0, 30.0]'))
    k = cam_contact(first, first.cams[0], np.radians([75.0]))[0][0]
    text = text.replace('links = ["cam", "rocker"]',
                        f'links = ["cam", "rocker"]\nat = [{float(k[0])!r}, {float(k[1])!r}]')
    text = text.replace("pivot = [70.0, 20.0]", "pivot = [70.0, 20.0]\ndrawn = 75.0")
    text += '\n[mechanism]\nfixed = "frame"\ndriver = "cam"\noutput = "rocker"\n'
    chain = chaingraph.load(write(text))
    m = chaingraph.solve(chain, inputs=["Q"], steps=50)
    cam = m.link("cam").angle - math.radians(chain.reference_direction("cam"))
    rocker = m.link("rocker").angle - math.radians(chain.reference_direction("rocker"))
    assert np.degrees(rocker[[0, -1]]) == pytest.approx([-10.0, 10.0], abs=1e-9)
    assert np.degrees(cam[[0, -1]]) == pytest.approx([-75.0, 75.0], abs=1e-6)
    s = follower_motion(chain.cams[0], math.radians(75.0) + cam)[0]
    np.testing.assert_allclose(s - s[25], rocker, atol=1e-10)
    assert s[25] == pytest.approx(math.radians(10.0), abs=1e-12)


def test_relabelled_chains_move_alike():
    chain = chaingraph.load(CAM_ROCKER)
    other = chain.relabelled(links={"cam": "disc", "follower": "tappet", "rocker": "lever"},
                             joints={"K": "contact", "S": "guide", "F": "pin"})
    a = chaingraph.solve(chain, steps=90)
    b = chaingraph.solve(other, steps=90)
    np.testing.assert_allclose(a.slide("S").s, b.slide("guide").s, atol=1e-12)
    np.testing.assert_allclose(a.link("rocker").alpha, b.link("lever").alpha, atol=1e-9)
    five = chaingraph.load(FIVE_BAR)
    swapped = five.relabelled(links={"left crank": "one", "right crank": "two"},
                              joints={"G": "mesh"})
    np.testing.assert_allclose(chaingraph.solve(five, steps=30).point("P").y,
                               chaingraph.solve(swapped, steps=30).point("P").y, atol=1e-12)


def test_single_pose_follows_the_pairs_too():
    chain = chaingraph.load(CAM_ROCKER)
    pose = chaingraph.pose_motion(chain, at=150.0)       # 60 degrees into the rise
    cam = chain.cams[0]
    s, ds, _, _ = follower_motion(cam, np.array([math.radians(60.0)]))
    assert pose.slides["S"].slide == pytest.approx(float(s[0]), abs=1e-9)
    assert pose.positions["F"][1] == pytest.approx(100.0 + float(s[0]), abs=1e-9)
    assert pose.links["follower"].velocity[1] == pytest.approx(float(ds[0]) * pose.omega,
                                                               abs=1e-9)


def test_a_simple_gear_train_turns_by_the_product_of_its_teeth():
    """The driver (20 teeth) turns the driven gear (50) through an idler (35): the
    driven gear turns 20/50 of the driver's angle, the same way, the idler -20/35."""
    chain = chaingraph.load(catalog_path("simple-gear-train"))
    m = chaingraph.solve(chain, fixed="frame", driver="driver", start=0.0, stop=360.0,
                         steps=36)
    turn = np.radians(m.theta - m.theta[0])
    for link, ratio in (("idler", -20 / 35), ("driven", 20 / 50)):
        angle = m.link(link).angle
        np.testing.assert_allclose(angle - angle[0], ratio * turn, atol=1e-12)
        np.testing.assert_allclose(m.link(link).omega, ratio * m.omega, rtol=1e-12)
    assert m.plan.mobility == 1        # Kutzbach: 3 x 3 - 2 x 3 - 2 = 1


def test_a_pair_no_input_drives_is_refused():
    chain = chaingraph.load(FIVE_BAR)
    with pytest.raises(MechanismError, match="gear pair 'G'") as e:
        build_plan(chain, inputs=[chaingraph.Input("C")])
    assert "cannot be derived" in str(e.value)


def test_a_follower_drawn_off_its_line_is_refused():
    text = _text(CAM_ROCKER).replace("offset = 0.0", "offset = 5.0")
    with pytest.raises(MechanismError, match="offset"):
        chaingraph.solve(chaingraph.loads(text), steps=10)


def test_the_command_line_refuses_in_one_line(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(_text(CAM_ROCKER).replace("offset = 0.0", "offset = 5.0"), encoding="utf-8")
    for args, said in (([bad], "drawn 0 to the right of the cam's centre (looking along the "
                                "follower); its 'offset' is 5"),
                       (["catalog/cam-and-follower.toml", "--fixed", "frame", "--driver", "cam"],
                        "cannot be solved for motion"),
                       ([FIVE_BAR, "--input", "C"], "cannot be derived from the inputs")):
        code, out, err = run_cli("solve", *args)
        assert code == 2 and out == "" and len(err.strip().splitlines()) == 1, err
        assert said in err


def test_a_follower_s_dwells_are_not_counted_in_its_strokes():
    """The catalog's cams rise over 120 degrees of cam turn and fall over 120, with a
    dwell of 60 at each end: forward and return strokes of 120 each (time ratio 1),
    the dwells said, not a stroke of 240 from the middle of one dwell to the other."""
    for name in ("disc-cam-roller-follower", "cam-rocker"):
        s = chaingraph.solve(chaingraph.load(f"catalog/{name}.toml")).summary
        assert abs(s.forward_deg - 120.0) < 1e-6 and abs(s.return_deg - 120.0) < 1e-6, name
        assert abs(s.time_ratio - 1.0) < 1e-6
        assert "dwells at its extremes (60 and 60 degrees" in s.note


# -- pairs driven through the linkage (Watt's sun and planet) --------------------------
SUN_AND_PLANET = "examples/sun-and-planet.toml"


def _turning(m, centre, point):
    """The direction (radians, unwrapped) of the line from joint ``centre`` to the
    joint or point ``point``, from the solved positions alone."""
    c, p = m.point(centre), m.point(point)
    return np.unwrap(np.arctan2(p.y - c.y, p.x - c.x))


def _sun_and_planet(teeth=(20, 20)):
    text = _text(SUN_AND_PLANET).replace("teeth = [20, 20]", f"teeth = [{teeth[0]}, {teeth[1]}]")
    return chaingraph.loads(text)


def test_watt_s_sun_turns_twice_for_each_turn_of_the_arm():
    """The planet is fixed to the rod, the arm carries it round the sun: Willis's
    equation (w_sun - w_arm) / (w_rod - w_arm) = -20/20 gives w_sun = 2 w_arm - w_rod,
    and as the rod only rocks, two turns of the sun for each turn of the arm. The
    angles are measured here from the solved positions alone: the arm's along OB, the
    rod's along BC, the sun's along OT (T on its rim)."""
    m = chaingraph.solve(chaingraph.load(SUN_AND_PLANET), steps=360)
    arm, rod, sun = _turning(m, "O", "B"), _turning(m, "B", "C"), _turning(m, "O", "T")
    arm, rod, sun = arm - arm[0], rod - rod[0], sun - sun[0]
    np.testing.assert_allclose(arm, np.radians(m.theta - m.theta[0]), atol=1e-12)
    np.testing.assert_allclose(sun, 2 * arm - rod, atol=1e-9)
    assert sun[-1] == pytest.approx(4 * math.pi, abs=1e-9)        # two turns
    assert rod[-1] == pytest.approx(0.0, abs=1e-9) and np.ptp(rod) < math.pi
    # the rolling of the pitch circles: the planet's centre stays at 40 from O
    np.testing.assert_allclose(np.hypot(m.joint("B").x, m.joint("B").y), 40.0, atol=1e-9)
    np.testing.assert_allclose(m.link("sun").omega,
                               2 * m.link("arm").omega - m.link("rod").omega, atol=1e-12)
    assert [s.pattern for s in m.plan.steps] == ["WR", "RRR", "WR"]   # the sun last
    assert m.plan.mobility == 1 and m.plan.numeric_mobility == 1


def test_a_geared_four_bar_s_sun_follows_willis_to_whole_turns():
    """Gears of 16 and 24 teeth (the ratio -2/3, not whole): the sun turns by
    theta_arm - 2/3 (theta_rod - theta_arm), 5/3 turns per turn of the arm, so the
    mechanism is back as drawn after three turns (1080 degrees), not one."""
    chain = _sun_and_planet((16, 24))
    m = chaingraph.solve(chain, start=0.0, stop=1080.0, steps=1080)
    arm, rod, sun = _turning(m, "O", "B"), _turning(m, "B", "C"), _turning(m, "O", "T")
    arm, rod, sun = arm - arm[0], rod - rod[0], sun - sun[0]
    np.testing.assert_allclose(sun, arm - 2 / 3 * (rod - arm), atol=1e-9)
    assert sun[360] == pytest.approx(2 * math.pi * 5 / 3, abs=1e-9)
    assert sun[-1] == pytest.approx(10 * math.pi, abs=1e-9)
    assert cycle(m.plan).period == pytest.approx(1080.0)


@pytest.mark.parametrize("teeth", [(20, 20), (16, 24)])
def test_sun_and_planet_rates_are_the_derivatives_of_its_positions(teeth):
    m = chaingraph.solve(_sun_and_planet(teeth), start=20.0, stop=80.0, steps=600)
    assert np.all(np.diff(m.theta) == pytest.approx(0.1))
    _check_finite_differences(m, ("T", "C"), 0.1, rtol_a=1e-4)


def test_the_beam_drives_the_sun_as_the_engine_does():
    """Watt's engine drives the beam, not the arm: the beam's rocking places the rod
    and the arm (a dyad), then the sun, by the same equation."""
    m = chaingraph.solve(chaingraph.load(SUN_AND_PLANET), inputs=["Q"], steps=60)
    arm, rod, sun = _turning(m, "O", "B"), _turning(m, "B", "C"), _turning(m, "O", "T")
    np.testing.assert_allclose(sun - sun[0], 2 * (arm - arm[0]) - (rod - rod[0]), atol=1e-9)
    assert m.plan.steps[-1].links == ("sun",)


def test_sun_and_planet_relabelled_moves_alike():
    chain = chaingraph.load(SUN_AND_PLANET)
    other = chain.relabelled(links={"sun": "wheel", "rod": "pitman", "arm": "carrier"},
                             joints={"O": "shaft", "G": "mesh", "B": "pin"})
    a, b = chaingraph.solve(chain, steps=72), chaingraph.solve(other, steps=72)
    np.testing.assert_allclose(a.point("T").x, b.point("T").x, atol=1e-12)
    np.testing.assert_allclose(a.link("sun").alpha, b.link("wheel").alpha, atol=1e-9)


def test_a_gear_loop_the_linkage_cannot_place_first_is_refused_saying_why():
    with pytest.raises(MechanismError, match="gear pair 'G'") as e:
        build_plan(chaingraph.load(FIVE_BAR), inputs=[chaingraph.Input("C")])
    assert "nor do the links placed before it turn its driving member" in str(e.value)


# -- a gear train's cycle from its teeth -----------------------------------------------
def test_a_train_of_ratio_5_2_is_solved_over_its_whole_cycle():
    """The catalog's simple train: the idler turns -20/35 = -4/7 of the driver, the
    driven gear 2/5: all three are back as drawn only after lcm(7, 5) = 35 turns of
    the driver, which the cycle takes from the teeth (the search stopped at four)."""
    chain = chaingraph.load(catalog_path("simple-gear-train"))
    plan = build_plan(chain, fixed="frame", driver="driver")
    assert cycle(plan).period == pytest.approx(35 * 360.0)
    m = chaingraph.solve(chain, fixed="frame", driver="driver", start=0.0, stop=35 * 360.0,
                         steps=35 * 8)
    turn = np.radians(m.theta - m.theta[0])
    for link, ratio, turns in (("idler", -4 / 7, -20), ("driven", 2 / 5, 14)):
        angle = m.link(link).angle
        np.testing.assert_allclose(angle - angle[0], ratio * turn, atol=1e-9)
        assert angle[-1] - angle[0] == pytest.approx(2 * math.pi * turns, abs=1e-9)
        inside = (angle[8::8] - angle[0]) / (2 * math.pi)        # after each whole turn
        whole = np.abs(inside - np.round(inside)) < 1e-9
        assert whole.sum() == (5 if link == "idler" else 7)       # at 7k turns, or 5k
    assert "input range         0 to 12600 degrees" in run_cli(
        "solve", catalog_path("simple-gear-train"), "--fixed", "frame", "--driver",
        "driver")[1]


def test_a_follower_the_linkage_moves_does_not_drive_its_cam():
    """The rocker as the input of the cam-driven rocker would have the linkage move the
    follower and the follower turn the cam: refused, saying when a follower drives its
    cam (as an input, the cam drawn inside a rise or fall)."""
    chain = chaingraph.load(CAM_ROCKER)
    with pytest.raises(MechanismError, match="the cam 'K'") as e:
        build_plan(chain, inputs=[chaingraph.Input("H")])
    assert "a follower drives its cam only as an input" in str(e.value)
    code, out, err = run_cli("solve", CAM_ROCKER, "--input", "H")
    assert code == 2 and len(err.strip().splitlines()) == 1
    assert "have no inverse" in err


def test_a_follower_drives_its_cam_through_the_rise_the_cam_is_drawn_in():
    """The cam-driven rocker drawn 60 degrees into its cycloidal rise (25 over 120),
    its follower's slide S the input: the cam turns by the program's inverse over the
    rise, the slide from -12.5 to 12.5 (the rise's ends, where the cam would turn
    infinitely fast, are the limits); the mechanism stands where the cam-driven one
    does at the same cam angle, and the cam's speed is the slide's over s'."""
    chain = drawn_into_its_program(CAM_ROCKER, 60.0)
    cam = chain.cams[0]
    m = chaingraph.solve(chain, inputs=["S"], steps=200)
    slide = m.slide("S").s
    assert (slide[0], slide[-1]) == (pytest.approx(-12.5, abs=1e-9),
                                     pytest.approx(12.5, abs=1e-9))
    turn = m.link("cam").angle - math.radians(chain.reference_direction("cam"))
    s = follower_motion(cam, math.radians(60.0) + turn)
    np.testing.assert_allclose(s[0] - 12.5, slide, atol=1e-9)
    inside = slice(1, -1)
    np.testing.assert_allclose(m.link("cam").omega[inside],
                               m.slide("S").v[inside] / s[1][inside], rtol=1e-9)
    by_cam = chaingraph.solve(chain, steps=8)   # the same chain with the cam driving
    for k in (20, 77, 150):
        at = chaingraph.pose_motion(chain, at=by_cam.theta[0] + math.degrees(turn[k]))
        assert at.positions["G"] == pytest.approx((m["x:G"][k], m["y:G"][k]), abs=1e-9)
    # and against differences of its angle, away from the ends (where it is unbounded)
    h = np.diff(slide)[0] / m.omega
    angle, middle = m.link("cam").angle, slice(40, -40)
    np.testing.assert_allclose(((angle[2:] - angle[:-2]) / (2 * h))[middle],
                               m.link("cam").omega[inside][middle], rtol=1e-4)
    np.testing.assert_allclose(((angle[2:] - 2 * angle[1:-1] + angle[:-2]) / h ** 2)[middle],
                               m.link("cam").alpha[inside][middle], rtol=1e-3, atol=1e-6)


@pytest.mark.parametrize("turn", [0.0, 150.0])
def test_a_follower_does_not_drive_a_cam_drawn_where_it_stands_still(turn):
    """Drawn at the start of the rise (0) or in the dwell at the top (150), the slide
    cannot turn the cam: refused, naming the cam's place in its program."""
    chain = chaingraph.load(CAM_ROCKER) if turn == 0.0 else \
        drawn_into_its_program(CAM_ROCKER, turn)
    with pytest.raises(MechanismError) as e:
        build_plan(chain, inputs=[chaingraph.Input("S")])
    said = str(e.value)
    assert f"the cam 'K' is drawn {turn:g} degrees into its program, in a dwell" in said
    assert "its follower cannot drive it" in said


# -- a cam drawn anywhere in its program ----------------------------------------------
def drawn_into_its_program(path, turn, *, contact=None):
    """The mechanism of ``path`` drawn with its cam ``turn`` degrees into its program:
    every joint and point where the solve of the original puts it there (the cam's
    contact K where the profile touches the follower), and ``drawn = turn``."""
    chain = chaingraph.load(path)
    m = chaingraph.solve(chain, start=90.0 + turn, stop=90.0 + turn, steps=1)
    doc = tomllib.loads(_text(path))
    cam = chain.cams[0]
    k = cam_contact(chain, cam, np.radians([turn]))[0][0] if contact is None else contact
    for j in doc["joints"]:
        j["at"] = [float(v) for v in k] if j["id"] == cam.id else \
            [float(m[f"x:{j['id']}"][0]), float(m[f"y:{j['id']}"][0])]
    for p in doc.get("points", []):
        p["at"] = [float(m[f"x:{p['id']}"][0]), float(m[f"y:{p['id']}"][0])]
    doc["cams"][0]["drawn"] = float(turn)
    return chaingraph.loads(toml_text(doc))


@pytest.mark.parametrize("turn", [60.0, 150.0, 250.0])
def test_a_cam_drawn_into_its_program_moves_as_drawn_at_its_start_shifted(turn):
    """The cam-driven rocker drawn with its cam 60, 150 or 250 degrees into its program
    (the rise, the dwell at the top, the fall): turned t from its drawing, it is where
    the one drawn at the start is turned turn + t."""
    first = chaingraph.load(CAM_ROCKER)
    moved = drawn_into_its_program(CAM_ROCKER, turn)
    assert moved.cams[0].drawn == pytest.approx(math.radians(turn))
    b = chaingraph.solve(moved, steps=72)
    t = b.theta - b.theta[0]                                   # the cam's turn from its drawing
    a = chaingraph.solve(first, start=90.0 + turn, stop=90.0 + turn + 360.0, steps=72)
    for joint in ("F", "G"):
        for c in ("x", "y"):
            np.testing.assert_allclose(b[f"{c}:{joint}"], a[f"{c}:{joint}"], atol=1e-9)
    np.testing.assert_allclose(b.link("rocker").omega, a.link("rocker").omega, atol=1e-9)
    np.testing.assert_allclose(b.link("rocker").alpha, a.link("rocker").alpha, atol=1e-7)
    # the slide from the drawing: the program from where the cam is drawn
    s = follower_motion(first.cams[0], np.radians(turn + t))[0]
    s0 = follower_motion(first.cams[0], np.radians([turn]))[0][0]
    np.testing.assert_allclose(b.slide("S").s, s - s0, atol=1e-12)
    # the roller's centre (the pair's columns) where the first one's is
    np.testing.assert_allclose(b["y:K"], a["y:K"], atol=1e-9)


def test_a_cam_drawn_where_its_program_does_not_put_the_follower_is_refused():
    """Drawn 60 degrees into the rise with the contact still on the base circle: the
    follower is drawn at its lowest, where the program has it 12.5 up."""
    moved = drawn_into_its_program(CAM_ROCKER, 60.0, contact=(0.0, 30.0))
    with pytest.raises(MechanismError) as e:
        chaingraph.solve(moved, steps=10)
    said = str(e.value)
    assert "its contact 'K' is drawn 30 from the cam's centre" in said
    s = float(follower_motion(moved.cams[0], np.radians([60.0]))[0][0])
    assert f"60 degrees into its program (its 'drawn'), the follower {s:.6g} above" in said
    assert chaingraph.loads(chaingraph.dumps(moved)).cams[0].drawn == moved.cams[0].drawn


_CAM_ON_A_CRANK = '''
[[joints]]
id = "B"
kind = "R"
links = ["cam", "coupler"]
at = [-20.0, 0.0]

[[joints]]
id = "D"
kind = "R"
links = ["coupler", "lever"]
at = [-76.60910972640129, 19.884886119469233]

[[joints]]
id = "E"
kind = "R"
links = ["lever", "frame"]
at = [-80.0, -30.0]
'''


def test_a_cam_the_linkage_turns_drives_its_follower_by_the_program():
    """The cam-driven rocker's cam keyed to the crank of a crank-rocker four-bar (O B D
    E) whose lever is the input: the four-bar turns the cam, the follower slides by
    the program at the cam's turn, measured here along OB from the solved positions."""
    text = _text(CAM_ROCKER).replace("[[cams]]", _CAM_ON_A_CRANK + "\n[[cams]]")
    chain = chaingraph.loads(text)
    m = chaingraph.solve(chain, inputs=["E"], steps=400)
    assert m.plan.derived[0].after == ("frame", "cam")
    turn = _turning(m, "O", "B") - math.pi           # from the drawing (B drawn at 180)
    assert np.ptp(turn) > math.radians(60.0)
    s = follower_motion(chain.cams[0], turn)[0]
    np.testing.assert_allclose(m.slide("S").s, s, atol=1e-12)
    np.testing.assert_allclose(m.joint("F").y, 100.0 + s, atol=1e-9)
    # the rate by the chain rule: ds/dt = s'(theta) times the cam's own speed
    np.testing.assert_allclose(m.slide("S").v,
                               follower_motion(chain.cams[0], turn)[1] * m.link("cam").omega,
                               atol=1e-9)
    low, high = m.theta[0], m.theta[-1]                 # the lever's limits
    middle = 0.5 * (low + high)
    b = chaingraph.solve(chain, inputs=[("E", middle - 10.0, middle + 10.0)], steps=400)
    assert np.ptp(b.slide("S").s) > 10.0                 # down the fall
    _check_finite_differences(b, ("F", "G"), 0.05, rtol_a=1e-3)


def test_sun_and_planet_by_newton_agrees_with_its_closed_forms():
    """Without closed forms the four-bar is one group solved by Newton's method, the sun
    still placed after it: the same poses and rates."""
    assert_newton_agrees_with_closed_forms(_sun_and_planet((16, 24)), ["group", "single"],
                                           720.0, 241)


def test_sun_and_planet_poses_do_not_depend_on_where_the_sweep_starts():
    """The 16/24 sun, its angle followed to whole turns over its three-turn cycle: the
    same at an input angle from any sweep, or from one pose."""
    chain = _sun_and_planet((16, 24))
    whole = chaingraph.solve(chain, start=0.0, stop=1080.0, steps=1080)
    for start, stop, steps in ((500.0, 860.0, 4), (-220.0, 140.0, 9), (1000.0, 1400.0, 8)):
        part = chaingraph.solve(chain, start=start, stop=stop, steps=steps)
        k = np.mod(np.round(part.theta).astype(int), 1080)
        for column in ("x:T", "y:T", "omega:sun", "alpha:sun"):
            np.testing.assert_allclose(part[column], whole[column][k], atol=1e-9)
    pose = chaingraph.pose_motion(chain, at=500.0)
    assert pose.positions["T"] == pytest.approx((whole["x:T"][500], whole["y:T"][500]),
                                                abs=1e-9)


_SUN_DRIVES_A_SLIDER = '''
[[joints]]
id = "E"
kind = "R"
links = ["sun", "pitman"]
at = [0.0, -20.0]

[[joints]]
id = "S"
kind = "P"
links = ["frame", "block"]
at = [70.0, -20.0]
axis = 0.0

[[joints]]
id = "F"
kind = "R"
links = ["pitman", "block"]
at = [70.0, -20.0]
'''


def test_a_linkage_goes_on_from_a_gear_the_linkage_drives():
    """The sun of the sun and planet drives a slider-crank (its pin E 20 from O, a
    pitman of 70 to a block sliding on the line y = -20): the sun is placed after the
    four-bar, then the slider-crank from it, the block where the slider-crank's
    closed form puts it for the sun's angle."""
    text = _text(SUN_AND_PLANET).replace("[[gears]]", _SUN_DRIVES_A_SLIDER + "\n[[gears]]")
    m = chaingraph.solve(chaingraph.loads(text), steps=180)
    assert [s.pattern for s in m.plan.steps][-2:] == ["WR", "RRP"]
    phi = _turning(m, "O", "E")
    sun = _turning(m, "O", "T")
    np.testing.assert_allclose(phi - phi[0], sun - sun[0], atol=1e-9)
    x = 20 * np.cos(phi) + np.sqrt(70.0 ** 2 - (20 * np.sin(phi) + 20) ** 2)
    np.testing.assert_allclose(m.joint("F").x, x, atol=1e-9)
    np.testing.assert_allclose(m.joint("F").y, -20.0, atol=1e-9)
    assert sun[-1] - sun[0] == pytest.approx(4 * math.pi, abs=1e-9)
    assert m.plan.mobility == 1
