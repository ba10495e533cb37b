"""Issue 10: no silent wrong answer. Each item of the fuzzing report is a test here,
plus property tests: a summary and every pose are unchanged (up to the
transformation) when the drawing is rotated, moved, scaled or its links renamed, and
the poses at an angle do not depend on how many steps are asked for."""

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import chaingraph
from chaingraph import AssemblyError, Chain, Joint, Mechanism
from chaingraph.naming.catalog import catalog_path
from chaingraph.kinematics.gears import is_gear_train

from ..conftest import run_cli
from .inversions import pinned_pairs

CASES = Path(__file__).parents[1] / "data" / "solver"


def transformed(chain, *, angle=0.0, shift=(0.0, 0.0), scale=1.0):
    """The same mechanism drawn rotated by ``angle`` degrees, scaled, then moved."""
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))

    def move(p):
        if p is None:
            return None
        return (scale * (c * p[0] - s * p[1]) + shift[0], scale * (s * p[0] + c * p[1]) + shift[1])
    joints = tuple(dataclasses.replace(j, at=move(j.at),
                                       axis=None if j.axis is None else j.axis + angle)
                   for j in chain.joints)
    points = tuple(dataclasses.replace(p, at=move(p.at)) for p in chain.points)
    masses = tuple(dataclasses.replace(m, centre=move(m.centre)) for m in chain.masses)
    return dataclasses.replace(chain, joints=joints, points=points, masses=masses)


def same_angle(a, b, tol):
    return abs(math.remainder(a - b, 360.0)) <= tol


# -- item 1: summaries under rotation and renaming ------------------------------------
def test_beam_engine_summary_unchanged_when_the_drawing_is_rotated():
    chain = chaingraph.load(catalog_path("beam-engine"))
    s0 = chaingraph.solve(chain).summary
    s1 = chaingraph.solve(transformed(chain, angle=-90.0)).summary
    assert s1["stroke"] == pytest.approx(s0["stroke"], rel=1e-9)
    assert s1["time_ratio"] == pytest.approx(s0["time_ratio"], rel=1e-9)
    assert s0["stroke"] < 60 and s0["time_ratio"] < 1.1
    for a, b in zip(s0["extremes"], s1["extremes"]):
        assert same_angle(b, a - 90.0, 1e-7)


SUMMARY_CATALOG = ["beam-engine", "crank-and-slotted-lever-mechanism", "reciprocating-engine",
                   "whitworth-quick-return-mechanism", "stephenson-iii-mechanism",
                   "watt-i-mechanism", "quick-return-worked-example-3"]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(name=st.sampled_from(SUMMARY_CATALOG), angle=st.floats(-180, 180),
       exponent=st.floats(-6, 6), far=st.floats(0, 1e6), data=st.data())
def test_summary_and_poses_are_invariant_under_rigid_motion_scale_and_renaming(
        name, angle, exponent, far, data):
    chain = chaingraph.load(catalog_path(name))
    size = max(max(j.at[0] for j in chain.joints) - min(j.at[0] for j in chain.joints),
               max(j.at[1] for j in chain.joints) - min(j.at[1] for j in chain.joints))
    scale = 10.0 ** exponent
    shift = (far * size * scale, -0.5 * far * size * scale)
    names = {x: f"renamed {i}" for i, x in enumerate(
        data.draw(st.permutations(list(chain.links))))}
    moved = transformed(chain, angle=angle, shift=shift, scale=scale).relabelled(names)
    m0 = chaingraph.solve(chain, steps=24)
    m1 = chaingraph.solve(moved, steps=24, start=m0.theta[0] + angle,
                          stop=m0.theta[-1] + angle)
    s0, s1 = m0.summary, m1.summary
    length = s0["stroke_unit"] != "deg"
    if s0["stroke"] is None:
        turns = "output_turns_fully"
        assert s1["stroke"] is None
        assert s1.to_dict().get(turns) == s0.to_dict().get(turns)
    else:
        assert s1["stroke"] == pytest.approx(s0["stroke"] * (scale if length else 1.0),
                                             rel=1e-6)
    if s0["time_ratio"] is None:
        assert s1["time_ratio"] is None
    else:
        assert s1["time_ratio"] == pytest.approx(s0["time_ratio"], rel=1e-6)
    shift_angle = angle
    for a, b in zip(s0["extremes"] or [], s1["extremes"] or []):
        assert same_angle(b, a + shift_angle, 1e-5)
    assert len(s0["dead_centres"]) == len(s1["dead_centres"])
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    for j in chain.joints:
        x0, y0 = m0[f"x:{j.id}"], m0[f"y:{j.id}"]
        x1 = scale * (c * x0 - s * y0) + shift[0]
        y1 = scale * (s * x0 + c * y0) + shift[1]
        tol = 1e-7 * size * scale * (1 + far)
        assert np.allclose(m1[f"x:{j.id}"], x1, atol=tol)
        assert np.allclose(m1[f"y:{j.id}"], y1, atol=tol)


