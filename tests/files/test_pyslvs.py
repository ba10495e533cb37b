"""Pyslvs's mechanism expression in and out (issue 40): every catalog mechanism of turning
and sliding pairs comes back the same chain (isomorphic, every joint and point where it
was, to the last digit); the others are refused with the reason; expressions written as
Pyslvs writes them (tests/files/data) are solved here where Pyslvs's own solver puts
them (make_pyslvs_traces.py, run in Pyslvs's venv); bad expressions are one line."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import chaingraph
from chaingraph.errors import InterchangeError
from chaingraph.files import pyslvs_expression, read_pyslvs
from chaingraph.files.pyslvs import link_names, pins_in_slots
from chaingraph.model.chainfile import Document
from chaingraph.naming.catalog import catalog_files, catalog_path
from chaingraph.structure.isomorphism import is_isomorphic

DATA = Path(__file__).resolve().parent / "data"
MECHANISMS = [p for p in catalog_files() if chaingraph.load(p).mechanism is not None]


@pytest.mark.parametrize("path", MECHANISMS, ids=lambda p: p.stem)
def test_a_catalog_mechanism_comes_back_the_same_or_is_refused_with_the_reason(path):
    chain = chaingraph.load(path)
    try:
        text = pyslvs_expression(chain)
    except InterchangeError as e:
        assert chain.cams or any(j.kind not in ("R", "P") for j in chain.joints)
        assert "a Pyslvs expression cannot hold it: Pyslvs's joints are turning and " \
               "sliding pairs" in str(e)
        return
    back = read_pyslvs(text, source=str(path)).chain
    assert is_isomorphic(chain, back)
    fixed, names = chain.mechanism.fixed, link_names(chain, chain.mechanism.fixed)
    # a block that is a pin in a slot went as an RP joint and came back as a block of
    # its own name: find it by its sliding pair, at the same place on the same guide
    pins = pins_in_slots(chain, {chain.mechanism.fixed, chain.mechanism.driver})
    for p in (j for j in chain.joints if j.kind == "P"):
        at = chain.joint(pins[p.id]).at if p.id in pins else p.at   # an RP is at its pin
        (q,) = [q for q in back.joints if q.kind == "P" and q.at == at
                and q.axis == p.axis and q.links[0] == names[p.links[0]]]
        names[p.links[1]] = q.links[1]
    for j in chain.joints:
        at = chain.joint(pins[j.id]).at if j.id in pins else j.at
        same = [x for x in back.joints if (x.kind, x.at) == (j.kind, at)
                and sorted(x.links) == sorted(names[y] for y in j.links)]
        assert len(same) == 1, j.id
    assert len(back.joints) == len(chain.joints)
    assert sorted((q.at, q.link) for q in back.points) == \
        sorted((q.at, names[q.link]) for q in chain.points)
    assert back.mechanism.fixed == names[fixed] == "ground"
    if chain.mechanism.driver is not None:
        assert back.mechanism.driver == names[chain.mechanism.driver]
    assert back.joints[0].at == chain.joint(_first(chain)).at     # the crank's pivot first


def _first(chain):
    """The joint the writer puts first: the crank's pivot."""
    m = chain.mechanism
    if m.inputs:
        return m.inputs[0].joint
    return next((j.id for j in chain.joints if j.kind == "R"
                 and {m.fixed, m.driver} <= set(j.links)), None)


def test_every_catalog_mechanism_of_turning_and_sliding_pairs_is_held():
    refused = []
    for path in MECHANISMS:
        try:
            pyslvs_expression(chaingraph.load(path))
        except InterchangeError:
            refused.append(path.stem)
    higher = [p.stem for p in MECHANISMS if chaingraph.load(p).cams or any(
        j.kind not in ("R", "P") for j in chaingraph.load(p).joints)]
    assert refused == higher == ["cam-rocker", "disc-cam-roller-follower", "geared-five-bar"]
    with pytest.raises(InterchangeError, match="no \\[mechanism\\]"):
        pyslvs_expression(chaingraph.load(catalog_path("four-bar-chain")))


