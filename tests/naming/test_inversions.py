"""Inversions, isomorphism, names and identify."""

import json
import math
import random
from collections import Counter

import networkx as nx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from networkx.algorithms.isomorphism import GraphMatcher

import chaingraph
from chaingraph import Chain, ChainStructureError, Joint, Mechanism
from chaingraph.kinematics.behaviour import behaviour, turning_links
from chaingraph.naming.catalog import catalog_files, catalog_path
from chaingraph.structure.generators import random_chain
from chaingraph.naming.identification import identify
from chaingraph.naming.inversion_classes import inversions
from chaingraph.structure.isomorphism import (automorphism_orbits, canonical, canonical_form,
                                    is_isomorphic, isomorphism)

from ..conftest import run_cli


def load(stem):
    return chaingraph.load(catalog_path(stem))


@pytest.mark.parametrize("stem, classes, with_input", [
    # single slider: no automorphism, so its 6 (fixed, input) pairs are 6 classes
    ("four-bar-chain", 1, 1), ("single-slider-crank-chain", 4, 6),
    ("double-slider-crank-chain", 3, 2), ("watt-six-bar-chain", 2, 4),
    ("stephenson-six-bar-chain", 3, 5), ("three-link-locked-chain", 1, 1),
    # two ternary joints: a link's partners on its ternary joint and on its binary
    # joint are two kinds of input
    ("six-link-two-ternary-joints", 1, 2),
])
def test_class_counts(stem, classes, with_input):
    result = inversions(load(stem), with_input=True)
    assert result.classes == classes
    assert result.classes_with_input == with_input
    assert len(result.inversions) == len(load(stem).links)


def test_double_slider_puts_the_two_sliders_together():
    result = inversions(load("double-slider-crank-chain"))
    cls = {i.fixed: i.class_ for i in result.inversions}
    assert cls["slider 1"] == cls["slider 3"]
    assert len({cls["slider 1"], cls["bar"], cls["plate"]}) == 3


def test_watt_and_stephenson_input_classes():
    watt = inversions(load("watt-six-bar-chain"), with_input=True)
    t1 = watt.inversion("t1")
    # a ternary link fixed: input the other ternary link, or a binary one
    assert sorted(i.driver for i in t1.inputs) == ["b1", "b3", "t2"]
    assert len({i.class_ for i in t1.inputs}) == 2
    steph = inversions(load("stephenson-six-bar-chain"), with_input=True)
    assert len({i.class_ for i in steph.inversion("b1").inputs}) == 1  # t1, t2 alike


def test_single_slider_names_come_through_the_isomorphism():
    names = {
        "frame": "Reciprocating engine",
        "crank": "Whitworth quick return mechanism",
        "rod": "Crank and slotted lever quick return mechanism",
        "crosshead": "Pendulum pump (bull engine)",
    }
    chain = load("single-slider-crank-chain")
    rng = random.Random(3)
    shuffled = rng.sample(chain.links, 4)
    renamed = chain.relabelled(links={x: f"part {i}" for i, x in enumerate(shuffled)},
                               joints={j.id: f"j{i}" for i, j in enumerate(chain.joints)})
    back = {f"part {i}": x for i, x in enumerate(shuffled)}
    for chain_ in (chain, renamed):
        result = inversions(chain_)
        for inv in result.inversions:
            original = back.get(inv.fixed, inv.fixed)
            assert names[original] in inv.names
    gnome = inversions(chain).inversion("crank").names
    assert "Rotary (Gnome) engine" in gnome
    assert "Oscillating cylinder engine" in inversions(chain).inversion("rod").names


def test_single_slider_chain_without_dimensions_still_named():
    chain = load("single-slider-crank-chain")
    bare = Chain(chain.name, tuple(Joint(j.id, j.kind, j.links) for j in chain.joints))
    result = inversions(bare)
    assert all(i.names for i in result.inversions) and all(i.behaviour is None for i in result.inversions)


