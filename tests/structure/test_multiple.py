"""The atlas with multiple joints against brute force, kept by the rank of the velocity
equations at a random pose (floating point; the product's count must agree with it on
each), told apart by the project's own canonical forms
(:mod:`chaingraph.structure.isomorphism`, not nauty):

* every set of joints on N links (each joint a set of two links or more, no two joints
  on the same two links), labelled, to 6 links;
* every link-joint graph up to isomorphism (each joint degree pattern's joints added in
  every way, told apart by nauty's labelling and, to 6 links, by the project's own
  alike), to 8 links: no bound of rigidity prunes it, so every graph of the pattern is
  decided by the rank."""

import itertools
import json

import numpy as np
import pytest

from chaingraph.cli.main import main
from chaingraph.model.chain import Chain, Joint
from chaingraph.naming.atlas import atlas_names
from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.admissibility import admissible, decide, verdicts
from chaingraph.structure.atlas.generic import generic_verdicts
from chaingraph.structure.atlas.labelling import link_joint_form, link_joint_keys
from chaingraph.structure.atlas.multiple import link_joint_graphs, multiple_atlas
from chaingraph.structure.classification import classify
from chaingraph.structure.isomorphism import automorphism_orbits, canonical_form

from .generic_rank import random_pose


def _verdict(links, joints, seed, kinds=None):
    """(mobility, any locked joint) at a random pose, the first link fixed (``kinds``:
    "R"/"P" per joint, all R by default)."""
    mobility, locked = random_pose(links, joints, kinds or "R" * len(joints),
                                   np.random.default_rng(seed))
    return mobility, bool(locked)


def _chain(joints):
    return Chain("x", tuple(Joint(f"J{i}", "R", tuple(f"L{x}" for x in j))
                            for i, j in enumerate(joints)))


def _keep(links, dof, joints, found):
    """Record ``joints`` in ``found`` (canonical form -> (inversion classes, degrees of
    its multiple joints)) when the rank admits it; the product's count must agree."""
    first = _verdict(links, joints, 1)
    # the product's proof, by Whiteley's count alone, is the same verdict (an unlucky
    # random draw would show here as a disagreement)
    assert (decide(links, joints) is None) == (first == (dof, False)), joints
    if first == (dof, False):
        chain = _chain(joints)
        form = canonical_form(chain, oriented=False)
        if form not in found:
            found[form] = (len(automorphism_orbits(chain, oriented=False)),
                           tuple(sorted((len(j) for j in joints if len(j) > 2),
                                        reverse=True)))


def _labelled(links, dof):
    """Every chain with multiple joints of this size, by brute force over every set of
    joints on the labelled links (each joint's pairs of links as a bit mask: no two
    joints may share a pair), each decided once per isomorphism class."""
    total = (3 * (links - 1) - dof) // 2            # simple joints' worth
    subsets = [s for k in range(2, links + 1) for s in itertools.combinations(range(links), k)]
    bit = {p: 1 << i for i, p in enumerate(itertools.combinations(range(links), 2))}
    masks = [sum(bit[p] for p in itertools.combinations(s, 2)) for s in subsets]
    cost = [len(s) - 1 for s in subsets]
    found, seen = {}, set()

    def grow(start, chosen, used, pairs):
        if used == total:
            joints = [subsets[j] for j in chosen]
            if all(sum(x in j for j in joints) >= 2 for x in range(links)):
                key, = link_joint_keys(links, [[sum(1 << x for x in j) for j in joints]])
                if key not in seen:
                    seen.add(key)
                    _keep(links, dof, joints, found)
            return
        for i in range(start, len(subsets)):
            if used + cost[i] <= total and not masks[i] & pairs:
                chosen.append(i)
                grow(i + 1, chosen, used + cost[i], pairs | masks[i])
                chosen.pop()
    grow(0, [], 0, 0)
    return found


