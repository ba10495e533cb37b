"""The rigid sub-chain search (minimum cuts over link sets) against the exhaustive scan
of every link set, and on long chains whose rigid parts are known by construction."""

import glob
import json
import itertools
import random
from math import comb
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import chaingraph
from chaingraph import Chain, Joint, classify
from chaingraph.structure import rigidity
from chaingraph.structure.atlas import atlas
from chaingraph.structure.generators import random_chain
from chaingraph.structure.rigidity import rigid_subchains, rigid_subchains_by_subsets

from ..conftest import run_cli
from .long_chains import buried_k23, ladder, random_dyads

PLANAR = ["R", "P", "cam", "gear", "rolling"]
SPATIAL = ["R", "P", "screw", "cylindrical", "spherical", "planar"]


def _agree(chain):
    assert rigid_subchains(chain) == rigid_subchains_by_subsets(chain), chain.name


def _rekinded(chain, kinds, rng, space="planar"):
    """The chain with each binary joint of a random kind (multiple joints stay R)."""
    return Chain(chain.name, tuple(
        Joint(j.id, rng.choice(kinds) if j.order == 2 else "R", j.links)
        for j in chain.joints), space=space)


@pytest.mark.parametrize("links, dof, prismatic, multiple", [
    (4, 1, "all", False), (5, 2, "all", False), (6, 1, "all", False),
    (7, 2, None, False), (8, 1, None, False), (8, 1, 2, False), (9, 2, None, False),
    (6, 1, None, True), (7, 2, None, True)])
def test_atlas_chains_agree_with_the_scan(links, dof, prismatic, multiple):
    # the atlas keeps only chains with no rigid part: both searches must find none,
    # and every chain with one joint doubled has the doubled pair as its rigid part
    chains = list(atlas(links=links, dof=dof, prismatic=prismatic, multiple=multiple))
    assert chains
    for chain in chains:
        assert rigid_subchains(chain) == rigid_subchains_by_subsets(chain) == []
        j = next(j for j in chain.joints if j.order == 2)
        doubled = Chain(chain.name, chain.joints + (Joint("twin", "R", j.links),))
        assert rigid_subchains(doubled) == rigid_subchains_by_subsets(doubled)
        assert tuple(x for x in chain.links if x in j.links) in rigid_subchains(doubled)


def test_catalog_chains_agree_with_the_scan():
    paths = glob.glob(str(chaingraph.naming.catalog.catalog_path("four-bar-chain").parent
                          / "*.toml"))
    assert len(paths) > 20
    for path in paths:
        _agree(chaingraph.load(path))


@settings(max_examples=300, deadline=None, derandomize=True)
@given(st.integers(2, 12), st.integers(-2, 7), st.integers(0, 3), st.integers(0, 3),
       st.sampled_from(["planar", "weighted", "spatial"]), st.integers(0, 10**6))
