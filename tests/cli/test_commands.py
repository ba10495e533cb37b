"""The commands on the fuzzing pass's reproducers (issue 35, item 4): each one answers,
in one line when it refuses, and its JSON says what its text says."""

import json
import tomllib
from pathlib import Path

import chaingraph

from ..conftest import run_cli

DATA = Path(__file__).parents[1] / "data"


def test_assemble_json_of_a_file_with_a_joint_not_placed():
    """A drawn file with one joint's `at` removed: the text leaves the `at` out, the
    JSON gives null for it (it ended in a TypeError traceback)."""
    path = DATA / "assemble-json-missing-at.toml"
    written = tomllib.loads(path.read_text())
    code, out, err = run_cli("assemble", path, "--json")
    assert code == 0 and "Traceback" not in err, err
    data = json.loads(out)
    placed = {j["id"]: j.get("at") for j in written["joints"]}
    assert placed["O"] is None
    assert data["joints"] == placed
    assert data["axes"] == {j["id"]: j["axis"] for j in written["joints"] if j["kind"] == "P"}
    assert data["points"] == {p["id"]: p["at"] for p in written["points"]}
    code, text, err = run_cli("assemble", path)
    assert code == 0
    again = chaingraph.loads(text)
    assert {j.id: None if j.at is None else list(j.at) for j in again.joints} == placed
