"""Issue 11: any R or P joint as an input, between any two links, one per degree of
freedom. Every reference is derived here in closed form (cosine law, circle
intersection, the ellipse of the trammels), independently of the solver."""

from __future__ import annotations

import itertools
import math
import random
from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph import AssemblyError, Chain, ChainFileError, Input, Joint, MechanismError
from chaingraph.naming.catalog import catalog_files, catalog_path

from ..conftest import run_cli

EXAMPLES = Path(__file__).parents[2] / "examples"


def joint_at(chain, name):
    return chain.joint(name).at


# -- the elliptical trammels driven by one slider ---------------------------------------
def test_trammels_driven_by_a_slider_trace_the_ellipse_and_the_midpoint_a_circle():
    chain = chaingraph.load(catalog_path("elliptical-trammels"))
    m = chaingraph.solve(chain, steps=200)          # the file's input: slider 1's slide
    assert m.inputs[0].joint == "G1" and list(m.columns)[:2] == ["input:G1", "theta"]
    a, b, p = joint_at(chain, "A"), joint_at(chain, "B"), chain.point("P").at
    ap, bp, ab = math.dist(a, p), math.dist(b, p), math.dist(a, b)
    # the guides cross at the centre (0, 0): x along G1, y along G3
    x, y = m["x:P"], m["y:P"]
    assert np.allclose((x / bp) ** 2 + (y / ap) ** 2, 1.0, atol=1e-9 * ab)
    mx, my = (m["x:A"] + m["x:B"]) / 2, (m["y:A"] + m["y:B"]) / 2
    assert np.allclose(np.hypot(mx, my), ab / 2, atol=1e-9 * ab)
    # the slide goes limit to limit: slider 1 from -AB to +AB about the centre
    s = m["input:G1"]
    assert s[0] == pytest.approx(-ab - a[0], abs=1e-6) and s[-1] == pytest.approx(ab - a[0], abs=1e-6)
    assert np.allclose(m["x:A"], a[0] + s, atol=1e-9 * ab)
    assert m.summary["stroke"] == pytest.approx(2 * bp, rel=1e-9)
    assert m.summary["dead_centres"] == pytest.approx(m.summary["input_range"], abs=1e-6)


# -- the reciprocating engine driven by its crosshead ------------------------------------
def test_engine_driven_by_its_crosshead_follows_the_cosine_law_with_dead_centres_at_both_ends():
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    o, a, b = joint_at(chain, "O"), joint_at(chain, "A"), joint_at(chain, "B")
    r, rod = math.dist(o, a), math.dist(a, b)
    m = chaingraph.solve(chain, inputs=["S"], steps=240)
    xb = b[0] + m["input:S"]
    assert np.allclose(m["x:B"], xb, atol=1e-9 * rod)
    crank = np.arctan2(m["y:A"] - o[1], m["x:A"] - o[0])     # the line O -> A
    # cosine law in triangle O A B: rod^2 = r^2 + xb^2 - 2 r xb cos(crank)
    assert np.allclose(np.cos(crank), (r * r + xb * xb - rod * rod) / (2 * r * xb), atol=1e-9)
    assert np.all(np.sin(crank) >= -1e-9)            # the drawn pose's side, kept
    s = m.summary
    assert s["stroke"] == pytest.approx(2 * r, rel=1e-12)
    lo, hi = s["input_range"]
    assert lo == pytest.approx(rod - r - b[0], abs=1e-6) and hi == pytest.approx(rod + r - b[0], abs=1e-6)
    assert s["dead_centres"] == pytest.approx([lo, hi], abs=1e-6)
    assert s["time_ratio"] is None and not s["full_turn"]
    # the crank turns half a turn between the dead centres
    assert abs(m["angle:crank"][-1] - m["angle:crank"][0]) == pytest.approx(180.0, abs=1e-5)
    assert np.all(np.isnan(m["omega:crank"][[0, -1]]))   # the flywheel carries it through


