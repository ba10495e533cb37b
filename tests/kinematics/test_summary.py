"""The summary as a result: a frozen dataclass with named fields, its JSON the contract's
keys, its rows the command line's and the report's."""

import dataclasses
import json
import math

import numpy as np
import pytest

import chaingraph
from chaingraph.cli.main import main
from chaingraph.kinematics import ExtremePosition, Summary, summary_rows
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli

CONTRACT = {"stroke", "time_ratio", "forward_deg", "return_deg", "extremes",
            "transmission_angle", "dead_centres", "input_range"}


@pytest.fixture(scope="module")
def engine():
    return chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")), steps=72)


def test_the_summary_is_a_frozen_dataclass_with_named_fields(engine):
    s = engine.summary
    assert isinstance(s, Summary) and dataclasses.is_dataclass(s)
    with pytest.raises(dataclasses.FrozenInstanceError):
        s.stroke = 0.0
    # the engine: crank 40, stroke 80, time ratio 1 (no offset), extremes at 0 and 180
    assert s.stroke == pytest.approx(80.0, abs=1e-9) and s.time_ratio == pytest.approx(1.0)
    assert s.stroke_unit == "mm" and s.full_turn and s.input_unit == "degrees"
    assert all(isinstance(e, ExtremePosition) for e in s.extreme_positions)
    assert sorted(e.kind for e in s.extreme_positions) == ["max", "min"]


def test_its_json_is_the_contract_s_and_reads_by_key(engine, capsys):
    d = engine.summary.to_dict()
    assert CONTRACT <= set(d)
    assert set(d["transmission_angle"] or {"min": 0, "max": 0}) == {"min", "max"}
    for key in d:
        assert engine.summary[key] == d[key]
    json.dumps(d)                                     # plain JSON, no numpy scalars
    assert main(["solve", str(catalog_path("reciprocating-engine")), "--json",
                 "--steps", "72"]) == 0
    printed = json.loads(capsys.readouterr().out)["summary"]
    assert printed == json.loads(json.dumps(d))


def test_its_rows_are_what_the_faces_render(engine):
    rows = dict(engine.summary.rows())
    assert rows["stroke"] == "80 mm" and rows["time ratio"] == "1"
    full = summary_rows(engine)
    assert full[0] == ("fixed link", "frame") and full[2:] == engine.summary.rows()


def test_without_a_summary_there_is_none():
    m = chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")), steps=4,
                         summary=False)
    assert m.summary is None and m.to_dict()["summary"] == {}


# -- any output, and how straight a point's path is ------------------------------------
def test_output_names_a_link_a_point_or_a_joint_without_editing_the_file():
    import numpy as np
    engine = chaingraph.load(catalog_path("reciprocating-engine"))
    by_file = chaingraph.solve(engine, steps=72).summary
    by_link = chaingraph.solve(engine, steps=72, output="crosshead").summary
    by_joint = chaingraph.solve(engine, steps=72, output="B").summary
    assert by_link.stroke == pytest.approx(by_file.stroke, rel=1e-12) == pytest.approx(80.0)
    # the crosshead's pin B travels the same stroke along the line of stroke
    assert by_joint.stroke == pytest.approx(80.0, rel=1e-9)
    assert by_joint.time_ratio == pytest.approx(by_file.time_ratio, rel=1e-9)
    assert by_joint.straightness.deviation == pytest.approx(0.0, abs=1e-9)
    # the crank pin A: a circle of 40 mm, its projection 80 long, 40 off its line
    a = chaingraph.solve(engine, steps=360, output="A")
    assert a.summary.straightness.length == pytest.approx(80.0, rel=1e-6)
    assert a.summary.straightness.deviation == pytest.approx(40.0, rel=1e-3)
    rocker = chaingraph.solve(engine, steps=72, output="connecting rod").summary
    assert rocker.stroke_unit == "deg" and rocker.straightness is None
    with pytest.raises(chaingraph.MechanismError, match="no link, joint or point"):
        chaingraph.solve(engine, output="piston")


def test_a_file_s_output_may_name_a_joint():
    text = catalog_path("reciprocating-engine").read_text().replace(
        'output = "crosshead"', 'output = "B"')
    m = chaingraph.solve(chaingraph.loads(text), steps=36)
    assert m.summary.output == "B" and m.summary.stroke == pytest.approx(80.0, rel=1e-9)
    bad = text.replace('output = "B"', 'output = "Q"')
    with pytest.raises(chaingraph.ChainFileError, match="names no link, joint or point"):
        chaingraph.loads(bad)