def _four_bar(frame, crank, coupler, rocker, angle=50.0, *, names=("frame", "a", "b", "c")):
    A, D = (0.0, 0.0), (frame, 0.0)
    B = (crank * math.cos(math.radians(angle)), crank * math.sin(math.radians(angle)))
    dx, dy = D[0] - B[0], D[1] - B[1]
    d = math.hypot(dx, dy)
    x = (coupler ** 2 - rocker ** 2 + d * d) / (2 * d)
    h = math.sqrt(coupler ** 2 - x * x)
    C = (B[0] + x * dx / d - h * dy / d, B[1] + x * dy / d + h * dx / d)
    f, a, b, c = names
    return Chain("four-bar", (Joint("A", "R", (f, a), at=A), Joint("B", "R", (a, b), at=B),
                              Joint("C", "R", (b, c), at=C), Joint("D", "R", (c, f), at=D)))


def test_grashof_four_bar_all_inversions_by_hand():
    # frame 100, a 40 (shortest), b 120 (longest), c 80: 40 + 120 < 100 + 80
    chain = _four_bar(100, 40, 120, 80)
    by_hand = {"frame": "crank-rocker", "a": "double crank", "b": "crank-rocker",
               "c": "double rocker"}
    result = inversions(chain)
    for inv in result.inversions:
        assert inv.behaviour == by_hand[inv.fixed]
    assert set(result.inversion("a").full_turns) == {"frame", "b", "c"}
    assert result.inversion("frame").full_turns == ("a",)
    assert result.inversion("c").full_turns == ("a",)  # the coupler turns fully
    assert result.inversion("frame").names == ("Beam engine (crank and lever mechanism)",)
    assert result.inversion("a").names == ("Coupling rod of a locomotive",)
    assert result.inversion("c").names == ("Watt's indicator mechanism",)


def test_non_grashof_four_bar_is_a_triple_rocker_everywhere():
    # 30 + 120 > 100 + 45: no link turns fully (the seeds' notes wrongly say double crank)
    chain = _four_bar(100, 45, 120, 30, angle=100)
    result = inversions(chain)
    assert [i.behaviour for i in result.inversions] == ["triple rocker"] * 4
    assert all(i.full_turns == () for i in result.inversions)
    # the catalog's non-Grashof four-bar is a triple rocker too: its name, every time
    assert all(i.names == ("Non-Grashof four-bar (triple rocker)",)
               for i in result.inversions)


def test_change_point_cases():
    assert {behaviour(_four_bar(100, 40, 100, 40), x) for x in ("frame", "a", "b", "c")} == \
        {"double crank, parallelogram"}
    kite = _four_bar(100, 100, 40, 40, angle=30)  # frame 100, a 100, b 40, c 40
    assert behaviour(kite, "frame") == "change point, deltoid"
    assert behaviour(kite, "b") == "change point, Galloway"
    assert behaviour(_four_bar(100, 70, 90, 60), "frame") == "change point"


def _slider_crank(crank, rod, offset, angle=60.0, *, guide_on_frame=True):
    O = (0.0, 0.0)
    A = (crank * math.cos(math.radians(angle)), crank * math.sin(math.radians(angle)))
    Bx = A[0] + math.sqrt(rod ** 2 - (offset - A[1]) ** 2)
    B = (Bx, offset)
    slide = ("frame", "slider") if guide_on_frame else ("slider", "frame")
    return Chain("offset slider crank", (
        Joint("O", "R", ("frame", "crank"), at=O), Joint("A", "R", ("crank", "rod"), at=A),
        Joint("B", "R", ("rod", "slider"), at=B), Joint("S", "P", slide, at=B, axis=0.0)),
        mechanism=Mechanism("frame", "crank", 1.0, "slider"))


@pytest.mark.parametrize("crank, rod, offset, turns", [
    (40, 120, 10, True), (40, 120, 80, True), (40, 120, 80.5, False), (50, 60, 20, False)])