def test_the_crank_pivot_as_input_is_the_driver():
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    by_driver = chaingraph.solve(chain, steps=36)
    by_input = chaingraph.solve(chain, inputs=["O"], steps=36)
    assert np.allclose(by_input["theta"], by_driver["theta"], atol=1e-12)
    assert np.allclose(by_input["input:O"], by_driver["theta"], atol=1e-12)
    for key in by_driver.columns:
        assert np.allclose(by_input[key], by_driver[key], atol=1e-9, equal_nan=True), key
    assert by_input.summary["time_ratio"] == pytest.approx(by_driver.summary["time_ratio"], rel=1e-9)
    assert list(by_driver.columns)[0] == "theta" and "inputs" not in by_driver.to_dict()


# -- an input between two moving links ----------------------------------------------------
def test_oscillating_cylinder_engine_driven_by_the_slide_of_its_piston_rod():
    chain = chaingraph.load(catalog_path("oscillating-cylinder-engine"))
    o, a, t = joint_at(chain, "O"), joint_at(chain, "A"), joint_at(chain, "T")
    r, d = math.dist(o, a), math.dist(o, t)
    m = chaingraph.solve(chain, inputs=["S"], steps=120)
    axis = math.radians(chain.joint("S").axis)
    # the P joint's first link (the piston rod, carrying A) is the guide: the slide is
    # the cylinder's (carrying T) along the rod's axis, so |TA| grows by s when the
    # axis points from A towards T
    a_to_t = (t[0] - a[0]) * math.cos(axis) + (t[1] - a[1]) * math.sin(axis)
    ta = math.dist(t, a) + math.copysign(1.0, a_to_t) * m["input:S"]
    crank = np.arctan2(m["y:A"] - o[1], m["x:A"] - o[0])
    assert np.allclose(ta ** 2, r * r + d * d - 2 * r * d * np.cos(crank), atol=1e-9 * d * d)
    assert m.summary["stroke"] is not None
    assert m.summary["input_range"][1] - m.summary["input_range"][0] == pytest.approx(2 * r, rel=1e-9)


def test_boom_raised_by_a_hydraulic_cylinder_follows_the_cosine_law():
    chain = chaingraph.load(EXAMPLES / "hydraulic-boom.toml")
    o, c, r_ = joint_at(chain, "O"), joint_at(chain, "C"), joint_at(chain, "R")
    oc, orr, cr0 = math.dist(o, c), math.dist(o, r_), math.dist(c, r_)
    m = chaingraph.solve(chain, steps=90)        # the file's sweep: -30 to 60 mm
    s = m["input:cylinder"]
    assert s[0] == -30.0 and s[-1] == 60.0
    # the cylinder's axis points from C to R: its length is cr0 + s
    cr = cr0 + s
    at_o = np.arccos((oc * oc + orr * orr - cr * cr) / (2 * oc * orr))
    direction_oc = math.atan2(c[1] - o[1], c[0] - o[0])
    drawn_side = math.atan2(r_[1] - o[1], r_[0] - o[0]) - direction_oc
    boom = direction_oc + math.copysign(1.0, math.remainder(drawn_side, 2 * math.pi)) * at_o
    got = np.arctan2(m["y:R"] - o[1], m["x:R"] - o[0])
    assert np.allclose(np.remainder(got - boom + np.pi, 2 * np.pi) - np.pi, 0.0, atol=1e-9)
    v = m["omega:boom"]
    assert np.all(np.isfinite(v)) and np.all(v > 0)      # extending the cylinder raises it


