"""``lint`` (issue 40): one fixture per kind of finding, each found where it is; the
catalog clean; the command's lines and exit statuses."""

import json
from pathlib import Path

import pytest

import chaingraph
from chaingraph.model.chainfile import parse_file
from chaingraph.naming import lint
from chaingraph.naming.catalog import catalog_files
from chaingraph.naming.linter import KINDS

from ..conftest import run_cli

HERE = Path(__file__).resolve().parent / "lint"

FOUND = {
    "pose": "joint 'C'",
    "degenerate": "links '1', '2', '3'",
    "locked": "chain",
    "mobility": "link 'left'",
    "name": "chain",
    "branch": "link 'crank'",
}


def test_every_kind_has_a_fixture():
    assert sorted(FOUND) == sorted(KINDS)


@pytest.mark.parametrize("kind", sorted(FOUND))
def test_each_fixture_gives_its_finding_and_only_it(kind):
    findings = lint(parse_file(HERE / f"{kind}.toml"))
    assert [(f.kind, f.where) for f in findings] == [(kind, FOUND[kind])]


def test_the_messages_say_what():
    said = {k: lint(parse_file(HERE / f"{k}.toml"))[0].message for k in FOUND}
    assert "does not close" in said["pose"] and "6.62097 mm" in said["pose"]
    assert "mobility 1" in said["degenerate"]
    assert "Kutzbach's mobility is 0" in said["locked"]
    assert "is 2 at the drawn pose" in said["mobility"]
    assert "Watt" in said["name"] and "Stephenson six-bar chain" in said["name"]
    assert "dead centre" in said["branch"]


def test_a_circuit_the_driver_cannot_reach():
    """A crank-rocker drawn crossed drives a dyad that stops its crank; open, with the
    same lengths, the crank turns fully (the solver says both)."""
    findings = lint(parse_file(HERE / "circuit.toml"))
    assert [(f.kind, f.where) for f in findings] == [("branch", "link 'crank'")]
    assert "assembled with C left" in findings[0].message
    drawn = chaingraph.solve(chaingraph.load(HERE / "circuit.toml"), steps=36)
    assert not drawn.summary.full_turn
    text = chaingraph.kinematics.measure(chaingraph.load(HERE / "circuit.toml"))
    other = chaingraph.loads(text.replace('C = "right"', 'C = "left"'))
    assert chaingraph.solve(other, steps=36).summary.full_turn


def test_a_name_of_the_wrong_count_of_links(tmp_path):
    text = (HERE / "mobility.toml").read_text().replace("Five links with one driver",
                                                       "Four-bar with one driver")
    (tmp_path / "x.toml").write_text(text)
    kinds = {(f.kind, f.message) for f in lint(parse_file(tmp_path / "x.toml"))}
    assert ("name", "the name says four-bar (4 links), the chain has 5 links") in kinds


def test_the_catalog_is_clean():
    found = {path.name: lint(parse_file(path)) for path in catalog_files()}
    assert {k: v for k, v in found.items() if v} == {}


def test_the_command_prints_a_line_per_finding_and_exits_1():
    files = [HERE / f"{k}.toml" for k in sorted(FOUND)]
    code, out, err = run_cli("lint", *files)
    assert code == 1, err
    lines = out.strip().splitlines()
    assert len(lines) == len(FOUND)
    for line, kind in zip(lines, sorted(FOUND)):
        assert line.startswith(f"{HERE / kind}.toml: {FOUND[kind]}: {kind}: ")


def test_clean_files_exit_0_and_an_unreadable_one_2(tmp_path):
    clean = catalog_files()[0]
    assert run_cli("lint", clean) == (0, "", "")
    (tmp_path / "bad.toml").write_text("name = ")
    code, out, err = run_cli("lint", tmp_path / "bad.toml", HERE / "name.toml")
    assert code == 2 and "TOML syntax error" in err and len(err.strip().splitlines()) == 1
    assert out.startswith(f"{HERE / 'name.toml'}: chain: name: ")


def test_a_chain_is_linted_as_its_file():
    chain = chaingraph.load(HERE / "name.toml")
    assert lint(chain) == lint(parse_file(HERE / "name.toml"))


def test_json_gives_each_file_s_findings():
    code, out, err = run_cli("lint", "--json", HERE / "mobility.toml", catalog_files()[0])
    assert code == 1, err
    data = json.loads(out)
    assert data[str(HERE / "mobility.toml")] == [
        {"where": "link 'left'", "kind": "mobility",
         "message": lint(parse_file(HERE / "mobility.toml"))[0].message}]
    assert data[str(catalog_files()[0])] == []


def test_a_mechanism_with_no_freedom_is_locked(tmp_path):
    text = (HERE / "locked.toml").read_text() + 'mechanism = {fixed = "frame", driver = "crank"}\n'
    (tmp_path / "x.toml").write_text(text)
    findings = lint(parse_file(tmp_path / "x.toml"))
    assert [(f.kind, f.where) for f in findings] == [("locked", "link 'crank'")]
    assert "no freedom at the drawn pose" in findings[0].message


def test_lint_reads_the_peers_models_as_import_reads_them():
    """A pylinkage JSON and a Pyslvs expression are linted as imported: pylinkage's
    Watt factory is a degenerate 8-link chain misnamed Watt; the hand-written Pyslvs
    Watt six-bar and pylinkage four-bar are clean."""
    data = "tests/files/data/"
    code, said, err = run_cli("lint", data + "pylinkage-watt-factory.json",
                              data + "pyslvs-watt.txt", data + "pylinkage-four-bar.json")
    assert code == 1, err
    lines = said.splitlines()
    assert [line.split(": ")[2] for line in lines] == ["degenerate", "name"]
    assert all(line.startswith(data + "pylinkage-watt-factory.json: ") for line in lines)
    code, said, err = run_cli("lint", data + "pyslvs-watt.txt")
    assert (code, said) == (0, "")
