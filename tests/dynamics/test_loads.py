"""Loads that follow the motion: the textbook's four-stroke engine by its own method, a
shaper cutting on its forward stroke, a resisting force and a table by hand, a load's
720-degree cycle, the summary over a rocking input's regular poses, every bad load."""

from __future__ import annotations

import csv
import io
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

import chaingraph
from chaingraph import Load
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli
from .conftest import L, R, slider_crank as engine

ROOT = Path(__file__).resolve().parents[2]
FOUR_STROKE = ROOT / "examples" / "four-stroke-engine.toml"


def piston_x(t, r, l):
    """The piston's distance from the crank's shaft, and its first and second
    derivatives in the crank angle t (radians): closed forms."""
    s, c = np.sin(t), np.cos(t)
    root = np.sqrt(l * l - r * r * s * s)
    x = r * c + root
    dx = -r * s - r * r * s * c / root
    ddx = -r * c - r * r * np.cos(2 * t) / root - r ** 4 * s * s * c * c / root ** 3
    return x, dx, ddx


# -- the textbook's four-stroke engine ---------------------------------------------------
def test_the_four_stroke_engine_by_the_textbook_method():
    """Piston effort = gas force minus the reciprocating parts' inertia force; crank
    effort from it; the turning-moment diagram over 720 degrees; the mean torque, the
    fluctuation of energy and the flywheel, all computed here from the file's data
    alone (closed forms, adaptive quadrature, roots by Brent's method)."""
    doc = tomllib.loads(FOUR_STROKE.read_text())
    joints = {j["id"]: j for j in doc["joints"]}
    r = math.hypot(*joints["A"]["at"]) / 1000
    l = math.dist(joints["A"]["at"], joints["B"]["at"]) / 1000
    m = next(x["mass"] for x in doc["links"] if x["name"] == "piston")
    w = doc["mechanism"]["omega"]
    gas = next(x for x in doc["loads"] if "pressure" in x)
    deg, p = np.array(gas["pressure"]).T
    area, cycle = gas["area"], gas["cycle"]

    def crank_effort(t):                                # the turning moment the engine gives
        d = np.mod(np.degrees(t), cycle)
        pressure = np.interp(d, np.r_[deg, cycle], np.r_[p, p[0]])
        _, dx, ddx = piston_x(t, r, l)
        piston_effort = pressure * area + m * ddx * w * w   # towards the crank
        return -piston_effort * dx

    knots = np.radians(np.r_[deg, cycle])
    pieces = list(zip(knots[:-1], knots[1:]))
    work = sum(quad(crank_effort, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in pieces)
    t_mean = work / math.radians(cycle)
    # the energy swings: the work of (T - T_mean) at every crossing of the mean line
    fine = np.radians(np.linspace(0.0, cycle, 7201))
    g = crank_effort(fine) - t_mean
    crossings = [brentq(lambda t: crank_effort(t) - t_mean, fine[k], fine[k + 1], xtol=1e-14)
                 for k in np.nonzero(np.sign(g[:-1]) * np.sign(g[1:]) < 0)[0]]
    ends = sorted(set([0.0, math.radians(cycle)] + crossings + list(knots)))
    swing, total = [0.0], 0.0
    for a, b in zip(ends[:-1], ends[1:]):
        total += quad(lambda t: crank_effort(t) - t_mean, a, b, epsabs=0, epsrel=1e-12)[0]
        swing.append(total)
    de = max(swing) - min(swing)
    inertia = de / (w * w * 0.02)

    chain = chaingraph.load(FOUR_STROKE)
    f = chaingraph.forces(chain, steps=360, speed_fluctuation=0.02)
    assert f.motion.theta[0] == 0.0 and f.motion.theta[-1] == cycle   # the load's cycle
    load = next(c for c in f.pose(0).couples if c.what == "load")
    assert load.link == "crank" and -load.value == pytest.approx(t_mean, rel=1e-9)
    assert f.load_torque == load.value
    # the effort is the load torque minus the engine's turning moment, step by step
    u = np.radians(f.motion.theta)
    want = t_mean - crank_effort(u)
    assert np.allclose(f["effort:O"], want, rtol=0, atol=1e-9 * np.abs(want).max())
    assert f.summary.mean_effort == pytest.approx(0.0, abs=1e-9 * t_mean)
    assert f.summary.energy_fluctuation == pytest.approx(de, rel=1e-9)
    assert f.summary.flywheel.inertia == pytest.approx(inertia, rel=1e-9)
    assert f.summary.flywheel.omega == w
    # at one pose the same loads (the mean torque found over the cycle)
    one = chaingraph.forces(chain, at=float(f.motion.theta[37]))
    assert one.effort() == pytest.approx(f["effort:O"][37], rel=1e-9)


def test_a_cycle_of_720_degrees_sweeps_two_turns_and_repeats_after_it():
    chain = chaingraph.load(FOUR_STROKE)
    f = chaingraph.forces(chain, steps=144, static=True)
    assert f.steps == 144 and f.motion.theta[0] == 0.0 and f.motion.theta[-1] == 720.0
    later = chaingraph.forces(chain, start=720.0, stop=1440.0, steps=144, static=True)
    assert np.allclose(later["effort:O"], f["effort:O"], rtol=1e-9, atol=1e-9)
    # a turn later the crank is where it was, the gas force is not: the strokes differ
    half = 72
    assert not np.allclose(f["effort:O"][:half], f["effort:O"][half:2 * half], rtol=1e-3)


# -- a shaper cutting on its forward stroke ----------------------------------------------
@pytest.mark.parametrize("name", ["shaper-crank-and-slotted-lever",
                                  "whitworth-quick-return-with-ram"])
@pytest.mark.parametrize("static", [True, False])
def test_a_shaper_cutting_on_its_forward_stroke_does_the_work_of_one_cut(name, static):
    chain = chaingraph.load(catalog_path(name))
    cut = next(x for x in chain.loads if x.resist is not None)
    assert cut.stroke == "forward"
    motion = chaingraph.solve(chain)
    f = chaingraph.forces(chain, omega=5.0, static=static)
    stroke = motion.summary.stroke / 1000                       # m
    assert f.summary.mean_effort * 2 * math.pi == pytest.approx(cut.resist * stroke, rel=1e-9)
    # the cutting force acts on the slow stroke only: the steps where it acts, against
    # the ram's motion, over those where the ram moves back, are the time ratio
    force = next(a[3][0] for a in f.solution.applied if a[1] == "load")
    ram = motion.point(cut.at)
    moving = np.abs(ram.vx) > 1e-9 * np.abs(ram.vx).max()
    on = moving & (np.abs(force) > 0)
    assert np.all(force[on] * ram.vx[on] < 0)
    assert np.all(np.abs(force[on]) == pytest.approx(cut.resist))
    ratio = on[:-1].sum() / (moving[:-1] & ~on[:-1]).sum()
    assert ratio == pytest.approx(motion.summary.time_ratio, abs=2 * 360 / on.size)


# -- a resisting force and a table, by hand ----------------------------------------------
@pytest.mark.parametrize("theta", [30.0, 100.0, 200.0, 320.0])
def test_resist_against_hand_equilibrium(theta):
    chain = engine(Load("piston", "B", resist=800.0))
    f = chaingraph.forces(chain, at=theta, static=True)
    t = math.radians(theta)
    r, l = R / 1000, L / 1000
    _, dx, _ = piston_x(t, r, l)
    # the piston's velocity is dx w (w > 0): the force is -800 sign(dx) along x, and
    # the crank holds minus its virtual work, 800 |dx|
    assert f.effort() == pytest.approx(800.0 * abs(dx), rel=1e-9)
    phi = math.asin(r * math.sin(t) / l)
    assert abs(f.reaction("S").normal) == pytest.approx(800.0 * abs(math.tan(phi)), rel=1e-9)
    assert f.power_balance == pytest.approx(0.0, abs=1e-9)


def test_resist_with_friction_by_hand_equilibrium_of_the_piston():
    mu, theta = 0.2, 60.0
    f = chaingraph.forces(engine(Load("piston", "B", resist=800.0), friction=mu),
                          at=theta, static=True)
    t = math.radians(theta)
    r, l = R / 1000, L / 1000
    phi = math.asin(r * math.sin(t) / l)
    # the piston moves towards the crank (dx < 0): the resisting force +800 along x and
    # friction +mu |N| along x; the rod's thrust C along the rod (angle phi below x)
    # balances both: C cos(phi) = 800 + mu C sin(phi)
    c = 800.0 / (math.cos(phi) - mu * math.sin(phi))
    _, dx, _ = piston_x(t, r, l)
    assert dx < 0
    assert abs(f.reaction("S").normal) == pytest.approx(c * math.sin(phi), rel=1e-9)
    assert f.reaction("B", "rod").force[0] is not None
    bx = f.reaction("B").force
    assert math.hypot(*bx) == pytest.approx(c, rel=1e-9)


TABLE = ((-60.0, 0.0), (-20.0, 3000.0), (0.0, 1000.0), (30.0, -500.0))


@pytest.mark.parametrize("stroke", [None, "out", "in"])
def test_a_table_against_the_slide_by_interpolation_by_hand(stroke):
    chain = engine(Load("piston", "B", along="S", table=TABLE, stroke=stroke))
    f = chaingraph.forces(chain, steps=72, static=True)
    motion = f.motion
    s = motion.slide("S").s                        # from the drawn pose, mm
    v = motion.slide("S").v
    xs, fs = np.array(TABLE).T
    force = np.interp(s, xs, fs)                   # held at the table's ends beyond it
    if stroke == "out":
        force = np.where(v > 0, force, 0.0)
    elif stroke == "in":
        force = np.where(v < 0, force, 0.0)
    _, dx, _ = piston_x(np.radians(motion.theta), R / 1000, L / 1000)
    want = -force * dx
    got = f["effort:O"]
    ok = np.abs(v) > 1e-9                          # (the stroke's ends: either side)
    assert np.allclose(got[ok], want[ok], rtol=0, atol=1e-9 * np.abs(want).max())
    assert np.abs(f.solution.power[ok]).max() < 1e-9


def test_a_table_against_the_input_by_interpolation_by_hand():
    table = tuple((math.radians(d), v) for d, v in ((0.0, 500.0), (90.0, -800.0),
                                                    (200.0, 100.0)))
    chain = engine(Load("piston", "B", along="S", table=table, against="input"))
    f = chaingraph.forces(chain, start=-30.0, stop=390.0, steps=84, static=True)
    d = np.mod(f.motion.theta, 360.0)
    # periodic over the turn: from 200 degrees back to 360 + 0
    force = np.interp(d, [0.0, 90.0, 200.0, 360.0], [500.0, -800.0, 100.0, 500.0])
    _, dx, _ = piston_x(np.radians(f.motion.theta), R / 1000, L / 1000)
    want = -force * dx
    assert np.allclose(f["effort:O"], want, rtol=0, atol=1e-9 * np.abs(want).max())


def test_the_mean_torque_with_friction_makes_the_mean_effort_zero():
    chain = engine(Load("piston", "B", resist=800.0), Load("crank", torque="mean"),
                   friction=0.15)
    f = chaingraph.forces(chain, steps=90, static=True)
    assert f.summary.mean_effort == pytest.approx(0.0, abs=1e-9 * 800 * R / 1000)
    free = chaingraph.forces(engine(Load("piston", "B", resist=800.0), friction=0.15),
                             steps=90, static=True)
    load = next(c for c in f.pose(0).couples if c.what == "load")
    # the crank carries the torque directly: the mean effort without it, the torque
    assert load.value == pytest.approx(free.summary.mean_effort, rel=1e-9)
    assert free.summary.mean_effort > 0


# -- a rocking input: the summary over the regular poses ---------------------------------
ROCKER = """name = "crank-rocker driven by its rocker"
units = "mm"
[[joints]]
id = "A"
kind = "R"
links = ["frame", "crank"]
at = [0.0, 0.0]
[[joints]]
id = "B"
kind = "R"
links = ["crank", "coupler"]
at = [%r, %r]
[[joints]]
id = "C"
kind = "R"
links = ["coupler", "rocker"]
at = [%r, %r]
[[joints]]
id = "D"
kind = "R"
links = ["rocker", "frame"]
at = [100.0, 0.0]
[mechanism]
fixed = "frame"
driver = "rocker"
[[links]]
name = "coupler"
mass = 1.2
inertia = 0.002
[[links]]
name = "crank"
mass = 0.4
[forces]
gravity = [0.0, -9.81]
[[loads]]
on = "crank"
torque = 3.0
"""


def rocker_file(tmp_path):
    b = np.array([30 * math.cos(math.radians(60)), 30 * math.sin(math.radians(60))])
    d = np.array([100.0, 0.0])
    # C: 100 from B, 80 from D, above the line BD
    dist = np.linalg.norm(d - b)
    a = (100 ** 2 - 80 ** 2 + dist ** 2) / (2 * dist)
    h = math.sqrt(100 ** 2 - a * a)
    u = (d - b) / dist
    c = b + a * u + h * np.array([-u[1], u[0]])
    path = tmp_path / "rocker.toml"
    path.write_text(ROCKER % (float(b[0]), float(b[1]), float(c[0]), float(c[1])))
    return path


def test_a_rocking_input_summarised_over_its_regular_poses(tmp_path):
    path = rocker_file(tmp_path)
    out = tmp_path / "f.csv"
    status, text, err = run_cli("forces", path, "--steps", "60", "--omega", "2",
                                "--csv", out, "--json")
    assert status == 0, err
    import json
    summary = json.loads(text)["summary"]
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    effort = np.array([float(r["effort:D"]) for r in rows])
    theta = np.array([float(r["theta"]) for r in rows])
    dead = ~np.isfinite(effort)
    assert dead[0] and dead[-1] and dead.sum() < 5          # the rocker's two ends
    good = effort[~dead]
    stats = summary["efforts"]["D"]
    assert stats["min"] == pytest.approx(good.min(), rel=1e-12)
    assert stats["max"] == pytest.approx(good.max(), rel=1e-12)
    assert stats["mean"] == pytest.approx(good.mean(), rel=1e-9, abs=1e-12 * abs(good).max())
    assert stats["rms"] == pytest.approx(math.sqrt(np.mean(good ** 2)), rel=1e-12)
    for joint in "ABCD":
        fx = np.array([float(r[f"Fx:{joint}"]) for r in rows])[~dead]
        fy = np.array([float(r[f"Fy:{joint}"]) for r in rows])[~dead]
        assert summary["reactions"][joint]["max"] == pytest.approx(np.hypot(fx, fy).max(),
                                                                   rel=1e-12)
    assert summary["dead_centres"] == pytest.approx(theta[dead].tolist(), rel=1e-12)
    status, text, err = run_cli("forces", path, "--steps", "60", "--omega", "2")
    assert "dead centres" in text and "unbounded" not in text.split("dead centres")[0]


# -- every bad load: one line, exit 2 ----------------------------------------------------
BAD = {
    "table not increasing": ('along = "S"\ntable = [[0.0, 1.0], [10.0, 2.0], [10.0, 3.0]]',
                             "increasing"),
    "cycle not a multiple of 360": ('along = "S"\ntable = [[0.0, 1.0]]\nagainst = "input"\n'
                                    'cycle = 500', "whole number of turns"),
    "resist negative": ("resist = -200.0", "'resist' must be"),
    "along an R joint": ('along = "B"\ntable = [[0.0, 1.0]]', "must name a P joint"),
    "pressure without area": ('along = "S"\npressure = [[0.0, 1e5]]', "needs 'area'"),
    "stroke of the wrong kind": ('resist = 100.0\nstroke = "out"', "'stroke'"),
    "a table without along": ("table = [[0.0, 1.0]]", "needs 'along'"),
    "torque neither number nor mean": ('torque = "average"', "'torque'"),
    "against unknown": ('along = "S"\ntable = [[0.0, 1.0]]\nagainst = "time"', "'against'"),
    "table rows not pairs": ('along = "S"\ntable = [[0.0, 1.0, 2.0]]', "'table'"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_every_bad_load_gets_one_line_and_exit_2(case, tmp_path):
    body, words = BAD[case]
    text = (FOUR_STROKE.read_text().split("[[loads]]")[0]
            + '[[loads]]\non = "piston"\nat = "B"\n' + body + "\n")
    path = tmp_path / "bad.toml"
    path.write_text(text)
    status, out, err = run_cli("forces", path)
    assert status == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and words in err, err


def test_a_table_against_the_input_of_a_p_input_is_refused_in_one_line(tmp_path):
    text = FOUR_STROKE.read_text().replace('driver = "crank"', 'inputs = ["S"]')
    path = tmp_path / "bad.toml"
    path.write_text(text)
    status, out, err = run_cli("forces", path)
    assert status == 2 and len(err.strip().splitlines()) == 1 and "R input" in err, err


def test_loads_round_trip_through_the_chain_file():
    chain = chaingraph.load(FOUR_STROKE)
    again = chaingraph.loads(chaingraph.dumps(chain))
    assert again.loads == chain.loads
    renamed = chain.relabelled(joints={"S": "guide"})
    assert next(x for x in renamed.loads if x.along).along == "guide"


# -- the summary's shape and the small things --------------------------------------------
def test_the_energy_fluctuation_does_not_depend_on_the_sweep_s_steps():
    chain = chaingraph.load(catalog_path("shaper-crank-and-slotted-lever"))
    coarse = chaingraph.forces(chain, omega=5.0, steps=40).summary
    fine = chaingraph.forces(chain, omega=5.0, steps=1000).summary
    assert coarse.energy_fluctuation == pytest.approx(fine.energy_fluctuation, rel=1e-12)
    assert coarse.mean_effort == pytest.approx(fine.mean_effort, rel=1e-12)


def test_a_flywheel_over_two_turns_is_that_of_one_and_a_part_turn_says_why_not(tmp_path):
    import json
    path = catalog_path("shaper-crank-and-slotted-lever")
    one = json.loads(run_cli("forces", path, "--omega", "5", "--speed-fluctuation", "0.05",
                             "--json")[1])
    status, out, err = run_cli("forces", path, "--omega", "5", "--speed-fluctuation", "0.05",
                               "--from", "60", "--to", "780", "--steps", "720", "--json")
    two = json.loads(out)
    assert status == 0
    assert set(two["summary"]["flywheel"]) == {"speed_fluctuation", "inertia", "omega"}
    assert two["summary"]["flywheel"]["inertia"] == pytest.approx(
        one["summary"]["flywheel"]["inertia"], rel=1e-9)
    status, out, err = run_cli("forces", path, "--omega", "5", "--speed-fluctuation", "0.05",
                               "--from", "60", "--to", "500")
    assert status == 0 and "flywheel" not in out.split("note:")[0]
    assert "whole cycle" in out and "440 degrees" in out


def test_a_p_input_s_csv_names_its_input_column_by_what_it_holds():
    steady = engine(Load("piston", "B", (-1000.0, 0.0)))
    f = chaingraph.forces(steady, inputs=["S"], steps=4, static=True)
    # the slide (mm) in its input: column, no "theta" holding millimetres
    assert list(f.columns)[:2] == ["input:S", "Fx:O"] and "theta" not in f.columns
    assert "theta" in chaingraph.forces(steady, steps=4, static=True).columns


def test_the_plot_option_says_what_it_plots():
    status, out, err = run_cli("forces", "--help")
    assert status == 0 and "(one input)" not in out and "each input's effort" in out


def test_a_mean_torque_where_it_cannot_be_is_one_line_exit_2(tmp_path):
    base = FOUR_STROKE.read_text().split("# The machine's load")[0]
    path = tmp_path / "frame.toml"
    path.write_text(base + '[[loads]]\non = "frame"\ntorque = "mean"\n')
    status, out, err = run_cli("forces", path, "--steps", "8")
    assert status == 2 and len(err.strip().splitlines()) == 1 and "fixed link" in err, err
    rocker = rocker_file(tmp_path)
    rocker.write_text(rocker.read_text().replace("torque = 3.0", 'torque = "mean"'))
    for args in (("--steps", "8"), ("--at", "100")):
        status, out, err = run_cli("forces", rocker, *args)
        assert status == 2 and len(err.strip().splitlines()) == 1 and "whole cycle" in err, err


def test_a_cutting_stroke_on_a_rocking_input_is_its_forward_swing(tmp_path):
    rocker = rocker_file(tmp_path)
    rocker.write_text(rocker.read_text().replace(
        "torque = 3.0", 'resist = 50.0\nat = "B"\nstroke = "forward"'))
    f = chaingraph.forces(chaingraph.load(rocker), steps=40, static=True)
    assert np.nanmax(np.abs(f.solution.power)) < 1e-9
    one = chaingraph.forces(chaingraph.load(rocker), at=float(f.motion.theta[13]), static=True)
    assert one.effort() == pytest.approx(f["effort:D"][13], rel=1e-9)
