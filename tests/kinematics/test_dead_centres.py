"""Dead centres exact to the rounding: a limit of the input's range is a fold of the
constraint equations, computed as one (a dyad's double root, a group's extended
system), so poses, strokes, extremes and time ratios there carry the rounding, not its
square root; symmetric mechanisms give exactly symmetric answers."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import chaingraph
from chaingraph.naming.catalog import catalog_path
from chaingraph.kinematics.equations import residuals
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.sweep import cycle

from ..conftest import CATALOG, run_cli, solver_takes

EXAMPLES = sorted((Path(__file__).parents[2] / "examples").glob("*.toml"))


def _mechanisms():
    for path in list(CATALOG) + EXAMPLES:
        chain = chaingraph.load(path)
        if chain.mechanism is not None and chain.has_pose and solver_takes(chain):
            yield path


def _rocking():
    out = []
    for path in _mechanisms():
        plan = chaingraph.solve(chaingraph.load(path), steps=4).plan
        if not cycle(plan).full_turn:
            out.append(path)
    return out


ROCKING = _rocking()


def test_the_catalog_has_mechanisms_that_end_at_dead_centres():
    names = {p.stem for p in ROCKING}
    assert {"non-grashof-four-bar", "pendulum-pump", "watts-indicator-mechanism",
            "hydraulic-boom", "elliptical-trammels"} <= names


@pytest.mark.parametrize("path", ROCKING, ids=lambda p: p.stem)
def test_a_limit_is_a_fold_to_the_rounding(path):
    """At both ends of the range the loops close to 1e-12 of the size and the driven
    mechanism is singular to the rounding (the normalized determinant of the step
    that folds is zero); bisection alone left it near the square root of its
    tolerance (1e-6)."""
    plan = chaingraph.solve(chaingraph.load(path), steps=4).plan
    for end in cycle(plan).limit_poses:
        assert float(np.max(residuals(plan, end.pose))) <= 1e-12 * plan.size
        _, _, measure = rates(plan, end.pose, 1.0, 1)
        assert float(np.min(np.abs(measure))) <= 1e-12


def _piston_driven_cylinder():
    text = catalog_path("oscillating-cylinder-engine").read_text()
    text = text.replace('driver = "crank"', 'inputs = ["S"]')
    return chaingraph.loads(text.replace('output = "piston"', 'output = "crank"'))


def test_an_oscillating_cylinder_driven_by_its_piston_ends_with_crank_and_cylinder_in_line():
    """Crank 30 mm, pivots 100 apart: the piston's range ends where crank and cylinder
    are in line, at crank angles 0 and 180 exactly (the crank pin on the line of
    centres; it was 3e-4 mm off), so the crank's stroke is 180 degrees."""
    motion = chaingraph.solve(_piston_driven_cylinder())
    s = motion.summary
    assert s["stroke"] == pytest.approx(180.0, abs=1e-12 * 180)
    size = motion.plan.size
    for k in (0, -1):
        assert abs(motion["y:A"][k]) <= 1e-12 * size
        assert abs(math.remainder(motion["angle:crank"][k], 180.0)) <= 1e-12 * 180
    # the slide's range is the difference of the distances T to A at the two ends
    low, high = s["input_range"]
    assert high - low == pytest.approx((100 + 30) - (100 - 30), abs=1e-12 * size)


@pytest.mark.parametrize("name, extremes", [
    ("oscillating-cylinder-engine", (0.0, 180.0)),
    ("reciprocating-engine", (0.0, 180.0)),
    ("scotch-yoke", (0.0, 180.0)),
])
def test_mechanisms_symmetric_by_construction_give_time_ratio_one(name, extremes):
    """A mechanism symmetric about the line of centres has equal forward and return
    strokes: the time ratio is 1 and the extremes at 0 and 180 to 1e-12 (the oscillating
    cylinder gave 1.00006 with extremes at 180.011 and 0.0059)."""
    s = chaingraph.solve(chaingraph.load(catalog_path(name))).summary
    assert s["time_ratio"] == pytest.approx(1.0, abs=1e-12)
    assert sorted(s["extremes"]) == pytest.approx(extremes, abs=1e-9)
    assert s["forward_deg"] == pytest.approx(180.0, abs=1e-9)


