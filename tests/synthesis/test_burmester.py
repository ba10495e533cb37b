"""Motion generation's geometry: poles, centre and circle points, the Burmester curves
and points, and the mechanisms two dyads make, checked against known mechanisms solved by
chaingraph (their couplers' poses give back their own pivots) and closed forms."""

import math
from dataclasses import replace

import numpy as np
import pytest

import chaingraph
from chaingraph import DesignError
from chaingraph.geometry import circle_circle
from chaingraph.model.chain import Mechanism, Point
from chaingraph.naming.catalog import catalog_path
from chaingraph.synthesis.burmester import (
    Dyad,
    candidates,
    centre_point,
    centre_point_curve,
    circle_point,
    circle_point_curve,
    burmester_points,
    dyad_inputs,
    mechanism,
    residual,
)
from chaingraph.synthesis.poses import displacement, inverted, moved, pole, task_size

INPUTS = (60.0, 85.0, 110.0, 140.0, 170.0)        # degrees, on a 5-degree grid


def _coupler_poses(chain, link, point):
    """The poses of ``link`` (its ``point`` and its angle) at INPUTS, solved by
    chaingraph, and the motion's first row of every joint (where pose 1 draws it)."""
    m = chaingraph.solve(chain, start=INPUTS[0], stop=INPUTS[-1], steps=22)
    rows = [int(np.argmin(abs(m["theta"] - v))) for v in INPUTS]
    assert np.allclose(m["theta"][rows], INPUTS, atol=1e-9)
    poses = [(float(m[f"x:{point}"][r]), float(m[f"y:{point}"][r]),
              math.radians(m[f"angle:{link}"][r])) for r in rows]
    at = {j.id: (float(m[f"x:{j.id}"][rows[0]]), float(m[f"y:{j.id}"][rows[0]]))
          for j in chain.joints}
    return poses, at


@pytest.fixture(scope="module")
def four_bar():
    """A crank-rocker's coupler (frame 100, crank 40, coupler 120, rocker 80) with a
    point off its line: its poses, circle points B, C and centre points A, D."""
    chain = chaingraph.load(catalog_path("four-bar-chain"))
    chain = replace(chain, points=(Point("P", "coupler", (70.0, 90.0)),),
                    mechanism=Mechanism("frame", "crank", 1.0, "coupler"))
    poses, at = _coupler_poses(chain, "coupler", "P")
    return poses, Dyad("RR", at["A"], at["B"]), Dyad("RR", at["D"], at["C"])


@pytest.fixture(scope="module")
def slider_crank():
    """The reciprocating engine's connecting rod: its poses, the crank's RR dyad and the
    crosshead's PR dyad (guide along x)."""
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    chain = replace(chain, points=(Point("P", "connecting rod", (90.0, 40.0)),))
    poses, at = _coupler_poses(chain, "connecting rod", "P")
    return poses, Dyad("RR", at["O"], at["A"]), Dyad("PR", None, at["B"], (1.0, 0.0))


@pytest.fixture(scope="module")
def oscillating():
    """The oscillating cylinder engine's piston rod: the crank's RR dyad and the
    cylinder's RP dyad (the trunnion T, the rod's guide along its axis at pose 1)."""
    chain = chaingraph.load(catalog_path("oscillating-cylinder-engine"))
    poses, at = _coupler_poses(chain, "piston rod", "piston")
    axis = math.radians(chain.joint("S").axis)   # drawn at the first input, 60 degrees
    return poses, Dyad("RR", at["O"], at["A"]), Dyad("RP", at["T"], None,
                                                     (math.cos(axis), math.sin(axis)))


def _same(d, e, tol):
    """Two dyads alike: kind, points within ``tol``, guides parallel within ``tol``."""
    if d.kind != e.kind:
        return False
    for p, q in ((d.centre, e.centre), (d.circle, e.circle)):
        if (p is None) != (q is None) or (p is not None and math.dist(p, q) > tol):
            return False
    return d.guide is None or abs(d.guide[0] * e.guide[1] - d.guide[1] * e.guide[0]) <= tol


def _among(found, dyad, tol):
    return any(_same(d, dyad, tol) for d in found)


