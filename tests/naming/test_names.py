"""Issue 12: names of structure and of behaviour; identification by structure alone;
chains written for their structure alone (no drawn pose, P joints without axis)."""

from __future__ import annotations

import json
import random
from pathlib import Path

import pytest

import chaingraph
from chaingraph import Chain, Joint, MechanismError
from chaingraph.naming.catalog import catalog_files, catalog_path
from chaingraph.naming.identification import identify
from chaingraph.naming.inversion_classes import inversions

from ..conftest import run_cli
from .test_inversions import _four_bar

EXAMPLES = Path(__file__).parents[2] / "examples"

# the slider crank chain written for its structure alone (no 'at', no 'axis'), ending
# with its P joint D
SINGLE_SLIDER = (EXAMPLES / "slider-crank-structure.toml").read_text()

# the same loop with C a sliding pair too: link 4 carries both blocks' guides here
DOUBLE_SLIDER = chaingraph.dumps(Chain("double slider, structure only", (
    Joint("A", "R", ("1", "2")), Joint("B", "R", ("2", "3")),
    Joint("C", "P", ("4", "3")), Joint("D", "P", ("4", "1")))))


def test_topology_only_single_slider_crank_chain_classifies_and_names_its_four_inversions(tmp_path):
    path = tmp_path / "ssc.toml"
    path.write_text(SINGLE_SLIDER)
    code, out, err = run_cli("classify", "--json", str(path))
    assert code == 0 and json.loads(out)["mobility"] == 1
    result = inversions(chaingraph.load(path))
    assert result.classes == 4
    names = {i.fixed: set(i.names) for i in result.inversions}
    assert names["1"] == {"Reciprocating engine"}
    assert names["2"] == {"Rotary (Gnome) engine", "Whitworth quick return mechanism"}
    assert names["3"] == {"Oscillating cylinder engine", "Crank and slotted lever quick return mechanism"}
    assert names["4"] == {"Duplex pump", "Pendulum pump (bull engine)"}
    assert all(i.behaviour is None for i in result.inversions)
    found = identify(chaingraph.load(path))
    assert found.chain == "Single slider crank chain" and found.joint_kinds == "respected"


def test_topology_only_double_slider_crank_chain_names_its_three_classes(tmp_path):
    path = tmp_path / "dsc.toml"
    path.write_text(DOUBLE_SLIDER)
    result = inversions(chaingraph.load(path))
    assert len(result.inversions) == 4 and result.classes == 3
    names = set().union(*(set(i.names) for i in result.inversions))
    assert names == {"Elliptical trammels", "Scotch yoke", "Oldham's coupling"}
    assert all(i.names for i in result.inversions)
    # the block of both sliding pairs (link 4), fixed, is the trammels' plate only when
    # orientation is forgotten: the two guides are on it in the catalog
    assert set(result.inversion("4").names) == {"Elliptical trammels"}
    found = identify(chaingraph.load(path))
    assert found.chain == "Double slider crank chain"


def test_a_topology_only_chain_cannot_be_solved_and_says_which_joints_lack_a_pose(tmp_path):
    path = tmp_path / "ssc.toml"
    path.write_text(SINGLE_SLIDER + '[mechanism]\nfixed = "1"\ndriver = "2"\n')
    code, out, err = run_cli("solve", str(path))
    assert code == 2 and "Traceback" not in err
    assert "solving needs a drawn pose" in err and "'A', 'B', 'C', 'D'" in err
    with pytest.raises(MechanismError, match="solving needs a drawn pose"):
        chaingraph.solve(chaingraph.load(path))


@pytest.mark.parametrize("extra, message", [
    ("at = [0.0, 0.0]", "a P joint with 'at' needs 'axis'"),
    ("axis = 30.0", "a P joint with 'axis' needs 'at'"),
])
def test_at_and_axis_of_a_p_joint_go_together(tmp_path, extra, message):
    path = tmp_path / "p.toml"
    path.write_text(SINGLE_SLIDER + extra + "\n")
    code, out, err = run_cli("classify", str(path))
    assert code == 2 and message in err and "joint 'D'" in err and "Traceback" not in err


@pytest.mark.parametrize("stem, structural", [
    ("watt-six-bar-chain", {"Watt I six-bar mechanism", "Watt II six-bar mechanism"}),
    ("stephenson-six-bar-chain", {"Stephenson I six-bar mechanism", "Stephenson II six-bar mechanism",
                                  "Stephenson III six-bar mechanism"}),
])
def test_the_six_bar_chains_name_every_inversion_whatever_their_dimensions(stem, structural):
    chain = chaingraph.load(catalog_path(stem))
    result = inversions(chain)
    assert all(len(i.names) == 1 for i in result.inversions)
    assert {n for i in result.inversions for n in i.names} == structural
    # one class, one name
    by_class = {}
    for i in result.inversions:
        by_class.setdefault(i.class_, set()).update(i.names)
    assert all(len(v) == 1 for v in by_class.values())
    bare = Chain(chain.name, tuple(Joint(j.id, j.kind, j.links) for j in chain.joints))
    assert [i.names for i in inversions(bare).inversions] == [i.names for i in result.inversions]


def test_the_report_names_every_inversion_of_the_six_bar_chains(tmp_path):
    from chaingraph.report.build import build_report
    build_report([catalog_path("watt-six-bar-chain"), catalog_path("stephenson-six-bar-chain")],
                 tmp_path / "r", progress=None)
    pages = "".join(p.read_text(encoding="utf-8") for p in (tmp_path / "r").rglob("*.html"))
    for name in ("Watt I six-bar mechanism", "Watt II six-bar mechanism",
                 "Stephenson I six-bar mechanism", "Stephenson II six-bar mechanism",
                 "Stephenson III six-bar mechanism"):
        assert name in pages, name


