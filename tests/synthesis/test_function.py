"""Function generation: precision points matched by the written file, solved by solve;
the structural error recomputed independently; certification's defects; bad tasks."""

import dataclasses
import json
import math

import numpy as np
import pytest

import chaingraph
from chaingraph import DesignError
from chaingraph.files import dumps, loads
from chaingraph.geometry import circle_circle
from chaingraph.model.chain import Chain, Joint, Mechanism, Point
from chaingraph.synthesis import (
    FunctionTargets,
    PointTargets,
    Rejected,
    certify,
    function,
)
from chaingraph.synthesis.expression import parse_expression
from chaingraph.synthesis.function_generation import freudenstein, slider_crank_closed_form
from chaingraph.synthesis.task import precision_x

from ..conftest import run_cli

LOG = dict(function="log10(x)", x=(1.0, 2.0), swing=(60.0, 90.0))


def _task_angles(table, xs):
    """(input, output) the task asks for at xs, from a solution file's [task]."""
    f = parse_expression(table["function"])
    (a, b), (turn, out), (t0, o0) = table["x"], table["swing"], table["start"]
    ya, yb = float(f(a)), float(f(b))
    xs = np.asarray(xs, dtype=float)
    return t0 + turn * (xs - a) / (b - a), o0 + out * (f(xs) - ya) / (yb - ya)


def _rocker(motion):
    """The rocker's angle, D to C, unwrapped (degrees)."""
    return np.degrees(np.unwrap(np.arctan2(motion["y:C"] - motion["y:D"],
                                           motion["x:C"] - motion["x:D"])))


def _near(angle, want):
    return angle + 360.0 * np.round((want - angle) / 360.0)


@pytest.fixture(scope="module")
def log_files(tmp_path_factory):
    """design function for log10 (60 and 90 degrees of swing), written with --out."""
    out = tmp_path_factory.mktemp("log10")
    code, stdout, err = run_cli("design", "function", "--function", "log10(x)", "--x", "1:2",
                                "--swing", "60:90", "--json", "--out", out)
    assert code == 0, err
    return json.loads(stdout), out


def test_log10_three_chebyshev_points_hit_by_the_written_file(log_files):
    result, out = log_files
    assert result["solutions"] and result["task"]["spacing"] == "chebyshev"
    xs = precision_x((1.0, 2.0), 3, "chebyshev")
    for sol in result["solutions"]:
        chain = chaingraph.load(out / f"solution-{sol['rank']}.toml")
        assert chain.task["kind"] == "function"
        thetas, wanted = _task_angles(chain.task, xs)
        assert sol["reached_at"] == pytest.approx(list(thetas), abs=1e-12)
        for theta, psi in zip(thetas, wanted):
            m = chaingraph.solve(chain, start=float(theta), stop=float(theta), steps=1,
                                 summary=False)
            got = _rocker(m)[0]
            assert abs(_near(got, psi) - psi) < 1e-9


def test_log10_structural_error_sampled_independently(log_files):
    result, out = log_files
    for sol in result["solutions"][:2]:
        chain = chaingraph.load(out / f"solution-{sol['rank']}.toml")
        (t0, _), turn = chain.task["start"], chain.task["swing"][0]
        m = chaingraph.solve(chain, start=t0, stop=t0 + turn, steps=5000, summary=False)
        xs = 1.0 + (m["theta"] - t0) / turn
        _, wanted = _task_angles(chain.task, xs)
        got = _rocker(m)
        err = _near(got[0], wanted[0]) - got[0] + got - wanted
        assert float(np.max(np.abs(err))) == pytest.approx(sol["error"]["max"], rel=1e-4)
        assert float(np.sqrt(np.mean(err ** 2))) == pytest.approx(sol["error"]["rms"],
                                                                 rel=1e-2)
        lo, hi = sol["transmission_angle"]
        assert 30.0 <= lo <= hi <= 150.0


