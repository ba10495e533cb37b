"""Motion generation: poses of known mechanisms' couplers (solved by chaingraph) give back
those mechanisms among certified solutions, each of which, re-solved from its written file,
passes the poses; every pair of five poses' Burmester dyads is checked; a crank whose input
turns back between poses is a branch defect; invariance; bad tasks; nothing certified."""

import math
from dataclasses import replace

import numpy as np
import pytest

import chaingraph
from chaingraph.cli.main import main
from chaingraph.model.chain import Mechanism, Point
from chaingraph.naming.catalog import catalog_path
from chaingraph.synthesis import Certified, PoseTargets, Rejected, certify, motion
from chaingraph.synthesis.burmester import Dyad, dyad_inputs, mechanism
from chaingraph.synthesis.poses import task_size

INPUTS = (60.0, 85.0, 110.0, 140.0, 170.0)        # degrees of the original's crank


def _coupler_poses(chain, link, point):
    """The poses (x, y, degrees) of ``link`` at INPUTS, solved by chaingraph, and where
    the first pose has every joint."""
    m = chaingraph.solve(chain, start=INPUTS[0], stop=INPUTS[-1], steps=22)
    rows = [int(np.argmin(abs(m["theta"] - v))) for v in INPUTS]
    poses = [(float(m[f"x:{point}"][r]), float(m[f"y:{point}"][r]),
              float(m[f"angle:{link}"][r])) for r in rows]
    at = {j.id: (float(m[f"x:{j.id}"][rows[0]]), float(m[f"y:{j.id}"][rows[0]]))
          for j in chain.joints}
    return poses, at


@pytest.fixture(scope="module")
def four_bar():
    """The catalog's crank-rocker (frame 100, crank 40, coupler 120, rocker 80), a
    coupler point off the coupler's line."""
    chain = chaingraph.load(catalog_path("four-bar-chain"))
    chain = replace(chain, points=(Point("P", "coupler", (70.0, 90.0)),),
                    mechanism=Mechanism("frame", "crank", 1.0, "coupler"))
    return _coupler_poses(chain, "coupler", "P")


@pytest.fixture(scope="module")
def engine():
    """The reciprocating engine's connecting rod: crank O-A, piston pin B on x."""
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    chain = replace(chain, points=(Point("P", "connecting rod", (90.0, 40.0)),))
    return _coupler_poses(chain, "connecting rod", "P")


def _passes(solution, poses):
    """The worst position (over the task's size) and angle (degrees) errors of the
    solution's file, written, read back and solved at its reached_at."""
    chain = chaingraph.loads(chaingraph.dumps(solution.mechanism))
    first = None
    worst = [0.0, 0.0]
    for value, pose in zip(solution.reached_at, poses):
        m = chaingraph.solve(chain, start=value, stop=value, steps=1, summary=False)
        angle = float(m["angle:coupler"][0])
        first = angle - pose[2] if first is None else first
        worst[0] = max(worst[0], math.dist((m["x:P"][0], m["y:P"][0]), pose[:2]))
        worst[1] = max(worst[1], abs(math.remainder(angle - first - pose[2], 360.0)))
    return worst[0] / task_size(poses), worst[1]


def _pivots(solution):
    return {j.id: j.at for j in solution.mechanism.joints}


def _is(solution, fixed, moving, tol):
    """The solution's driving dyad is (fixed, moving) A-B and its other D-C."""
    at = _pivots(solution)
    return all(math.dist(at[k], p) < tol for k, p in zip("ADBC", fixed + moving))


@pytest.mark.parametrize("count", [3, 4])
def test_a_four_bar_s_poses_give_it_back_and_every_solution_passes(four_bar, count):
    poses, at = four_bar
    tol = 1e-9 * task_size(poses[:count])
    found = motion(poses=poses[:count], circle_points=[at["B"], at["C"]], min_transmission=0,
                   solutions=4)
    assert found.solutions
    original = [s for s in found.solutions
                if _is(s, (at["A"], at["D"]), (at["B"], at["C"]), 1e-6 * 100)]
    assert len(original) == 1
    assert original[0].reached_at == pytest.approx(INPUTS[:count], abs=1e-6)
    assert original[0].grashof is not None and original[0].input == "turns fully"
    default = motion(poses=poses[:count])
    assert default.solutions
    for s in found.solutions + default.solutions:
        position, angle = _passes(s, poses[:count])
        assert position < 1e-9 and angle < 1e-9
        assert s.error.max < tol and s.error.angle < 1e-9
        ta = s.transmission_angle
        assert ta is None or (ta[0] >= s.mechanism.task["min_transmission"] - 1e-9)