def test_a_behaviour_that_matches_no_catalog_name_is_said_not_left_silent():
    result = inversions(_four_bar(100, 70, 90, 60, names=("frame", "a", "b", "c")))  # change point
    for i in result.inversions:
        assert i.behaviour == "change point" and i.names == ()
        assert "Beam engine" in i.note and "need that behaviour" in i.note
    found = identify(_four_bar(100, 70, 90, 60).with_mechanism("frame", "a"))
    assert found.chain == "Four-bar chain" and found.inversion is None
    assert "behaves otherwise" in found.note
    # a Grashof double rocker is Watt's indicator, and only that
    rocker = inversions(_four_bar(100, 80, 40, 70))      # the shortest link is b
    assert rocker.inversion("frame").behaviour == "double rocker"
    assert rocker.inversion("frame").names == ("Watt's indicator mechanism",)
    assert rocker.inversion("b").names == ("Coupling rod of a locomotive",)


def test_natural_crank_and_slotted_lever_maps_its_frame_onto_the_catalog_frame():
    path = EXAMPLES / "slot-on-the-lever.toml"       # the slot on the lever, as drawn
    found = identify(chaingraph.load(path))
    entry = chaingraph.load(found.inversion_file)
    assert found.inversion == "Crank and slotted lever quick return mechanism"
    assert found.mapping["frame"] == entry.mechanism.fixed
    assert found.mapping["crank"] == entry.mechanism.driver
    # the slot is on the lever here and on the block in the catalog's chain: said so
    assert found.orientation == "ignored"
    code, out, err = run_cli("identify", "--json", str(path))
    assert json.loads(out)["orientation"] == "ignored"


def _scrambled(chain, seed, *, stretch):
    """The chain relabelled at random, its drawing scaled and each joint moved by up to
    ``stretch`` of the size (dimensions changed, perhaps out of their behaviour)."""
    rng = random.Random(seed)
    links = list(chain.links)
    shuffled = links[:]
    rng.shuffle(shuffled)
    names = {a: f"link {i}" for i, a in enumerate(shuffled)}
    if not chain.has_pose:
        return chain.relabelled(names)
    xs = [j.at[0] for j in chain.joints] + [j.at[1] for j in chain.joints]
    size = max(xs) - min(xs) or 1.0
    scale = rng.choice([0.01, 1.0, 37.0])

    def move(p):
        return (scale * (p[0] + rng.uniform(-stretch, stretch) * size),
                scale * (p[1] + rng.uniform(-stretch, stretch) * size))
    joints = tuple(Joint(j.id, j.kind, j.links, at=move(j.at), axis=j.axis, closure=j.closure)
                   for j in chain.joints)
    import dataclasses
    moved = dataclasses.replace(chain, joints=joints, points=tuple(
        dataclasses.replace(p, at=(scale * p.at[0], scale * p.at[1])) for p in chain.points))
    return moved.relabelled(names)


CATALOG = [p for p in catalog_files()]


@pytest.mark.parametrize("path", CATALOG, ids=[p.stem for p in CATALOG])
def test_every_catalog_entry_identifies_to_the_same_chain_relabelled_scaled_and_perturbed(path):
    chain = chaingraph.load(path)
    if len(chain.pieces) > 1:
        pytest.skip("several pieces")
    reference = identify(chain)
    # (the 16-link rotary engine, relabelled once: its behaviour is solved per variant)
    variants = ((1, 0.0), (2, 0.02), (3, 0.3)) if len(chain.links) <= 8 else ((3, 0.3),)
    for seed, stretch in variants:
        other = _scrambled(chain, seed, stretch=stretch)
        found = identify(other)
        assert found.chain == reference.chain, (seed, stretch)
        for bare in (other, Chain(other.name, tuple(Joint(j.id, j.kind, j.links)
                                                    for j in other.joints))):
            assert identify(bare).chain == reference.chain
        if chain.mechanism is not None and found.inversion is not None:
            # the mapping is the inversion's: the fixed link onto the entry's fixed link
            entry = chaingraph.load(found.inversion_file)
            assert found.mapping[other.mechanism.fixed] == entry.mechanism.fixed
        if chain.mechanism is not None and chain.naming == "structure":
            # a name of structure holds whatever the dimensions
            assert found.inversion == reference.inversion or \
                found.inversion in _structural_names_of(chain)


def _structural_names_of(chain):
    names = inversions(chain).inversion(chain.mechanism.fixed).names
    return set(names)


def test_a_hand_written_shaper_gets_the_general_name_not_a_worked_examples():
    """A shaper of other proportions than any worked example is the shaper, not
    "assignment problem 2"; the worked example's own file keeps its name; catalog files
    are shown as catalog/NAME.toml wherever the package is installed."""
    text = catalog_path("quick-return-assignment-2").read_text()
    text = text.replace("naming = \"example\"\n", "").replace("crank = 75.0 ", "crank = 80.0 ")
    mine = chaingraph.loads(text.replace("(assignment problem 2)", "(mine)"))
    found = chaingraph.identify(mine)
    assert found.inversion == "Shaper: crank and slotted lever with ram"
    assert found.inversion_file == "catalog/shaper-crank-and-slotted-lever.toml"
    assert found.chain_file.startswith("catalog/")
    itself = chaingraph.identify(chaingraph.load(catalog_path("quick-return-assignment-2")))
    assert itself.inversion == "Crank and slotted lever with ram (assignment problem 2)"