def test_ranked_best_first_with_the_contract_keys(log_files):
    result, _ = log_files
    errors = [s["error"]["max"] for s in result["solutions"]]
    assert errors == sorted(errors)
    assert [s["rank"] for s in result["solutions"]] == list(range(1, len(errors) + 1))
    assert set(result) == {"task", "solutions", "rejected", "searched"}
    assert set(result["solutions"][0]) == {"rank", "names", "atlas", "mechanism", "error",
                                           "reached_at", "transmission_angle", "grashof",
                                           "input"}
    assert "Four-bar chain" in result["solutions"][0]["names"]
    doc = result["solutions"][0]["mechanism"]
    assert chaingraph.files.from_document(doc).task == doc["task"]


def test_freudenstein_gives_back_a_known_four_bar():
    """Three poses of a four-bar (a 40, b 120, c 80, d 100), by the circle intersection:
    the linear solve gives d/a, d/c and R3, hence the lengths."""
    a, b, c, d = 40.0, 120.0, 80.0, 100.0
    t = np.radians([20.0, 75.0, 130.0])
    (mx, my), (nx, ny), raw = circle_circle((a * np.cos(t), a * np.sin(t)), b, (d, 0.0), c)
    psi = np.arctan2(my + np.sqrt(raw) * ny, mx + np.sqrt(raw) * nx - d)
    r1, r2, r3 = freudenstein(t, psi)
    assert (d / r1, d / r2) == pytest.approx((a, c), rel=1e-12)
    assert math.sqrt(a * a + c * c + d * d - 2 * a * c * r3) == pytest.approx(b, rel=1e-12)


def test_slider_crank_three_points_exact(tmp_path):
    found = function(function="x**2", x=(0, 1), swing=(90, 40), kind="slider-crank")
    assert found.solutions
    for sol in found.solutions:
        path = tmp_path / f"s{sol.rank}.toml"
        chaingraph.save(sol.mechanism, path)
        chain = chaingraph.load(path)
        xs = precision_x((0, 1), 3, "chebyshev")
        thetas, wanted = _task_angles(chain.task, xs)
        size = max(sol.dimensions["crank"], sol.dimensions["rod"])
        for theta, s in zip(thetas, wanted):
            m = chaingraph.solve(chain, start=float(theta), stop=float(theta), steps=1,
                                 summary=False)
            assert abs(float(m["x:C"][0]) - s) < 1e-9 * size
        # the closed form gives back the lengths from the three poses
        r, l2, e = slider_crank_closed_form(np.radians(thetas), wanted)
        assert (r, math.sqrt(l2), e) == pytest.approx(
            (sol.dimensions["crank"], sol.dimensions["rod"], sol.dimensions["offset"]),
            rel=1e-9, abs=1e-9 * size)


def test_slider_crank_scales_with_the_slide():
    """Invariance: the task's slide scaled by k scales the slider crank and its error."""
    one = function(function="sqrt(x)", x=(1, 4), swing=(120, 30), kind="slider-crank",
                   solutions=1)
    three = function(function="sqrt(x)", x=(1, 4), swing=(120, 90), kind="slider-crank",
                     solutions=1)
    a, b = one.solutions[0], three.solutions[0]
    for key in ("crank", "rod", "offset", "output_start"):
        assert b.dimensions[key] == pytest.approx(3 * a.dimensions[key], rel=1e-9, abs=1e-9)
    assert b.dimensions["input_start"] == pytest.approx(a.dimensions["input_start"])
    assert b.error.max == pytest.approx(3 * a.error.max, rel=1e-6)


def test_more_points_fit_the_whole_range_better_than_three():
    three = function(**LOG, solutions=1)
    start = (three.solutions[0].dimensions["input_start"],
             three.solutions[0].dimensions["output_start"])
    fixed3 = function(**LOG, start=start, solutions=1)
    fitted = function(**LOG, start=start, points=6, solutions=1)
    assert fitted.solutions[0].error.max < fixed3.solutions[0].error.max
    assert len(fitted.solutions[0].reached_at) == 6