# -- item 2 and 11: poses do not depend on the sampling or the start ----------------------
def test_coupling_rod_stays_a_parallelogram_at_any_number_of_steps():
    chain = chaingraph.load(catalog_path("coupling-rod-of-a-locomotive"))
    fine = chaingraph.solve(chain, start=0, stop=360, steps=360, summary=False)
    for steps in (4, 6, 8, 12):
        m = chaingraph.solve(chain, start=0, stop=360, steps=steps, summary=False)
        k = np.arange(steps + 1) * (360 // steps)
        for column in m.columns:
            if column.startswith(("x:", "y:")):
                assert np.allclose(m[column], fine[column][k], atol=1e-9), (steps, column)


@pytest.mark.parametrize("steps", range(2, 13))
def test_three_wheel_coupling_solves_at_coarse_steps(steps):
    chain = chaingraph.load(catalog_path("locomotive-coupling-three-wheels"))
    m = chaingraph.solve(chain, steps=steps, summary=False)
    assert m.theta.size == steps + 1


def test_parallelogram_answer_does_not_depend_on_where_the_sweep_starts():
    chain = chaingraph.load(CASES / "parallelogram.toml")
    a = chaingraph.solve(chain, start=0, stop=360, steps=360, summary=False)
    b = chaingraph.solve(chain, start=180, stop=540, steps=360, summary=False)
    # the coupler of a parallelogram keeps its drawn direction
    assert np.allclose(b["angle:coupler"], a["angle:coupler"][0], atol=1e-6)
    for column in ("x:C", "y:C"):
        assert np.allclose(b[column][:181], a[column][180:], atol=1e-9)


def test_antiparallelogram_returns_to_its_start_after_a_turn():
    chain = chaingraph.load(CASES / "antiparallelogram.toml")
    m = chaingraph.solve(chain, steps=36, summary=False)
    for j in chain.joints:
        assert m[f"x:{j.id}"][-1] == pytest.approx(m[f"x:{j.id}"][0], abs=1e-9)
        assert m[f"y:{j.id}"][-1] == pytest.approx(m[f"y:{j.id}"][0], abs=1e-9)


@settings(max_examples=15, deadline=None)
@given(steps=st.integers(1, 400))
def test_poses_at_an_angle_do_not_depend_on_the_number_of_steps(steps):
    chain = chaingraph.load(CASES / "near-fold-crank-rocker-delta-0.01-th0-0.toml")
    m = chaingraph.solve(chain, steps=steps, summary=False)
    ref = chaingraph.solve(chain, start=float(m.theta[-1]), stop=float(m.theta[-1]),
                           steps=1, summary=False)
    assert m["angle:rocker"][-1] == pytest.approx(ref["angle:rocker"][0], abs=1e-9)
    assert m["x:C"][0] == pytest.approx(m["x:C"][-1], abs=1e-9)  # back where it started


# -- item 10: no flip near a fold --------------------------------------------------------
@pytest.mark.parametrize("delta", ["0.0001", "0.01"])
@pytest.mark.parametrize("steps", [36, 360, 3600])
def test_near_fold_crank_rocker_ends_its_turn_in_its_own_mode(delta, steps):
    chain = chaingraph.load(CASES / f"near-fold-crank-rocker-delta-{delta}-th0-0.toml")
    m = chaingraph.solve(chain, steps=steps, summary=False)
    assert m["angle:rocker"][-1] == pytest.approx(m["angle:rocker"][0], abs=1e-9)


# -- item 3 and 9: where and how large the drawing is -----------------------------------
@pytest.mark.parametrize("name, how", [
    (name, how) for name in ("reciprocating-engine", "beam-engine", "watt-i-mechanism")
    for how in (dict(shift=(3e5, 3e5)), dict(scale=1e9), dict(scale=1e-12))
] + [
    ("stephenson-iii-mechanism", how) for how in (dict(shift=(3e5, 3e5)), dict(scale=1e9),
                                                  dict(scale=1e-12))])
def test_mobility_does_not_depend_on_where_or_how_large(name, how):
    chain = transformed(chaingraph.load(catalog_path(name)), **how)
    m = chaingraph.solve(chain, steps=12)
    assert m.summary["numeric_mobility"] == 1


def test_design_at_large_size_solves(tmp_path):
    out = tmp_path / "big.toml"
    code, _, err = run_cli(*["design", "slotted-lever", "--time-ratio", "1.7", "--crank", "1e6",
                            "--stroke", "5e6", "--out", str(out)])
    assert code == 0, err
    code, _, err = run_cli(*["solve", str(out), "--json"])
    assert code == 0, err


# -- item 4, 14, 15: rocking inputs over their whole range -----------------------------------
ROCKING = [("catalog", "stephenson-six-bar-chain", "t2", "b4"),
           ("catalog", "stephenson-six-bar-chain", "b4", "t2"),
           ("catalog", "stephenson-six-bar-chain", "b4", "b3"),
           ("cases", "stephenson-PB-F-7", "b3", "t1"),
           ("cases", "atlas8-04-0", "L1", "L5"),
           ("cases", "atlas8-14-0", "L6", "L8"),
           ("cases", "atlas8-08-0", "L1", "L2"),
           ("cases", "atlas8-02-0", "L6", "L2")]


@pytest.mark.parametrize("where, name, fixed, driver", ROCKING)
def test_rocking_input_solves_over_its_feasible_range_limits_included(where, name, fixed,
                                                                      driver):
    path = catalog_path(name) if where == "catalog" else CASES / f"{name}.toml"
    chain = chaingraph.load(path)
    m = chaingraph.solve(chain, fixed=fixed, driver=driver, steps=60)
    lo, hi = m.summary["input_range"]
    assert (m.theta[0], m.theta[-1]) == (lo, hi)
    assert lo in m.summary["dead_centres"] and hi in m.summary["dead_centres"]
    for j in chain.joints:      # exact positions at the limits
        assert np.isfinite(m[f"x:{j.id}"]).all()


def test_a_range_wider_than_a_turn_is_not_called_a_crank():
    chain = chaingraph.load(CASES / "stephenson-PB-F-7.toml")
    m = chaingraph.solve(chain, fixed="b3", driver="t1", steps=36)
    lo, hi = m.summary["input_range"]
    assert not m.summary["full_turn"] and hi - lo > 360.0


@pytest.mark.slow
def test_every_input_of_every_inversion_of_every_catalog_chain_solves_or_is_refused():
    """Every (fixed link, link pinned to it) of every catalog file with a drawn pose
    solves over its default sweep (a full turn, or its whole range, limits included);
    the only refusals are the legitimate ones: a cam or gear pair that the driver does
    not drive (a cam's follower or a gear's mate as the input), or a mobility other than
    1 with that driver. (The rotary engine with its seven cylinders, 16 links, whose
    other inversions are groups of high class, is tested on its own inversion, in
    tests/kinematics/test_machines.py.)"""
    from chaingraph import MechanismError
    from chaingraph.naming.catalog import catalog_files
    solved = 0
    for path in catalog_files():
        chain = chaingraph.load(path)
        if not chain.has_pose or len(chain.links) > 8:
            continue
        if is_gear_train(chain):        # its speeds are `chaingraph gears`' (conftest)
            continue
        for fixed, driver in pinned_pairs(chain):
            try:
                m = chaingraph.solve(chain, fixed=fixed, driver=driver, steps=12)
            except MechanismError as e:
                assert ("mobility" in str(e) or "only R and P" in str(e)
                        or "cannot be derived from the inputs" in str(e)), (path, e)
                continue
            assert all(np.isfinite(m[f"x:{k.id}"]).all() for k in chain.joints)
            solved += 1
    assert solved >= 300


def test_every_rocking_input_of_the_stephenson_chain_solves():
    chain = chaingraph.load(catalog_path("stephenson-six-bar-chain"))
    for fixed, driver in pinned_pairs(chain):
        m = chaingraph.solve(chain, fixed=fixed, driver=driver, steps=12)
        assert m.theta.size == 13


# -- item 5: a singular drawn pose ----------------------------------------------------
def test_four_bar_drawn_at_its_only_pose_is_mobility_one_with_that_range(tmp_path):
    """A four-bar that assembles at one angle only (60 + 20 + 20 = 100, all in line) is
    mobility 1 there: asked to sweep, it fails (exit 1) with that range. (At a double
    root the discriminant's tolerance, 1e-13 of the size squared, resolves the angle
    to about its square root: the range is 0 within 1e-4 degrees.)"""
    def R(i, links, at):
        return Joint(i, "R", tuple(links), at=at)
    chain = Chain("collinear", (R("A", ["frame", "crank"], (0.0, 0.0)),
                                R("B", ["crank", "coupler"], (60.0, 0.0)),
                                R("C", ["coupler", "rocker"], (80.0, 0.0)),
                                R("D", ["rocker", "frame"], (100.0, 0.0))),
                  mechanism=Mechanism("frame", "crank", 1.0, "rocker"))
    with pytest.raises(AssemblyError) as info:
        chaingraph.solve(chain, start=0, stop=90)
    lo, hi = info.value.feasible_range
    assert lo == pytest.approx(0.0, abs=1e-4) and hi == pytest.approx(0.0, abs=1e-4)
    path = tmp_path / "collinear.toml"
    chaingraph.save(chain, path)
    code, _, err = run_cli(*["solve", str(path), "--from", "0", "--to", "90"])
    assert code == 1 and "can turn only from" in err and "Traceback" not in err


# -- item 7: offset sliders (see also test_solver) -------------------------------------
# -- item 12: rates near a change point are exact or NaN ---------------------------------
@pytest.mark.parametrize("distance", [1e-6, 1e-4, 1e-2, 0.5, 5.0])
def test_parallelogram_rates_near_its_change_point_are_exact_or_nan(distance):
    chain = chaingraph.load(CASES / "parallelogram.toml")
    m = chaingraph.solve(chain, start=180 - distance, stop=180 - distance, steps=1,
                         summary=False)
    # exact: the coupler does not turn, the rocker turns with the crank
    for column, exact in (("omega:coupler", 0.0), ("alpha:coupler", 0.0),
                          ("omega:rocker", 1.0), ("alpha:rocker", 0.0)):
        value = m[column][0]
        assert np.isnan(value) or value == pytest.approx(exact, abs=1e-6), (column, value)


# -- item 13: narrow windows near a change point ------------------------------------------
@pytest.mark.parametrize("eps, limit", [("1e-06", 179.98520629332995),
                                        ("0.0001", 179.85206291542536)])
def test_narrow_infeasible_window_is_found_with_its_exact_limits(eps, limit):
    chain = chaingraph.load(CASES / f"near-change-point-eps-{eps}-th0-100.25.toml")
    for steps in (360, 3600):
        s = chaingraph.solve(chain, steps=steps).summary
        assert not s["full_turn"]
        assert s["input_range"] == pytest.approx([-limit, limit], abs=1e-5)


# -- item 16: a summary costs no more than a sweep ---------------------------------------
def test_rocking_group_summary_is_quick(monkeypatch):
    """The summary of a rocking group solves a few thousand points, not a fine walk of
    its range (5,494 when this was written: the sweep, the summary's grid of 3,601 and
    the refinements)."""
    from chaingraph.kinematics import tracking
    solved = []
    evaluate = tracking._evaluate
    monkeypatch.setattr(tracking, "_evaluate",
                        lambda plan, theta, start: solved.append(theta.size) or
                        evaluate(plan, theta, start))
    chain = chaingraph.load(catalog_path("stephenson-six-bar-chain"))
    chaingraph.solve(chain, fixed="t2", driver="b4")
    assert sum(solved) <= 10_000


# -- item 8: every extreme is stationary; one maximum per turn gives a time ratio -----------
@pytest.mark.parametrize("name", ["beam-engine", "crank-and-slotted-lever-mechanism",
                                  "whitworth-quick-return-with-ram",
                                  "shaper-crank-and-slotted-lever"])
def test_every_reported_extreme_is_a_stationary_point(name):
    chain = chaingraph.load(catalog_path(name))
    s = chaingraph.solve(chain).summary
    maxima = [e for e in s["extreme_positions"] if e["kind"] == "max"]
    assert len(maxima) == 1 and s["time_ratio"] is not None and s["note"] is None
    for e in s["extreme_positions"]:
        at = chaingraph.solve(chain, start=e["input"], stop=e["input"], steps=1, summary=False)
        from chaingraph.kinematics import output_signal
        signal = output_signal(at.plan, chain.mechanism.output, at.columns)
        kind = signal.kind
        if kind != "point":
            value, rate, _ = signal.values(at.columns)
            assert rate[0] == pytest.approx(0.0, abs=1e-6 * max(1.0, abs(value[0])))
            assert value[0] == pytest.approx(e["value"], abs=1e-9 * max(1.0, abs(value[0])))


def test_toggle_press_has_two_maxima_and_no_time_ratio():
    """A ram that tops out twice per turn (item 8): every extreme is reported, from
    closed form; there is no time ratio, and the note says why."""
    chain = chaingraph.load(CASES / "toggle-press.toml")
    d0 = chain.joint("D").at[1]
    s = chaingraph.solve(chain).summary
    assert s["time_ratio"] is None and s["forward_deg"] is None
    assert "2 maxima and 2 minima" in s["note"]
    kinds = [e["kind"] for e in s["extreme_positions"]]
    assert sorted(kinds) == ["max", "max", "min", "min"]
    assert all(a != b for a, b in zip(kinds, kinds[1:] + kinds[:1]))   # they alternate
    # highest with rocker and rod vertical: 6000 cos t + 4200 sin t = 5800
    phi = math.degrees(math.atan2(4200.0, 6000.0))
    spread = math.degrees(math.acos(5800.0 / math.hypot(6000.0, 4200.0)))
    tops = sorted((phi + sign * spread) % 360.0 for sign in (1, -1))
    maxima = sorted(e["input"] for e in s["extreme_positions"] if e["kind"] == "max")
    assert maxima == pytest.approx(tops, abs=1e-7)
    for e in s["extreme_positions"]:
        if e["kind"] == "max":
            assert e["value"] == pytest.approx(70.0 + 120.0 - d0, abs=1e-9)
    # lowest at the rocker's extremes, crank and coupler in line (|O2 B| = 130 or 70)
    lows = []
    for reach in (130.0, 70.0):
        a = (reach ** 2 - 70.0 ** 2 + 100.0 ** 2) / 200.0
        bx, by = a, math.sqrt(reach ** 2 - a * a)
        lows.append(by + math.sqrt(120.0 ** 2 - (bx - 100.0) ** 2) - d0)
    minima = sorted(e["value"] for e in s["extreme_positions"] if e["kind"] == "min")
    assert minima == pytest.approx(sorted(lows), abs=1e-9)
    assert s["stroke"] == pytest.approx(70.0 + 120.0 - d0 - min(lows), abs=1e-9)


# -- item 17 -------------------------------------------------------------------------
def test_catalog_non_grashof_four_bar_is_non_grashof():
    chain = chaingraph.load(catalog_path("non-grashof-four-bar"))
    at = {j.id: j.at for j in chain.joints}
    lengths = sorted(math.dist(at[a], at[b]) for a, b in ("AB", "BC", "CD", "DA"))
    assert lengths[0] + lengths[3] > lengths[1] + lengths[2] + 1.0
    assert not chaingraph.solve(chain).summary["full_turn"]


# -- items 6 and 15: never a traceback from the group solver ---------------------------------
@pytest.mark.parametrize("name, fixed, driver", [("atlas8-14-0", "L6", "L8"),
                                                 ("atlas8-08-0", "L1", "L2")])
def test_group_solver_failures_are_assembly_errors_or_answers(name, fixed, driver):
    code, _, err = run_cli(*["solve", str(CASES / f"{name}.toml"), "--fixed", fixed,
                            "--driver", driver, "--json"])
    assert code in (0, 1) and "Traceback" not in err


def _isolated_jumps(motion, chain):
    """(link, input, jump in degrees) wherever a link's angle jumps between two
    samples by more than 20 degrees and ten times either neighbouring step: a
    discontinuity, not a fast motion."""
    out = []
    for link in chain.links:
        step = np.degrees(np.abs(np.diff(np.unwrap(np.radians(motion[f"angle:{link}"])))))
        for k in np.flatnonzero(step > 20.0):
            around = max(step[k - 1] if k else 0.0, step[k + 1] if k + 1 < step.size else 0.0)
            if step[k] > 10.0 * around:
                out.append((link, float(motion.theta[k]), float(step[k])))
    return out


@pytest.mark.parametrize("name", ["watt-six-bar-chain", "six-link-two-ternary-joints"])
def test_no_link_jumps_in_any_inversion(name):
    """Every inversion of two chains that once jumped: the Watt chain drawn with a
    parallelogram loop (a sharp touch of a dyad's modes that the cycle's coarse walk
    missed, so that the limit's pose was in the other label), and the chain whose two
    ternary joints pass over each other (the dyad on them turned over at once)."""
    chain = chaingraph.load(catalog_path(name))
    solved = 0
    for fixed, driver in pinned_pairs(chain):
        m = chaingraph.solve(chain, fixed=fixed, driver=driver, steps=360, summary=False)
        assert _isolated_jumps(m, chain) == [], (fixed, driver)
        solved += 1
    assert solved >= 10


def test_a_sample_where_two_joints_meet_is_the_motion_s_limit_there():
    """Ternary joints T1 and T2 meet half way through the range (d fixed, f driving):
    there the dyad b-e on them is undetermined by its lengths, and the closed form's
    line through the two points has no direction. The sample exactly there (the middle
    one of 12 steps, limit to limit) is the pose the motion passes through, as a fine
    sweep about it shows; the motion after it goes on smoothly (b turns on, by 17.5
    degrees a step, not over by half a turn)."""
    chain = chaingraph.load(catalog_path("six-link-two-ternary-joints"))
    m = chaingraph.solve(chain, fixed="d", driver="f", steps=12, summary=False)
    t = float(m.theta[6])
    near = chaingraph.solve(chain, fixed="d", driver="f", start=t - 1e-3, stop=t + 1e-3,
                            steps=2, summary=False)
    for column in ("angle:b", "angle:e", "x:Y", "y:Y"):
        assert m[column][6] == pytest.approx(near[column][1], abs=1e-6), column
        assert near[column][0] < near[column][1] < near[column][2] or \
            near[column][0] > near[column][1] > near[column][2], column
    turn = np.diff(np.unwrap(np.radians(m["angle:b"])))
    assert np.degrees(np.abs(turn[:-1])).max() < 40.0


def test_a_group_drawn_a_hair_from_its_fold_keeps_its_branch():
    """An eight-link chain of the atlas (one sliding pair) drawn 0.0002 degrees from a
    fold of its group (L3 fixed, L4 driving: the range starts there). Stepping out of
    the drawn pose, next to the fold, Newton's method lands on either of the two
    branches that meet there; the points the trace's correction missed are approached
    back from the trace's own, so the sweep to the limit is the one a fine sweep from
    inside the range traces (it jumped to the other branch for four steps, L1 by 31
    degrees)."""
    chain = chaingraph.load(CASES / "atlas8p1-51-near-fold.toml")
    m = chaingraph.solve(chain, fixed="L3", driver="L4", steps=720, summary=False)
    assert _isolated_jumps(m, chain) == []
    lo = float(m.theta[0])
    fine = chaingraph.solve(chain, fixed="L3", driver="L4", start=float(m.theta[6]),
                            stop=lo, steps=600, summary=False)
    for k in range(1, 6):
        got, want = m["angle:L1"][k], fine["angle:L1"][600 - 100 * k]
        assert got == pytest.approx(want, abs=1e-6), k


@pytest.mark.parametrize("fixed, driver", [("L4", "L6"), ("L6", "L4")])
def test_a_window_seen_only_between_a_coarse_path_s_last_samples_ends_the_range(fixed, driver):
    """Chain 18 of the eight-link atlas with multiple joints: with L4 fixed and L6
    driving, the dyad L3-L7 cannot be assembled in a narrow window (its discriminant
    dips to -2e-4) near the end of the range the dyad L1-L8 allows. The cycle's coarse
    walk stopped for L1-L8 one sample past the window, and a dyad's last sample before
    a stop was never refined (as if the stop were its own): the range ran through the
    window, and the default sweep, finer, refused its own range. The range ends at the
    window; the default sweep solves; its ends are the range's."""
    chain = chaingraph.load(CASES / "atlas8m-18-window.toml")
    m = chaingraph.solve(chain, fixed=fixed, driver=driver, steps=720)
    low, high = m.summary["input_range"]
    assert (m.theta[0], m.theta[-1]) == (low, high)
    with pytest.raises(AssemblyError, match="leaves the range"):
        chaingraph.solve(chain, fixed=fixed, driver=driver, start=low, stop=high + 0.05,
                         steps=4, summary=False)


def test_a_group_near_its_fold_closes_its_loops_as_the_check_asks():
    """Chain 43 of the eight-link atlas with one sliding pair, L4 fixed, L8 driving: a
    group of six links (Newton's method). Near the fold at the low end of its range the
    chord method, whose convergence is linear, left points whose equations held to
    8.8e-10 of the size and took them as converged; their joints closed to 1.09e-9 of
    it, and the check of the poses refused the default sweep. The chord now hands such
    points to Newton's method, which finishes them."""
    chain = chaingraph.load(CASES / "atlas8p1-43-group-near-fold.toml")
    m = chaingraph.solve(chain, fixed="L4", driver="L8", steps=720, summary=False)
    assert np.isfinite(m["x:J1"]).all() and m.theta.size == 721


def test_a_group_keeps_its_branch_where_another_passes_close():
    """A Stephenson III sampled by type synthesis (six links, L1 fixed, L2 driving, a
    point P on L6): near 248.6 degrees the group's Jacobian has a singular value of
    0.0041 on a mechanism of about 50 mm, another branch passing within about 1e-4 of
    the size, and the trace's step crossed onto it (P at (-12.806, -28.276) at 256.07
    degrees). A crossing changes the sign of det [J; tangent], which a branch keeps,
    folds included; the trace now shortens its step there. The answer is an independent
    continuation's (a Newton continuation of the written file with finite-difference
    Jacobians, at 1, 0.2 and 0.1 degree steps, all three agreeing): (-12.384, -25.462)."""
    chain = chaingraph.load(CASES / "stephenson-iii-near-bifurcation.toml")
    m = chaingraph.solve(chain, steps=720, summary=False)
    k = int(np.argmin(np.abs(m.theta - 256.07)))
    assert abs(m.theta[k] - 256.066) < 1e-3
    assert (m["x:P"][k], m["y:P"][k]) == pytest.approx((-12.384, -25.462), abs=2e-3)
    assert _isolated_jumps(m, chain) == []
