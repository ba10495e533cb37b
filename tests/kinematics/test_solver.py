"""The numeric solver: closed-form geometry, finite differences, the textbook's figures,
assembly modes, feasible ranges, dead centres and every bad input."""

import contextlib
import csv
import io
import json
import math
from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph import AssemblyError, Chain, Joint, Mechanism, MechanismError
from chaingraph.naming.catalog import catalog_files, catalog_path
from chaingraph.cli.main import main
from chaingraph.kinematics import solve
from chaingraph.kinematics.sweep import evaluate_sweep
from chaingraph.kinematics.plan import build_plan
from chaingraph.kinematics.equations import check_poses, residuals
from chaingraph.kinematics.rates import rates
from chaingraph.kinematics.tracking import evaluate

from ..conftest import run_cli, solver_takes
from .newton_check import assert_newton_agrees_with_closed_forms

SOLVABLE = [p for p in catalog_files()
            if (c := chaingraph.load(p)).mechanism is not None and c.mechanism.driver
            and solver_takes(c)]


def R(joint_id, links, at):
    return Joint(joint_id, "R", tuple(links), at=(float(at[0]), float(at[1])))


def P(joint_id, links, at, axis):
    return Joint(joint_id, "P", tuple(links), at=(float(at[0]), float(at[1])), axis=float(axis))


def circle_circle(p, r1, q, r2, sign=1):
    dx, dy = q[0] - p[0], q[1] - p[1]
    d = math.hypot(dx, dy)
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = math.sqrt(r1 * r1 - a * a)
    return (p[0] + a * dx / d - sign * h * dy / d, p[1] + a * dy / d + sign * h * dx / d)


# -- the crank-rocker four-bar against closed form -----------------------------------
GROUND, CRANK, COUPLER, ROCKER = 100.0, 40.0, 120.0, 80.0


def four_bar(angle=30.0, sign=1):
    A, D = (0.0, 0.0), (GROUND, 0.0)
    B = (CRANK * math.cos(math.radians(angle)), CRANK * math.sin(math.radians(angle)))
    C = circle_circle(B, COUPLER, D, ROCKER, sign)
    return Chain("crank-rocker", (R("A", ["frame", "crank"], A), R("B", ["crank", "coupler"], B),
                                  R("C", ["coupler", "rocker"], C), R("D", ["rocker", "frame"], D)),
                 mechanism=Mechanism("frame", "crank", 2.5, "rocker"))


def four_bar_by_hand(theta, omega, sign):
    """Loop closure a e^{i th} + b e^{i beta} = d + c e^{i gamma}, solved and
    differentiated by hand (complex numbers), independent of the solver."""
    a, b, c, d = CRANK, COUPLER, ROCKER, GROUND
    th = np.radians(theta)
    B = a * np.exp(1j * th)
    BD = d - B
    L = np.abs(BD)
    # C = B + b e^{i beta}, |C - D| = c: the angle at B between BD and BC
    cos_phi = (b * b + L * L - c * c) / (2 * b * L)
    beta = np.angle(BD) + sign * np.arccos(cos_phi)
    C = B + b * np.exp(1j * beta)
    gamma = np.angle(C - d)
    # velocities: i a w e^{i th} + i b w3 e^{i beta} = i c w4 e^{i gamma}
    M = np.array([[-b * np.sin(beta), c * np.sin(gamma)], [b * np.cos(beta), -c * np.cos(gamma)]])
    rhs = np.array([a * omega * np.sin(th), -a * omega * np.cos(th)])
    sol = np.linalg.solve(np.moveaxis(M, -1, 0), np.moveaxis(rhs, -1, 0)[..., None])[..., 0]
    w3, w4 = sol[:, 0], sol[:, 1]
    # accelerations: -a w^2 e^{i th} + (i al3 - w3^2) b e^{i beta} = (i al4 - w4^2) c e^{i gamma}
    accel = (a * omega ** 2 * np.exp(1j * th) + b * w3 ** 2 * np.exp(1j * beta)
             - c * w4 ** 2 * np.exp(1j * gamma))
    rhs2 = np.array([accel.real, accel.imag])
    sol2 = np.linalg.solve(np.moveaxis(M, -1, 0), np.moveaxis(rhs2, -1, 0)[..., None])[..., 0]
    return C, np.degrees(beta), np.degrees(gamma), w3, w4, sol2[:, 0], sol2[:, 1]


def _close_angles(a, b, tol):
    return np.allclose(np.remainder(a - b + 180.0, 360.0) - 180.0, 0.0, atol=tol)


@pytest.mark.parametrize("sign", [1, -1])
def test_crank_rocker_every_step_against_closed_form(sign):
    chain = four_bar(30.0, sign)
    motion = solve(chain, steps=720)
    theta = motion["theta"]
    C, beta, gamma, w3, w4, al3, al4 = four_bar_by_hand(theta, 2.5, sign)
    assert np.allclose(motion["x:C"], C.real, atol=1e-9) and np.allclose(motion["y:C"], C.imag, atol=1e-9)
    assert _close_angles(motion["angle:coupler"], beta, 1e-9)
    assert _close_angles(motion["angle:rocker"], gamma + 180.0, 1e-9)  # line C -> D
    assert np.allclose(motion["omega:coupler"], w3, atol=1e-10)
    assert np.allclose(motion["omega:rocker"], w4, atol=1e-10)
    assert np.allclose(motion["alpha:coupler"], al3, atol=1e-9)
    assert np.allclose(motion["alpha:rocker"], al4, atol=1e-9)
    assert np.allclose(motion["omega:crank"], 2.5) and np.allclose(motion["alpha:crank"], 0.0)
    # velocity of C is the rocker's rotation about D
    vc = motion["vx:C"] + 1j * motion["vy:C"]
    assert np.allclose(vc, 1j * w4 * (C - GROUND), atol=1e-9)