# -- two inputs ---------------------------------------------------------------------------------
def test_five_bar_with_two_cranks_puts_the_pen_on_the_circles_intersection():
    chain = chaingraph.load(EXAMPLES / "five-bar-robot.toml")
    m = chaingraph.solve(chain, steps=60)
    a_in, e_in = m["input:A"], m["input:E"]
    assert a_in[0] == 70.0 and a_in[-1] == 130.0 and e_in[0] == 110.0 and e_in[-1] == 50.0
    assert np.allclose(a_in + e_in, 180.0)                # linearly, together
    A, B, C, D, E = (joint_at(chain, k) for k in "ABCDE")
    crank_l, crank_r = math.dist(A, B), math.dist(E, D)
    arm_l, arm_r = math.dist(B, C), math.dist(D, C)
    bx = A[0] + crank_l * np.cos(np.radians(a_in))
    by = A[1] + crank_l * np.sin(np.radians(a_in))
    dx = E[0] + crank_r * np.cos(np.radians(e_in))
    dy = E[1] + crank_r * np.sin(np.radians(e_in))
    gap = np.hypot(dx - bx, dy - by)
    along = (arm_l ** 2 - arm_r ** 2 + gap ** 2) / (2 * gap)
    h = np.sqrt(arm_l ** 2 - along ** 2)
    ux, uy = (dx - bx) / gap, (dy - by) / gap
    cx, cy = bx + along * ux - h * uy, by + along * uy + h * ux    # the upper one, as drawn
    assert np.allclose(m["x:C"], cx, atol=1e-9 * 100) and np.allclose(m["y:C"], cy, atol=1e-9 * 100)
    assert np.allclose(m["x:pen"], cx, atol=1e-9 * 100)
    s = m.summary
    assert s["time_ratio"] is None and s["stroke"] > 0 and s["dead_centres"] == []


def test_a_sweep_of_two_inputs_that_misses_the_drawn_pose_is_reached_from_it():
    chain = chaingraph.load(EXAMPLES / "five-bar-robot.toml")
    m = chaingraph.solve(chain, inputs=[("A", 80.0, 100.0), ("E", 60.0, 70.0)], steps=10)
    assert m["input:A"][0] == 80.0 and m["input:E"][-1] == 70.0
    # the left crank's pin is where the input says
    assert np.allclose(m["x:B"], 60.0 * np.cos(np.radians(m["input:A"])), atol=1e-9)
    # and the same poses whatever the number of steps
    fine = chaingraph.solve(chain, inputs=[("A", 80.0, 100.0), ("E", 60.0, 70.0)], steps=40)
    assert np.allclose(fine["x:C"][::4], m["x:C"], atol=1e-9)


def test_an_input_held_at_its_drawn_value_while_the_other_turns():
    chain = chaingraph.load(EXAMPLES / "five-bar-robot.toml")
    m = chaingraph.solve(chain, inputs=["A", "E"], start=80.0, stop=100.0, steps=8)
    assert np.allclose(m["input:E"], 90.0) and m["input:A"][0] == 80.0
    assert np.allclose(m["angle:right crank"], -90.0, atol=1e-9)   # the line D -> E


def test_inputs_from_the_command_line(tmp_path):
    code, out, err = run_cli("solve", str(EXAMPLES / "five-bar-robot.toml"), "--json")
    assert code == 0, err
    import json
    data = json.loads(out)
    assert [i["joint"] for i in data["inputs"]] == ["A", "E"] and data["driver"] is None
    csv_path = tmp_path / "engine.csv"
    code, out, err = run_cli("solve", str(catalog_path("reciprocating-engine")), "--input", "S",
                             "--from", "-40", "--to", "0", "--steps", "4", "--csv", str(csv_path))
    assert code == 0, err
    header = csv_path.read_text().splitlines()[0].split(",")
    assert header[:2] == ["input:S", "theta"] and "s:S" in header
    assert "inputs" in out and "S (P)" in out


# -- bad input -----------------------------------------------------------------------------
@pytest.mark.parametrize("args, message, status", [
    (["--input", "nowhere"], "the input 'nowhere' is not a joint of the chain", 2),
    (["--input", "S", "--input", "O"], "mobility with 'frame' fixed is 1 .* needs 1 input", 2),
    (["--input", "S", "--from", "0", "--to", "500"], "can slide only from", 1),
    (["--input", "S", "--driver", "crank"], "not allowed with argument", 2),
])
def test_bad_inputs_get_one_clear_line(args, message, status):
    import re
    code, out, err = run_cli("solve", str(catalog_path("reciprocating-engine")), *args)
    assert code == status and re.search(message, err), err
    assert "Traceback" not in err