def test_slider_crank_turns_fully_when_crank_plus_offset_within_rod(crank, rod, offset, turns):
    chain = _slider_crank(crank, rod, offset, angle=60 if offset < 75 else 90)
    assert ("crank" in turning_links(chain, "frame")) is turns


def test_identify_offset_slider_crank_is_a_reciprocating_engine():
    found = identify(_slider_crank(40, 120, 10))
    assert found.chain == "Single slider crank chain"
    assert found.inversion == "Reciprocating engine"
    # the mapping is onto the inversion named (the catalog's reciprocating engine)
    assert found.mapping == {"frame": "frame", "crank": "crank", "rod": "connecting rod",
                             "slider": "crosshead"}
    assert found.orientation == "respected"


def test_identify_natural_crank_and_slotted_lever():
    # written as the contract's example: the lever carries the slot (guide)
    A, C = (0.0, 0.0), (0.0, 300.0)
    B = (120.0, 300.0)
    axis = math.degrees(math.atan2(B[1], B[0]))
    chain = Chain("my shaper", (
        Joint("O", "R", ("frame", "crank"), at=C), Joint("B", "R", ("crank", "block"), at=B),
        Joint("slot", "P", ("lever", "block"), at=B, axis=axis),
        Joint("A", "R", ("lever", "frame"), at=A)),
        mechanism=Mechanism("frame", "crank", 1.0, "lever"))
    assert identify(chain).inversion == "Crank and slotted lever quick return mechanism"


CATALOG_MECHANISMS = [p for p in catalog_files() if chaingraph.load(p).mechanism
                      and not chaingraph.load(p).task]
#: synthesised mechanisms (a [task]): examples of a design, which name nothing
SYNTHESISED = [p for p in catalog_files() if chaingraph.load(p).task]


@pytest.mark.parametrize("path", SYNTHESISED, ids=[p.stem for p in SYNTHESISED])
def test_a_synthesised_catalog_mechanism_is_named_by_its_kind_not_by_itself(path):
    chain = chaingraph.load(path)
    found = identify(chain)
    assert found.inversion is not None and found.inversion != chain.name
    assert chaingraph.load(found.inversion_file).task is None


@pytest.mark.parametrize("path", CATALOG_MECHANISMS, ids=[p.stem for p in CATALOG_MECHANISMS])
def test_every_catalog_mechanism_identifies_as_itself(path):
    chain = chaingraph.load(path)
    found = identify(chain)
    assert found.inversion == chain.name
    chains = {c.name: c for c in (chaingraph.load(p) for p in catalog_files()) if c.mechanism is None}
    if found.chain is None:        # no catalog chain of this structure: said so
        assert "the catalog has no chain of this structure" in found.note
    else:
        assert found.chain in chains
    # the mapping sends the fixed link to the catalog inversion's own
    assert found.mapping[chain.mechanism.fixed] == chain.mechanism.fixed
    code, out, err = run_cli("identify", "--json", path)
    assert code == 0 and json.loads(out)["inversion"] == chain.name


def test_catalog_has_the_named_mechanisms():
    names = {chaingraph.load(p).name for p in CATALOG_MECHANISMS}
    for word in ("Beam engine", "Coupling rod", "Watt's indicator", "Reciprocating engine",
                 "Pendulum pump", "Oscillating cylinder", "Crank and slotted lever",
                 "Whitworth", "Gnome", "Elliptical trammels", "Scotch yoke", "Oldham"):
        assert any(word in n for n in names), word


@pytest.mark.parametrize("path", catalog_files(), ids=[p.stem for p in catalog_files()])
def test_every_catalog_chain_identifies(path):
    chain = chaingraph.load(path)
    if chain.mechanism is None:
        assert identify(chain).chain == chain.name


