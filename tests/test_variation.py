"""vary: the summary over one link's length, against separate solves of edited files;
the lecture's two arguments; every bad input."""

import json
import math
import re
from pathlib import Path

import pytest

import chaingraph
from chaingraph.naming.catalog import catalog_path
from chaingraph.variation import length_values, vary

from .conftest import run_cli

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def test_the_slotted_lever_s_ratio_falls_towards_one_as_its_crank_shortens():
    """The lecture: 300 mm between the centres, crank 120, 90, 60, 30: 1.710, 1.481,
    1.294, 1.136 (rounded there); exactly (c + a) / (c - a) turns of the crank, where
    sin(a) = crank / 300: the ratio (180 + 2 asin(r/300)) / (180 - 2 asin(r/300))."""
    lever = chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))
    v = vary(lever, "crank", length_values(30, 120, 30))
    for row in v.rows:
        beta = math.degrees(2 * math.asin(row.value / 300.0))
        assert row.summary.time_ratio == pytest.approx((180 + beta) / (180 - beta), rel=1e-9)
    assert [round(r.summary.time_ratio, 3) for r in v.rows] == [1.136, 1.294, 1.481, 1.71]


def test_the_whitworth_drive_s_ratio_does_not_change_with_its_stroke():
    whitworth = chaingraph.load(catalog_path("whitworth-quick-return-with-ram"))
    v = vary(whitworth, "slotted lever", [30.0, 50.0, 70.0])
    ratios = {round(r.summary.time_ratio, 9) for r in v.rows}
    assert len(ratios) == 1 and round(ratios.pop(), 3) == 2.735
    # the stroke is twice the arm (the ram on a line through the lever's pivot)
    assert [r.summary.stroke for r in v.rows] == pytest.approx([60.0, 100.0, 140.0], rel=1e-9)


def test_vary_is_the_same_as_editing_the_file_and_solving_it(tmp_path):
    four_bar = chaingraph.load(EXAMPLES / "four-bar-lengths.toml")
    v = vary(four_bar, "coupler", [100.0, 120.0, 140.0], steps=120)
    source = (EXAMPLES / "four-bar-lengths.toml").read_text()
    for row in v.rows:
        edited = re.sub(r"coupler = 120\.0", f"coupler = {row.value!r}", source)
        path = tmp_path / "edited.toml"
        path.write_text(edited)
        alone = chaingraph.solve(chaingraph.load(path), steps=120).summary
        for key in ("time_ratio", "stroke", "input_range"):
            assert row.summary[key] == pytest.approx(alone[key], rel=1e-9, abs=1e-9), key
        # (a transmission angle that reaches 0 at a fold: to the square root of rounding)
        assert row.summary["transmission_angle"] == pytest.approx(
            alone["transmission_angle"], rel=1e-9, abs=1e-5)


def test_a_value_that_cannot_be_assembled_is_a_row_that_says_so():
    four_bar = chaingraph.load(EXAMPLES / "four-bar-lengths.toml")
    v = vary(four_bar, "coupler", [5.0, 120.0])
    assert v.rows[0].summary is None and "cannot be assembled" in v.rows[0].error
    assert v.rows[1].summary is not None and v.rows[1].error is None
    d = v.to_dict()
    assert set(d) == {"name", "link", "rows"}
    assert d["rows"][0]["summary"] is None and d["rows"][1]["error"] is None


def test_vary_on_the_command_line(tmp_path):
    status, out, err = run_cli("vary", catalog_path("crank-and-slotted-lever-mechanism"),
                               "--length", "crank=30:120:30", "--json",
                               "--plot", tmp_path / "v.svg")
    assert status == 0, err
    d = json.loads(out)
    assert d["link"] == "crank" and [r["value"] for r in d["rows"]] == [30, 60, 90, 120]
    assert round(d["rows"][-1]["summary"]["time_ratio"], 5) == 1.70995
    assert "<svg" in (tmp_path / "v.svg").read_text()
    status, out, err = run_cli("vary", catalog_path("crank-and-slotted-lever-mechanism"),
                               "--length", "crank=30:120:30")
    assert status == 0 and "1.70995" in out and "time ratio" in out


@pytest.mark.parametrize("length, words", [
    ("wheel=10:20:5", "'wheel' is no link of the chain"),
    ("crank=30:10:10", "has no values"),
    ("crank=30:40:0", "step must not be 0"),
    ("crank=30:40", "write LINK=FROM:TO:STEP"),
    ("crank=a:40:5", "must be numbers"),
    ("frame=10:20:5", "is the fixed link"),
])
def test_bad_lengths_are_one_line_and_exit_2(length, words):
    status, out, err = run_cli("vary", catalog_path("crank-and-slotted-lever-mechanism"),
                               "--length", length)
    assert status == 2 and words in err and err.count("\n") == 1 and "Traceback" not in err


def test_a_link_of_several_dimensions_is_refused():
    status, out, err = run_cli("vary", catalog_path("stephenson-iii-mechanism"),
                               "--length", "rocker=50:60:5")
    assert status == 2 and "is not given by a single length but by 3" in err