def _patterns(links, dof):
    """Every multiset of joint degrees (2 or more, largest first) with the Kutzbach
    count of ``dof``: sum (d - 1) = (3 (links - 1) - dof) / 2."""
    total = (3 * (links - 1) - dof) // 2
    return [p for k in range(1, total + 1)
            for p in itertools.combinations_with_replacement(range(links, 1, -1), k)
            if sum(d - 1 for d in p) == total]


def _every_graph(links, dof, *, check=False):
    """Every link-joint graph of this size up to isomorphism, admissible or not: for
    each joint pattern, its joints added in every way (no two on the same two links),
    one graph kept per class of nauty's labelling (``check``: the project's own
    labelling must make the same classes); those whose every link is on two joints or
    more, as tuples of joints (tuples of links)."""
    out = []
    for pattern in _patterns(links, dof):
        level = [((), 0)]
        for d in pattern:
            joints_of = [(sum(1 << x for x in c),
                          sum(1 << (a * links + b) for a, b in itertools.combinations(c, 2)))
                         for c in itertools.combinations(range(links), d)]
            children = [(joints + (joint,), pairs | mask) for joints, pairs in level
                        for joint, mask in joints_of if not mask & pairs]
            keys = link_joint_keys(links, [j for j, _ in children])
            if check:
                own = link_joint_keys(links, [j for j, _ in children], backend="own")
                assert len(set(zip(keys, own))) == len(set(keys)) == len(set(own))
            level = list(dict(zip(keys, children)).values())
        for joints, _ in level:
            graph = [tuple(x for x in range(links) if m >> x & 1) for m in joints]
            if all(sum(x in j for j in graph) >= 2 for x in range(links)):
                out.append(graph)
    return out


def _isomorphism_classes(links, dof):
    found = {}
    for joints in _every_graph(links, dof, check=links < 7):
        _keep(links, dof, joints, found)
    return found


def _compare(got, direct):
    assert len(got) == len(direct)
    assert {canonical_form(e.chain(), oriented=False) for e in got} == set(direct)
    assert got.distinct_inversions == sum(orbits for orbits, _ in direct.values())
    by_degrees = {}
    for _, degrees in direct.values():
        by_degrees[degrees] = by_degrees.get(degrees, 0) + 1
    assert got.count_by_degrees == by_degrees
    assert got.rejected == {"mobility": 0, "locked": 0}


@pytest.mark.parametrize("links, dof", [(4, 1), (5, 2), (6, 1), (6, 3)])
def test_the_atlas_with_multiple_joints_is_every_labelled_set_of_joints(links, dof):
    _compare(multiple_atlas(atlas_graphs(links, dof)), _labelled(links, dof))


@pytest.mark.parametrize("links, dof", [(6, 1), (7, 2), (8, 1)])
def test_the_atlas_with_multiple_joints_is_every_link_joint_graph(links, dof):
    """Seven links and two freedoms hold a case that merging only vertex-disjoint trees
    of simple joints missed (two ternary joints that share a link), eight links one that
    merging any forest of them missed (the pins' trees together close a loop)."""
    _compare(multiple_atlas(atlas_graphs(links, dof)), _isomorphism_classes(links, dof))


def test_the_four_pins_in_a_loop_with_two_dyads_on_their_diagonals():
    """Eight binary links on four ternary joints in a loop (links 0-3 between them),
    each diagonal carrying a binary dyad (links 4-5 and 6-7): a kinematic chain, which
    no merging of a forest of a simple chain's joints makes."""
    pins = [(0, 3, 4), (0, 1, 6), (1, 2, 5), (2, 3, 7), (4, 5), (6, 7)]
    chain = _chain(pins)
    facts = classify(chain)
    assert (facts.verdict, facts.degenerate, facts.mobility) == ("kinematic chain", False, 1)
    eight = multiple_atlas(atlas_graphs(8, 1))
    form = canonical_form(chain, oriented=False)
    found = [e for e in eight if canonical_form(e.chain(), oriented=False) == form]
    assert len(found) == 1 and found[0].degrees == (3, 3, 3, 3)
    assert found[0].inversion_classes == len(automorphism_orbits(chain, oriented=False))