def test_crank_rocker_transmission_angle_range():
    s = solve(four_bar()).summary
    b, c = COUPLER, ROCKER
    mu_min = math.degrees(math.acos((b * b + c * c - (GROUND - CRANK) ** 2) / (2 * b * c)))
    mu_max = math.degrees(math.acos((b * b + c * c - (GROUND + CRANK) ** 2) / (2 * b * c)))
    assert s["transmission_angle"]["min"] == pytest.approx(mu_min, abs=1e-7)
    assert s["transmission_angle"]["max"] == pytest.approx(mu_max, abs=1e-7)
    assert s["full_turn"] is True and s["dead_centres"] == []


def test_crank_rocker_limit_positions_and_time_ratio():
    s = solve(four_bar()).summary
    # the rocker's extremes: crank and coupler in line, |AC| = coupler -+ crank
    ext = []
    for r, add in ((COUPLER + CRANK, 0.0), (COUPLER - CRANK, 180.0)):
        C = circle_circle((0.0, 0.0), r, (GROUND, 0.0), ROCKER, 1)
        ext.append((math.degrees(math.atan2(C[1], C[0])) + add) % 360.0)
    assert sorted(s["extremes"]) == pytest.approx(sorted(ext), abs=1e-7)
    a = (ext[1] - ext[0]) % 360.0
    assert s["time_ratio"] == pytest.approx(max(a, 360 - a) / min(a, 360 - a), rel=1e-9)


# -- the offset slider crank against closed form ------------------------------------
def slider_crank(a=40.0, rod=120.0, e=10.0, angle=45.0):
    A = (a * math.cos(math.radians(angle)), a * math.sin(math.radians(angle)))
    B = (A[0] + math.sqrt(rod ** 2 - (e - A[1]) ** 2), e)
    return Chain("offset slider crank", (
        R("O", ["frame", "crank"], (0, 0)), R("A", ["crank", "rod"], A),
        R("B", ["rod", "slider"], B), P("S", ["frame", "slider"], B, 0.0)),
        mechanism=Mechanism("frame", "crank", 3.0, "slider"), units="mm")


def test_offset_slider_crank_every_step_against_closed_form():
    a, l, e, w = 40.0, 120.0, 10.0, 3.0
    motion = solve(slider_crank(a, l, e), steps=720)
    th = np.radians(motion["theta"])
    s, c = np.sin(th), np.cos(th)
    u, du, ddu = e - a * s, -a * c, a * s
    S = np.sqrt(l * l - u * u)
    dS = u * a * c / S
    ddS = a * (du * c - u * s) / S - a * c * u * dS / S ** 2
    x = a * c + S
    dx = -a * s + dS
    ddx = -a * c + ddS
    phi = np.degrees(np.arctan2(u, S))
    dphi = (du * S - u * dS) / (l * l)
    ddphi = (ddu * S - u * ddS) / (l * l)
    assert np.allclose(motion["x:B"], x, atol=1e-9) and np.allclose(motion["y:B"], e, atol=1e-9)
    assert np.allclose(motion["vx:B"], w * dx, atol=1e-9)
    assert np.allclose(motion["ax:B"], w * w * ddx, atol=1e-8)
    assert np.allclose(motion["vy:B"], 0.0, atol=1e-9) and np.allclose(motion["ay:B"], 0.0, atol=1e-8)
    assert _close_angles(motion["angle:rod"], phi, 1e-9)
    assert np.allclose(motion["omega:rod"], w * dphi, atol=1e-10)
    assert np.allclose(motion["alpha:rod"], w * w * ddphi, atol=1e-9)
    # slide displacement from the drawn pose, its rate and acceleration
    assert np.allclose(motion["s:S"], x - x[0], atol=1e-9)
    assert np.allclose(motion["v:S"], w * dx, atol=1e-9)
    assert np.allclose(motion["a:S"], w * w * ddx, atol=1e-8)
    summary = motion.summary
    xs = [a + l, -a + l]  # not exact with an offset: check the stroke directly
    stroke = math.sqrt((l + a) ** 2 - e ** 2) - math.sqrt((l - a) ** 2 - e ** 2)
    assert summary["stroke"] == pytest.approx(stroke, abs=1e-9)
    assert summary["stroke_unit"] == "mm" and xs


# -- the textbook's quick return figures ------------------------------------------------
def test_crank_and_slotted_lever_time_ratio_is_1_710():
    s = solve(chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))).summary
    alpha = 2 * math.degrees(math.acos(120 / 300))  # return angle: lever tangent to the circle
    exact = (360 - alpha) / alpha
    assert s["time_ratio"] == pytest.approx(exact, abs=1e-9)
    assert round(s["time_ratio"], 3) == 1.710 and round(s["time_ratio"], 2) != 1.72
    assert s["forward_deg"] == pytest.approx(360 - alpha, abs=1e-7)
    assert s["return_deg"] == pytest.approx(alpha, abs=1e-7)