def test_random_chains_agree_with_the_scan(n, extra, ternary, sliding, kinds, seed):
    rng = random.Random(seed)
    joints = max(n - 1, 3 * n // 2 - 2 + extra)
    chain = random_chain(n, joints, ternary=ternary, sliding=sliding, seed=seed)
    if kinds == "weighted":
        chain = _rekinded(chain, PLANAR, rng)
    elif kinds == "spatial":
        chain = _rekinded(chain, SPATIAL, rng, space="spatial")
    _agree(chain)


def test_every_triangle_of_a_complete_chain():
    # 26 links all pinned together (past the scan's limit of work): every three links
    # make a triangle, F = 0, and any larger set holds one
    chain = Chain("K26", tuple(Joint(f"J{a}-{b}", "R", (f"L{a}", f"L{b}"))
                               for a, b in itertools.combinations(range(26), 2)))
    found = rigid_subchains(chain)
    assert len(found) == comb(26, 3) and {len(s) for s in found} == {3}
    assert found == sorted(found, key=lambda s: sum(1 << chain.links.index(x) for x in s))


def _hub_on_ladder(k):
    """A hub link pinned to every node link of a 2-by-k grid, whose edges are binary
    links: each cycle of the grid with the hub is a minimal rigid set (F = 0, every
    part of it a path with the hub, F >= 1), and there are no others."""
    nodes = [(r, c) for r in range(2) for c in range(k)]
    edges = [((0, c), (1, c)) for c in range(k)]
    edges += [((r, c), (r, c + 1)) for r in range(2) for c in range(k - 1)]
    name = lambda p: f"x{p[0]}{p[1]}"           # noqa: E731
    joints = [Joint(f"H{name(p)}", "R", ("hub", name(p))) for p in nodes]
    for i, (p, q) in enumerate(edges):
        joints += [Joint(f"A{i}", "R", (name(p), f"y{i}")), Joint(f"B{i}", "R", (f"y{i}", name(q)))]
    return Chain(f"hub on a 2x{k} grid", tuple(joints))


def test_exponentially_many_minimal_rigid_sets_are_all_found():
    # the cycles of a 2-by-k grid: k choose 2 (one per pair of rungs)
    for k in (3, 4):                               # 14 and 19 links
        chain = _hub_on_ladder(k)
        assert len(rigid_subchains(chain)) == comb(k, 2)
        _agree(chain)


def test_long_chains_with_known_rigid_parts():
    chain = ladder(100)
    c = classify(chain)
    assert (c.links, c.mobility, c.degenerate, c.rigid_subchains) == (100, 1, False, ())
    chain, rigid = buried_k23(100)
    c = classify(chain)
    assert (c.links, c.mobility, c.degenerate) == (100, 1, True)
    assert [sorted(s) for s in c.rigid_subchains] == [sorted(rigid)]
    for seed in range(3):
        for triangle in (False, True):
            chain, rigid = random_dyads(100, seed=seed, triangle=triangle)
            c = classify(chain)
            assert (c.links, c.mobility, c.degenerate) == (100, 1, triangle)
            assert [sorted(s) for s in c.rigid_subchains] == [sorted(s) for s in rigid]


@pytest.mark.parametrize("seed", range(3))
def test_relabelling_keeps_the_rigid_sets_of_a_long_chain(seed):
    rng = random.Random(seed)
    chain, rigid = random_dyads(100, seed=seed, triangle=True)
    k23 = [Joint(f"K{i}", "R", (f"L{a}" if a < 100 else f"M{a}", f"M{b}"))
           for i, (a, b) in enumerate((x, y) for x in (rng.randrange(100), 100)
                                      for y in (101, 102, 103))]
    chain = Chain(chain.name, chain.joints + tuple(k23))
    names = dict(zip(chain.links, rng.sample([f"n{i}" for i in range(len(chain.links))],
                                             len(chain.links))))
    other = chain.relabelled(links=names)
    order = list(other.joints)
    rng.shuffle(order)
    other = Chain(other.name, tuple(order))
    a, b = rigid_subchains(chain), rigid_subchains(other)
    assert len(a) == 2
    assert sorted(sorted(names[x] for x in s) for s in a) == sorted(sorted(s) for s in b)


def test_a_search_past_its_budget_is_scanned_or_refused(monkeypatch):
    monkeypatch.setattr(rigidity, "MAX_FLOWS", 20)
    small = _hub_on_ladder(4)                      # 19 links: the scan takes it
    assert len(rigid_subchains(small)) == comb(4, 2)
    with pytest.raises(chaingraph.ChainStructureError, match="20 maximum flows"):
        rigid_subchains(_hub_on_ladder(7))         # 34 links: refused


def test_the_scan_refuses_what_it_cannot_finish():
    with pytest.raises(chaingraph.ChainStructureError, match="at most 26 links"):
        rigid_subchains_by_subsets(random_chain(27, seed=0))


def test_cli_classifies_the_long_chain_file():
    path = Path(__file__).parents[1] / "data" / "long-chain-100.toml"
    code, out, err = run_cli("classify", "--json", path)
    assert code == 0 and err == ""
    d = json.loads(out)
    assert (d["links"], d["mobility"], d["degenerate"]) == (100, 1, True)
    assert len(d["rigid_subchains"]) == 1 and len(d["rigid_subchains"][0]) == 5