def test_identify_unknown_chain_is_not_an_error():
    code, out, err = run_cli("identify", "--json", catalog_path("five-link-chain"))
    assert code == 0
    pent = Chain("hexagon", tuple(Joint(f"J{i}", "R", (f"{i}", f"{(i + 1) % 6}")) for i in range(6)))
    assert identify(pent).to_dict() == {"chain": None, "inversion": None, "mapping": {},
                                        "orientation": "respected", "joint_kinds": "respected",
                                        "note": "the catalog has no chain of this structure"}


def test_disconnected_chain_is_refused_with_its_pieces(tmp_path):
    path = tmp_path / "apart.toml"
    path.write_text('name = "apart"\n' + "".join(
        f'[[joints]]\nid = "{i}"\nkind = "R"\nlinks = ["{a}", "{b}"]\n'
        for i, (a, b) in enumerate([("1", "2"), ("2", "3"), ("3", "1"), ("4", "5")])))
    with pytest.raises(ChainStructureError, match="2 pieces"):
        inversions(chaingraph.load(path))
    for command in ("inversions", "identify"):
        code, out, err = run_cli(command, path)
        assert code == 2 and "{1, 2, 3}; {4, 5}" in err and "Traceback" not in err


def test_mechanism_naming_no_link_exits_2(tmp_path):
    text = catalog_path("beam-engine").read_text().replace('driver = "crank"', 'driver = "cranks"')
    path = tmp_path / "bad.toml"
    path.write_text(text)
    code, out, err = run_cli("inversions", path)
    assert code == 2 and "'driver' names no link" in err


def test_cli_inversions_json_keys():
    code, out, err = run_cli("inversions", "--json", "--with-input",
                             catalog_path("single-slider-crank-chain"))
    d = json.loads(out)
    assert code == 0 and set(d) == {"name", "links", "classes", "inversions", "classes_with_input"}
    assert d["classes"] == 4 and d["classes_with_input"] == 6
    inv = d["inversions"][0]
    assert {"fixed", "class", "names", "behaviour", "inputs"} <= set(inv)
    assert inv["inputs"] == [{"driver": "crank", "class": 1}]
    code, out, _ = run_cli("inversions", catalog_path("four-bar-chain"))
    assert code == 0 and "1 class by structure" in out and "Watt's indicator" in out


# -- isomorphism ------------------------------------------------------------------------
def _node_match(a, b):
    return a["part"] == b["part"] and a.get("kind") == b.get("kind")


def _edge_match(a, b):
    return a["role"] == b["role"]


def test_canonical_form_agrees_with_vf2_on_many_small_chains():
    chains = [random_chain(6, seed=s, ternary=s % 2, sliding=s % 3) for s in range(120)]
    forms = [canonical_form(c) for c in chains]
    for i in range(0, 120, 3):
        for j in range(i + 1, 120, 7):
            same = nx.is_isomorphic(chains[i].graph, chains[j].graph,
                                    node_match=_node_match, edge_match=_edge_match)
            assert same == (forms[i] == forms[j])
    assert len(set(forms)) < len(forms)  # the sample has isomorphic pairs to tell apart


def test_group_order_and_orbits_agree_with_vf2():
    for seed in range(60):
        chain = random_chain(random.Random(seed).randint(4, 8), seed=seed, ternary=seed % 2,
                             sliding=seed % 3)
        autos = list(GraphMatcher(chain.graph, chain.graph, _node_match,
                                  _edge_match).isomorphisms_iter())
        assert canonical(chain).group_size == len(autos)
        orbits = {frozenset(("link", y) for y in o) for o in automorphism_orbits(chain)}
        vf2 = {frozenset(a[("link", x)] for a in autos) for x in chain.links}
        assert orbits == vf2


