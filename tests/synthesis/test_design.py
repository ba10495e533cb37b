"""Dimensional synthesis of quick return drives, and the round trip through solve."""

import json
import math

import pytest

import chaingraph
from chaingraph import DesignError
from chaingraph.synthesis.design import slotted_lever, whitworth

from ..conftest import run_cli


def test_textbook_worked_example_exact_figures():
    d = slotted_lever(time_ratio=1.7, crank=30, stroke=120)
    half = math.radians(360 / 2.7 / 2)
    assert d.centre_distance == pytest.approx(30 / math.cos(half), rel=1e-12)
    assert d.lever == pytest.approx(120 / (2 * math.cos(half)), rel=1e-12)
    # the book prints 75.7 and 151.4 from a rounded cosine; the exact lever is 151.48...
    assert round(d.centre_distance, 1) == 75.7 and round(d.lever, 1) == 151.5
    assert d.return_deg == pytest.approx(133.333333, abs=1e-6)
    assert d.forward_deg + d.return_deg == pytest.approx(360)


def test_whitworth_assignment():
    d = whitworth(time_ratio=2, crank=40, stroke=150)
    # cos(beta/2) = CD / crank with beta = 120: CD = 20; the stroke is twice PD
    assert d.centre_distance == pytest.approx(20.0, abs=1e-12)
    assert d.lever_arm == pytest.approx(75.0)
    assert (d.forward_deg, d.return_deg) == pytest.approx((240.0, 120.0))


@pytest.mark.parametrize("kind", ["slotted-lever", "whitworth"])
@pytest.mark.parametrize("ratio", [1.2, 1.5, 2.0, 2.6])
@pytest.mark.parametrize("stroke", [150.0, 400.0])
def test_round_trip_through_solve(kind, ratio, stroke, tmp_path):
    design = chaingraph.synthesis.design.KINDS[kind]
    d = design(time_ratio=ratio, crank=40.0, stroke=stroke)
    path = tmp_path / "designed.toml"
    chaingraph.save(d.mechanism, path)
    s = chaingraph.solve(chaingraph.load(path)).summary
    assert s["time_ratio"] == pytest.approx(ratio, rel=1e-6)
    assert s["stroke"] == pytest.approx(stroke, rel=1e-6)
    assert s["forward_deg"] == pytest.approx(d.forward_deg, rel=1e-6)


@pytest.mark.parametrize("args, words", [
    ({"time_ratio": 1.0, "crank": 30, "stroke": 120}, "above 1"),
    ({"time_ratio": 0.5, "crank": 30, "stroke": 120}, "above 1"),
    ({"time_ratio": 2.0, "crank": 0, "stroke": 120}, "crank must be a positive"),
    ({"time_ratio": 2.0, "crank": 30, "stroke": -5}, "stroke must be a positive"),
    ({"time_ratio": math.nan, "crank": 30, "stroke": 120}, "finite"),
])
def test_bad_requests(args, words):
    for design in (slotted_lever, whitworth):
        with pytest.raises(DesignError, match=words):
            design(**args)


def test_stroke_too_short_for_a_slotted_lever_says_why():
    with pytest.raises(DesignError, match="run off the lever's end; ask for a stroke above"):
        slotted_lever(time_ratio=3, crank=30, stroke=50)


def test_cli_design(tmp_path):
    out = tmp_path / "w.toml"
    code, stdout, err = run_cli("design", "whitworth", "--time-ratio", "2", "--crank", "40",
                                "--stroke", "150", "--json", "--out", out)
    assert code == 0, err
    d = json.loads(stdout)
    assert {"centre_distance", "lever_arm", "forward_deg", "return_deg"} <= set(d)
    assert chaingraph.load(out).mechanism.driver == "crank"
    code, stdout, err = run_cli("design", "slotted-lever", "--time-ratio", "1.7", "--crank", "30",
                                "--stroke", "120")
    assert code == 0 and "centre distance" in stdout and "75.7423" in stdout
    code, stdout, err = run_cli("design", "slotted-lever", "--time-ratio", "0.9", "--crank", "30",
                                "--stroke", "120")
    assert code == 2 and "above 1" in err and "Traceback" not in err