def _four_bar(o2, a, b, o4):
    joints = (chaingraph.Joint("O2", "R", ("frame", "crank"), at=o2),
              chaingraph.Joint("A", "R", ("crank", "coupler"), at=a),
              chaingraph.Joint("B", "R", ("coupler", "rocker"), at=b),
              chaingraph.Joint("O4", "R", ("rocker", "frame"), at=o4))
    return chaingraph.Chain("four-bar drawn at a dead centre", joints, units="mm",
                            mechanism=chaingraph.Mechanism("frame", driver="crank"))


def _cross(p, q, r):
    """The sine of the angle at q between q->p and q->r (0: the three in line)."""
    u, v = np.subtract(p, q), np.subtract(r, q)
    return abs(u[0] * v[1] - u[1] * v[0]) / (np.linalg.norm(u) * np.linalg.norm(v))


@settings(max_examples=40, deadline=None)
@given(crank=st.floats(10, 60), coupler=st.floats(40, 120), rocker=st.floats(20, 100),
       heading=st.floats(-180, 180), at_crank=st.floats(-180, 180),
       folded=st.booleans(), off=st.sampled_from([0.0, 1e-13, 1e-9, 1e-6, 1e-3]))
@example(crank=20.0, coupler=80.03978258737749, rocker=24.53978258737749,
         heading=90.0, at_crank=60.0, folded=True, off=0.0)
def test_a_four_bar_drawn_at_or_near_its_dead_centre(crank, coupler, rocker, heading,
                                                     at_crank, folded, off):
    """Coupler and rocker drawn in line (``folded``: the rocker turned back along the
    coupler), or a hair off it (``off`` of the size, across the line): the drawn value
    gives the drawing itself, and each limit of the crank's range has coupler and rocker
    in line to 1e-12 with the loops closed to 1e-12 of the size."""
    if folded and abs(coupler - rocker) < 5:
        return
    u = (math.cos(math.radians(heading)), math.sin(math.radians(heading)))
    a = (crank * math.cos(math.radians(at_crank)), crank * math.sin(math.radians(at_crank)))
    b = (a[0] + coupler * u[0], a[1] + coupler * u[1])
    sign = -1.0 if folded else 1.0
    o4 = (b[0] + sign * rocker * u[0], b[1] + sign * rocker * u[1])
    if math.dist(o4, (0.0, 0.0)) < 5 or math.dist(o4, a) < 5:
        return
    size = max(crank, coupler, rocker, math.dist(o4, (0.0, 0.0)))
    b = (b[0] - off * size * u[1], b[1] + off * size * u[0])
    chain = _four_bar((0.0, 0.0), a, b, o4)
    try:
        motion = chaingraph.solve(chain)
    except chaingraph.AssemblyError:
        return                       # a drawing that is already past no fold (rare)
    plan = motion.plan
    theta = motion["theta"]
    drawn = plan.inputs[0].value0                 # the crank's drawn angle
    assert drawn == pytest.approx(math.degrees(math.atan2(a[1], a[0])), abs=1e-12 * 360)
    at = chaingraph.solve(chain, start=drawn, stop=drawn, steps=1)
    assert math.dist((at["x:B"][0], at["y:B"][0]), b) <= 1e-12 * size
    c = cycle(plan)
    if c.full_turn:                  # a hair off the line may leave a crank (Grashof)
        return
    for end in c.limit_poses:
        assert float(np.max(residuals(plan, end.pose))) <= 1e-12 * plan.size
    for k in (0, -1):
        pa, pb = (motion["x:A"][k], motion["y:A"][k]), (motion["x:B"][k], motion["y:B"][k])
        po4 = (motion["x:O4"][k], motion["y:O4"][k])
        # at a limit either the coupler and rocker (the driven dyad) are in line
        assert _cross(pa, pb, po4) <= 1e-12, theta[k]


