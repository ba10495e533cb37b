"""``chaingraph import PATH --from pylinkage|pyslvs [-o FILE]`` (issue 40): the chain file
printed or written (loaded back, it is the imported chain), the notes one line each on
standard error, every bad input one line and exit 2; and the writers ``export --to
pylinkage|pyslvs`` takes (``peer_writers``)."""

import json
import math
from pathlib import Path

import pytest

import chaingraph
from chaingraph.cli.interchange import peer_writers
from chaingraph.files import pylinkage_json, pyslvs_expression, read_pylinkage
from chaingraph.naming.catalog import catalog_path

from ..conftest import run_cli

DATA = Path(__file__).resolve().parent.parent / "files" / "data"


def test_a_pylinkage_model_is_printed_as_a_chain_file_with_its_notes(tmp_path):
    code, out, err = run_cli("import", DATA / "pylinkage-watt.json", "--from", "pylinkage")
    assert code == 0, err
    chain = chaingraph.loads(out)
    assert chain == read_pylinkage((DATA / "pylinkage-watt.json").read_text()).chain
    assert chaingraph.identify(chain).inversion == "Watt I six-bar mechanism"
    lines = err.splitlines()
    assert lines == [f"chaingraph import: note: driver 'crank': 0.0174533 rad a step is "
                     f"pylinkage's sampling (360 steps a turn), not a speed; not carried"]


def test_the_chain_file_written_loads_and_solves(tmp_path):
    path = tmp_path / "deep" / "slider.toml"
    code, out, err = run_cli("import", DATA / "pylinkage-slider-crank.json", "--from",
                             "pylinkage", "-o", path)
    assert code == 0 and out == "", err
    code, out, err = run_cli("solve", path, "--output", "slider rod.1", "--json")
    assert code == 0, err
    # crank 30, rod 100, its end on the line through (0, 15) along (1, 0.25): offset e
    # from the crank's pivot, the stroke between the two dead centres in line
    e = 15.0 / math.hypot(1.0, 0.25)
    stroke = math.sqrt(130.0 ** 2 - e ** 2) - math.sqrt(70.0 ** 2 - e ** 2)
    assert json.loads(out)["summary"]["stroke"] == pytest.approx(stroke, abs=1e-6)


def test_a_pyslvs_expression_with_its_input_and_name():
    code, out, err = run_cli("import", DATA / "pyslvs-four-bar.txt", "--from", "pyslvs",
                             "--input", "4:2", "--name", "my four-bar")
    assert code == 0 and err == ""
    chain = chaingraph.loads(out)
    assert (chain.name, chain.mechanism.driver, chain.mechanism.output) == \
        ("my four-bar", "L3", "P3")
    code, out, err = run_cli("import", DATA / "pyslvs-four-bar.txt", "--from", "pyslvs")
    assert code == 0 and err.splitlines() == [
        "chaingraph import: note: the expression holds no input: 'L1', on the first "
        "ground pivot P0, taken as the driver"]


@pytest.mark.parametrize("content, args, message", [
    ('{"joints": [', ("--from", "pylinkage"), "not JSON: Expecting value"),
    ('{"joints": [{"id": "A", "type": "hinge", "position": [0, 0]}], "links": []}',
     ("--from", "pylinkage"), "joint 'A': unknown type 'hinge'"),
    ("M[J[Q, P[0, 0], L[ground, a]]]", ("--from", "pyslvs"), "unknown joint type 'Q'"),
    ("M[J[R, P[0, 0], L[ground, a]]", ("--from", "pyslvs"), "not a Pyslvs expression"),
    ("M[J[R, P[0, 0], L[ground, a]]]", ("--from", "pylinkage"), "not JSON"),
    ("M[J[R, P[0, 0], L[ground, a]], J[R, P[1, 0], L[a, b]]]",
     ("--from", "pyslvs", "--driver", "c"), "no link 'c' to drive"),
    ('{"joints": []}', ("--from", "pylinkage", "--driver", "x"),
     "--driver, --input and --name are for --from pyslvs"),
    ('{"joints": []}', ("--from", "sam"), "invalid choice: 'sam'"),
    ("M[]", ("--from", "pyslvs", "--input", "0-1"), "expected BASE:DRIVE"),
])
def test_a_bad_model_or_flag_is_one_line_and_exit_2(tmp_path, content, args, message):
    path = tmp_path / "model"
    path.write_text(content)
    code, out, err = run_cli("import", path, *args)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and message in err, err


def test_a_missing_file_or_an_output_folder_is_one_line_and_exit_2(tmp_path):
    code, out, err = run_cli("import", tmp_path / "none.json", "--from", "pylinkage")
    assert code == 2 and err.strip().endswith("none.json: no such file")
    code, out, err = run_cli("import", DATA / "pylinkage-four-bar.json", "--from",
                             "pylinkage", "-o", tmp_path)
    assert code == 2 and "is a folder" in err and len(err.strip().splitlines()) == 1


def test_a_model_whose_drawing_does_not_close_is_refused_as_a_file_is(tmp_path):
    # a slider off its line is put on it; a link drawn with no length cannot be a link
    path = tmp_path / "flat.txt"
    path.write_text("M[J[R, P[0, 0], L[ground, a]], J[R, P[0, 0], L[a, b]], "
                    "J[R, P[0, 0], L[b, ground]]]")
    code, out, err = run_cli("import", path, "--from", "pyslvs")
    assert code == 2 and out == "" and "error" in err.splitlines()[-1]


def test_the_writers_for_export_are_the_library_s():
    writers = peer_writers()
    chain = chaingraph.load(catalog_path("beam-engine"))
    assert set(writers) == {"pylinkage", "pyslvs"}
    assert writers["pylinkage"](chain) == pylinkage_json(chain)
    assert writers["pyslvs"](chain) == pyslvs_expression(chain)