def test_five_poses_check_every_burmester_pair(four_bar):
    poses, at = four_bar
    found = motion(poses=poses, min_transmission=0, solutions=100)
    # each candidate is certified or rejected with a reason: none left unexamined
    assert len(found.solutions) + sum(found.rejected.values()) == found.searched.candidates
    assert found.searched.candidates % 2 == 0          # every pair, each dyad driving
    assert any(_is(s, (at["A"], at["D"]), (at["B"], at["C"]), 1e-6) for s in found.solutions)
    for s in found.solutions:
        position, angle = _passes(s, poses)
        assert position < 1e-9 and angle < 1e-9


@pytest.mark.parametrize("count", [3, 4])
def test_a_slider_crank_s_poses_give_a_slider_crank(engine, count):
    poses, at = engine
    found = motion(poses=poses[:count], circle_points=[at["A"], at["B"]], min_transmission=0)
    sliders = [s for s in found.solutions if "Single slider crank chain" in s.names]
    assert sliders
    for s in sliders:
        assert _passes(s, poses[:count])[0] < 1e-9
        guide = next(j for j in s.mechanism.joints if j.kind == "P")
        assert math.remainder(guide.axis, 180.0) == pytest.approx(0.0, abs=1e-6)
        assert abs(guide.at[1]) < 1e-6               # the piston's line, y = 0


def test_an_input_that_turns_back_between_poses_is_a_branch_defect():
    """The oscillating cylinder engine: driven by its crank it passes the piston rod's
    poses; driven by the cylinder, whose angle goes back between poses 1 and 3 (past its
    limit), it cannot: a branch defect, in certify and in the synthesis's screen."""
    chain = chaingraph.load(catalog_path("oscillating-cylinder-engine"))
    poses, at = _coupler_poses(chain, "piston rod", "piston")
    rad = [(x, y, math.radians(a)) for x, y, a in poses[:3]]
    axis = math.radians(chain.joint("S").axis)
    crank = Dyad("RR", at["O"], at["A"])
    cylinder = Dyad("RP", at["T"], None, (math.cos(axis), math.sin(axis)))
    verdicts = []
    for driver, lead in ((0, crank), (1, cylinder)):
        m = mechanism(rad, crank, cylinder, driver=driver)
        ref = m.reference_direction("coupler")
        targets = PoseTargets(tuple(p[:2] for p in poses[:3]),
                              tuple(ref + p[2] - poses[0][2] for p in poses[:3]), "P",
                              "coupler", dyad_inputs(rad, lead))
        verdicts.append(certify(m, targets, min_transmission=0))
    assert isinstance(verdicts[0], Certified) and verdicts[0].error_max < 1e-9 * 100
    assert isinstance(verdicts[1], Rejected) and verdicts[1].reason == "branch defect"
    values = dyad_inputs(rad, cylinder)
    assert values[1] < values[0] < values[2]           # it turns back
    found = motion(poses=poses, min_transmission=0, solutions=100)
    assert found.rejected.get("branch defect", 0) >= 1
    assert any(s.mechanism.mechanism.driver == "crank" and "block" in s.mechanism.links
               and _passes(s, poses)[0] < 1e-9 for s in found.solutions)


def _moved(poses, turn, shift, scale):
    c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
    return [(scale * (c * x - s * y) + shift[0], scale * (s * x + c * y) + shift[1], a + turn)
            for x, y, a in poses]


@pytest.mark.parametrize("count", [3, 4])
def test_rotating_translating_and_scaling_the_task_moves_the_solutions(four_bar, count):
    poses = four_bar[0][:count]
    base = motion(poses=poses)
    turn, shift, scale = 37.0, (250.0, -80.0), 2.5
    moved = motion(poses=_moved(poses, turn, shift, scale))
    assert len(base.solutions) == len(moved.solutions) > 0
    for s, t in zip(base.solutions, moved.solutions):
        here = {j.id: j.at for j in s.mechanism.joints}
        there = {j.id: j.at for j in t.mechanism.joints}
        assert here.keys() == there.keys()
        for k, (x, y) in here.items():
            (u, v, _), = _moved([(x, y, 0.0)], turn, shift, scale)
            assert math.dist((u, v), there[k]) < 1e-6 * scale * 100
        assert t.transmission_angle == pytest.approx(s.transmission_angle, abs=1e-6)
        assert t.reached_at[-1] - t.reached_at[0] == pytest.approx(
            s.reached_at[-1] - s.reached_at[0], abs=1e-6)