def _misfit(poses, d):
    """The largest failure of the dyad's constant-distance (or collinearity) conditions
    over the poses, in lengths, measured directly."""
    if d.kind == "RR":
        r = [math.dist(moved(poses, d.circle, j), d.centre) for j in range(len(poses))]
        return max(r) - min(r)
    if d.kind == "PR":
        n = (-d.guide[1], d.guide[0])
        return max(abs(n[0] * (p[0] - d.circle[0]) + n[1] * (p[1] - d.circle[1]))
                   for p in (moved(poses, d.circle, j) for j in range(len(poses))))
    inv = inverted(poses)
    n = (-d.guide[1], d.guide[0])
    return max(abs(n[0] * (p[0] - d.centre[0]) + n[1] * (p[1] - d.centre[1]))
               for p in (moved(inv, d.centre, j) for j in range(len(inv))))


# -- poles -------------------------------------------------------------------------------
def test_pole_and_rotation_of_a_hand_example():
    # a quarter turn taking the origin to (2, 0): about (1, 1), since (0,0) - (1,1)
    # turned a quarter is (1, -1)
    poses = [(0.0, 0.0, 0.0), (2.0, 0.0, math.pi / 2)]
    p = pole(poses, 0, 1)
    assert p.at == pytest.approx((1.0, 1.0), abs=1e-15) and not p.at_infinity
    assert p.angle == pytest.approx(math.pi / 2, abs=1e-15)
    back = pole(poses, 1, 0)
    assert back.at == pytest.approx((1.0, 1.0), abs=1e-15)
    assert back.angle == pytest.approx(-math.pi / 2, abs=1e-15)


def test_a_translation_s_pole_is_at_infinity_square_to_it():
    p = pole([(1.0, 2.0, 0.7), (4.0, 6.0, 0.7 + 2 * math.pi)], 0, 1)
    assert p.at_infinity and p.at is None
    assert p.direction == pytest.approx((-0.8, 0.6), abs=1e-15)
    assert p.angle == pytest.approx(0.0, abs=1e-15)


def test_every_pole_is_left_in_place(four_bar):
    poses = four_bar[0]
    for i in range(5):
        for j in range(5):
            if i != j:
                p = pole(poses, i, j)
                d = displacement(poses, i, j)
                assert p.angle == pytest.approx(math.remainder(poses[j][2] - poses[i][2],
                                                               2 * math.pi), abs=1e-15)
                # the plane's point at the pole in pose i is there in pose j too
                image = moved([poses[i], poses[j]], p.at, 1)
                assert math.dist(image, p.at) < 1e-12 * task_size(poses)
                assert d[0] == pytest.approx(p.angle, abs=1e-15)


# -- two and three poses ------------------------------------------------------------------
@pytest.mark.parametrize("which", [(0, 1, 2), (0, 2, 4), (0, 3, 4)])
def test_three_poses_give_the_fixed_pivots(four_bar, which):
    poses, crank, rocker = four_bar
    three = [poses[i] for i in which]
    size = task_size(poses)
    for d in (crank, rocker):
        found = centre_point(three, d.circle)
        assert found.kind == "RR" and found.circle == d.circle
        assert math.dist(found.centre, d.centre) < 1e-9 * size
        back = circle_point(three, d.centre)
        assert back.kind == "RR" and back.centre == d.centre
        assert math.dist(back.circle, d.circle) < 1e-9 * size


def test_two_poses_put_the_centre_on_the_bisector(four_bar):
    poses, crank, _ = four_bar
    b1, b2 = crank.circle, moved(poses[:2], crank.circle, 1)
    mid = ((b1[0] + b2[0]) / 2, (b1[1] + b2[1]) / 2)
    chord = (b2[0] - b1[0], b2[1] - b1[1])
    left = (-chord[1] / math.hypot(*chord), chord[0] / math.hypot(*chord))
    offset = (crank.centre[0] - mid[0]) * left[0] + (crank.centre[1] - mid[1]) * left[1]
    found = centre_point(poses[:2], crank.circle, offset=offset)
    assert math.dist(found.centre, crank.centre) < 1e-9 * task_size(poses)
    for t in (-30.0, 0.0, 12.5):
        c = centre_point(poses[:2], crank.circle, offset=t).centre
        assert math.dist(c, b1) == pytest.approx(math.dist(c, b2), rel=1e-12)
        assert math.dist(c, mid) == pytest.approx(abs(t), abs=1e-12)
    back = circle_point(poses[:2], crank.centre)
    assert _misfit(poses[:2], back) < 1e-12 * task_size(poses)