def test_an_input_that_is_not_r_or_p_is_refused():
    cam = chaingraph.load(catalog_path("cam-and-follower"))
    higher = next(j for j in cam.joints if j.kind not in ("R", "P"))
    with pytest.raises(MechanismError, match="R or P"):
        chaingraph.solve(cam, fixed="frame", inputs=[higher.id])


def test_two_inputs_that_drive_the_same_freedom_are_refused():
    """Two four-bars on one frame (2 dof): both inputs on the first leave the second free."""
    def R(i, links, at):
        return Joint(i, "R", tuple(links), at=at)
    chain = Chain("two four-bars", (
        R("A", ["frame", "a1"], (0.0, 0.0)), R("B", ["a1", "b1"], (10.0, 30.0)),
        R("C", ["b1", "c1"], (60.0, 40.0)), R("D", ["c1", "frame"], (70.0, 0.0)),
        R("E", ["frame", "a2"], (0.0, -100.0)), R("F", ["a2", "b2"], (10.0, -70.0)),
        R("G", ["b2", "c2"], (60.0, -60.0)), R("H", ["c2", "frame"], (70.0, -100.0))))
    with pytest.raises(MechanismError, match="do not determine the motion"):
        chaingraph.solve(chain, fixed="frame", inputs=["A", "D"], start=80, stop=90)
    m = chaingraph.solve(chain, fixed="frame", inputs=["A", "E"], steps=4,
                         start=71.0, stop=73.0, summary=False)
    assert np.allclose(m["input:E"], m["input:E"][0])


@pytest.mark.parametrize("text, message", [
    ('inputs = ["Q"]', "'inputs' names no joint of the chain: 'Q'"),
    ('inputs = "A"', "'inputs' must be a non-empty array"),
    ('inputs = [{joint = "A", from = "x", to = 2.0}]', "inputs #1 key 'from': must be a number"),
    ('inputs = [{joint = "A", from = 1.0}]', "give both 'from' and 'to'"),
    ('inputs = [{joint = "A", to = 1.0, by = 3}]', "unknown key"),
    ('inputs = ["A", "A"]', "named twice"),
])
def test_bad_inputs_in_the_file_are_file_errors(text, message):
    base = (EXAMPLES / "five-bar-robot.toml").read_text()
    start = base.index("inputs =")
    doc = base[:start] + text + base[base.index("\n", start):]
    with pytest.raises(ChainFileError) as info:
        chaingraph.loads(doc)
    assert message in str(info.value)


def test_inputs_round_trip_through_the_file_format():
    chain = chaingraph.load(EXAMPLES / "five-bar-robot.toml")
    again = chaingraph.loads(chaingraph.dumps(chain))
    assert again.mechanism.inputs == chain.mechanism.inputs
    renamed = chain.relabelled(joints={"A": "motor 1"})
    assert renamed.mechanism.inputs[0].joint == "motor 1"


# -- property: every admissible choice of inputs solves, closes, and differentiates --------
def _random_pose_chain(edges, links, seed):
    """An atlas chain (link adjacency, one R joint per edge) drawn at random: with R
    joints only, any placement of the joints is a valid pose."""
    rng = random.Random(seed)
    joints = tuple(Joint(f"J{i}", "R", (f"L{a}", f"L{b}"),
                         at=(rng.uniform(-100, 100), rng.uniform(-100, 100)))
                   for i, (a, b) in enumerate(edges))
    return Chain(f"atlas {links} seed {seed}", joints)


