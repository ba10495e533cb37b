"""The atlas's chains and inversion classes under the catalog's names."""

import json

import pytest

import chaingraph
from chaingraph.cli.main import main
from chaingraph.naming.atlas import atlas_names
from chaingraph.naming.catalog import bundled_catalog
from chaingraph.structure.atlas import atlas
from chaingraph.structure.atlas.contracted import joints_for
from chaingraph.structure.isomorphism import canonical_form


def test_the_four_link_chains_are_the_textbook_s():
    named = {tuple(j.kind for j in c.joints): atlas_names(c)["chain"]
             for c in atlas(links=4, prismatic="all")}
    assert sorted(n for names in named.values() for n in names) == [
        "Double slider crank chain", "Four-bar chain", "Single slider crank chain"]


def test_the_single_slider_crank_chain_s_inversions_oriented():
    """Oriented (which link carries the guide counts), its four inversions are the
    textbook's four: the frame, the crank, the rod, the slider fixed."""
    chain, = atlas(links=4, prismatic=1, oriented=True)
    names = atlas_names(chain, oriented=True)
    classes = sorted(sorted(c["names"]) for c in names["inversions"])
    assert len(classes) == 4
    assert ["Reciprocating engine"] in classes
    assert ["Duplex pump", "Pendulum pump (bull engine)"] in classes
    assert ["Rotary (Gnome) engine", "Whitworth quick return mechanism"] in classes
    assert ["Crank and slotted lever quick return mechanism",
            "Oscillating cylinder engine"] in classes


def test_the_six_link_chains_with_two_sliding_pairs_include_the_quick_returns():
    found = [atlas_names(c) for c in atlas(links=6, prismatic=2)]
    ram = [n for n in found if n["chain"] == ["Quick return chain with ram"]]
    assert len(ram) == 1
    names = {x for c in ram[0]["inversions"] for x in c["names"]}
    assert {"Shaper: crank and slotted lever with ram",
            "Whitworth quick return drive with ram"} <= names


def _one_dof_size(entry):
    twice = 3 * (len(entry.links) - 1) - 1
    return twice % 2 == 0 and len(entry.joints) == joints_for(len(entry.links), 1)


SIMPLE = [e for e in bundled_catalog() if e.mechanism is not None and e.space == "planar"
          and all(j.kind in "RP" and len(j.links) == 2 for j in e.joints)
          and _one_dof_size(e)]


@pytest.mark.parametrize("entry", SIMPLE, ids=lambda e: e.name)
def test_every_catalog_mechanism_is_in_the_atlas_under_its_name(entry):
    """A catalog mechanism of simple R and P joints is in the atlas of its size, and the
    class of its fixed link carries its name; names survive relabelling."""
    k = sum(j.kind == "P" for j in entry.joints)
    form = canonical_form(entry, oriented=False)
    hits = [c for c in atlas(links=len(entry.links), prismatic=k)
            if canonical_form(c, oriented=False) == form]
    assert len(hits) == 1
    names = atlas_names(hits[0])
    assert any(entry.name in c["names"] for c in names["inversions"])
    renamed = hits[0].relabelled(links={"L1": "first", "L2": "second"})
    again = atlas_names(renamed)
    assert sorted(map(sorted, (c["names"] for c in again["inversions"]))) == \
        sorted(map(sorted, (c["names"] for c in names["inversions"])))


def test_the_catalog_has_a_chain_for_every_mechanism_s_structure():
    """identify names the chain of every catalog mechanism (the toggle press's too)."""
    for entry in bundled_catalog():
        if entry.mechanism is not None and entry.space == "planar":
            found = chaingraph.identify(entry)
            assert found.chain is not None, entry.name
            assert found.joint_kinds == "respected", entry.name


def test_the_names_are_in_the_atlas_json(capsys):
    assert main(["atlas", "--links", "4", "--prismatic", "2", "--json"]) == 0
    chains = json.loads(capsys.readouterr().out)["chains"]
    named = [c["names"] for c in chains]
    assert {"chain": [], "inversions": []} in named
    double = next(n for n in named if n["chain"] == ["Double slider crank chain"])
    assert sorted(x for c in double["inversions"] for x in c["names"]) == [
        "Elliptical trammels", "Oldham's coupling", "Scotch yoke"]