def test_shaper_with_ram_time_ratio_2_stroke_450():
    s = solve(chaingraph.load(catalog_path("shaper-crank-and-slotted-lever"))).summary
    assert s["time_ratio"] == pytest.approx(2.0, abs=1e-9)
    assert s["stroke"] == pytest.approx(2 * 450 * 120 / 240, abs=1e-8)


def whitworth(arm, rod, crank=75.0, centres=50.0, angle=90.0):
    D, C = (0.0, 0.0), (0.0, -centres)
    A = (C[0] + crank * math.cos(math.radians(angle)), C[1] + crank * math.sin(math.radians(angle)))
    u = (A[0] - D[0], A[1] - D[1])
    n = math.hypot(*u)
    Pp = (-arm * u[0] / n, -arm * u[1] / n)
    Rr = (Pp[0] + math.sqrt(rod ** 2 - Pp[1] ** 2), 0.0)
    return Chain("Whitworth", (
        R("C", ["frame", "crank"], C), R("A", ["crank", "block"], A),
        P("S", ["lever", "block"], A, math.degrees(math.atan2(u[1], u[0]))),
        R("D", ["lever", "frame"], D), R("P", ["lever", "rod"], Pp),
        R("R", ["rod", "ram"], Rr), P("G", ["frame", "ram"], Rr, 0.0)),
        mechanism=Mechanism("frame", "crank", 1.0, "ram"))


@pytest.mark.parametrize("arm, rod", [(50.0, 135.0), (30.0, 100.0), (70.0, 200.0)])
def test_whitworth_time_ratio_2_735_whatever_the_arm_and_rod(arm, rod):
    s = solve(whitworth(arm, rod)).summary
    beta = 2 * math.degrees(math.acos(50 / 75))  # the crank's return angle
    assert s["time_ratio"] == pytest.approx((360 - beta) / beta, abs=1e-9)
    assert round(s["time_ratio"], 3) == 2.735
    assert s["stroke"] == pytest.approx(2 * arm, abs=1e-8)


def test_lecture_crank_rocker_with_slider_against_a_construction():
    chain = chaingraph.load(catalog_path("crank-rocker-with-slider"))
    s = solve(chain).summary
    O2, O4 = (0.0, 0.0), (100.0, 0.0)
    crank, coupler, rocker, link, y_d = 30.0, 100.0, 70.0, 120.0, 20.0
    # the rocker's extremes: crank and coupler in line (the lecture's construction)
    b_out = circle_circle(O2, coupler + crank, O4, rocker, 1)
    b_in = circle_circle(O2, coupler - crank, O4, rocker, 1)
    t_out = math.degrees(math.atan2(b_out[1], b_out[0])) % 360
    t_in = (math.degrees(math.atan2(b_in[1], b_in[0])) + 180) % 360

    def slider_x(b):
        return b[0] + math.sqrt(link ** 2 - (y_d - b[1]) ** 2)
    # the slider follows the rocker monotonically over its range, so its extremes are
    # the rocker's
    psi = np.linspace(math.atan2(b_in[1] - O4[1], b_in[0] - O4[0]),
                      math.atan2(b_out[1] - O4[1], b_out[0] - O4[0]), 2001)
    xs = [slider_x((O4[0] + rocker * math.cos(p), rocker * math.sin(p))) for p in psi]
    assert np.all(np.diff(xs) > 0) or np.all(np.diff(xs) < 0)
    assert s["stroke"] == pytest.approx(abs(slider_x(b_out) - slider_x(b_in)), abs=1e-8)
    a = (t_out - t_in) % 360
    assert s["time_ratio"] == pytest.approx(max(a, 360 - a) / min(a, 360 - a), rel=1e-9)
    assert sorted(s["extremes"]) == pytest.approx(sorted([t_in, t_out]), abs=1e-7)


# -- every catalog mechanism: residuals and finite differences ----------------------
@pytest.mark.parametrize("path", SOLVABLE, ids=[p.stem for p in SOLVABLE])
def test_every_catalog_mechanism_solves_and_differentiates(path):
    chain = chaingraph.load(path)
    motion = solve(chain, steps=180)
    plan = motion.plan
    theta = motion["theta"]
    assert theta.size == 181
    # loop closure at every returned pose (reached from the drawn pose as solve does)
    ev = evaluate_sweep(plan, theta)
    assert residuals(plan, ev.pose).max() <= 1e-9 * plan.size
    # velocities against central differences of positions, accelerations against
    # central differences of the exact velocities (at interior points of the sweep;
    # steps small enough for the truncation, large enough for the rounding)
    w = chain.mechanism.omega
    for k in range(20, theta.size - 20, 23):  # away from a rocking driver's limits
        t = float(theta[k])
        for h, check in ((1e-4, "v"), (1e-3, "a")):
            near = solve(chain, start=t - h, stop=t + h, steps=2, summary=False)
            dt = math.radians(h) / w
            for name in near.columns:
                if not name.startswith(("x:", "y:", "angle:", "s:")):
                    continue
                kind, item = name.split(":", 1)
                if kind == "angle":
                    pos, vel, acc = (np.radians(near[name]), near[f"omega:{item}"],
                                     near[f"alpha:{item}"])
                elif kind == "s":
                    pos, vel, acc = near[name], near[f"v:{item}"], near[f"a:{item}"]
                else:
                    pos, vel, acc = near[name], near[f"v{kind}:{item}"], near[f"a{kind}:{item}"]
                if check == "v":
                    fd, exact = (pos[2] - pos[0]) / (2 * dt), vel[1]
                    column = _rate_column(motion, kind, item, "v")
                else:
                    fd, exact = (vel[2] - vel[0]) / (2 * dt), acc[1]
                    column = _rate_column(motion, kind, item, "a")
                scale = 1.0 + np.nanmax(np.abs(column))   # the size of that rate over the sweep
                assert abs(fd - exact) <= 1e-6 * scale, (name, check, fd, exact)


