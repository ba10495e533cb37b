"""Admissibility with proofs: forests for turning and sliding pairs, Whiteley's count for
pins, an exact evaluation for admissions; against closed-form cases and the
floating-point rank of tests/structure/generic_rank.py."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from chaingraph.errors import ChainStructureError
from chaingraph.structure.atlas import admissibility
from chaingraph.structure.atlas.admissibility import decide, verdicts
from chaingraph.structure.atlas.forests import ANY, OMEGA, Forests, forest_verdicts
from chaingraph.structure.atlas.pins import overbraced, pin_verdicts, weld

from .generic_rank import random_pose

RING = ((0, 1), (1, 2), (2, 3), (3, 0))
STEPHENSON = ((0, 1), (0, 4), (1, 5), (2, 4), (2, 5), (3, 4), (3, 5))


def test_three_forests_hold_a_rigid_body_s_three_freedoms():
    """Two links: three rows at most, whatever they are; a fixed turn row goes in the
    first forest only, so two of them between the same links are one too many."""
    f = Forests(2)
    assert [f.add(0, 1, ANY) for _ in range(4)] == [True, True, True, False]
    g = Forests(2)
    assert [g.add(0, 1, OMEGA), g.add(0, 1, OMEGA), g.add(0, 1, ANY)] == [True, False, True]


def test_an_augmenting_path_moves_rows_between_forests():
    """A triangle of links takes six generic rows only by moving a row already placed:
    the greedy split fails where the partition does not."""
    f = Forests(3)
    rows = [(0, 1, OMEGA), (0, 1, ANY), (1, 2, ANY), (1, 2, ANY), (0, 2, ANY), (0, 2, ANY)]
    assert all(f.add(*r) for r in rows[:5])
    before = list(f.where)
    assert f.add(*rows[5]) and f.rank == 6
    assert f.where[:5] != before                  # it moved rows already placed
    assert f.where[0] == 0                        # the fixed turn row stays in omega
    for k in range(3):          # every forest is a forest
        kept = [rows[i][:2] for i, w in enumerate(f.where) if w == k]
        assert len(kept) <= 2 and len({frozenset(e) for e in kept}) == len(kept)


def test_the_four_link_chains():
    """The four-bar, the slider crank and the double slider chains have one freedom; a
    ring of four sliding pairs two; three sliding pairs lock the turning pair."""
    got = {k: forest_verdicts(4, RING, k) for k in ("RRRR", "PRRR", "PPRR", "PRPR", "RPPP",
                                                    "PPPP")}
    assert got == {"RRRR": (8, False), "PRRR": (8, False), "PPRR": (8, False),
                   "PRPR": (8, False), "RPPP": (8, True), "PPPP": (7, False)}
    assert verdicts(4, [RING] * 4, kinds=["PRRR", "PRPR", "RPPP", "PPPP"], dof=1) == \
        [None, None, "locked", "mobility"]


def test_stephenson_s_rigid_sub_chain_is_proven_locked():
    """A path P-P-P between the ternary links keeps them parallel: with the two binary
    links between them they make a rigid sub-chain. The structure of the P joints does
    not see it; forests do, and the floating-point rank agrees."""
    kinds = "PPPRRRR"
    assert admissibility.admissible(6, STEPHENSON, kinds) is None
    assert forest_verdicts(6, STEPHENSON, kinds) == (14, True)
    assert decide(6, STEPHENSON, kinds) == "locked"


def test_pins_are_counted():
    """A pin of three links with three more joints on four links is overbraced (10 rows,
    9 freedoms); so are two links held by a pin and a joint; six links with one pin of
    three (the toggle press's chain) have one freedom and lock nothing, as the
    floating-point rank says."""
    fan = ((0, 1, 2), (1, 3), (2, 3), (0, 3))
    assert bin(overbraced(4, fan)) == "0b1111"
    assert decide(4, fan) == "mobility"
    assert overbraced(3, ((0, 1, 2), (0, 2))) == 0b101
    toggle = ((0, 1), (1, 2), (2, 3, 4), (3, 0), (4, 5), (5, 0))
    dependent, locked = pin_verdicts(6, [toggle])
    assert (dependent.tolist(), locked.tolist()) == ([False], [False])
    assert decide(6, toggle) is None and _float(6, toggle, "R" * 6) == (1, False)
    # with a slider: the bounds reject nothing, and an evaluation proves it admissible
    assert decide(6, toggle, "RRRRPR") == "undecided"
    assert verdicts(6, [toggle], kinds=["RRRRPR"], dof=1) == [None]
    assert _float(6, toggle, "RRRRPR") == (1, False)


def test_a_weld_makes_two_links_one():
    assert weld(((0, 1, 2), (1, 3), (2, 3)), "RRR", 1, 2) == ([(0, 1), (1, 2), (1, 2)],
                                                            ["R", "R", "R"])
    assert weld(((0, 1), (1, 2)), "PR", 0, 1) == ([(0, 1)], ["R"])


def _float(links, joints, kinds, seed=3):
    """(mobility, any joint locked) by the floating-point rank at a random pose."""
    mobility, locked = random_pose(links, joints, kinds, np.random.default_rng(seed))
    return mobility, bool(locked)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.data())
def test_renaming_the_links_changes_no_verdict(data):
    """Relabel the links (the fixed link too) of a chain of turning and sliding pairs:
    the forests' rank and locks are the same; and they are the floating-point rank's."""
    kinds = data.draw(st.text(alphabet="RP", min_size=7, max_size=7))
    order = data.draw(st.permutations(range(6)))
    relabelled = tuple((order[a], order[b]) for a, b in STEPHENSON)
    rank, locked = forest_verdicts(6, STEPHENSON, kinds)
    assert forest_verdicts(6, relabelled, kinds) == (rank, locked)
    assert (15 - rank, locked) == _float(6, STEPHENSON, kinds)


def test_pins_with_a_parallel_path_are_proven_locked_by_the_path_s_row():
    """Links 4 and 5 kept parallel by the path P-P-P through 0 and 1, and a pin of three
    links (2, 3, 6) on links joined to 4, 5 and 7: a rigid sub-chain that spreading the
    pin hides from forests, and that the plain count misses. Counting the path as one
    row proves it: welding 4 and 7 overbraces the links 2 to 7. The floating-point
    rank agrees, and should every bound fail, four evaluations would still say so."""
    joints = ((0, 1), (0, 4), (1, 5), (2, 3, 6), (2, 4), (3, 5), (4, 7), (5, 7), (6, 7))
    kinds = "PPPRRRRRR"
    assert decide(8, joints, kinds, independent=True) == "locked"
    assert decide(8, joints, kinds, independent=False) == "undecided"   # needs independence
    assert forest_verdicts(8, joints, kinds) == (20, False)
    assert _float(8, joints, kinds) == (1, True)
    assert verdicts(8, [joints], kinds=[kinds], dof=1) == ["locked"]


def test_every_evaluation_rejecting_is_the_last_resort(monkeypatch):
    """With the bounds taken away, a chain no evaluation admits is rejected for what
    the evaluations say."""
    monkeypatch.setattr(admissibility, "decide", lambda *a, **k: "undecided")
    joints = ((0, 1), (0, 4), (1, 5), (2, 3, 6), (2, 4), (3, 5), (4, 7), (5, 7), (6, 7))
    assert verdicts(8, [joints], kinds=["PPPRRRRRR"], dof=1) == ["locked"]
    ring = ((0, 1), (1, 2), (2, 3), (3, 0))
    assert verdicts(4, [ring], kinds=["PRRR"], dof=1) == [None]     # an evaluation admits


def test_a_candidate_with_the_wrong_joints_for_its_freedoms_is_named():
    ring = ((0, 1), (1, 2), (2, 3), (3, 0))
    with pytest.raises(ChainStructureError, match=r"leave 1 degree of freedom by their "
                                                  r"count, not 2"):
        verdicts(4, [ring], dof=2)
