"""The atlas with multiple joints against a direct enumeration: every set of joints (each
joint a set of two links or more, no two joints on the same two links) on N links, kept
by the rank of the velocity equations at a random pose (floating point; the product's
count must agree with it on every set), told apart by canonical forms."""

import itertools
import json

import numpy as np
import pytest

from chaingraph.cli.main import main
from chaingraph.model.chain import Chain, Joint
from chaingraph.naming.atlas import atlas_names
from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.admissibility import admissible, decide, verdicts
from chaingraph.structure.atlas.multiple import _merges, multiple_atlas
from chaingraph.structure.isomorphism import automorphism_orbits, canonical_form

from .generic_rank import random_pose


def _verdict(links, joints, seed, kinds=None):
    """(mobility, any locked joint) at a random pose, the first link fixed (``kinds``:
    "R"/"P" per joint, all R by default)."""
    mobility, locked = random_pose(links, joints, kinds or "R" * len(joints),
                                   np.random.default_rng(seed))
    return mobility, bool(locked)


def _direct(links, dof):
    """Every chain with multiple joints of this size, by brute force (each joint's pairs
    of links as a bit mask: no two joints may share a pair)."""
    total = (3 * (links - 1) - dof) // 2            # simple joints' worth
    subsets = [s for k in range(2, links + 1) for s in itertools.combinations(range(links), k)]
    bit = {p: 1 << i for i, p in enumerate(itertools.combinations(range(links), 2))}
    masks = [sum(bit[p] for p in itertools.combinations(s, 2)) for s in subsets]
    cost = [len(s) - 1 for s in subsets]
    found = {}

    def leaf(chosen):
        degree = [0] * links
        for j in chosen:
            for x in subsets[j]:
                degree[x] += 1
        if min(degree) < 2:
            return
        joints = [subsets[j] for j in chosen]
        first = _verdict(links, joints, 1)
        # the product's proof, by Whiteley's count alone, is the same verdict (an
        # unlucky random draw would show here as a disagreement)
        assert (decide(links, joints) is None) == (first == (dof, False)), joints
        if first == (dof, False):
            chain = Chain("x", tuple(Joint(f"J{i}", "R", tuple(f"L{x}" for x in j))
                                     for i, j in enumerate(joints)))
            form = canonical_form(chain, oriented=False)
            if form not in found:
                found[form] = len(automorphism_orbits(chain, oriented=False))

    def grow(start, chosen, used, pairs):
        if used == total:
            leaf(chosen)
            return
        for i in range(start, len(subsets)):
            if used + cost[i] <= total and not masks[i] & pairs:
                chosen.append(i)
                grow(i + 1, chosen, used + cost[i], pairs | masks[i])
                chosen.pop()
    grow(0, [], 0, 0)
    return found


@pytest.mark.parametrize("links, dof", [(4, 1), (5, 2), (6, 1), (6, 3),
                                        pytest.param(7, 2, marks=pytest.mark.slow)])
def test_the_atlas_with_multiple_joints_is_the_direct_enumeration(links, dof):
    """Seven links and two freedoms hold the case that merging only vertex-disjoint trees
    missed: two ternary joints that share a link."""
    direct = _direct(links, dof)
    got = multiple_atlas(atlas_graphs(links, dof))
    assert len(got) == len(direct)
    forms = {canonical_form(e.chain(), oriented=False) for e in got}
    assert forms == set(direct)
    assert got.distinct_inversions == sum(direct.values())


@pytest.mark.parametrize("links, dof", [(6, 1), pytest.param(7, 2, marks=pytest.mark.slow)])
def test_pins_with_sliding_pairs_are_decided_as_the_rank_decides(links, dof):
    """Every merge of pins in every chain, with every set of its simple joints made
    sliding that the structure of the P joints leaves open: the product's verdict
    (an evaluation's proof or a bound's) is the floating-point rank's at two random
    poses, and every rejection is proven by a bound."""
    candidates, kinds = [], []
    for entry in atlas_graphs(links, dof):
        for joints in sorted(set(_merges(links, [tuple(e) for e in entry.edges]))):
            simple = [i for i, j in enumerate(joints) if len(j) == 2]
            for k in range(len(simple) + 1):
                for chosen in itertools.combinations(simple, k):
                    kind = "".join("P" if i in chosen else "R" for i in range(len(joints)))
                    if admissible(links, joints, kind) is None:
                        candidates.append(joints)
                        kinds.append(kind)
    got = verdicts(links, candidates, kinds=kinds, dof=dof)
    assert len(got) > 100 and got.count(None) > 10 and got.count("locked") > 0
    for joints, kind, reason in zip(candidates, kinds, got):
        first = _verdict(links, joints, 1, kind)
        assert first == _verdict(links, joints, 2, kind), (joints, kind)
        assert (reason is None) == (first == (dof, False)), (joints, kind, reason, first)
        if reason is not None:      # every rejection has its proof: a bound, not a draw
            assert decide(links, joints, kind, independent=reason == "locked") == reason


def test_the_six_link_chains_with_multiple_joints_are_named():
    """Six links: Watt's and Stephenson's chains, the chain of one ternary joint (with a
    sliding pair on the rocker's rod: the toggle press's) and the catalog's six links on
    two ternary joints."""
    six = multiple_atlas(atlas_graphs(6, 1))
    assert six.count_by_multiple == {0: 2, 1: 1, 2: 1}
    names = sorted(n for e in six for n in atlas_names(e.chain())["chain"])
    assert names == ["Six links on two ternary joints", "Stephenson six-bar chain",
                     "Watt six-bar chain"]


def test_atlas_multiple_on_the_command_line(capsys):
    assert main(["atlas", "--links", "6", "--multiple", "--prismatic", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["count"] == 10 and out["multiple"] is True
    assert out["count_by_multiple"] == {"0": 6, "1": 3, "2": 1}
    toggle = [c for c in out["chains"] if c["names"]["chain"] == ["Crank-rocker with slider chain"]]
    assert len(toggle) == 1
    assert "edges" not in toggle[0] and any(len(j) == 3 for j in toggle[0]["joints"])
    assert toggle[0]["kinds"].count("P") == 1
    for c in out["chains"]:                  # only simple joints slide
        assert all(len(j) == 2 for j, k in zip(c["joints"], c["kinds"]) if k == "P")