def _check_motion(m, plan_size):
    """Checks a short sweep's rates against finite differences; returns how many of
    its points' accelerations were checked, and of how many."""
    chain = m.plan.chain
    checked = total = 0
    # poses close: every joint's point is the same on each of its links (the solver's
    # own check raises otherwise); velocities and accelerations against finite
    # differences of the positions in the lead input's native units
    lead = m.plan.inputs[m.plan.lead]
    u = np.radians(m["theta"]) if lead.kind == "R" else m["theta"]
    h = u[1] - u[0]
    for j in chain.joints:
        for axis in ("x", "y"):
            pos, vel, acc = m[f"{axis}:{j.id}"], m[f"v{axis}:{j.id}"], m[f"a{axis}:{j.id}"]
            # five-point stencils (error h**4), trusted where the three-point ones agree
            # with them: a random pose may lie just by a dead centre, where the rates
            # grow without bound and no finite difference has converged
            x2, x1, x0, y1, y2 = pos[4:], pos[3:-1], pos[2:-2], pos[1:-3], pos[:-4]
            fd_v = (-x2 + 8 * x1 - 8 * y1 + y2) / (12 * h) * m.omega
            fd_a = (-x2 + 16 * x1 - 30 * x0 + 16 * y1 - y2) / (12 * h * h) * m.omega ** 2
            fd_v3 = (x1 - y1) / (2 * h) * m.omega
            fd_a3 = (x1 - 2 * x0 + y1) / (h * h) * m.omega ** 2
            v, a = vel[2:-2], acc[2:-2]
            scale_v = max(plan_size * abs(m.omega) * (1 if lead.kind == "R" else 1 / plan_size), 1.0)
            calm_v = np.abs(fd_v - fd_v3) <= 1e-6 * (scale_v + np.abs(fd_v))
            calm_a = np.abs(fd_a - fd_a3) <= 1e-4 * (scale_v + np.abs(fd_a))
            ok_v = np.isfinite(v) & calm_v
            ok_a = np.isfinite(a) & calm_a
            checked += int(ok_a.sum())
            total += v.size
            assert np.allclose(v[ok_v], fd_v[ok_v], atol=1e-6 * scale_v, rtol=1e-5), \
                (chain.name, j.id)
            assert np.allclose(a[ok_a], fd_a[ok_a], atol=1e-3 * scale_v, rtol=1e-3), \
                (chain.name, j.id)
    return checked, total


def _admissible(chain, fixed, dof):
    on_fixed = sorted(j.id for j in chain.joints if fixed in j.links)
    return list(itertools.combinations(on_fixed, dof))


@pytest.mark.slow
def test_every_admissible_choice_of_inputs_of_the_atlas_to_8_links_solves():
    from chaingraph.structure.atlas import atlas_graphs
    solved, refused, checked, total = 0, [], 0, 0
    for links, dof in ((4, 1), (6, 1), (8, 1), (5, 2), (7, 2)):
        for entry in atlas_graphs(links, dof):
            chain = _random_pose_chain(entry.edges, links, seed=entry.id)
            for fixed in chain.links:
                choices = _admissible(chain, fixed, dof)
                # and some between moving links: the first joint not on the fixed link
                free = [j.id for j in chain.joints if fixed not in j.links]
                if free:
                    choices.append(tuple(free[:1]) + tuple(choices[0][1:]) if choices else ())
                for inputs in choices:
                    if not inputs:
                        continue
                    try:
                        plan = chaingraph.build_plan(chain, fixed, inputs=[Input(k) for k in inputs])
                    except MechanismError as e:
                        assert "do not determine the motion" in str(e), (chain.name, fixed, inputs, e)
                        refused.append((chain.name, fixed, inputs, str(e)))
                        continue
                    value = float(plan.value(plan.theta0))
                    span = 0.1 if plan.inputs[plan.lead].kind == "R" else 0.002 * plan.size
                    m = None
                    for way in (1.0, -1.0):      # a random pose may lie by a limit
                        try:
                            m = chaingraph.solve(
                                chain, fixed=fixed, steps=64, summary=False,
                                inputs=[Input(inputs[0], value, value + way * span)]
                                + [Input(k) for k in inputs[1:]])
                            break
                        except AssemblyError as e:
                            problem = str(e)
                    if m is None:
                        refused.append((chain.name, fixed, inputs, problem))
                        continue
                    done, of = _check_motion(m, plan.size)
                    checked, total = checked + done, total + of
                    solved += 1
    assert solved >= 300, (solved, refused[:5])
    assert checked >= 0.9 * total, (checked, total)
    assert len(refused) <= 0.05 * (solved + len(refused)), refused


