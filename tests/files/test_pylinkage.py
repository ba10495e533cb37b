"""pylinkage 1.3's JSON in and out (issue 40): every catalog mechanism that pylinkage can
hold comes back the same chain (isomorphic, every joint and point where it was, so every
length the same, to 1e-12); the others are refused with the reason; models written by
pylinkage itself (tests/files/data, made by make_pylinkage_models.py in pylinkage's venv)
are solved here and land where pylinkage's own simulation put them; bad files are one
line."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph.errors import ChainFileError, InterchangeError
from chaingraph.files import pylinkage_json, read_pylinkage
from chaingraph.model.chain import Chain
from chaingraph.naming.catalog import catalog_files, catalog_path
from chaingraph.structure.isomorphism import is_isomorphic

DATA = Path(__file__).resolve().parent / "data"
MECHANISMS = [p for p in catalog_files() if chaingraph.load(p).mechanism is not None]


def _size(chain: Chain) -> float:
    xy = [j.at for j in chain.joints if j.at is not None]
    return max(math.dist(a, b) for a in xy for b in xy)


def _lengths(chain: Chain, rename: dict[str, str]) -> dict[str, list[float]]:
    """Each link's distances between its R joints and points, sorted, the link renamed."""
    out = {}
    for link in chain.links:
        spots = [j.at for j in chain.joints_of(link) if j.kind == "R"] + \
            [q.at for q in chain.points if q.link == link]
        out[rename.get(link, link)] = sorted(math.dist(a, b) for k, a in enumerate(spots)
                                             for b in spots[k + 1:])
    return out


def _round_trip_or_refusal(path):
    chain = chaingraph.load(path)
    try:
        text = pylinkage_json(chain)
    except InterchangeError as e:
        return chain, None, e
    return chain, read_pylinkage(text, source=str(path)), None


@pytest.mark.parametrize("path", MECHANISMS, ids=lambda p: p.stem)
def test_a_catalog_mechanism_comes_back_the_same_or_is_refused_with_the_reason(path):
    chain, model, refusal = _round_trip_or_refusal(path)
    if refusal is not None:
        assert "pylinkage cannot hold it: " in str(refusal) and refusal.format == "pylinkage"
        reasons = ("sliding pair between two moving links", "turning and sliding pairs",
                   "input is not a crank", "slider is one pin", "slider has no body")
        assert any(r in str(refusal) for r in reasons), str(refusal)
        return
    back = model.chain
    assert is_isomorphic(chain, back)
    sliders = {p.links[1 - p.links.index(chain.mechanism.fixed)]: next(
        j.id for j in chain.joints_of(p.links[1 - p.links.index(chain.mechanism.fixed)])
        if j.kind == "R") for p in chain.joints if p.kind == "P"}
    rename = {block: f"slider {pin}" for block, pin in sliders.items()}
    tol = 1e-12 * _size(chain)
    for j in (j for j in chain.joints if j.kind == "R"):
        again = back.joint(j.id)
        assert math.dist(again.at, j.at) <= tol
        assert sorted(rename.get(x, x) for x in j.links) == sorted(again.links)
    for q in chain.points:
        assert math.dist(back.point(q.id).at, q.at) <= tol
        assert back.point(q.id).link == q.link
    assert [j.axis for j in chain.joints if j.kind == "P"] == \
        pytest.approx([j.axis for j in back.joints if j.kind == "P"], abs=1e-12)
    a, b = _lengths(chain, rename), _lengths(back, {})
    assert a.keys() == b.keys()
    for link in a:
        assert a[link] == pytest.approx(b[link], abs=tol)
    assert back.mechanism.fixed == chain.mechanism.fixed
    if back.mechanism.driver is not None:
        assert back.mechanism.driver == chain.mechanism.driver
    else:   # a driver that rocks went as an arc_driver: back as its range, limit to limit
        (item,) = back.mechanism.inputs
        assert set(back.joint(item.joint).links) == {chain.mechanism.fixed,
                                                     chain.mechanism.driver}
        theta = chaingraph.solve(chain, steps=4, summary=False).columns["theta"]
        assert (item.start, item.stop) == pytest.approx((min(theta), max(theta)), abs=1e-6)