def _four_bar(theta, mode, point=None):
    """The four-bar a 40, b 120, c 80, d 100 drawn at crank angle theta, its coupler's
    pin C in ``mode``; with a coupler point P at ``point`` (in B's frame along BC)."""
    t = math.radians(theta)
    bx, by = 40 * math.cos(t), 40 * math.sin(t)
    (mx, my), (nx, ny), raw = circle_circle((bx, by), 120.0, (100.0, 0.0), 80.0)
    c = (mx + mode * math.sqrt(raw) * nx, my + mode * math.sqrt(raw) * ny)
    points = ()
    if point is not None:
        ux, uy = (c[0] - bx) / 120, (c[1] - by) / 120
        points = (Point("P", "coupler", (bx + point[0] * ux - point[1] * uy,
                                         by + point[0] * uy + point[1] * ux)),)
    return Chain("four-bar", (Joint("A", "R", ("frame", "crank"), at=(0.0, 0.0)),
                              Joint("B", "R", ("crank", "coupler"), at=(bx, by)),
                              Joint("C", "R", ("coupler", "rocker"), at=c),
                              Joint("D", "R", ("rocker", "frame"), at=(100.0, 0.0))),
                 points=points, units="mm", mechanism=Mechanism("frame", "crank", 1.0, "rocker"))


def _rocker_at(theta, mode):
    c = _four_bar(theta, mode).joint("C").at
    return math.degrees(math.atan2(c[1], c[0] - 100.0))


def test_certification_rejects_a_circuit_defect():
    """Targets 2 and 3 on the other circuit from the first: the solver, tracking the
    drawn pose's circuit, does not meet them."""
    inputs = (30.0, 60.0, 90.0)
    outputs = (_rocker_at(30, 1), _rocker_at(60, -1), _rocker_at(90, -1))
    targets = FunctionTargets(inputs, outputs, "rocker", (30.0, 90.0), lambda t: t * 0)
    found = certify(_four_bar(30, 1), targets)
    assert isinstance(found, Rejected) and found.reason == "circuit defect"
    assert "target 2" in found.detail
    same = FunctionTargets(inputs, tuple(_rocker_at(t, 1) for t in inputs), "rocker",
                           (30.0, 90.0), lambda t: t * 0)
    assert not isinstance(certify(_four_bar(30, 1), same, min_transmission=0), Rejected)


def test_certification_rejects_an_order_defect():
    """Four points of a crank's coupler curve, given out of order: passed, but not in
    order as the crank turns one way."""
    chain = _four_bar(0, 1, point=(60.0, 30.0))

    def at(theta):
        m = chaingraph.solve(chain, start=theta, stop=theta, steps=1, summary=False)
        return float(m["x:P"][0]), float(m["y:P"][0])
    in_order = PointTargets(tuple(at(t) for t in (0.0, 90.0, 180.0, 270.0)), "P")
    good = certify(chain, in_order, min_transmission=0)
    assert not isinstance(good, Rejected)
    assert good.reached_at == pytest.approx((0.0, 90.0, 180.0, 270.0), abs=1e-6)
    assert good.error_max < 1e-9 * 200
    shuffled = PointTargets(tuple(at(t) for t in (0.0, 180.0, 90.0, 270.0)), "P")
    found = certify(chain, shuffled, min_transmission=0)
    assert isinstance(found, Rejected) and found.reason == "order defect"


def test_the_task_table_is_kept_and_ignored_by_solve():
    chain = _four_bar(30, 1)
    task = {"kind": "function", "function": "log10(x)", "x": [1.0, 2.0]}
    with_task = loads(dumps(dataclasses.replace(chain, task=task)))
    assert with_task.task == task and "[task]" in dumps(with_task)
    a = chaingraph.solve(with_task, steps=8)
    b = chaingraph.solve(chain, steps=8)
    assert np.array_equal(a["x:C"], b["x:C"])
    with pytest.raises(chaingraph.ChainFileError, match=r"\[task\]"):
        loads(dumps(chain) + "\n[task]\nfunction = 'x'\n")