def test_names_pyslvs_cannot_spell_are_spelled_its_way_and_a_crosshead_is_a_pin_in_a_slot():
    text = pyslvs_expression(chaingraph.load(catalog_path("reciprocating-engine")))
    assert "L[crank, connecting_rod]" in text and "L[ground, crank]" in text
    assert text.splitlines()[1] == "  J[R, color[Green], P[0.0, 0.0], L[ground, crank]],"
    assert text.splitlines()[3] == \
        "  J[RP, A[0.0], color[Green], P[176.20499351813308, 0.0], L[ground, connecting_rod]],"
    # a block with more than a pin (the slotted lever's block is pinned to the crank,
    # the driver, and slides in the lever) is still an RP; the shaper's ram is a P
    text = pyslvs_expression(chaingraph.load(catalog_path("shaper-crank-and-slotted-lever")))
    assert "J[RP, A[" in text and "L[slotted_lever, crank]]" in text


MODELS = ["pyslvs-four-bar", "pyslvs-slider-crank", "pyslvs-watt", "pyslvs-stephenson"]


@pytest.mark.parametrize("stem", MODELS)
def test_an_expression_as_pyslvs_writes_it_is_solved_here_where_pyslvs_puts_it(stem):
    model = read_pyslvs((DATA / f"{stem}.txt").read_text(), source=stem)
    trace = json.loads((DATA / f"{stem}.trace.json").read_text())
    chain = model.chain
    assert chain.mechanism.driver == "L1"
    motion = chaingraph.solve(chain, steps=12, summary=False)
    assert motion.columns["theta"][0] == pytest.approx(trace["start_deg"], abs=1e-9)
    positions = np.array(trace["positions"])          # step, joint, xy
    points = {q.id for q in chain.points}
    size = float(np.ptp(positions[0], axis=0).max())
    for k in range(positions.shape[1]):
        ours = motion.point(f"P{k}") if f"P{k}" in points else motion.joint(f"P{k}")
        got = np.column_stack([ours.x, ours.y])
        assert np.abs(got - positions[:, k, :]).max() < 1e-9 * size, f"P{k}"
    assert model.notes == ("the expression holds no input: 'L1', on the first ground "
                           "pivot P0, taken as the driver",)


def test_an_rp_joint_is_a_pin_on_a_block_in_a_slot():
    model = read_pyslvs((DATA / "pyslvs-slider-crank.txt").read_text())
    chain = model.chain
    slot, pin = chain.joint("P2_slot"), chain.joint("P2")
    assert (slot.kind, slot.links, slot.axis) == ("P", ("ground", "P2_block"), 0.0)
    assert (pin.kind, pin.links, pin.at) == ("R", ("P2_block", "L2"), (117.3825, 10.0))
    assert chaingraph.identify(chain).inversion == "Reciprocating engine"


def test_inputs_and_a_driver_given_choose_the_input():
    text = (DATA / "pyslvs-four-bar.txt").read_text()
    assert read_pyslvs(text, driver="L3").chain.mechanism.driver == "L3"
    assert read_pyslvs(text, inputs=[(4, 2)]).chain.mechanism.driver == "L3"
    assert read_pyslvs(text, inputs=[(0, 1)]).notes == ()
    with pytest.raises(InterchangeError, match="P1 is not a pivot on the ground"):
        read_pyslvs(text, inputs=[(1, 2)])
    with pytest.raises(InterchangeError, match="no link 'L9' to drive"):
        read_pyslvs(text, driver="L9")


def test_comments_colours_and_joints_on_one_link_are_read():
    text = """# a four-bar, as Pyslvs's editor saves it
    M[
      J[R, color[(172, 68, 68)], P[0, 0], L[ground, L1]],  # the crank's pivot
      #[ a block comment
         over two lines #]
      J[R, color[dark-blue], P[0, 2.5e1], L[L1, L2]],
      J[R, P[60, 40], L[L2, L3]],
      J[R, P[70, 0], L[ground, L3]],
      J[R, P[30, 50], L[L2]],
      J[R, P[-1, -1], L[]],
    ]"""
    model = read_pyslvs(text)
    assert [j.id for j in model.chain.joints] == ["P0", "P1", "P2", "P3"]
    assert model.chain.point("P4").link == "L2" and model.chain.joint("P1").at == (0, 25)
    assert "P5 (line 10) is on no link: left out" in model.notes