def test_watt_s_straight_line_against_a_least_squares_fit_in_the_test():
    """Watt's indicator: over a small swing of the piston lever about the drawn pose the
    tracing point E draws 'approximately a straight line' (the notes)."""
    import numpy as np
    watt = chaingraph.load(catalog_path("watts-indicator-mechanism"))
    f, d = watt.joint("F").at, watt.joint("D").at
    drawn = math.degrees(math.atan2(d[1] - f[1], d[0] - f[0]))   # the lever FD as drawn
    m = chaingraph.solve(watt, start=drawn, stop=drawn + 10, steps=96)
    x, y = m["x:E"], m["y:E"]
    # the test's own fit: the line minimising the squared distances is through the
    # mean along the covariance's larger eigenvector
    c = np.cov(np.vstack([x, y]))
    w, v = np.linalg.eigh(c)
    d = v[:, 1]
    n = np.array([-d[1], d[0]])
    px, py = x - x.mean(), y - y.mean()
    deviation = np.abs(px * n[0] + py * n[1]).max()
    along = px * d[0] + py * d[1]
    s = m.summary.straightness
    assert s.deviation == pytest.approx(deviation, rel=1e-9)
    assert s.length == pytest.approx(along.max() - along.min(), rel=1e-9)
    assert s.deviation < 0.02 * s.length          # straight to 2 per cent over the swing
    status, out, err = run_cli("solve", catalog_path("watts-indicator-mechanism"), "--from",
                               repr(drawn), "--to", repr(drawn + 10), "--steps", "96",
                               "--json")
    assert json.loads(out)["summary"]["straightness"]["deviation"] == pytest.approx(
        deviation, rel=1e-9)


def test_output_on_the_command_line():
    status, out, err = run_cli("solve", catalog_path("reciprocating-engine"), "--output", "B",
                               "--steps", "36")
    assert status == 0 and "straightness" in out
    status, out, err = run_cli("solve", catalog_path("reciprocating-engine"), "--output", "Z")
    assert status == 2 and "no link, joint or point" in err and "--output NAME" in err


def test_a_fine_sweep_s_extremes_from_its_own_samples_are_the_mechanism_s(monkeypatch):
    """Where the sweep's grid is fine, the summary takes an extreme from the sweep's own
    values, rates and accelerations (summary._interpolated_extremes) instead of solving
    the mechanism there again: every catalog mechanism's extremes are then those found
    on the mechanism (Newton's method on the exact rate) to 1e-12 of the scale (what
    tidy rounds within), and most extremes are taken so (the path is exercised)."""
    from chaingraph.kinematics import summary as module
    from chaingraph.naming.catalog import catalog_files
    interpolate = module._interpolated_extremes
    taken = []

    def counted(*args):
        t, value, sure = interpolate(*args)
        taken.append(int(sure.sum()))
        return t, value, sure

    def never(theta, u, du, ddu, ka, kb, guess, *rest):
        return guess.copy(), np.full(ka.size, np.nan), np.zeros(ka.size, dtype=bool)
    compared = 0
    for path in catalog_files():
        chain = chaingraph.load(path)
        if chain.mechanism is None or chain.mechanism.output is None:
            continue
        monkeypatch.setattr(module, "_interpolated_extremes", counted)
        fine = chaingraph.solve(chain).summary
        monkeypatch.setattr(module, "_interpolated_extremes", never)
        exact = chaingraph.solve(chain).summary
        if exact.extreme_positions is None:
            continue
        lead = 360.0 if exact.input_unit == "degrees" else fine_scale(chain)
        out = 360.0 if exact.stroke_unit == "deg" else fine_scale(chain)
        assert len(fine.extreme_positions) == len(exact.extreme_positions), path.name
        for a, b in zip(fine.extreme_positions, exact.extreme_positions):
            assert a.kind == b.kind
            assert a.input == pytest.approx(b.input, rel=0, abs=1e-12 * lead), path.name
            assert a.value == pytest.approx(b.value, rel=0, abs=1e-12 * out), path.name
        assert fine.stroke == pytest.approx(exact.stroke, rel=0, abs=1e-12 * out)
        compared += len(exact.extreme_positions)
    assert compared >= 40 and sum(taken) >= compared // 3, (compared, sum(taken))


def fine_scale(chain):
    """The chain's size, as the plan takes it (the scale of its lengths)."""
    return chaingraph.build_plan(chain).size