def _rate_column(motion, kind, item, which):
    if kind == "angle":
        return motion[f"{'omega' if which == 'v' else 'alpha'}:{item}"]
    if kind == "s":
        return motion[f"{which}:{item}"]
    return motion[f"{which}{kind}:{item}"]


def test_sweep_rows_and_csv_columns(tmp_path):
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    motion = solve(chain, start=0, stop=90, steps=3)
    assert list(motion["theta"]) == [0.0, 30.0, 60.0, 90.0]
    path = tmp_path / "out.csv"
    motion.to_csv(path)
    rows = list(csv.reader(path.open()))
    header = rows[0]
    assert header[0] == "theta" and len(rows) == 5
    for link in chain.links:
        assert {f"angle:{link}", f"omega:{link}", f"alpha:{link}"} <= set(header)
    for name in [j.id for j in chain.joints]:
        assert {f"x:{name}", f"y:{name}", f"vx:{name}", f"vy:{name}", f"ax:{name}",
                f"ay:{name}"} <= set(header)
    assert {"s:S", "v:S", "a:S"} <= set(header)
    # the crank's line runs through its joints A then O (id order): theta - 180
    angle = float(rows[2][header.index("angle:crank")])
    assert math.remainder(angle - (30.0 - 180.0), 360.0) == pytest.approx(0.0, abs=1e-9)


def test_points_are_tracked():
    chain = chaingraph.load(catalog_path("beam-engine"))
    m = solve(chain, steps=36)
    lever_turn = np.radians(m["angle:lever"] - m["angle:lever"][0])
    E0 = np.array(chain.point("E").at) - np.array(chain.joint("D").at)
    c, s = np.cos(lever_turn), np.sin(lever_turn)
    ex = chain.joint("D").at[0] + c * E0[0] - s * E0[1]
    assert np.allclose(m["x:E"], ex, atol=1e-9)


# -- assembly mode, feasible range, dead centres ------------------------------------
def test_assembly_mode_is_kept_over_many_turns():
    for sign in (1, -1):
        m = solve(four_bar(30.0, sign), start=30, stop=30 + 720, steps=720)
        assert np.allclose(m["x:C"][:361], m["x:C"][360:], atol=1e-9)
        C, *_ = four_bar_by_hand(m["theta"], 1.0, sign)
        assert np.allclose(m["y:C"], C.imag, atol=1e-9)


def test_parallelogram_passes_its_change_points_without_flipping():
    chain = chaingraph.load(catalog_path("coupling-rod-of-a-locomotive"))
    m = solve(chain, start=0, stop=360, steps=360)
    assert _close_angles(m["angle:wheel 2"], m["angle:wheel 1"], 1e-6)
    s = m.summary
    assert s["dead_centres"] == pytest.approx([0.0, 180.0], abs=1e-5)
    # at the change points the rates are NaN, never a finite wrong number
    k0, k180 = 0, 180
    assert math.isnan(m["omega:wheel 2"][k0]) and math.isnan(m["omega:wheel 2"][k180])
    finite = np.isfinite(m["omega:wheel 2"])
    assert np.allclose(m["omega:wheel 2"][finite], 1.0, atol=1e-6)


def test_redundant_parallelogram_moves_though_kutzbach_says_locked():
    chain = chaingraph.load(catalog_path("locomotive-coupling-three-wheels"))
    assert chaingraph.classify(chain).mobility == 0
    m = solve(chain, start=10, stop=350, steps=34)
    s = m.summary
    assert s["mobility"] == 0 and s["numeric_mobility"] == 1
    assert _close_angles(m["angle:wheel 3"], m["angle:wheel 1"], 1e-6)
    # solved step by step, the dyad (rod, wheel 2) is singular at the change point
    # (180 degrees) before wheel 3 is reached: NaN there, never a wrong number
    finite = np.isfinite(m["omega:wheel 3"])
    assert list(m["theta"][~finite]) == [180.0]
    assert np.allclose(m["omega:wheel 3"][finite], 1.0, atol=1e-6)