@settings(max_examples=50, deadline=None)
@given(st.integers(3, 12), st.integers(0, 3), st.integers(0, 3), st.integers(0, 10 ** 6))
def test_relabelled_chains_are_isomorphic_and_mapped(n, ternary, sliding, seed):
    chain = random_chain(n, seed=seed, ternary=ternary, sliding=sliding)
    rng = random.Random(seed)
    names = {x: f"n{rng.random()}" for x in chain.links}
    other = chain.relabelled(links=names)
    other = Chain(other.name, tuple(rng.sample(other.joints, len(other.joints))))
    assert is_isomorphic(chain, other)
    mapping = isomorphism(chain, other)
    moved = chain.relabelled(links=mapping)
    shape = lambda c: Counter((j.kind, frozenset(j.links), j.guide) for j in c.joints)  # noqa: E731
    assert shape(moved) == shape(other)


def test_p_orientation_matters_only_when_asked():
    chain = load("single-slider-crank-chain")
    assert len(automorphism_orbits(chain)) == 4
    assert len(automorphism_orbits(chain, oriented=False)) == 2
    flipped = Chain(chain.name, tuple(
        Joint(j.id, j.kind, j.links[::-1] if j.kind == "P" else j.links, at=j.at, axis=j.axis)
        for j in chain.joints))
    assert is_isomorphic(chain, flipped)  # every oriented slider crank chain is the same
    four = load("four-bar-chain")
    assert not is_isomorphic(four, chain) and not is_isomorphic(four, chain, oriented=False)


# -- large chains: behaviour solved where a name needs it, and bounded ----------------------
def _dyadic_chain(dyads):
    """A four-bar with ``dyads`` dyads chained on, each pinned to the last and the
    frame, drawn (4 + 2 dyads links)."""
    joints = [Joint("O2", "R", ("frame", "crank"), at=(0.0, 0.0)),
              Joint("A", "R", ("crank", "coupler"), at=(20.0, 35.0)),
              Joint("B", "R", ("coupler", "rocker"), at=(110.0, 60.0)),
              Joint("O4", "R", ("rocker", "frame"), at=(100.0, 0.0))]
    prev, x = "rocker", 100.0
    for k in range(dyads):
        a, b = f"d{k}a", f"d{k}b"
        x += 60.0
        joints += [Joint(f"P{k}", "R", (prev, a), at=(x - 40.0, 50.0 + 3 * (k % 3))),
                   Joint(f"Q{k}", "R", (a, b), at=(x, 90.0 - 2 * (k % 4))),
                   Joint(f"R{k}", "R", (b, "frame"), at=(x + 20.0, 0.0))]
        prev = b
    return Chain(f"four-bar with {dyads} dyads", tuple(joints),
                 mechanism=chaingraph.Mechanism("frame", driver="crank"))


def _counting_full_turns(monkeypatch):
    import chaingraph.kinematics.behaviour as behaviour
    calls = []
    full_turns = behaviour.full_turns
    monkeypatch.setattr(behaviour, "full_turns",
                        lambda chain, fixed: calls.append(fixed) or full_turns(chain, fixed))
    return calls


def test_a_large_chain_solves_each_inversions_behaviour_once(monkeypatch):
    """16 links, no catalog mechanism of its size: each inversion's behaviour is solved
    once (for its own field), not again for catalog keys that no name needs (a 20-link
    chain took over 100 s)."""
    calls = _counting_full_turns(monkeypatch)
    chain = _dyadic_chain(6)
    found = inversions(chain)
    assert len(found.inversions) == 16
    assert sorted(calls) == sorted(chain.links)
    assert found.inversions[0].behaviour is not None


def test_past_the_bound_no_behaviour_is_solved_and_the_note_says_so(monkeypatch):
    from chaingraph.naming.inversion_classes import BEHAVIOUR_LINKS
    calls = _counting_full_turns(monkeypatch)
    chain = _dyadic_chain((BEHAVIOUR_LINKS - 4) // 2 + 1)
    found = inversions(chain)
    assert calls == []
    assert all(i.behaviour is None and "not solved" in i.note for i in found.inversions)