def test_the_chains_are_the_same_relabelled_and_by_either_labelling():
    """A chain's canonical joints do not depend on how its links are numbered or its
    joints listed (by nauty, and by the project's own search: each labelling canonical
    on its own), and its link orbits are its inversion classes; the search finds the
    same chains with either labelling."""
    rng = np.random.default_rng(7)
    eight = multiple_atlas(atlas_graphs(8, 1))
    for entry in eight:
        masks = [sum(1 << x for x in j) for j in entry.joints]
        forms = {"nauty": set(), "own": set()}
        for _ in range(3):
            perm = rng.permutation(8)
            moved = [sum(1 << int(perm[x]) for x in range(8) if m >> x & 1) for m in masks]
            moved = [moved[i] for i in rng.permutation(len(moved))]
            for backend, seen in forms.items():
                seen.add(link_joint_form(8, moved, backend=backend))
        assert [len(seen) for seen in forms.values()] == [1, 1]
        assert {seen.pop()[1] for seen in forms.values()} == {entry.inversion_classes}
    for pattern in [(4, 3, 2, 2, 2, 2, 2), (3, 3, 3, 3, 2, 2)]:
        by = {b: {canonical_form(_chain([[x for x in range(8) if m >> x & 1] for m in g]),
                                 oriented=False)
                  for g in link_joint_graphs(8, pattern, backend=b)}
              for b in ("nauty", "own")}
        assert by["nauty"] == by["own"] and by["own"]


@pytest.mark.parametrize("links, dof", [(8, 3), (9, 2)])
def test_fractionated_chains_are_the_ones_classify_finds(links, dof):
    """A chain is fractionated when a link or a joint separates it into closed parts:
    those of the atlas's chains of simple joints, and the chains with multiple joints
    whose link-joint graph a node separates."""
    got = multiple_atlas(atlas_graphs(links, dof))
    assert [e.fractionated for e in got] == [classify(e.chain()).fractionated for e in got]
    assert any(e.fractionated for e in got if e.multiple)


def _mask(kinds):
    """The sliding pairs of ``kinds`` ("R"/"P" per joint) as a bit mask."""
    return sum(1 << i for i, k in enumerate(kinds) if k == "P")


def _every_pin_graph(links, dof):
    """Every link-joint graph of this size with a multiple joint, admissible or not."""
    return [g for g in _every_graph(links, dof) if any(len(j) > 2 for j in g)]


@pytest.mark.parametrize("links, dof", [(6, 1), (7, 2)])
def test_pins_with_sliding_pairs_are_decided_as_the_rank_decides(links, dof):
    """Every link-joint graph with a multiple joint (admissible or not), with every set
    of its simple joints made sliding that the structure of the P joints leaves open:
    the product's verdict (an evaluation's proof or a bound's) is the floating-point
    rank's at two random poses, and every rejection is proven by a bound; the exact
    evaluation of all of a chain's assignments at once (the sliding atlas's) finds the
    mobility and locks the rank finds."""
    candidates, kinds = [], []
    for joints in _every_pin_graph(links, dof):
        joints = tuple(joints)
        simple = [i for i, j in enumerate(joints) if len(j) == 2]
        for k in range(len(simple) + 1):
            for chosen in itertools.combinations(simple, k):
                kind = "".join("P" if i in chosen else "R" for i in range(len(joints)))
                if admissible(links, joints, kind) is None:
                    candidates.append(joints)
                    kinds.append(kind)
    got = verdicts(links, candidates, kinds=kinds, dof=dof)
    assert len(got) > 100 and got.count(None) > 10 and got.count("locked") > 0
    drawn = {}                 # the sliding atlas's one evaluation of a chain's every mask
    for joints in set(candidates):
        masks = [_mask(kind) for c, kind in zip(candidates, kinds) if c == joints]
        mobility, locked = generic_verdicts(links, joints, masks)
        drawn.update(((joints, m), (int(f), bool(s))) for m, f, s in zip(masks, mobility, locked))
    for joints, kind, reason in zip(candidates, kinds, got):
        first = _verdict(links, joints, 1, kind)
        assert drawn[joints, _mask(kind)] == first
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