def test_rocker_driver_default_sweep_is_its_feasible_range():
    chain = chaingraph.load(catalog_path("watts-indicator-mechanism"))
    m = solve(chain, steps=100)
    lo, hi = m.summary["input_range"]
    assert m["theta"][0] == lo and m["theta"][-1] == hi
    assert m.summary["full_turn"] is False
    assert m.summary["dead_centres"] == pytest.approx([lo, hi])
    # just inside the range assembles, just outside does not
    solve(chain, start=lo + 1e-6, stop=hi - 1e-6, steps=4)
    with pytest.raises(AssemblyError) as info:
        solve(chain, start=lo, stop=hi + 1.0, steps=4)
    assert info.value.feasible_range == pytest.approx((lo, hi))
    assert f"{lo:.6f}" in str(info.value) and f"{hi:.6f}" in str(info.value)


def test_rocker_range_by_hand():
    # four-bar driven by its rocker (80): its range ends where crank and coupler are in line
    chain = four_bar().with_mechanism("frame", "rocker")
    lo, hi = chaingraph.feasible_range(build_plan(chain))
    ends = []
    for r in (COUPLER + CRANK, COUPLER - CRANK):
        C = circle_circle((0.0, 0.0), r, (GROUND, 0.0), ROCKER, 1)
        ends.append(math.degrees(math.atan2(C[1] - 0.0, C[0] - GROUND)))
    # theta is measured from D (the pivot) to C, the rocker's other joint
    assert sorted([lo % 360, hi % 360]) == pytest.approx(sorted(e % 360 for e in ends), abs=1e-7)


def test_cli_sweep_past_range_exits_1():
    code, out, err = run_cli("solve", catalog_path("watts-indicator-mechanism"), "--from", "0",
                             "--to", "180")
    assert code == 1 and "can turn only from" in err and "Traceback" not in err


# -- higher-class groups (Newton) ------------------------------------------------------
@pytest.mark.parametrize("stem", ["beam-engine", "shaper-crank-and-slotted-lever",
                                  "oldhams-coupling", "crank-rocker-with-slider"])
def test_newton_agrees_with_closed_form(stem):
    assert_newton_agrees_with_closed_forms(chaingraph.load(catalog_path(stem)), ["group"],
                                           360.0, 181)


def stephenson_three():
    """A Stephenson chain with its binary link b3 fixed and ternary link t1 driven: the
    remaining four links form a triad, solved by Newton's method."""
    return chaingraph.load(catalog_path("stephenson-six-bar-chain")).with_mechanism("b4", "t2")


def test_stephenson_third_inversion_needs_newton_and_closes():
    chain = stephenson_three()
    plan = build_plan(chain)
    assert [s.kind for s in plan.steps] == ["single", "group"]   # the driver, then the triad
    m = solve(chain, start=plan.theta0, stop=plan.theta0 + 60, steps=600, summary=False)
    ev = evaluate(plan, m["theta"])
    assert ev.feasible.all() and residuals(plan, ev.pose).max() <= 1e-9 * plan.size
    # rates against central differences
    k = 300
    t = float(m["theta"][k])
    near = solve(chain, start=t - 1e-5, stop=t + 1e-5, steps=2, summary=False)
    dt = math.radians(1e-5)
    for name in ("x:B", "y:D", "x:A"):
        key = name[0]
        v = near[f"v{key}:{name[2:]}"]
        assert (near[name][2] - near[name][0]) / (2 * dt) == pytest.approx(v[1], rel=1e-5, abs=1e-6)
        a = near[f"a{key}:{name[2:]}"]
        assert (v[2] - v[0]) / (2 * dt) == pytest.approx(a[1], rel=1e-5, abs=1e-5)


def test_eight_bar_of_dyads():
    # a crank-rocker with two more dyads hung on it: eight links, three RRR dyads
    A, D = (0.0, 0.0), (100.0, 0.0)
    B = (40 * math.cos(math.radians(40)), 40 * math.sin(math.radians(40)))
    C = circle_circle(B, 120, D, 80)
    E = (60.0, 150.0)
    F = circle_circle(C, 90, E, 70)
    G = (F[0] + 150.0, F[1] - 40.0)
    H = circle_circle(F, 150, G, 100, -1)
    chain = Chain("eight-bar", (
        R("A", ["frame", "crank"], A), R("B", ["crank", "coupler"], B),
        R("C", ["coupler", "rocker", "link 5"], C), R("D", ["rocker", "frame"], D),
        R("F", ["link 5", "link 6", "link 7"], F), R("E", ["link 6", "frame"], E),
        R("H", ["link 7", "link 8"], H), R("G", ["link 8", "frame"], G)),
        mechanism=Mechanism("frame", "crank"))
    assert len(chain.links) == 8 and chaingraph.classify(chain).mobility == 1
    plan = build_plan(chain)
    assert [s.pattern for s in plan.steps] == ["WR", "RRR", "RRR", "RRR"]
    m = solve(chain, start=plan.theta0 - 5, stop=plan.theta0 + 5, steps=20)
    ev = evaluate(plan, np.array([plan.theta0]))
    assert residuals(plan, ev.pose).max() < 1e-12
    assert np.all(np.isfinite(m["omega:link 8"]))