def test_most_catalog_mechanisms_go_to_pylinkage_and_those_with_moving_slides_do_not():
    held = {p.stem for p in MECHANISMS if _round_trip_or_refusal(p)[2] is None}
    assert {"beam-engine", "reciprocating-engine", "crank-rocker-with-slider",
            "watt-i-mechanism", "watt-ii-mechanism", "stephenson-i-mechanism",
            "stephenson-ii-mechanism", "stephenson-iii-mechanism"} <= held
    refusal = _round_trip_or_refusal(catalog_path("crank-and-slotted-lever-mechanism"))[2]
    assert "a sliding pair between two moving links ('block', 'slotted lever')" in \
        str(refusal) and refusal.where == "joint 'S'"
    refusal = _round_trip_or_refusal(catalog_path("cam-and-follower"))[2]
    assert "turning and sliding pairs (this has cam)" in str(refusal)
    with pytest.raises(InterchangeError, match="no \\[mechanism\\]"):
        pylinkage_json(chaingraph.load(catalog_path("four-bar-chain")))


def test_the_crank_and_its_tracker_are_written_as_pylinkage_reads_them():
    chain = chaingraph.load(catalog_path("beam-engine"))
    data = json.loads(pylinkage_json(chain))
    crank = next(x for x in data["links"] if x["type"] == "driver")
    a, b = chain.joint("A").at, chain.joint("B").at
    assert crank["motor_joint"] == "A" and crank["joints"] == ["A", "B"]
    assert crank["initial_angle"] == pytest.approx(math.atan2(b[1] - a[1], b[0] - a[0]))
    assert crank["angular_velocity"] == pytest.approx(math.tau / 360)
    # the tracker E, put back where pylinkage's TrackerJoint.update_position puts it
    e = next(j for j in data["joints"] if j["type"] == "tracker")
    one, two = (chain.joint(e[k]).at for k in ("ref_joint1_id", "ref_joint2_id"))
    turn = math.atan2(two[1] - one[1], two[0] - one[0]) + e["angle"]
    placed = (one[0] + e["distance"] * math.cos(turn), one[1] + e["distance"] * math.sin(turn))
    assert math.dist(placed, chain.point("E").at) < 1e-12 * 200
    assert data["ground"] == "frame"


def test_a_swept_input_is_an_arc_driver_and_comes_back_as_its_sweep():
    chain = chaingraph.load(catalog_path("beam-engine"))
    swept = chaingraph.loads(chaingraph.dumps(chain).replace(
        'driver = "crank"', 'inputs = [{joint = "A", from = 40.0, to = 100.0}]'))
    data = json.loads(pylinkage_json(swept))
    arc = next(x for x in data["links"] if x["type"] == "arc_driver")
    assert (arc["arc_start"], arc["arc_end"]) == pytest.approx(
        (math.radians(40.0), math.radians(100.0)))
    back = read_pylinkage(json.dumps(data)).chain
    (item,) = back.mechanism.inputs
    assert (item.joint, item.start, item.stop) == ("A", pytest.approx(40.0),
                                                   pytest.approx(100.0))


MODELS = ["pylinkage-four-bar", "pylinkage-slider-crank", "pylinkage-watt",
          "pylinkage-stephenson"]


