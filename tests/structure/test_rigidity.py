"""The rigid parts of a chain against the exhaustive scan of every link set: the
polynomial verdict and witness, the rigid regions (against a brute force over
partitions), the listing of every smallest rigid sub-chain (minimum cuts over link
sets) and its budget; long chains whose rigid parts are known by construction."""

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
from chaingraph.files import dumps
from chaingraph.structure.atlas import atlas
from chaingraph.structure.atlas.admissibility import decide
from chaingraph.structure.generators import random_chain
from chaingraph.structure.rigidity import (
    one_rigid_subchain, rigid_parts, rigid_regions, rigid_subchains,
    rigid_subchains_by_subsets, subchain_mobility)

from ..conftest import run_cli
from .long_chains import buried_k23, hub_cycles, hub_on_grid, ladder, random_dyads

PLANAR = ["R", "P", "cam", "gear", "rolling"]
SPATIAL = ["R", "P", "screw", "cylindrical", "spherical", "planar"]


def _mobilities(chain):
    """The mobility of every set of links (a bit mask), by the definition: d (|S| - 1)
    less (d - f) (k_S - 1) for each joint with k_S of its links in S."""
    d = 3 if chain.space == "planar" else 6
    index = {x: i for i, x in enumerate(chain.links)}
    joints = [(sum(1 << index[x] for x in j.links), d - j.pair.freedom(chain.space))
              for j in chain.joints]
    return [d * (s.bit_count() - 1)
            - sum(w * ((m & s).bit_count() - 1) for m, w in joints if m & s)
            for s in range(1 << len(chain.links))]


def _maximal_bodies(chain):
    """The rigid regions by brute force: the largest sets S of two links or more whose
    mobility is at most the sum of their parts' over every partition of S (the least
    such sum by a recursion over the part that holds S's first link)."""
    f = _mobilities(chain)
    least = [0] * len(f)                      # the least sum over partitions
    for s in range(1, len(f)):
        low, rest = s & -s, s & ~(s & -s)
        best, sub = f[s], rest
        while True:                           # the part through low: low | sub, sub <= rest
            part = low | sub
            if part != s:
                best = min(best, f[part] + least[s & ~part])
            if not sub:
                break
            sub = (sub - 1) & rest
        least[s] = best
    bodies = [s for s in range(len(f)) if s.bit_count() >= 2 and f[s] <= least[s]]
    maximal = []
    for s in sorted(bodies, key=lambda s: -s.bit_count()):
        if not any(s & t == s for t in maximal):
            maximal.append(s)
    assert all(not a & b for a, b in itertools.combinations(maximal, 2))   # disjoint
    return sorted(tuple(x for i, x in enumerate(chain.links) if s >> i & 1) for s in maximal)


def _union_closure(sets):
    """The unions of the sets that share links, joined until none share one."""
    groups = [set(s) for s in sets]
    merged = True
    while merged:
        merged = False
        for a, b in itertools.combinations(range(len(groups)), 2):
            if groups[a] & groups[b]:
                groups[a] |= groups.pop(b)
                merged = True
                break
    return groups


def _agree(chain, *, regions=True):
    """Every answer of the polynomial methods and of the listing against the scan: the
    verdict, the witness (one of the scan's sets), the list, the regions (brute force
    up to 10 links; each holds the sets of the scan that meet it)."""
    reference = rigid_subchains_by_subsets(chain)
    parts = rigid_parts(chain)
    assert list(parts.smallest) == rigid_subchains(chain) == reference, chain.name
    assert parts.complete and parts.degenerate is bool(reference)
    witness = one_rigid_subchain(chain)
    assert (witness in reference) if reference else witness is None
    for group in _union_closure(reference):
        assert any(group <= set(r) for r in parts.regions)
    if regions and len(chain.links) <= 10:
        assert sorted(parts.regions) == _maximal_bodies(chain), chain.name
    return reference


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
        _agree(chain)
        j = next(j for j in chain.joints if j.order == 2)
        doubled = Chain(chain.name, chain.joints + (Joint("twin", "R", j.links),))
        _agree(doubled)
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


def R(joint_id, a, b):
    return Joint(joint_id, "R", (a, b))