def test_every_inversion_of_the_catalog_with_every_input_on_the_fixed_link():
    """Every catalog chain with a drawn pose, every fixed link, every R or P joint on it
    as the one input (where the mobility is 1), and every joint between two moving links
    too: solves over a short sweep, closes, and its rates agree with finite
    differences; a refusal says why."""
    solved = between = 0
    for path in catalog_files():
        chain = chaingraph.load(path)
        if not chain.has_pose or any(j.kind not in ("R", "P") for j in chain.joints) \
                or len(chain.links) > 8:          # the 16-link rotary engine: test_machines
            continue
        for fixed in chain.links:
            for j in chain.joints:
                try:
                    plan = chaingraph.build_plan(chain, fixed, inputs=[Input(j.id)])
                except MechanismError as e:
                    assert "mobility" in str(e) or "do not determine" in str(e), (path, fixed, j.id, e)
                    continue
                value = float(plan.value(plan.theta0))
                span = 0.1 if j.kind == "R" else 0.002 * plan.size
                try:
                    m = chaingraph.solve(chain, fixed=fixed, inputs=[Input(j.id, value, value + span)],
                                         steps=64, summary=False)
                except AssemblyError as e:
                    # the drawn pose at a limit of this input's range
                    assert "only from" in str(e), (path, fixed, j.id, e)
                    continue
                _check_motion(m, plan.size)
                solved += 1
                between += fixed not in j.links
    assert solved >= 100 and between >= 50, (solved, between)


# -- a P input's value: one reference ------------------------------------------------------
SLIDER_BY_LENGTHS = Path(__file__).parents[1] / "data" / "slider-by-lengths-piston-input.toml"


def test_a_piston_input_given_by_lengths_is_measured_from_the_guides_origin_throughout():
    """``inputs = [{joint = "S", at = 180}]`` places the block 180 mm from the guide's
    origin; the range, the sweep, the ``input:S`` column and --from/--to measure from
    there too (they measured from the drawn pose: 0 there, -80 to 20): crank 50, rod 150
    gives 100 to 200 mm, the block's own x."""
    chain = chaingraph.load(SLIDER_BY_LENGTHS)
    motion = chaingraph.solve(chain, steps=4)
    assert motion.summary["input_range"] == pytest.approx([100.0, 200.0], abs=1e-9)
    assert motion["input:S"] == pytest.approx(motion["x:B"], abs=1e-9)
    again = chaingraph.solve(chain, inputs=["S"], start=150.0, stop=160.0, steps=1)
    assert again["x:B"] == pytest.approx([150.0, 160.0], abs=1e-9)
    # written out with coordinates, the file keeps the reference
    text = chaingraph.dumps(chain)
    assert '{joint = "S", at = 180.0}' in text
    assert chaingraph.solve(chaingraph.loads(text), steps=4)["input:S"] == \
        pytest.approx(motion["input:S"], abs=1e-9)


def test_at_on_an_r_input_of_a_file_of_coordinates_is_refused():
    text = chaingraph.dumps(chaingraph.load(SLIDER_BY_LENGTHS))
    text = text.replace('inputs = [{joint = "S", at = 180.0}]',
                        'inputs = [{joint = "O", at = 30.0}]')
    with pytest.raises(chaingraph.ChainFileError, match="only for a P input"):
        chaingraph.loads(text)