def test_a_circle_point_turning_about_a_hand_centre():
    # the plane turns about (5, 0): each of its points about (5, 0)
    poses = [(5 - 5 * math.cos(a), -5 * math.sin(a), a) for a in (0.0, 0.4, 1.1)]
    for circle in ((0.0, 0.0), (3.0, 7.0), (-2.0, 1.0)):
        assert centre_point(poses, circle).centre == pytest.approx((5.0, 0.0), abs=1e-12)


def test_a_slider_crank_s_slider_is_a_centre_at_infinity(slider_crank):
    poses, crank, slider = slider_crank
    size = task_size(poses)
    found = centre_point(poses[:3], slider.circle)
    assert found.kind == "PR" and _same(found, slider, 1e-9 * size)
    assert _among([centre_point(poses[:3], crank.circle)], crank, 1e-9 * size)


def test_a_trunnion_is_a_circle_point_at_infinity(oscillating):
    poses, _, cylinder = oscillating
    found = circle_point(poses[:3], cylinder.centre)
    assert found.kind == "RP" and _same(found, cylinder, 1e-9 * task_size(poses))


# -- four poses: the Burmester curves --------------------------------------------------------
def test_the_original_dyads_lie_on_both_curves(four_bar):
    poses, crank, rocker = four_bar
    four, size = poses[:4], task_size(poses)
    centres, circles = centre_point_curve(four), circle_point_curve(four)
    for d in (crank, rocker):
        c = math.atan2(d.centre[1] - centres.base[1], d.centre[0] - centres.base[0])
        assert _among(centres.dyads(c), d, 1e-9 * size)
        a = math.atan2(d.circle[1] - circles.base[1], d.circle[0] - circles.base[0])
        assert _among(circles.dyads(a), d, 1e-9 * size)
        assert residual(four, d) < 1e-12


def test_the_curves_are_the_same_dyads_seen_from_either_side(four_bar):
    poses = four_bar[0][:4]
    size = task_size(poses)
    centres, circles = centre_point_curve(poses), circle_point_curve(poses)
    assert centres.base == pytest.approx(circles.base, abs=1e-12 * size)
    sample = centres.sample(90)
    assert len(sample) > 90
    for d in sample:
        assert residual(poses, d) < 1e-12
        if d.kind == "RR" and math.dist(d.centre, d.circle) < 100 * size:
            assert _misfit(poses, d) < 1e-9 * size
            # the same dyad on the circle-point curve, along the line to its circle point
            a = math.atan2(d.circle[1] - circles.base[1], d.circle[0] - circles.base[0])
            if math.dist(d.circle, circles.base) > 1e-6 * size:
                assert _among(circles.dyads(a), d, 1e-8 * size)


def test_each_curve_s_point_at_infinity_is_a_slider(four_bar, slider_crank, oscillating):
    for poses, _, _ in (four_bar, slider_crank, oscillating):
        four = poses[:4]
        pr, rp = centre_point_curve(four).at_infinity, circle_point_curve(four).at_infinity
        assert (pr.kind, rp.kind) == ("PR", "RP")
        assert _misfit(four, pr) < 1e-9 * task_size(four)
        assert _misfit(four, rp) < 1e-9 * task_size(four)
    poses, _, slider = slider_crank
    assert _same(centre_point_curve(poses[:4]).at_infinity, slider, 1e-9 * task_size(poses))
    poses, _, cylinder = oscillating
    assert _same(circle_point_curve(poses[:4]).at_infinity, cylinder,
                 1e-9 * task_size(poses))