@pytest.mark.parametrize("args, names", [
    (["--points", "2"], "--points"),
    (["--x", "0:2"], "--function"),
    (["--function", "__import__('os').system('x')"], "--function"),
    (["--function", "x % 2"], "--function"),
    (["--function", "log10(y)"], "--function"),
    (["--swing", "0:90"], "--swing"),
    (["--swing", "60:400"], "--swing"),
    (["--swing", "60:nan"], "--swing"),
    (["--x", "1:inf"], "--x"),
    (["--x", "2:2"], "--x"),
    (["--kind", "six-bar"], "--kind"),
    (["--spacing", "random"], "--spacing"),
    (["--solutions", "0"], "--solutions"),
])
def test_a_bad_task_exits_2_in_one_line(args, names):
    base = {"--function": "log10(x)", "--x": "1:2", "--swing": "60:90"}
    given = dict(zip(args[::2], args[1::2]))
    words = [w for k, v in {**base, **given}.items() for w in (k, v)]
    code, out, err = run_cli("design", "function", *words)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and names in err and "Traceback" not in err, err


def test_nothing_certified_exits_1_with_the_reasons():
    """The textbook's task below, its least transmission angle 25.8 degrees: under the
    default bound of 30, nothing is certified."""
    code, out, err = run_cli("design", "function", "--function", "log10(x)", "--x", "1:2",
                             "--swing", "60:90", "--start", "45:135")
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and "no certified solution" in err
    assert "transmission angle 1" in err


def test_the_textbook_task_in_the_textbook_s_own_angles(tmp_path):
    """The textbooks' classic task: y = log10(x) for 1 <= x <= 2, three Chebyshev points,
    the input turning 60 degrees from 45, the output 90 degrees from 135, solved by hand
    the textbooks' way and compared with what chaingraph designs from the same numbers.

    The textbooks' loop (the frame r1 drawn at 180 degrees, as course notes on
    Freudenstein's equation draw it) is r2 + r3 + r4 = r1: the input crank r2 from its pivot O2 (the origin), the coupler r3,
    then r4 from the coupler's pin to the output's pivot O4 = (r1, 0). So the textbooks'
    output angle theta4 is the direction from the pin to the pivot, and chaingraph's
    rocker angle (from the pivot D to the pin C, CCW from +x) is theta4 + 180 degrees.
    Eliminating theta3 gives their form of Freudenstein's equation,
    K1 cos(theta2) + K2 cos(theta4) + K3 = cos(theta2 - theta4), K1 = r1/r4, K2 = r1/r2,
    K3 = (r3^2 - r1^2 - r2^2 - r4^2) / (2 r2 r4), solved here for r1 = 1.

    chaingraph reads the same starting angles 45 and 135 (a negative length out of its
    own form is the link pointing the other way along its line, as the textbooks read
    it); its least transmission angle, 25.8 degrees, needs a bound below the default."""
    xs = precision_x((1.0, 2.0), 3, "chebyshev")
    assert [round(float(v), 3) for v in xs] == [1.067, 1.5, 1.933]
    theta2 = 45.0 + 60.0 * (xs - 1.0)
    theta4 = 135.0 + 90.0 * np.log10(xs) / math.log10(2.0)
    assert [round(float(v), 2) for v in theta2] == [49.02, 75.0, 100.98]
    assert [round(float(v), 2) for v in theta4] == [143.42, 187.65, 220.58]
    t2, t4 = np.radians(theta2), np.radians(theta4)
    k1, k2, k3 = np.linalg.solve(np.stack([np.cos(t2), np.cos(t4), np.ones(3)], axis=1),
                                 np.cos(t2 - t4))
    r1 = 1.0
    r2, r4 = r1 / k2, r1 / k1
    r3 = math.sqrt(2 * r2 * r4 * k3 + r1 * r1 + r2 * r2 + r4 * r4)
    assert min(r2, r4) > 0                  # positive lengths, in the textbooks' angles

    s = function(**LOG, start=(45.0, 135.0), solutions=1, min_transmission=25.0)
    best = s.solutions[0]
    dim = best.dimensions
    frame = dim["frame"]
    assert (dim["crank"] / frame, dim["coupler"] / frame, dim["rocker"] / frame) == \
        pytest.approx((r2 / r1, r3 / r1, r4 / r1), rel=1e-9)
    assert best.reached_at == pytest.approx(list(theta2), abs=1e-9)
    assert best.transmission_angle[0] == pytest.approx(25.83, abs=0.01)
    # the written file, solved: chaingraph's rocker angle is theta4 + 180 at each point
    path = tmp_path / "textbook.toml"
    path.write_text(dumps(best.mechanism))
    chain = chaingraph.load(path)
    for theta, want in zip(theta2, theta4 + 180.0):
        m = chaingraph.solve(chain, start=float(theta), stop=float(theta), steps=1,
                             summary=False)
        got = _rocker(m)[0]
        assert abs(_near(got, want) - want) < 1e-9


