"""Property tests: malformed documents raise only ChainFileError, with a message."""

import copy
import datetime as dt

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from chaingraph import ChainFileError, Chain
from chaingraph.files import dumps, from_document, loads

BASE = {
    "name": "Offset slider crank",
    "family": "single slider crank chain",
    "units": "mm",
    "notes": "n",
    "space": "planar",
    "joints": [
        {"id": "O", "kind": "R", "links": ["frame", "crank"], "at": [0.0, 0.0]},
        {"id": "A", "kind": "R", "links": ["crank", "rod"], "at": [40.0, 0.0]},
        {"id": "B", "kind": "R", "links": ["rod", "slider"], "at": [159.58, 10.0]},
        {"id": "S", "kind": "P", "links": ["frame", "slider"], "at": [159.58, 10.0], "axis": 0.0},
    ],
    "points": [{"id": "tip", "link": "rod", "at": [100.0, 5.0]}],
    "mechanism": {"fixed": "frame", "driver": "crank", "omega": 2.0, "output": "slider"},
}

SCALARS = st.one_of(
    st.text(max_size=8), st.integers(-2**63, 2**63 - 1),
    st.floats(allow_nan=True, allow_infinity=True), st.booleans(),
    st.datetimes(), st.dates(), st.times(),
    st.sampled_from(["R", "P", "cam", "frame", "crank", "slider", "tip", "O", "", "spatial"]))
VALUES = st.recursive(SCALARS, lambda inner: st.one_of(
    st.lists(inner, max_size=4), st.dictionaries(st.text(max_size=5), inner, max_size=3)),
    max_leaves=8)
KEYS = st.sampled_from(["name", "family", "units", "space", "notes", "joints", "points",
                        "mechanism", "id", "kind", "links", "at", "axis", "closure", "link",
                        "fixed", "driver", "omega", "output", "extra"])


def _tables(doc):
    """Every table of the document, with the top level first."""
    tables = [doc]
    for key in ("joints", "points"):
        if isinstance(doc.get(key), list):
            tables += [t for t in doc[key] if isinstance(t, dict)]
    if isinstance(doc.get("mechanism"), dict):
        tables.append(doc["mechanism"])
    return tables


@st.composite
def malformed(draw):
    doc = copy.deepcopy(BASE)
    for _ in range(draw(st.integers(1, 4))):
        tables = _tables(doc)
        table = tables[draw(st.integers(0, len(tables) - 1))]
        action = draw(st.sampled_from(["set", "delete", "add"]))
        if action == "set" and table:
            table[draw(st.sampled_from(sorted(table)))] = draw(VALUES)
        elif action == "delete" and table:
            del table[draw(st.sampled_from(sorted(table)))]
        else:
            table[draw(KEYS)] = draw(VALUES)
    return doc


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(malformed())
def test_malformed_documents_raise_only_chain_file_error(doc):
    try:
        chain = from_document(doc, source="fuzz.toml")
    except ChainFileError as e:
        message = str(e)
        assert message.startswith("fuzz.toml") and len(message) > len("fuzz.toml: ")
        assert "\n" not in message
        assert e.problem
    else:
        assert isinstance(chain, Chain)
        assert loads(dumps(chain)) == chain  # whatever loads, writes back the same


@settings(max_examples=300, deadline=None)
@given(st.text(max_size=200))
def test_any_text_raises_only_chain_file_error(text):
    try:
        loads(text, source="t.toml")
    except ChainFileError as e:
        assert str(e).startswith("t.toml")


@settings(max_examples=100, deadline=None)
@given(st.text(min_size=1, max_size=12), st.text(min_size=1, max_size=12),
       st.floats(-1e9, 1e9), st.floats(-1e9, 1e9))
def test_any_names_and_numbers_round_trip(link, joint_id, x, y):
    doc = {"name": "chain", "joints": [
        {"id": joint_id, "kind": "R", "links": [link, link + "2"], "at": [x, y]}]}
    chain = from_document(doc)
    assert loads(dumps(chain)) == chain


def test_base_document_is_valid():
    chain = from_document(BASE)
    assert chain.mechanism.output == "slider" and dt  # dt is used by the strategies