# -- five poses: the Burmester points -----------------------------------------------------------
@pytest.mark.parametrize("task", ["four_bar", "slider_crank", "oscillating"])
def test_the_original_dyads_are_among_the_burmester_points(task, request):
    poses, first, second = request.getfixturevalue(task)
    size = task_size(poses)
    found = burmester_points(poses)
    assert len(found) in (2, 4)
    assert _among(found, first, 1e-9 * size) and _among(found, second, 1e-9 * size)
    for d in found:
        assert residual(poses, d) < 1e-12
        # far points are fitted to rounding of their own size
        reach = max([size] + [math.dist(p, poses[0][:2]) for p in (d.centre, d.circle)
                              if p is not None])
        assert _misfit(poses, d) < 1e-9 * reach


def _random_four_bar_poses(rng):
    """Five poses of a random four-bar's coupler at increasing crank angles (solved in
    closed form, the crank angles kept within one circuit), and its two dyads."""
    while True:
        a, d = np.array([0.0, 0.0]), np.array([rng.uniform(60, 140), rng.uniform(-30, 30)])
        crank, coupler, rocker = rng.uniform(15, 40), rng.uniform(60, 150), rng.uniform(50, 120)
        q = rng.uniform(-60, 60, 2)
        angles = np.sort(rng.uniform(0, 2 * np.pi, 5))
        poses, pivots = [], []
        for t in angles:
            b = a + crank * np.array([math.cos(t), math.sin(t)])
            mid, across, raw = circle_circle(tuple(b), coupler, tuple(d), rocker)
            if raw <= 1e-6 * coupler ** 2:
                break
            c = np.array(mid) + math.sqrt(raw) * np.array(across)
            phi = math.atan2(c[1] - b[1], c[0] - b[0])
            p = b + np.array([q[0] * math.cos(phi) - q[1] * math.sin(phi),
                              q[0] * math.sin(phi) + q[1] * math.cos(phi)])
            poses.append((float(p[0]), float(p[1]), phi))
            pivots.append((tuple(map(float, b)), tuple(map(float, c))))
        if len(poses) == 5:
            b, c = pivots[0]
            return poses, Dyad("RR", (0.0, 0.0), b), Dyad("RR", tuple(map(float, d)), c)


def test_random_four_bars_are_found_again():
    rng = np.random.default_rng(37)
    worst = 0.0
    for _ in range(12):
        poses, crank, rocker = _random_four_bar_poses(rng)
        size = task_size(poses)
        found = burmester_points(poses)
        assert len(found) in (2, 4)
        assert _among(found, crank, 1e-9 * size) and _among(found, rocker, 1e-9 * size)
        worst = max([worst] + [residual(poses, d) for d in found])
    assert worst < 1e-12


# -- invariance ---------------------------------------------------------------------------------
def _moved_task(poses, turn, scale, shift):
    c, s = math.cos(turn), math.sin(turn)

    def point(p):
        return (scale * (c * p[0] - s * p[1]) + shift[0], scale * (s * p[0] + c * p[1]) + shift[1])

    def dyad(d):
        guide = None if d.guide is None else (c * d.guide[0] - s * d.guide[1],
                                              s * d.guide[0] + c * d.guide[1])
        return Dyad(d.kind, None if d.centre is None else point(d.centre),
                    None if d.circle is None else point(d.circle), guide)
    return [point(p[:2]) + (p[2] + turn,) for p in poses], point, dyad


@pytest.mark.parametrize("turn, scale, shift", [(0.7, 2.5, (30.0, -12.0)),
                                                (-2.9, 0.01, (-1e3, 4e3)), (math.pi, 40.0, (0, 0))])