# -- bad input ---------------------------------------------------------------------------
def test_bad_mechanisms_are_refused_with_a_reason():
    four = four_bar()
    with pytest.raises(MechanismError, match="not pinned to the fixed link"):
        build_plan(four, "frame", "coupler")
    five = chaingraph.load(catalog_path("five-link-chain"))
    with pytest.raises(MechanismError, match="mobility with '1' fixed is 2 .* so it needs 2 inputs"):
        build_plan(five, "1", "2")
    cam = chaingraph.load(catalog_path("cam-and-follower"))
    with pytest.raises(MechanismError, match="cam pair .* cannot be solved"):
        build_plan(cam, "frame", "cam")
    spatial = Chain("RSSR", (Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
                             Joint("B", "spherical", ("crank", "rod"), at=(1.0, 0.0)),
                             Joint("C", "spherical", ("rod", "rocker"), at=(2.0, 1.0)),
                             Joint("D", "R", ("rocker", "frame"), at=(3.0, 0.0))),
                    space="spatial")
    with pytest.raises(MechanismError, match="spatial"):
        build_plan(spatial, "frame", "crank")
    bare = Chain("no pose", tuple(Joint(j.id, j.kind, j.links) for j in four.joints))
    with pytest.raises(MechanismError, match="solving needs a drawn pose.*joints 'A', 'B', 'C', 'D' have no position"):
        build_plan(bare, "frame", "crank")
    with pytest.raises(MechanismError, match="'ground' is not a link"):
        build_plan(four, "ground", "crank")
    with pytest.raises(MechanismError, match="no driver"):
        build_plan(four.with_mechanism("frame"))


def test_block_whose_pin_is_off_its_sliding_line_moves_as_an_offset_slider():
    """A P joint's line may lie anywhere on the block (issue 10, item 7): a block whose
    pin B is 3 mm below the sliding line moves exactly as the pin of an offset slider
    crank with its line through B (offset e = 10)."""
    chain = slider_crank()
    joints = [j if j.id != "S" else P("S", ["frame", "slider"], (j.at[0] - 25.0, j.at[1] + 3.0), 0.0)
              for j in chain.joints]
    offset = Chain(chain.name, tuple(joints), mechanism=chain.mechanism, units="mm")
    a, rod, e = 40.0, 120.0, 10.0
    m = solve(offset, steps=72)
    th = np.radians(m["theta"])
    x = a * np.cos(th) + np.sqrt(rod ** 2 - (e - a * np.sin(th)) ** 2)
    assert np.allclose(m["x:B"], x, atol=1e-9) and np.allclose(m["y:B"], e, atol=1e-9)
    assert np.allclose(m["s:S"], x - x[0], atol=1e-9)
    exact = math.sqrt((rod + a) ** 2 - e ** 2) - math.sqrt((rod - a) ** 2 - e ** 2)
    assert m.summary["stroke"] == pytest.approx(exact, rel=1e-9)


@pytest.mark.parametrize("args, words", [
    (["--driver", "connecting rod"], "not pinned to the fixed link"),
    (["--fixed", "ground"], "'ground' is not a link"),
    (["--steps", "0"], "--steps: must be 1 or more"),
])
def test_cli_bad_solve_arguments_exit_2(args, words):
    code, out, err = run_cli("solve", catalog_path("beam-engine"), *args)
    assert code == 2 and words in err and "Traceback" not in err


def test_cli_cam_cannot_be_solved():
    code, out, err = run_cli("solve", catalog_path("cam-and-follower"), "--fixed", "frame",
                             "--driver", "cam")
    assert code == 2 and "cannot be solved" in err


def test_cli_solve_json_summary_keys(tmp_path):
    code, out, err = run_cli("solve", catalog_path("crank-and-slotted-lever-mechanism"),
                             "--json", "--csv", tmp_path / "m.csv", "--steps", "72")
    assert code == 0, err
    d = json.loads(out)
    assert set(d) == {"name", "fixed", "driver", "steps", "summary"} and d["steps"] == 72
    for key in ("stroke", "time_ratio", "forward_deg", "return_deg", "extremes",
                "transmission_angle", "dead_centres", "input_range"):
        assert key in d["summary"]
    assert round(d["summary"]["time_ratio"], 3) == 1.710
    assert len((tmp_path / "m.csv").read_text().splitlines()) == 74
    text = run_cli("solve", catalog_path("crank-and-slotted-lever-mechanism"))[1]
    assert "time ratio" in text and "1.70995" in text


def test_cli_plot_and_draw_write_svg(tmp_path):
    plot, draw = tmp_path / "motion.svg", tmp_path / "pose.svg"
    code, out, err = run_cli("solve", catalog_path("shaper-crank-and-slotted-lever"),
                             "--plot", plot, "--draw", draw, "--steps", "90")
    assert code == 0, err
    for path in (plot, draw):
        text = path.read_text()
        assert text.lstrip().startswith("<?xml") and "<svg" in text and len(text) > 5000
    assert "time ratio 2.0000" in plot.read_text() or "2.0000" in plot.read_text()


RRR_MECHANISMS = [p for p in SOLVABLE
                  if any(s.pattern == "RRR" for s in build_plan(chaingraph.load(p)).steps)]