UNBOUNDED = Path(__file__).parent.parent / "data" / "rprp-unbounded-slide.toml"


def test_a_slide_without_limits_is_solved_over_the_sweep_given_and_its_range_is_unbounded():
    chain = chaingraph.load(UNBOUNDED)
    with pytest.raises(chaingraph.UnboundedRangeError, match="give its sweep's ends"):
        chaingraph.solve(chain)
    motion = chaingraph.solve(chain, inputs=[("J1", -150.0, 150.0)], steps=30)
    assert motion.summary.input_range == (None, None)
    assert motion.summary.to_dict()["input_range"] == [None, None]
    # the arm's line passes through its pivot (0, 40) and the block's pin (50 + s, 0)
    s = motion["input:J1"]
    expected = np.degrees(np.arctan2(-40.0, 50.0 + s)) % 180.0
    assert np.allclose(motion["angle:arm"] % 180.0, expected, atol=1e-9)


def test_a_slide_without_limits_on_the_command_line(tmp_path):
    status, out, err = run_cli("solve", UNBOUNDED)
    assert status == 1 and "without returning to the drawn pose or reaching a limit" in err
    status, out, err = run_cli("solve", UNBOUNDED, "--from", "-150", "--to", "150",
                                "--steps", "6")
    assert status == 0 and "without limits" in out


# -- issue 36: one front door for the inputs, for a sweep and one pose alike -----------------
@pytest.mark.parametrize("kwargs, message", [
    (dict(inputs=[("S", float("nan"), 1.0)]), "not a finite number"),
    (dict(inputs=[3]), "an input must be a joint id"),
    (dict(inputs=[]), "no inputs given"),
    (dict(omega=float("inf")), "the input speed omega must be a finite number"),
    (dict(omega=2e9), "the input speed omega 2e[+]09 is too large"),
    (dict(inputs=["nowhere"]), "the input 'nowhere' is not a joint of the chain"),
    (dict(fixed="nowhere"), "nowhere"),
])
def test_a_sweep_and_a_pose_refuse_the_same_inputs_alike(kwargs, message):
    from chaingraph.kinematics.inputs import pose_drive, sweep_drive
    engine = chaingraph.load(catalog_path("reciprocating-engine"))
    for call in (sweep_drive, pose_drive, chaingraph.solve, chaingraph.instant_centres):
        with pytest.raises(MechanismError, match=message):
            call(engine, **kwargs)


def test_the_front_door_gives_the_plan_the_sweep_s_ends_and_the_pose_s_value():
    from chaingraph.kinematics.inputs import pose_drive, sweep_drive
    engine = chaingraph.load(catalog_path("reciprocating-engine"))
    drive = sweep_drive(engine, inputs=[("S", -30.0, 10.0)], stop=20.0)
    # the first input's stop given here takes the place of its own
    assert (drive.start, drive.stop) == (-30.0, 20.0) and drive.plan.inputs[0].joint == "S"
    assert drive.omega == engine.mechanism.omega
    by_driver = sweep_drive(engine, omega=4)
    assert by_driver.plan.driver == "crank" and by_driver.omega == 4
    assert (by_driver.start, by_driver.stop) == (None, None)        # its cycle decides
    pose = pose_drive(engine, inputs=["S"], at=-20.0)
    assert float(pose.plan.value(pose.tau)) == pytest.approx(-20.0, abs=1e-12)
    drawn = pose_drive(engine)             # the drawn pose: the crank's direction O -> A
    (ax, ay), (ox, oy) = engine.joint("A").at, engine.joint("O").at
    assert drawn.plan.driver == "crank"
    assert drawn.tau == pytest.approx(math.degrees(math.atan2(ay - oy, ax - ox)), abs=1e-9)
    with pytest.raises(MechanismError, match="2 input values given for 1 inputs"):
        pose_drive(engine, inputs=["S"], at=[1.0, 2.0])