def test_relabelling_the_links_never_matters(four_bar):
    poses = four_bar[0][:3]
    best = motion(poses=poses, solutions=1).solutions[0]
    chain = best.mechanism
    names = {"frame": "ground", "crank": "input arm", "coupler": "platform",
             "rocker": "follower", "block": "pivoting block", "slider": "carriage"}
    text = chaingraph.dumps(chain)
    for old, new in names.items():
        text = text.replace(f'"{old}"', f'"{new}"')
    renamed = chaingraph.loads(text)
    ref = renamed.reference_direction("platform")
    targets = PoseTargets(tuple(p[:2] for p in poses),
                          tuple(ref + p[2] - poses[0][2] for p in poses), "P", "platform",
                          best.reached_at)
    again = certify(renamed, targets)
    assert isinstance(again, Certified)
    assert again.reached_at == pytest.approx(best.reached_at)
    assert again.error_max == pytest.approx(best.error.max, abs=1e-9)
    assert again.transmission_angle == pytest.approx(best.transmission_angle)


def test_the_command_writes_json_files_and_a_drawing(four_bar, tmp_path, capsys):
    poses = "; ".join(",".join(f"{v:.12g}" for v in p) for p in four_bar[0][:3])
    out, draw = tmp_path / "out", tmp_path / "motion.svg"
    assert main(["design", "motion", "--poses", poses, "--solutions", "2", "--json",
                 "--out", str(out), "--draw", str(draw)]) == 0
    import json
    record = json.loads(capsys.readouterr().out)
    assert set(record) == {"task", "solutions", "rejected", "searched"}
    assert record["task"]["kind"] == "motion" and len(record["task"]["poses"]) == 3
    first = record["solutions"][0]
    assert set(first) == {"rank", "names", "atlas", "mechanism", "error", "reached_at",
                          "transmission_angle", "grashof", "input"}
    assert set(first["error"]) == {"max", "rms", "angle_error"}
    assert sorted(p.name for p in out.iterdir()) == ["solution-1.toml", "solution-2.toml"]
    written = chaingraph.load(out / "solution-1.toml")
    assert written.task["kind"] == "motion" and written.mechanism.output == "coupler"
    assert main(["solve", str(out / "solution-1.toml"), "--steps", "8"]) == 0
    assert draw.read_text().count("<svg") == 1


def _status(args):
    """main's exit status, argparse's refusals included."""
    try:
        return main(args)
    except SystemExit as stop:
        return stop.code


@pytest.mark.parametrize("poses, words", [
    ("0,0,0", "needs 2 to 5 poses, got 1"),
    ("0,0,0; 1,0,10; 2,0,20; 3,1,30; 4,2,40; 5,2,50", "got 6"),
    ("0,0,0; 1,2,30; 0,0,360", "poses 1 and 3 are the same pose"),
    ("0,0,0; nan,1,30", "pose 2's x must be a finite number"),
    ("0,0,0; 1,1,inf", "pose 2's angle must be a finite number"),
    ("0,0,0; 1,1", "poses X,Y,DEG"),
])
def test_a_bad_task_exits_2_in_one_line(poses, words, capsys):
    assert _status(["design", "motion", "--poses", poses]) == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1


@pytest.mark.parametrize("option", [["--min-transmission", "95"], ["--solutions", "0"]])
def test_a_bad_option_exits_2_in_one_line(option, capsys):
    assert _status(["design", "motion", "--poses", "0,0,0; 1,0,10"] + option) == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_nothing_certified_exits_1_with_the_reasons(capsys):
    poses = "0,0,0; 40,10,20; 70,40,50; 90,80,70; 95,110,95"
    assert main(["design", "motion", "--poses", poses]) == 1
    err = capsys.readouterr().err
    assert "no certified solution of 12 candidates (rejected: branch defect" in err
    assert err.count("\n") == 1
