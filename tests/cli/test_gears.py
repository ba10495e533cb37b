"""``chaingraph gears`` (issue 39): the contract's JSON, the text, and bad input as one
line with exit status 2."""

import json

import pytest

from chaingraph.naming import catalog_dir

from ..conftest import run_cli

EPICYCLIC = catalog_dir() / "epicyclic-gear-train.toml"
DIFFERENTIAL = catalog_dir() / "differential-gear-train.toml"


def test_json_is_the_contracts():
    code, out, err = run_cli("gears", EPICYCLIC, "--fixed", "frame", "--speed", "annulus=0",
                             "--speed", "sun=1000", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert set(data) == {"name", "fixed", "speeds", "kind", "graph"}
    assert data["fixed"] == "frame" and data["kind"] == "epicyclic"
    # annulus held: the arm turns at sun * zs / (zs + za) = 1000 * 20 / 100
    assert data["speeds"]["arm"] == 200.0 and data["speeds"]["annulus"] == 0.0
    assert data["graph"]["gears"] == [["sun", "planet", "arm"], ["planet", "annulus", "arm"]]
    assert sorted(map(sorted, data["graph"]["turning"])) == [
        ["annulus", "frame"], ["arm", "frame"], ["arm", "planet"], ["frame", "sun"]]
    assert set(data["graph"]["links"]) == {"frame", "sun", "planet", "annulus", "arm"}


def test_text_shows_speeds_ratios_and_the_table():
    code, out, err = run_cli("gears", DIFFERENTIAL, "--fixed", "frame", "--speed",
                             "pinion=1000", "--speed", "left=-240")
    assert code == 0, err
    rows: dict[str, str] = {}
    for line in out.splitlines():            # the speeds' table comes first
        if line.split() and line.split()[0] in ("case", "right"):
            rows.setdefault(line.split()[0], line.split()[1])
    assert rows == {"case": "-250", "right": "-260"}
    assert "kind: epicyclic, 2 degrees of freedom" in out
    assert "carrier case: " in out and "carrier frame: " in out


@pytest.mark.parametrize("args, words", [
    (["--fixed", "nope"], "'fixed' names no link"),
    (["--fixed", "frame", "--speed", "nope=1"], "'speeds' names no link"),
    (["--fixed", "frame", "--speed", "sun"], "expected LINK=RPM"),
    (["--fixed", "frame", "--speed", "sun=fast"], "expected LINK=RPM"),
    (["--fixed", "frame", "--speed", "sun=inf"], "expected LINK=RPM"),
    (["--fixed", "frame", "--speed", "sun=1", "--speed", "sun=2"], "gives 'sun' twice"),
    (["--fixed", "frame", "--speed", "frame=1"], "to the fixed link"),
    (["--fixed", "frame", "--speed", "sun=1"], "give 2 speed(s)"),
    (["--fixed", "frame", "--speed", "sun=1", "--speed", "annulus=0", "--speed", "arm=7"],
     "disagree"),
    ([], "no fixed link"),
])
def test_bad_speeds_one_line_exit_2(args, words):
    code, out, err = run_cli("gears", EPICYCLIC, *args)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and words in err and "Traceback" not in err


@pytest.mark.parametrize("table, words", [
    ('teeth = [0, 30]', "gear pair 'G': key 'teeth' must be two positive whole numbers"),
    ('teeth = [20, 30]\ncarrier = "b"', "gear pair 'G': key 'carrier' is one of the gears"),
    ('teeth = [20, 30]\ncarrier = "arm"', "gear pair 'G': key 'carrier' 'arm' does not hold"),
    ('teeth = ["20", 30]', "gear pair 'G': key 'teeth'"),
])
def test_bad_gear_pairs_one_line_exit_2(tmp_path, table, words):
    path = tmp_path / "bad.toml"
    path.write_text('name = "bad"\n[[joints]]\nid = "A"\nkind = "R"\nlinks = ["frame", "a"]\n'
                    '[[joints]]\nid = "B"\nkind = "R"\nlinks = ["frame", "b"]\n'
                    '[[joints]]\nid = "C"\nkind = "R"\nlinks = ["arm", "a"]\n'
                    '[mechanism]\nfixed = "frame"\ndriver = "a"\n'
                    f'[[gears]]\nid = "G"\nlinks = ["a", "b"]\n{table}\n')
    code, out, err = run_cli("gears", path)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and words in err and "Traceback" not in err


def test_a_chain_without_gears_one_line_exit_2():
    code, out, err = run_cli("gears", catalog_dir() / "four-bar-chain.toml", "--fixed", "frame")
    assert code == 2 and "no gear pairs" in err and err.count("\n") == 1