def test_a_lecture_s_worked_example_with_its_printed_dimensions(tmp_path):
    """A published worked example and its printed answer: "Lecture Problem: 3 Position
    Synthesis" and its "Solution", slides 12-13 of ME 3751 (Kinematics and mechanisms),
    Lecture 12, "Analytical synthesis of 4-bar with three rocker positions", The Ohio State
    University (the PDF's author: Robert A. Siston; after Waldron, Kinzel and Agrawal,
    Kinematics, Dynamics, and Design of Machinery, section 3.2), published with
    https://github.com/haijunsu-osu/rocker_synthesis_4bar ("Lecture 12 Three position
    synthesis.pdf", commit 9658bb0).

    The slide prints the task as three positions of the input and output links, theta =
    35.02, 67.50, 100.0 and phi = 91.21, 101.79, 117.19 degrees, with the base link r1 =
    4.5 inches, and the answer: z1, z2, z3 = 5.150, 11.20, 5.321; r2, r3, r4 = 0.0893,
    0.9329, 0.1879 (r1 = 1); R2, R3, R4 = 0.4018, 4.198, 0.8456 inches. Its angles are
    chaingraph's own: theta the input link's at O2, phi the output link's at O4 (from O4
    to its pin), both CCW from the base line O2 -> O4 (+x), so nothing is converted; its
    equation z1 + z2 cos(phi) - z3 cos(theta) = cos(theta - phi), z2 = r1/r2, z3 = r1/r4,
    z1 = (r1^2 + r2^2 + r4^2 - r3^2) / (2 r2 r4), is Freudenstein's.

    The slide names no function, but its numbers are a function generator's: y = x**2 for
    1 <= x <= 2.5, three Chebyshev points, the input turning 75 degrees from 30, the
    output 30 degrees from 90. Its precision points round to every printed angle, and its
    3x3 system to every printed entry of the slide's matrix. The slide solved from those
    unrounded angles: from the printed, rounded ones r2 comes out 1% smaller (the system's
    condition number is about 320, so an angle's last printed digit moves r2 and r4 by
    about 1%). chaingraph's design of that task gives every printed figure to its last
    digit: seven rounded, two truncated (z3 = 5.32159 and r3 = 0.93298 printed 5.321 and
    0.9329, not 5.322 and 0.9330); the exact figures are right, and the slide's r4 and R3,
    computed from them, agree with the exact ones."""
    xs = precision_x((1.0, 2.5), 3, "chebyshev")
    theta = 30.0 + 75.0 * (xs - 1.0) / 1.5
    phi = 90.0 + 30.0 * (xs * xs - 1.0) / (2.5 ** 2 - 1.0)
    assert [round(float(v), 2) for v in theta[:2]] == [35.02, 67.5]
    assert round(float(theta[2]), 1) == 100.0
    assert [round(float(v), 2) for v in phi] == [91.21, 101.79, 117.19]
    t, p = np.radians(theta), np.radians(phi)
    matrix = np.stack([np.ones(3), np.cos(p), -np.cos(t)], axis=1)    # the slide's layout
    printed = [[1, -0.0210, -0.8189], [1, -0.2043, -0.3827], [1, -0.4569, 0.1732]]
    assert np.abs(matrix - printed).max() <= 5e-5
    assert np.abs(np.cos(t - p) - [0.5566, 0.8262, 0.9552]).max() <= 5e-5
    z = np.linalg.solve(matrix, np.cos(t - p))
    r2, r4 = 1 / z[1], 1 / z[2]
    r3 = math.sqrt(1 + r2 * r2 + r4 * r4 - 2 * r2 * r4 * z[0])
    assert 300 < np.linalg.cond(matrix) < 330

    s = function(function="x**2", x=(1.0, 2.5), swing=(75.0, 30.0), start=(30.0, 90.0),
                 solutions=1)
    best = s.solutions[0]
    dim = best.dimensions
    a, b, c, d = (dim[k] for k in ("crank", "coupler", "rocker", "frame"))
    assert (a / d, b / d, c / d) == pytest.approx((r2, r3, r4), rel=1e-9)
    assert (dim["input_start"], dim["output_start"]) == (30.0, 90.0)   # no link turned
    # chaingraph's R3, R1, R2 are the slide's z1, z2, z3; its figures, r1 = 4.5 inches,
    # each the exact one to its last printed digit, rounded but z3 and r3, truncated
    figures = {"z1": ((a * a - b * b + c * c + d * d) / (2 * a * c), 5.150, 3),
               "z2": (d / a, 11.20, 2), "z3": (d / c, 5.321, 3), "r2": (a / d, 0.0893, 4),
               "r3": (b / d, 0.9329, 4), "r4": (c / d, 0.1879, 4),
               "R2": (4.5 * a / d, 0.4018, 4), "R3": (4.5 * b / d, 4.198, 3),
               "R4": (4.5 * c / d, 0.8456, 4)}
    rounded = [k for k, (got, shown, n) in figures.items() if round(got, n) == shown]
    truncated = [k for k, (got, shown, n) in figures.items()
                 if math.floor(got * 10 ** n) / 10 ** n == shown and k not in rounded]
    assert len(rounded) == 7 and truncated == ["z3", "r3"]
    # from the printed, rounded angles instead: r2 1% smaller than the slide's
    t0, p0 = np.radians([35.02, 67.50, 100.0]), np.radians([91.21, 101.79, 117.19])
    z0 = np.linalg.solve(np.stack([np.ones(3), np.cos(p0), -np.cos(t0)], axis=1),
                         np.cos(t0 - p0))
    assert 0.985 < (1 / z0[1]) / (a / d) < 0.995

    # the written file, solved: the rocker's angle is the slide's phi at each theta
    assert best.reached_at == pytest.approx(list(theta), abs=1e-9)
    path = tmp_path / "lecture12.toml"
    path.write_text(dumps(best.mechanism))
    chain = chaingraph.load(path)
    for th, want in zip(theta, phi):
        m = chaingraph.solve(chain, start=float(th), stop=float(th), steps=1,
                             summary=False)
        got = _rocker(m)[0]
        assert abs(_near(got, want) - want) < 1e-9


def test_the_library_names_the_parameter():
    with pytest.raises(DesignError) as e:
        function(function="sqrt(x)", x=(-1, 1), swing=(60, 90))
    assert e.value.parameter == "function" and "not finite" in str(e.value)