def test_rotating_translating_and_scaling_the_task_moves_the_results(four_bar, turn, scale,
                                                                    shift):
    poses, crank, _ = four_bar
    new, point, dyad = _moved_task(poses, turn, scale, shift)
    tol = 1e-9 * task_size(new)
    for i, j in ((0, 1), (2, 4)):
        assert math.dist(pole(new, i, j).at, point(pole(poses, i, j).at)) < tol
        assert pole(new, i, j).angle == pytest.approx(pole(poses, i, j).angle, abs=1e-12)
    assert _same(centre_point(new[:3], point(crank.circle)), dyad(crank), tol)
    before, after = centre_point_curve(poses[:4]), centre_point_curve(new[:4])
    assert math.dist(after.base, point(before.base)) < tol
    for direction in (0.3, 1.9):
        expect = before.dyads(direction)
        got = after.dyads(direction + turn)
        assert len(got) == len(expect) and all(_among(got, dyad(d), tol) for d in expect)
    assert _same(after.at_infinity, dyad(before.at_infinity), tol)
    expect, got = burmester_points(poses), burmester_points(new)
    assert len(got) == len(expect)
    for d in expect:
        # a point R sizes away has homogeneous coordinates of about 1 / R: their rounding
        # moves it by about R^2 (one dyad here has its circle point 940 sizes away)
        reach = max([1.0] + [math.dist(p, poses[0][:2]) / task_size(poses)
                             for p in (d.centre, d.circle) if p is not None])
        assert _among(got, dyad(d), tol * reach ** 2)


def test_relabelling_the_poses_never_matters(four_bar):
    """The same dyads whatever the order of the poses: with the first kept, the same
    points; with another first, the same centre points, the circle points moved to
    where that pose puts them."""
    rng = np.random.default_rng(7)
    tasks = [four_bar[0]] + [[tuple(map(float, (x, y, a))) for x, y, a in zip(
        rng.uniform(-50, 50, 5), rng.uniform(-50, 50, 5), rng.uniform(-1.5, 1.5, 5))]
        for _ in range(3)]
    for poses in tasks:
        tol = 1e-8 * task_size(poses)
        found = burmester_points(poses)
        for order in ((0, 3, 1, 4, 2), (0, 4, 3, 2, 1)):
            again = burmester_points([poses[i] for i in order])
            assert len(again) == len(found) and all(_among(again, d, tol) for d in found)
        again = burmester_points([poses[i] for i in (2, 0, 1, 3, 4)])
        assert len(again) == len(found)
        turn = displacement(poses, 0, 2)[0]
        for d in found:
            if d.kind == "RP":      # its guide is the guided link's: it turns with it
                g = (math.cos(turn) * d.guide[0] - math.sin(turn) * d.guide[1],
                     math.sin(turn) * d.guide[0] + math.cos(turn) * d.guide[1])
                d = replace(d, guide=g)
            if d.circle is not None:
                d = replace(d, circle=moved(poses, d.circle, 2))
            assert _among(again, d, tol)


# -- bad tasks ------------------------------------------------------------------------------------
def test_two_equal_poses_are_named(four_bar):
    poses = list(four_bar[0])
    poses[3] = (poses[1][0], poses[1][1], poses[1][2] - 2 * math.pi)
    for call, named in ((lambda: burmester_points(poses), "poses 2 and 4"),
                        (lambda: centre_point_curve(poses[:4]), "poses 2 and 4"),
                        (lambda: centre_point(poses[:2] + [poses[3]], (0.0, 0.0)),
                         "poses 2 and 3")):
        with pytest.raises(DesignError, match=named + " are the same pose") as e:
            call()
        assert e.value.parameter == "poses"


@pytest.mark.parametrize("call, count, needs", [
    (lambda p: centre_point(p, (1.0, 2.0)), 1, "needs 2 or 3 poses, got 1"),
    (lambda p: circle_point(p, (1.0, 2.0)), 4, "needs 2 or 3 poses, got 4"),
    (centre_point_curve, 3, "needs 4 poses, got 3"),
    (circle_point_curve, 5, "needs 4 poses, got 5"),
    (burmester_points, 4, "needs 5 poses, got 4")])
def test_the_wrong_number_of_poses_is_refused(four_bar, call, count, needs):
    with pytest.raises(DesignError, match=needs):
        call(four_bar[0][:count])


def test_a_non_finite_pose_is_named(four_bar):
    poses = list(four_bar[0])
    poses[2] = (poses[2][0], math.nan, poses[2][2])
    with pytest.raises(DesignError, match="pose 3 must be three finite numbers"):
        burmester_points(poses)


def test_a_circle_point_at_a_pole_has_no_one_centre(four_bar):
    poses = four_bar[0][:3]
    with pytest.raises(DesignError, match="pole of poses 1 and 3"):
        centre_point(poses, pole(poses, 0, 2).at)
    with pytest.raises(DesignError, match="pole of poses 2 and 3"):
        circle_point(poses, pole(poses, 1, 2).at)


