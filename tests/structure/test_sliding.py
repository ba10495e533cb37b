"""The atlas with sliding pairs against brute force: every assignment of P joints to
every turning-pair chain, admissibility by the rank of the velocity equations at a
random pose (floating point) against the product's forests and its exact evaluation,
isomorphism by canonical forms of every candidate."""

import json
import zlib

import numpy as np
import pytest

from chaingraph.cli.main import main
from chaingraph.model.chain import Chain, Joint
from chaingraph.structure.atlas import atlas_graphs
from chaingraph.structure.atlas.admissibility import admissible, verdicts
from chaingraph.structure.atlas.forests import forest_verdicts
from chaingraph.structure.atlas.generic import generic_verdicts
from chaingraph.structure.atlas.sliding import sliding_atlas
from chaingraph.structure.isomorphism import automorphism_orbits, canonical_form

from .generic_rank import random_pose


def generic_verdict(links, edges, kinds, dof, seed):
    """(mobility, locked joints) of the chain at a random pose (random pins, random
    sliding directions), the first link fixed; the rank and the kernel by the singular
    values (floating point, well conditioned at random poses of a few links)."""
    # a seed of the chain's own, the same in every run (str hashes are not)
    rnd = np.random.default_rng(zlib.crc32(repr((seed, tuple(kinds), tuple(edges))).encode()))
    return random_pose(links, edges, kinds, rnd)


def reference(links, edges, kinds, dof):
    """(mobility, locked joints) by the floating-point rank at a random pose (an unlucky
    draw would show as a disagreement with the forests, which are exact)."""
    return generic_verdict(links, edges, kinds, dof, seed=(1, tuple(kinds)))


def admissible_by_rank(links, edges, kinds, dof):
    mobility, locked = reference(links, edges, kinds, dof)
    return mobility == dof and not locked


def _shape(edges, kinds):
    """The kinds around a ring of four links, read from its least rotation."""
    order, at, seen = [], 0, set()
    ring = {}
    for (a, b), k in zip(edges, kinds):
        ring.setdefault(a, []).append((b, k))
        ring.setdefault(b, []).append((a, k))
    prev = None
    while len(order) < len(edges):
        nxt, k = next((x, k) for x, k in ring[at] if (x, k) != prev and x not in seen
                      or len(order) == len(edges) - 1 and x == 0)
        seen.add(at)
        order.append(k)
        prev, at = (at, k), nxt
    word = "".join(order)
    return min(min(word[i:] + word[:i], (word[::-1])[i:] + (word[::-1])[:i])
               for i in range(len(word)))


def _chain(links, edges, kinds):
    return Chain("x", tuple(Joint(f"J{i}", k, (f"L{a}", f"L{b}"))
                            for i, ((a, b), k) in enumerate(zip(edges, kinds))))


def _brute_force(links, dof):
    """By K: the admissible chains, up to isomorphism by canonical forms, and their
    inversion classes; every assignment of every turning-pair chain tried."""
    forms = {}
    for entry in atlas_graphs(links, dof):
        edges = [tuple(e) for e in entry.edges]
        masks = list(range(1 << len(edges)))
        mobility, locked = generic_verdicts(links, edges, masks)   # one exact evaluation
        for mask in masks:
            kinds = ["P" if mask >> i & 1 else "R" for i in range(len(edges))]
            float_mobility, float_locked = reference(links, edges, kinds, dof)
            by_rank = float_mobility == dof and not float_locked
            if admissible(links, edges, kinds) is not None:    # the structure's verdict
                assert not by_rank, (edges, kinds)
            # forests decide exactly: the generic rank and every lock, not only the verdict
            rank, stuck = forest_verdicts(links, edges, kinds)
            assert (3 * (links - 1) - rank, stuck) == (float_mobility, bool(float_locked))
            if int(mobility[mask]) == dof and not locked[mask]:
                assert by_rank, (edges, kinds)            # an evaluation's admission is proof
            if by_rank:
                chain = _chain(links, edges, kinds)
                form = canonical_form(chain, oriented=False)
                found = forms.setdefault(kinds.count("P"), {})
                if form not in found:
                    found[form] = len(automorphism_orbits(chain, oriented=False))
    return forms


def _check_counts(links, dof):
    forms = _brute_force(links, dof)
    got = sliding_atlas(atlas_graphs(links, dof), prismatic=range(2 * links))
    for k, counted in got.count_by_prismatic.items():
        assert counted == len(forms.get(k, {})), k
    assert got.distinct_inversions == sum(sum(f.values()) for f in forms.values())