def test_a_limit_where_a_dyad_degenerates_is_no_fold():
    """Six links on two ternary joints, c fixed and f driving: at 135 degrees a dyad's
    two known joints meet (its discriminant is undefined there, not zero): the range
    ends there with the loops closed, not with the dyad forced to a double root."""
    chain = chaingraph.load(catalog_path("six-link-two-ternary-joints"))
    for fixed, driver in (("c", "f"), ("f", "c")):
        motion = chaingraph.solve(chain, fixed=fixed, driver=driver, steps=12)
        plan = motion.plan
        for end in cycle(plan).limit_poses:
            assert float(np.max(residuals(plan, end.pose))) <= 1e-9 * plan.size


# -- issue 35, item 4: a crank far shorter than the mechanism, driven by its rocker ----
def _rocker_driven_tiny_crank_closed_form(a, b, c, f):
    """The rocker's limits (crank and coupler in line: the distance from the crank's
    pivot to the rocker's joint is b + a or b - a, by the law of cosines at the rocker's
    pivot, the frame along x from (0, 0) to (f, 0), the rocker above it), and the crank's
    direction there (towards the rocker's joint, then away from it), in degrees."""
    limits, crank = [], []
    for sign in (1.0, -1.0):
        psi = math.acos(((b + sign * a) ** 2 - f * f - c * c) / (2 * f * c))
        cx, cy = f + c * math.cos(psi), c * math.sin(psi)
        limits.append(math.degrees(psi))
        crank.append(math.degrees(math.atan2(cy, cx)) + (0.0 if sign > 0 else 180.0))
    return limits, crank


def _tiny_crank_file(tmp_path, crank):
    at = (crank / math.sqrt(2), crank / math.sqrt(2))
    joints = (chaingraph.Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
              chaingraph.Joint("B", "R", ("crank", "coupler"), at=at),
              chaingraph.Joint("C", "R", ("coupler", "rocker"), at=(60.0, 50.0)),
              chaingraph.Joint("D", "R", ("rocker", "frame"), at=(100.0, 0.0)))
    chain = chaingraph.Chain("tiny crank", joints, units="mm",
                             mechanism=chaingraph.Mechanism("frame", driver="rocker",
                                                            output="crank"))
    path = tmp_path / "tiny.toml"
    chaingraph.save(chain, path)
    return path, at


@pytest.mark.parametrize("crank", [None, 1.0, 1e-1, 1e-2, 1e-3, 1e-4])
def test_a_crank_far_shorter_than_the_frame_driven_by_its_rocker(tmp_path, crank):
    """The solver's reproducer (a crank of 0.003 mm in a 100 mm four-bar, driven by its
    rocker: refused at step 0 when a dyad's discriminant was cut relative to the
    mechanism's size squared) and the same four-bar with cranks of 1e-2 to 1e-6 of the
    frame: the input range is the rocker's limits in closed form to 1e-9 degrees, and
    the crank's extremes its directions there, to 1e-9 degrees or the rounding of its
    joints' places seen from its length (its stroke is 180 degrees plus the angle the
    rocker's joint turns through about the crank's pivot: 180.0000878 for 0.003 mm)."""
    if crank is None:
        path = Path(__file__).parents[1] / "data" / "solver" / \
            "solver-tiny-crank-rocker-driven.toml"
        at = chaingraph.load(path).joint("B").at
    else:
        path, at = _tiny_crank_file(tmp_path, crank)
    code, out, err = run_cli("solve", path, "--json")
    assert code == 0, err
    s = json.loads(out)["summary"]
    a = math.hypot(*at)
    b, c = math.dist(at, (60.0, 50.0)), math.dist((60.0, 50.0), (100.0, 0.0))
    limits, crank_at = _rocker_driven_tiny_crank_closed_form(a, b, c, 100.0)
    assert s["input_range"] == pytest.approx(sorted(limits), abs=1e-9)
    # the crank's direction is known only as well as its joints' places, which carry a
    # rounding of the size: a few of them, seen from the crank's length
    tol = max(1e-9, math.degrees(4 * np.finfo(float).eps * 100.0 / a))
    values = {round(e["input"], 6): e["value"] for e in s["extreme_positions"]}
    assert [values[round(t, 6)] for t in limits] == pytest.approx(crank_at, abs=tol)
    assert s["stroke"] == pytest.approx(abs(crank_at[1] - crank_at[0]), abs=2 * tol)