def test_a_region_holds_what_is_rigid_with_it():
    # a triangle 2-5-6 on a four-bar and a dyad 7-8 hung on 5 and 6: the dyad is rigid
    # with the triangle (F = 0 for the five) though in no smallest rigid sub-chain,
    # so the union of those (the triangle) is not the region
    c = Chain("x", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "4"), R("D", "4", "1"),
                    R("E", "2", "5"), R("F", "5", "6"), R("G", "6", "2"), R("H", "5", "7"),
                    R("I", "7", "8"), R("K", "8", "6")))
    assert rigid_subchains(c) == [("2", "5", "6")]
    assert rigid_regions(c) == [("2", "5", "6", "7", "8")]
    _agree(c)


def test_rigid_sets_that_share_links_need_not_make_a_rigid_union():
    # links 1 and 2 pinned twice (F = -1), 3 and 4 each pinned once to 1: {1, 2, 3} and
    # {1, 2, 4} count as rigid (F = 0), their union does not (F = 1), and 3 and 4 turn
    # about 1: the region is the pair
    c = Chain("x", (R("A", "1", "2"), R("B", "1", "2"), R("C", "1", "3"), R("D", "1", "4")))
    assert [subchain_mobility(c, s) for s in ("12", "123", "124", "1234")] == [-1, 0, 0, 1]
    assert rigid_subchains(c) == [("1", "2")] and rigid_regions(c) == [("1", "2")]
    _agree(c)


def test_a_locked_chain_is_one_region_and_not_degenerate():
    triangle = Chain("x", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "1")))
    parts = rigid_parts(triangle)
    assert (parts.degenerate, parts.smallest, parts.regions) == (False, (), (("1", "2", "3"),))
    _agree(triangle)


def test_every_triangle_of_a_complete_chain():
    # 26 links all pinned together (past the scan's limit of work): every three links
    # make a triangle, F = 0, and any larger set holds one
    chain = Chain("K26", tuple(Joint(f"J{a}-{b}", "R", (f"L{a}", f"L{b}"))
                               for a, b in itertools.combinations(range(26), 2)))
    found = rigid_subchains(chain)
    assert len(found) == comb(26, 3) and {len(s) for s in found} == {3}
    assert found == sorted(found, key=lambda s: sum(1 << chain.links.index(x) for x in s))


def test_exponentially_many_minimal_rigid_sets_are_all_found():
    # the cycles of a 2-by-k grid: k choose 2 (one per pair of rungs)
    for k in (3, 4):                               # 14 and 19 links
        chain = hub_on_grid(k)
        assert set(map(frozenset, _agree(chain))) == hub_cycles(k)


def test_long_chains_with_known_rigid_parts():
    chain = ladder(100)
    c = classify(chain)
    assert (c.links, c.mobility, c.degenerate, c.rigid_subchains) == (100, 1, False, ())
    assert c.rigid_regions == () and c.rigid_subchains_complete
    chain, rigid = buried_k23(100)
    c = classify(chain)
    assert (c.links, c.mobility, c.degenerate) == (100, 1, True)
    assert [sorted(s) for s in c.rigid_subchains] == [sorted(rigid)]
    assert [sorted(s) for s in c.rigid_regions] == [sorted(rigid)]
    assert c.rigid_subchains_complete
    for seed in range(3):
        for triangle in (False, True):
            chain, rigid = random_dyads(100, seed=seed, triangle=triangle)
            c = classify(chain)
            assert (c.links, c.mobility, c.degenerate) == (100, 1, triangle)
            assert [sorted(s) for s in c.rigid_subchains] == [sorted(s) for s in rigid]
            assert [sorted(s) for s in c.rigid_regions] == [sorted(s) for s in rigid]
            assert one_rigid_subchain(chain) == (c.rigid_subchains[0] if triangle else None)


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
    a, b = rigid_regions(chain), rigid_regions(other)
    assert sorted(sorted(names[x] for x in s) for s in a) == sorted(sorted(s) for s in b)


def _induced(chain, links):
    """The sub-chain of ``links`` and the joints among them."""
    inside = set(links)
    return Chain("part", tuple(Joint(j.id, j.kind, tuple(x for x in j.links if x in inside))
                               for j in chain.joints
                               if sum(x in inside for x in j.links) >= 2), space=chain.space)