@pytest.mark.parametrize("path", RRR_MECHANISMS, ids=[p.stem for p in RRR_MECHANISMS])
def test_rrr_fast_path_agrees_with_the_general_reduction(path, monkeypatch):
    import chaingraph.kinematics.rates as solver
    chain = chaingraph.load(path)
    plan = build_plan(chain)
    theta = np.linspace(plan.theta0, plan.theta0 + 5.0, 11)
    ev = evaluate(plan, theta)
    fast = rates(plan, ev.pose, 1.7, theta.size)
    monkeypatch.setattr(solver, "_POINT_DYADS", False)
    general = rates(plan, ev.pose, 1.7, theta.size)
    for table_fast, table_general in zip(fast[:2], general[:2]):
        for link in chain.links:
            for j in range(3):
                a = np.broadcast_to(table_fast[link][j], theta.shape)
                b = np.broadcast_to(table_general[link][j], theta.shape)
                assert np.allclose(a, b, rtol=1e-9, atol=1e-9), (link, j)


# -- figures within rounding of a round number are that number ---------------------------
def test_rounding_noise_is_not_printed_as_a_figure():
    """The shaper's crank is drawn along +x (atan2 gives 1.357e-14 degrees), the engine
    driven by its piston has coupler and crank in line at its ends (transmission angle
    1.5e-14): text and JSON say 0."""
    shaper = chaingraph.solve(chaingraph.load(catalog_path("shaper-crank-and-slotted-lever")))
    assert shaper.theta[0] == 0.0 and shaper.summary["input_range"] == [0.0, 360.0]
    engine = chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")),
                              inputs=["S"]).summary
    assert engine["transmission_angle"] == {"min": 0.0, "max": 180.0}
    assert engine["stroke"] == 80.0
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["solve", str(catalog_path("reciprocating-engine")), "--input", "S"]) == 0
    assert "transmission angle  0 to 180 degrees" in out.getvalue()
    assert "e-1" not in out.getvalue()


def test_a_motion_has_typed_accessors_over_its_columns():
    engine = chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")), steps=8)
    crank, pin, slide = engine.link("crank"), engine.joint("A"), engine.slide("S")
    # radians inside, degrees where the name says so (the CSV's angle column)
    assert np.array_equal(crank.angle_deg, engine["angle:crank"])
    assert np.allclose(crank.angle, np.radians(engine["angle:crank"]), rtol=0, atol=1e-15)
    assert crank.angle[0] == pytest.approx(-2 * math.pi / 3)          # drawn at -120 degrees
    assert crank.omega is engine["omega:crank"] and crank.alpha is engine["alpha:crank"]
    assert pin.x is engine["x:A"] and pin.ay is engine["ay:A"] and engine.point("A") is pin
    assert slide.s is engine["s:S"] and slide.a is engine["a:S"]
    assert engine.links["crank"] is crank and engine.slides["S"] is slide
    with pytest.raises(KeyError, match="'rod' is no link"):
        engine.link("rod")
    with pytest.raises(KeyError, match="'P' is no joint"):
        engine.joint("P")
    with pytest.raises(KeyError):
        engine["x:nowhere"]


def test_where_a_slide_runs_off_to_infinity_the_range_ends_on_every_path_alike():
    """An atlas chain (6 links, 4 sliding pairs) whose input turns towards an angle at
    which two guides turn parallel and a slide runs off to infinity: the range ends
    where a link is RUNAWAY_SIZES sizes out, the same from the drawn pose and from the
    limit search, so the summary's grid assembles to both ends; before, the trace walked thousands of
    steps towards that angle."""
    from chaingraph.kinematics.groups import RUNAWAY_SIZES
    chain = chaingraph.load(Path(__file__).parent.parent / "data" / "atlas-slides-run-off.toml")
    motion = chaingraph.solve(chain, steps=48)
    low, high = motion.summary.input_range
    assert -54.0 < high < -53.8 and -233.0 < low < -232.0
    plan = motion.plan
    out = max(float(np.abs(motion[c] - plan.origin[c[0] == "y"]).max())
              for c in motion.columns if c[:2] in ("x:", "y:"))
    # (the trace measures a link's reference point, the columns its joints: within a size)
    assert abs(out - RUNAWAY_SIZES * plan.size) < plan.size


def test_a_pose_that_is_not_a_number_is_named_not_told_residual_nan():
    """A pose whose residual is not a number (a step that degenerated) is refused with
    the joint whose place is undefined, never with "residual nan"."""
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    m = chaingraph.solve(chain, steps=4, summary=False)
    ev = evaluate(m.plan, m.theta)
    x, y, phi, c, s = ev.pose["connecting rod"]
    ev.pose["connecting rod"] = (np.where(np.arange(x.size) == 2, np.nan, x), y, phi, c, s)
    with pytest.raises(chaingraph.AssemblyError) as caught:
        check_poses(m.plan, ev.pose, ev.feasible)
    said = str(caught.value)
    assert "nan" not in said and "step 2" in said and "'connecting rod'" in said