def test_translations_alone_make_no_burmester_curve():
    poses = [(0, 0, 0.2), (1, 0, 0.2), (1, 1, 0.2), (0, 3, 0.2)]
    with pytest.raises(DesignError, match="only translates"):
        centre_point_curve(poses)


# -- mechanisms --------------------------------------------------------------------------------------
def _passes(poses, chain, lead_dyad):
    """The worst position (over the size) and angle (degrees) errors of ``chain`` solved
    from its drawn pose to each pose's input value."""
    values = dyad_inputs(poses, lead_dyad)
    worst = [0.0, 0.0]
    for j in range(1, len(poses)):
        if chain.mechanism.driver is None:
            m = chaingraph.solve(chain, inputs=[(chain.mechanism.inputs[0].joint, values[0],
                                                 values[j])], steps=40)
        else:
            m = chaingraph.solve(chain, start=values[0], stop=values[j], steps=40)
        turn = math.radians(m["angle:coupler"][-1] - m["angle:coupler"][0])
        worst[0] = max(worst[0], math.dist((m["x:P"][-1], m["y:P"][-1]), poses[j][:2]))
        worst[1] = max(worst[1], abs(math.degrees(
            math.remainder(poses[0][2] + turn - poses[j][2], 2 * math.pi))))
    return worst[0] / task_size(poses), worst[1]


@pytest.mark.parametrize("task", ["four_bar", "slider_crank", "oscillating"])
@pytest.mark.parametrize("driver", [0, 1])
def test_the_original_dyads_make_a_mechanism_that_passes_the_poses(task, driver, request):
    poses, first, second = request.getfixturevalue(task)
    chain = mechanism(poses, first, second, driver=driver)
    assert chain.points[0].at == poses[0][:2] and chain.mechanism.output == "coupler"
    values = dyad_inputs(poses, (first, second)[driver])
    position, angle = _passes(poses, chain, (first, second)[driver])
    if task == "oscillating" and driver == 1:
        # the cylinder turns back between poses 1 and 3 (at its limit, 342.54 degrees):
        # driven by it, the mechanism reaches them on the other branch, not the poses
        assert values[1] < values[0] < values[2]
        assert position > 1e-3
    else:
        assert len(set(np.sign(np.diff(values)))) == 1     # the input moves one way
        assert position < 1e-9 and angle < 1e-9
    again = chaingraph.loads(chaingraph.dumps(chain))    # the chain file says the same
    assert again.joints == chain.joints and again.mechanism == chain.mechanism


def test_a_crank_s_inputs_are_its_angles(four_bar):
    poses, crank, _ = four_bar
    assert dyad_inputs(poses, crank) == pytest.approx(INPUTS, abs=1e-9)


def test_candidates_pair_every_two_dyads_both_ways(four_bar, slider_crank):
    poses, crank, rocker = four_bar
    found = burmester_points(poses)
    chains = candidates(poses, found)
    assert len(chains) == len(found) * (len(found) - 1)
    assert {c.name for c in chains} == {"Four-bar through 5 poses"}
    tol = 1e-9 * task_size(poses)

    def drawn(chain, ids, d):
        return all(math.dist(chain.joint(i).at, p) < tol for i, p in zip(ids, (d.centre, d.circle)))
    assert sum(drawn(c, "AB", crank) and drawn(c, "DC", rocker) for c in chains) == 1
    assert sum(drawn(c, "AB", rocker) and drawn(c, "DC", crank) for c in chains) == 1
    poses, crank, slider = slider_crank
    kinds = {c.name for c in candidates(poses, burmester_points(poses))}
    assert kinds == {"Four-bar through 5 poses", "Slider crank through 5 poses"}


def test_dyads_that_share_a_pivot_make_no_mechanism(four_bar):
    poses, crank, rocker = four_bar
    shared = Dyad("RR", rocker.centre, crank.circle)
    with pytest.raises(DesignError, match="circle point"):
        mechanism(poses, crank, shared)
    assert candidates(poses, [crank, shared, crank]) == ()