def _smallest_and_in_regions(chain, sets, regions):
    """Each set is a smallest rigid sub-chain (rigid, and its own sub-chain not
    degenerate: the polynomial verdict, checked against the scan above) inside one of
    the regions, which are rigid and share no link."""
    for s in sets:
        assert subchain_mobility(chain, s) <= 0 and len(s) < len(chain.links)
        assert one_rigid_subchain(_induced(chain, s)) is None
        assert sum(set(s) <= set(r) for r in regions) == 1
    for r in regions:
        assert subchain_mobility(chain, r) <= 0
    assert len({x for r in regions for x in r}) == sum(map(len, regions))


def test_a_listing_past_its_budget_keeps_what_it_found():
    chain = hub_on_grid(7)        # 34 links, 21 smallest rigid sub-chains
    parts = rigid_parts(chain, budget=50_000)
    assert parts.degenerate and not parts.complete
    assert 1 <= len(parts.smallest) < comb(7, 2)
    assert set(map(frozenset, parts.smallest)) <= hub_cycles(7)
    assert one_rigid_subchain(chain) in parts.smallest
    assert parts.regions == (tuple(chain.links),)        # the hub holds every cycle
    small = Chain("x", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "4"),
                        R("D", "4", "1"), R("E", "2", "5"), R("F", "5", "6"),
                        R("G", "6", "2")))   # no budget needed: its region is scanned
    assert rigid_parts(small, budget=0) == rigid_parts(small, budget=None)
    assert rigid_parts(small, budget=0).complete


def test_cli_says_when_the_listing_stopped_at_its_bound():
    path = Path(__file__).parents[1] / "data" / "hub-on-grid-24.toml"
    chain = hub_on_grid(5)                      # 24 links: searched, past the budget
    assert path.read_text(encoding="utf-8") == dumps(chain)   # as its generator writes it
    code, out, err = run_cli("classify", "--json", path)
    assert code == 0 and err == ""
    d = json.loads(out)
    assert d["degenerate"] is True and d["rigid_subchains_complete"] is False
    assert 1 <= len(d["rigid_subchains"]) < comb(5, 2)
    assert set(map(frozenset, d["rigid_subchains"])) <= hub_cycles(5)
    code, out, err = run_cli("classify", path)
    assert code == 0
    assert (f"note: smallest rigid sub-chains: {len(d['rigid_subchains'])} found, the "
            "search stopped at its bound; more may exist") in out.splitlines()


@pytest.mark.parametrize("seed", [0, 1])
def test_random_hundred_link_chains_classify(tmp_path, seed):
    # J = 3L/2 - 2, F = 1: degenerate exactly when some part is rigid, which the
    # atlas's forests (Edmonds' matroid partition, an independent method) decide
    chain = random_chain(100, seed=seed)
    path = tmp_path / "random.toml"
    path.write_text(dumps(chain), encoding="utf-8")
    code, out, err = run_cli("classify", path, "--json")
    assert code == 0 and err == ""
    d = json.loads(out)
    index = {x: i for i, x in enumerate(chain.links)}
    verdict = decide(100, [tuple(index[x] for x in j.links) for j in chain.joints])
    assert (d["links"], d["mobility"]) == (100, 1)
    assert d["degenerate"] is (verdict is not None)
    assert bool(d["rigid_subchains"]) is d["degenerate"]
    assert isinstance(d["rigid_subchains_complete"], bool)
    _smallest_and_in_regions(chain, d["rigid_subchains"], d["rigid_regions"])


@pytest.mark.parametrize("seed", [0, 1])
def test_hundred_link_chains_known_by_construction_classify(tmp_path, seed):
    for triangle in (False, True):
        chain, rigid = random_dyads(100, seed=seed, triangle=triangle)
        path = tmp_path / "dyads.toml"
        path.write_text(dumps(chain), encoding="utf-8")
        code, out, err = run_cli("classify", path, "--json")
        d = json.loads(out)
        assert (code, d["degenerate"], d["rigid_subchains_complete"]) == (0, triangle, True)
        assert [sorted(s) for s in d["rigid_subchains"]] == [sorted(s) for s in rigid]


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
    assert d["rigid_subchains_complete"] is True
    assert d["rigid_regions"] == d["rigid_subchains"]