# -- issue 36: typed results, radians inside, the CSV a view ------------------------------
@pytest.mark.parametrize("sign", [1, -1])
def test_the_typed_fields_against_the_closed_form_in_radians(sign):
    chain = four_bar(30.0, sign)
    motion = solve(chain, steps=72)
    theta = motion.theta
    C, beta, gamma, w3, w4, al3, al4 = four_bar_by_hand(theta, 2.5, sign)
    coupler, rocker, c = motion.link("coupler"), motion.link("rocker"), motion.joint("C")

    def same_direction(radians, degrees):
        return np.allclose(np.remainder(radians - np.radians(degrees) + math.pi,
                                        2 * math.pi) - math.pi, 0.0, atol=1e-11)
    assert same_direction(coupler.angle, beta) and same_direction(rocker.angle, gamma + 180.0)
    # continuous over the sweep, the first in (-pi, pi]
    assert -math.pi < coupler.angle[0] <= math.pi
    assert np.abs(np.diff(coupler.angle)).max() < math.pi / 2
    assert np.allclose(coupler.omega, w3, atol=1e-10) and np.allclose(rocker.alpha, al4, atol=1e-9)
    assert np.allclose(c.x + 1j * c.y, C, atol=1e-9)
    assert np.allclose(c.vx + 1j * c.vy, 1j * w4 * (C - GROUND), atol=1e-9)
    # the driver's angle is the input angle: its direction is theta itself
    assert same_direction(motion.link("crank").angle, theta)


def test_the_csv_is_a_view_of_the_typed_fields_in_its_order():
    chain = chaingraph.load(catalog_path("shaper-crank-and-slotted-lever"))
    m = solve(chain, steps=12)
    names = list(m.columns)
    expected = ["theta"]
    expected += [f"{k}:{x}" for x in chain.links for k in ("angle", "omega", "alpha")]
    expected += [f"{k}:{x}" for x in [j.id for j in chain.joints] + [p.id for p in chain.points]
                 for k in ("x", "y", "vx", "vy", "ax", "ay")]
    expected += [f"{k}:{j.id}" for j in chain.joints if j.kind == "P" for k in ("s", "v", "a")]
    assert names == expected
    assert m.to_csv().splitlines()[0].split(",") == names
    rows = m.rows()
    assert len(rows) == m.steps + 1 and len(rows[5]) == len(names)
    for name, values in m.columns.items():
        assert np.array_equal(m[name], values, equal_nan=True)
        assert [r[names.index(name)] for r in rows] == pytest.approx(values.tolist(), nan_ok=True)
    assert np.array_equal(m["angle:ram"], m.link("ram").angle_deg)
    assert m["s:G"] is m.slide("G").s and m["vy:P"] is m.point("P").vy


def test_rates_scale_with_the_input_speed_and_positions_do_not():
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    slow, fast = solve(chain, steps=8, omega=1.0), solve(chain, steps=8, omega=3.0)
    for name in ("connecting rod", "crank"):
        a, b = slow.link(name), fast.link(name)
        assert np.array_equal(a.angle, b.angle)
        assert np.allclose(b.omega, 3 * a.omega, rtol=1e-12)
        assert np.allclose(b.alpha, 9 * a.alpha, rtol=1e-12, atol=1e-12)
    a, b = slow.joint("B"), fast.joint("B")
    assert np.array_equal(a.x, b.x) and np.allclose(b.vx, 3 * a.vx) and np.allclose(b.ax, 9 * a.ax)
    assert np.allclose(fast.slide("S").a, 9 * slow.slide("S").a)


def test_at_a_rocker_s_limits_the_rates_are_unknown_and_what_is_fixed_stays_zero():
    m = solve(chaingraph.load(catalog_path("watts-indicator-mechanism")), steps=10)
    assert not m.summary.full_turn
    moving = [x for x in m.links.values() if x.name != m.fixed]
    for link in moving:
        assert np.isnan(link.omega[[0, -1]]).all() and np.isfinite(link.omega[1:-1]).all()
    frame = m.link(m.fixed)
    assert np.array_equal(frame.omega, np.zeros(11)) and np.array_equal(frame.alpha, np.zeros(11))


def test_motions_joined_run_one_after_the_other():
    chain = chaingraph.load(catalog_path("beam-engine"))
    a = solve(chain, start=0.0, stop=90.0, steps=3, summary=False)
    b = solve(chain, start=90.0, stop=180.0, steps=3, summary=False)
    both = a.joined(b)
    assert both.theta.tolist() == a.theta.tolist() + b.theta.tolist()
    assert both.joint("C").y.tolist() == a.joint("C").y.tolist() + b.joint("C").y.tolist()
    assert both.link("lever").alpha.size == 8 and both.states is None and a.states is not None
    assert both.to_csv().count("\n") == 9 and both.steps == 7


def test_one_link_motion_and_the_single_pose_s_link_state():
    from chaingraph.kinematics.pose import LinkState, pose_motion
    assert chaingraph.kinematics.LinkMotion is chaingraph.kinematics.motion.LinkMotion
    assert not hasattr(chaingraph.kinematics.pose, "LinkMotion")
    engine = chaingraph.load(catalog_path("reciprocating-engine"))
    state = pose_motion(engine, at=60.0)
    sweep = solve(engine, start=60.0, stop=60.0, steps=1, summary=False)
    rod = state.links["connecting rod"]
    assert isinstance(rod, LinkState)
    assert rod.omega == sweep.link("connecting rod").omega[0]
    assert state.positions["B"] == (sweep.joint("B").x[0], sweep.joint("B").y[0])
    assert state.slides["S"].speed == sweep.slide("S").v[0]
