"""``chaingraph cam FILE`` (issue 39): the JSON keys and CSV columns of the contract, the
drawings written, the file read back as written, every bad input one line and exit 2."""

import csv
import json
import math

import pytest

import chaingraph
from chaingraph.files import dumps, loads
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli

CAM = catalog_path("disc-cam-roller-follower")
KEYS = {"name", "cam", "follower", "contact", "base", "roller", "offset", "stroke",
        "pressure_angle", "curvature", "undercut", "min_base"}


def test_cam_json_has_the_contract_s_keys():
    code, out, err = run_cli("cam", CAM, "--json", "--max-pressure-angle", "30")
    assert code == 0, err
    data = json.loads(out)
    assert set(data) == KEYS
    assert data["stroke"] == 30.0 and data["contact"] == "roller"
    # a centred roller follower: tan(alpha) = s' / (s + Rp), worked here over a fine turn
    rise = math.radians(120.0)
    best = max(abs(math.degrees(math.atan(30 / rise * (1 - math.cos(2 * math.pi * u))
                                          / (30 * (u - math.sin(2 * math.pi * u) / (2 * math.pi))
                                             + 50.0))))
               for u in (k / 20000 for k in range(20001)))
    assert data["pressure_angle"]["max"] >= best - 1e-6
    assert data["pressure_angle"]["max"] == pytest.approx(best, abs=0.02)
    assert data["undercut"] is False and data["min_base"] < 40.0


def test_cam_csv_columns_and_rows(tmp_path):
    path = tmp_path / "cam.csv"
    code, out, err = run_cli("cam", CAM, "--csv", path, "--steps", "36")
    assert code == 0, err
    rows = list(csv.reader(path.open()))
    assert rows[0] == ["theta", "s", "ds", "dds", "ddds", "pressure_angle", "x_pitch",
                       "y_pitch", "x_profile", "y_profile"]
    assert len(rows) == 38
    values = [[float(x) for x in r] for r in rows[1:]]
    assert [r[0] for r in values] == pytest.approx([10.0 * k for k in range(37)])
    for r in values:                  # the profile at the roller's radius from the pitch curve
        assert math.hypot(r[6] - r[8], r[7] - r[9]) == pytest.approx(10.0, abs=1e-7)
    assert values[6][1] == pytest.approx(15.0)          # the rise's middle, at 60 degrees


def test_cam_text_draw_and_plot(tmp_path):
    draw, plot = tmp_path / "cam.svg", tmp_path / "plot.svg"
    code, out, err = run_cli("cam", CAM, "--draw", draw, "--plot", plot, "--at", "45")
    assert code == 0, err
    assert "largest pressure angle" in out and "undercut" in out
    assert draw.read_text().count('class="roller"') == 1
    assert "<svg" in plot.read_text()


def test_a_cam_file_is_written_back_as_read():
    chain = chaingraph.load(CAM)
    again = loads(dumps(chain))
    assert again.cams == chain.cams


GOOD = """name = "bad cam"
[[joints]]
id = "O"
kind = "R"
links = ["frame", "cam"]
[[joints]]
id = "K"
kind = "cam"
links = ["cam", "follower"]
[[joints]]
id = "S"
kind = "P"
links = ["follower", "frame"]
[[cams]]
id = "K"
cam = "cam"
follower = "follower"
contact = "roller"
roller = 10.0
base = 40.0
motion = [{rise = 30.0, over = 120.0, law = "cycloidal"}, {dwell = 60.0},
          {fall = 30.0, over = 120.0, law = "shm"}, {dwell = 60.0}]
"""


@pytest.mark.parametrize("old, new, words", [
    ('{fall = 30.0', '{fall = 20.0', "do not return to the start"),
    ('{dwell = 60.0}]', '{dwell = 50.0}]', "sum to 360"),
    ('base = 40.0', 'base = -40.0', "must be positive"),
    ('roller = 10.0', 'roller = 50.0', "smaller than the base circle"),
    ('"cycloidal"', '"sine"', "unknown law"),
    ('contact = "roller"', 'contact = "ball"', "unknown contact"),
    ('{fall = 30.0', '{fall = 40.0', "falls below the start"),
    ('follower = "follower"', 'follower = "rod"', "no link 'rod'"),
], ids=["not-returning", "not-360", "negative-radius", "roller-too-big", "law", "contact",
        "below-start", "no-link"])
def test_every_bad_cam_is_one_line_and_exit_2(tmp_path, old, new, words):
    assert old in GOOD
    path = tmp_path / "bad.toml"
    path.write_text(GOOD.replace(old, new, 1))
    code, out, err = run_cli("cam", path)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and words in err and "[[cams]]" in err


def test_a_good_file_passes_and_bad_options_are_one_line(tmp_path):
    path = tmp_path / "good.toml"
    path.write_text(GOOD)
    assert run_cli("cam", path)[0] == 0
    for args in (["--max-pressure-angle", "95"], ["--at", "nan"], ["--draw", tmp_path / "x.png"]):
        code, out, err = run_cli("cam", path, *args)
        assert code == 2 and len(err.strip().splitlines()) == 1, (args, err)
    code, out, err = run_cli("cam", catalog_path("four-bar-chain"))
    assert code == 2 and "no [[cams]]" in err


def test_an_oscillating_follower_json(tmp_path):
    path = tmp_path / "rocker.toml"
    path.write_text(GOOD.replace('kind = "P"', 'kind = "R"').replace(
        "roller = 10.0", "roller = 8.0\narm = 60.0\npivot = [70.0, 20.0]").replace(
        "rise = 30.0", "rise = 20.0").replace("fall = 30.0", "fall = 20.0"))
    code, out, err = run_cli("cam", path, "--json")
    assert code == 0, err
    data = json.loads(out)
    assert KEYS <= set(data) and data["offset"] is None and data["arm"] == 60.0
    assert data["stroke"] == pytest.approx(20.0)