def test_the_rule_is_the_rank_and_the_count_is_brute_force_to_6_links():
    """Four links: the four-bar chain, the single slider crank chain and the two double
    slider chains (the P joints adjacent, or opposite); six links: every assignment."""
    _check_counts(4, 1)
    _check_counts(6, 1)
    _check_counts(7, 2)


@pytest.mark.slow
def test_the_rule_is_the_rank_and_the_count_is_brute_force_at_8_links():
    _check_counts(8, 1)


def test_orientation_counts_are_brute_force():
    """With --oriented: which link carries each guide, one chain per orbit."""
    for links, dof in ((4, 1), (6, 1)):
        forms = {}
        for entry in atlas_graphs(links, dof):
            edges = [tuple(e) for e in entry.edges]
            for mask in range(1 << len(edges)):
                kinds = ["P" if mask >> i & 1 else "R" for i in range(len(edges))]
                if not admissible_by_rank(links, edges, kinds, dof):
                    continue
                sliding = [i for i, k in enumerate(kinds) if k == "P"]
                for bits in range(1 << len(sliding)):
                    flipped = list(edges)
                    for j, i in enumerate(sliding):
                        if bits >> j & 1:
                            flipped[i] = edges[i][::-1]
                    chain = _chain(links, flipped, kinds)
                    forms[canonical_form(chain, oriented=True)] = \
                        len(automorphism_orbits(chain, oriented=True))
        got = sliding_atlas(atlas_graphs(links, dof), prismatic=range(2 * links), oriented=True)
        assert len(got) == len(forms)
        assert got.distinct_inversions == sum(forms.values())


def test_the_rejected_are_the_textbook_s_cases():
    """A loop of sliding pairs only has a freedom too many; a turning pair between two
    links joined by sliding pairs cannot turn; in Stephenson's chain, a path of three
    sliding pairs between the ternary links keeps them parallel, and the two binary
    links between them then make a rigid sub-chain that locks four turning pairs
    (which the structure of the P joints alone does not see)."""
    ring = [(0, 1), (1, 2), (2, 3), (3, 0)]
    assert admissible(4, ring, "PPPP") == "mobility"
    assert admissible(4, ring, "RPPP") == "locked"
    assert generic_verdict(4, ring, "PPPP", 1, 0)[0] == 2
    assert generic_verdict(4, ring, "RPPP", 1, 0) == (1, [0])
    stephenson = [(0, 1), (0, 4), (1, 5), (2, 4), (2, 5), (3, 4), (3, 5)]
    kinds = "PPPRRRR"
    assert admissible(6, stephenson, kinds) is None
    assert generic_verdict(6, stephenson, kinds, 1, 0) == (1, [3, 4, 5, 6])
    assert forest_verdicts(6, stephenson, kinds) == (14, True)
    assert verdicts(6, [stephenson], kinds=[kinds], dof=1) == ["locked"]


def test_atlas_prismatic_on_the_command_line(capsys):
    assert main(["atlas", "--links", "4", "--prismatic", "all", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["count"] == 4 and out["count_by_prismatic"] == {"0": 1, "1": 1, "2": 2, "3": 0,
                                                               "4": 0}
    assert out["rejected"] == {"mobility": 1, "locked": 1}
    # the four-bar chain, the single slider crank chain, the two double slider chains
    shapes = sorted(_shape(c["edges"], c["kinds"]) for c in out["chains"])
    assert shapes == ["PPRR", "PRPR", "PRRR", "RRRR"]
    for c in out["chains"]:
        assert len(c["kinds"]) == len(c["edges"]) == 4
    assert main(["atlas", "--links", "6", "--prismatic", "1", "--summary"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["count"] == 6 and "chains" not in summary
    assert main(["atlas", "--links", "4", "--prismatic", "2", "--oriented", "--summary"]) == 0
    assert json.loads(capsys.readouterr().out)["count"] == 5


@pytest.mark.parametrize("argv, words", [
    (["atlas", "--links", "4", "--prismatic", "-1"], "prismatic"),
    (["atlas", "--links", "4", "--prismatic", "x"], "prismatic"),
    (["atlas", "--links", "4", "--prismatic", "9"], "at most 4"),
    (["atlas", "--links", "4", "--oriented"], "--oriented"),
])
def test_bad_sliding_requests_are_one_line(argv, words, capsys):
    with pytest.raises(SystemExit) as info:
        code = main(argv)
        raise SystemExit(code)
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert words in err and err.count("\n") == 1