@pytest.mark.parametrize("stem", MODELS)
def test_a_model_pylinkage_wrote_is_solved_here_where_pylinkage_put_it(stem):
    model = read_pylinkage((DATA / f"{stem}.json").read_text(), source=stem)
    trace = json.loads((DATA / f"{stem}.trace.json").read_text())
    chain = model.chain
    motion = chaingraph.solve(chain, steps=12, summary=False)
    positions = np.array(trace["positions"])          # step, joint, xy
    size = _size(chain)
    for k, joint in enumerate(trace["joints"]):
        ours = motion.point(joint) if joint in {q.id for q in chain.points} \
            else motion.joint(joint)
        got = np.column_stack([ours.x, ours.y])
        assert np.abs(got - positions[:, k, :]).max() < 1e-9 * size, joint
    # the drawn pose is the model's own, and the notes say what was left
    assert any("rad a step" in n for n in model.notes)


def test_the_models_are_named_here_by_their_structure():
    named = {}
    for stem in MODELS:
        chain = read_pylinkage((DATA / f"{stem}.json").read_text()).chain
        named[stem] = chaingraph.identify(chain).inversion
    assert named["pylinkage-four-bar"] == "Beam engine (crank and lever mechanism)"
    assert named["pylinkage-slider-crank"] == "Reciprocating engine"
    assert named["pylinkage-watt"] == "Watt I six-bar mechanism"
    assert named["pylinkage-stephenson"].startswith("Stephenson")


def test_pylinkage_s_six_bar_factories_are_degenerate_eight_link_chains():
    """pylinkage.synthesis's watt_from_lengths and stephenson_from_lengths build their
    second loop as dyads on two joints of one link: a rigid triangle of three binary
    links, eight links in all, which no six-bar is."""
    for stem in ("pylinkage-watt-factory", "pylinkage-stephenson-factory"):
        chain = read_pylinkage((DATA / f"{stem}.json").read_text()).chain
        result = chaingraph.classify(chain)
        assert len(chain.links) == 8 and result.degenerate
        assert any(len(group) == 3 for group in result.rigid_subchains)


def test_links_that_share_two_joints_are_one_link_and_the_note_says_so():
    chain = chaingraph.load(catalog_path("stephenson-i-mechanism"))
    data = json.loads(pylinkage_json(chain))
    assert any(x["id"] == "crank plate" for x in data["links"])
    model = read_pylinkage(json.dumps(data))
    assert "crank plate" not in model.chain.links
    assert any("'crank' and 'crank plate' share joints" in n for n in model.notes)


def _model(**change):
    data = json.loads((DATA / "pylinkage-four-bar.json").read_text())
    data.update(change)
    return data


@pytest.mark.parametrize("text, message", [
    ('{"joints": [', "not JSON: Expecting value (line 1, column 13)"),
    ("[1, 2]", "not a pylinkage mechanism"),
    (json.dumps({"joints": [{"id": "A", "type": "hinge", "position": [0, 0]}], "links": []}),
     "joint 'A': unknown type 'hinge' (expected one of ground, revolute, prismatic, tracker)"),
    (json.dumps({"joints": [{"id": "A", "type": "revolute", "position": [0, "x"]}],
                 "links": []}), "joint 'A': its position is not two finite numbers"),
    (json.dumps(_model(links=[{"id": "bar", "type": "spring", "joints": []}])),
     "link 'bar': unknown type 'spring'"),
    (json.dumps(_model(links=[{"id": "bar", "type": "link", "joints": ["Z"]}])),
     "link 'bar': names no joint 'Z'"),
    (json.dumps({"joints": [{"id": "A", "type": "Crank"}], "links": []}),
     "pylinkage's legacy format (joint type 'Crank')"),
    (json.dumps(_model(links=[])), "no ground link"),
])
def test_a_bad_model_is_one_line_naming_what(text, message):
    with pytest.raises(InterchangeError) as caught:
        read_pylinkage(text, source="m.json")
    assert message in str(caught.value) and "\n" not in str(caught.value)
    assert str(caught.value).startswith("m.json: ")


def test_a_model_that_is_no_valid_chain_is_a_chain_file_error():
    data = _model()
    for x in data["links"]:
        if x["type"] == "link":
            x["joints"] = x["joints"][:1]
    with pytest.raises(ChainFileError):
        read_pylinkage(json.dumps(data)).chain