@pytest.mark.parametrize("text, message", [
    ("M[J[Q, P[0, 0], L[ground, a]]]", "line 1: not a Pyslvs expression: unknown joint "
                                       "type 'Q' (expected one of R, P, RP)"),
    ("M[J[R, P[0, 0], L[ground, a]]", "expected 'close', found 'the end'"),
    ("M[J[P, P[0, 0], L[ground, a]]]", "a P joint needs its angle A[...]"),
    ("M[J[R, A[3], P[0, 0], L[ground, a]]]", "an R joint takes no angle A[...]"),
    ("M[J[R, color[mauve], P[0, 0], L[ground, a]]]", "unknown color 'mauve'"),
    ("M[J[R, P[0, x], L[ground, a]]]", "expected 'number', found 'x'"),
    ("M[J[R, P[0, 0], L[ground, a-b]]]", "'a-b' is not a link name"),
    ("M[J[R, P[0, 0], L[ground, a]]] extra", "'extra' after the mechanism's closing ']'"),
    ("M[\n J[R, P[0, 0], L[ground, a]],\n J[R, P[0; 0], L[a, b]]]",
     "line 3: not a Pyslvs expression: unexpected ';'"),
    ("M[J[P, A[0], P[0, 0], L[ground, a, b]]]", "P0: a P joint on 3 links"),
    ('{"joints": []}', "not a Pyslvs expression"),
])
def test_a_bad_expression_is_one_line_naming_where(text, message):
    with pytest.raises(InterchangeError) as caught:
        read_pyslvs(text, source="m.txt")
    assert message in str(caught.value) and "\n" not in str(caught.value)
    assert str(caught.value).startswith("m.txt: ") and caught.value.format == "pyslvs"


def test_a_round_trip_keeps_every_digit():
    chain = chaingraph.load(catalog_path("watt-i-mechanism"))
    moved = chaingraph.loads(chaingraph.dumps(chain).replace("[127.3, 23.301]",
                                                             "[127.3, 23.301000000000002]"))
    again = read_pyslvs(pyslvs_expression(moved)).chain
    assert any(j.at == (127.3, 23.301000000000002) for j in again.joints)
    assert math.isclose(again.joint("P0").at[0], 118.241)


def test_a_slider_s_own_input_pair_drives_its_slot():
    """Pyslvs's input (k, k) on an RP joint drives the slider along its slot (its
    "Slider lifter"): here a P input on the slot."""
    text = ("M[J[RP, A[0.0], P[0.0, 0.0], L[ground, L2]], J[R, P[50.0, 0.0], L[ground, L1]],"
            " J[R, P[25.0, 27.0], L[L1, L2]], J[R, P[50.0, 53.0], L[L2]]]")
    model = read_pyslvs(text, inputs=[(0, 0)])
    assert [i.joint for i in model.chain.mechanism.inputs] == ["P0_slot"]
    assert model.chain.mechanism.output == "P3" and model.notes == ()
    motion = chaingraph.solve(model.chain, start=0.0, stop=-10.0, steps=2, summary=False)
    # the block slides 10 back along x; L1 (pivot (50, 0), 36.8 long) keeps its length
    block = motion.joint("P0")
    assert block.x[-1] == pytest.approx(-10.0) and block.y[-1] == pytest.approx(0.0)
    pin = motion.joint("P2")
    assert math.hypot(pin.x[-1] - 50.0, pin.y[-1]) == pytest.approx(math.hypot(25.0, 27.0))


def test_the_imported_model_is_the_parsed_chain_file_and_its_text():
    model = read_pyslvs((DATA / "pyslvs-watt.txt").read_text(), name="Watt")
    assert isinstance(model.document, Document) and model.document.chain.name == "Watt"
    assert chaingraph.loads(model.toml()) == model.chain
