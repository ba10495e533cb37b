"""The summary as a result: a frozen dataclass with named fields, its JSON the contract's
keys, its rows the command line's and the report's."""

import dataclasses
import json

import pytest

import chaingraph
from chaingraph.cli.main import main
from chaingraph.kinematics import ExtremePosition, Summary, summary_rows
from chaingraph.naming.catalog import catalog_path

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
