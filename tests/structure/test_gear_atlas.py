"""The atlas of epicyclic gear trains (issue 39) against a brute force written here: every
labelled tree of turning pairs (Pruefer sequences) and every set of gear pairs with a
carrier on it, each rule checked on its own (the axes by every partition of the turning
pairs into axes; the generic freedom by exact rational elimination with random ratios;
a link separating the equations by removing each link), isomorphism by every
permutation of the links. Then the published counts, the key's invariance under
renumbering and the textbook's trains (the example files) found in the atlas."""

import itertools
import random
from fractions import Fraction

import networkx as nx
import pytest

from chaingraph.files import load
from chaingraph.naming.catalog import catalog_path
from chaingraph.errors import AtlasSizeError
from chaingraph.structure.atlas.gears import (
    chain_graph,
    fractionated,
    gear_atlas,
    train_key,
    train_levels,
    train_verdict,
)



def _trees(n):
    """Every labelled tree on n vertices, from its Pruefer sequence."""
    if n == 2:
        yield ((0, 1),)
        return
    for seq in itertools.product(range(n), repeat=n - 2):
        yield tuple(sorted(tuple(sorted(e)) for e in nx.from_prufer_sequence(list(seq)).edges))


def _partitions(items):
    """Every partition of a list into blocks (as a block number per item)."""
    if not items:
        yield {}
        return
    first, rest = items[0], items[1:]
    for p in _partitions(rest):
        blocks = set(p.values())
        for b in blocks:
            yield {**p, first: b}
        yield {**p, first: len(blocks)}


def _axes_exist(tree, paths, gears):
    """Some partition of the turning pairs into axes puts each gear's side of its
    circuit on one axis and the two sides on different axes."""
    edges = list(tree)
    sides = []
    for a, b, c in gears:
        path = paths[a][b]
        k = path.index(c)
        pairs = [tuple(sorted(p)) for p in zip(path, path[1:])]
        sides.append((pairs[:k], pairs[k:]))
    for axis in _partitions(edges):
        if all(len({axis[e] for e in left}) == 1 and len({axis[e] for e in right}) == 1
               and axis[left[0]] != axis[right[0]] for left, right in sides):
            return True
    return False


def _rank(rows):
    rows = [list(r) for r in rows]
    rank, col = 0, 0
    width = len(rows[0]) if rows else 0
    while rank < len(rows) and col < width:
        k = next((i for i in range(rank, len(rows)) if rows[i][col] != 0), None)
        if k is None:
            col += 1
            continue
        rows[rank], rows[k] = rows[k], rows[rank]
        for i in range(len(rows)):
            if i != rank and rows[i][col] != 0:
                f = rows[i][col] / rows[rank][col]
                rows[i] = [x - f * y for x, y in zip(rows[i], rows[rank])]
        rank, col = rank + 1, col + 1
    return rank


def _generic(n, gears, rng):
    """The equations independent, no two links bound together (e_x - e_y in their
    span), with random rational ratios."""
    rows = []
    for a, b, c in gears:
        k = Fraction(rng.randint(2, 10**6), rng.randint(2, 10**6))
        row = [Fraction(0)] * n
        row[a], row[b], row[c] = Fraction(1), k, -1 - k
        rows.append(row)
    r = _rank(rows)
    if r < len(gears):
        return False
    for x, y in itertools.combinations(range(n), 2):
        v = [Fraction(0)] * n
        v[x], v[y] = Fraction(1), Fraction(-1)
        if _rank(rows + [v]) == r:
            return False
    return True


def _brute_fractionated(n, gears):
    for x in range(n):
        rest = [set(g) - {x} for g in gears]
        groups = []
        for s in rest:
            joined = [g for g in groups if g & s]
            for g in joined:
                groups.remove(g)
                s = s | g
            groups.append(s)
        if len(groups) > 1:
            return True
    return False


def _canonical(n, gears):
    """The least relabelled gear set over every permutation of the links."""
    return min(tuple(sorted((min(p[a], p[b]), max(p[a], p[b]), p[c]) for a, b, c in gears))
               for p in itertools.permutations(range(n)))


def brute_force(n, dof):
    """Every train of n links and dof freedoms by exhaustive search: {canonical gear set:
    fractionated}."""
    rng = random.Random(5)
    found, generic, canonical = {}, {}, {}
    for tree in _trees(n):
        g = nx.Graph(tree)
        paths = dict(nx.all_pairs_shortest_path(g))
        triples = [(a, b, c) for a, b in itertools.combinations(range(n), 2)
                   for c in range(n) if c in paths[a][b][1:-1]]
        for gears in itertools.combinations(triples, n - 1 - dof):
            if len({g[:2] for g in gears}) < len(gears):
                continue
            if {x for g in gears for x in g} != set(range(n)):
                continue
            if not _axes_exist(tree, paths, gears):
                continue
            if gears not in generic:             # (the tree does not enter them)
                generic[gears] = _generic(n, gears, rng)
                canonical[gears] = _canonical(n, gears)
            if not generic[gears]:
                continue
            found[canonical[gears]] = _brute_fractionated(n, gears)
    return found


@pytest.mark.parametrize("n, dof", [(3, 1), (4, 1), (5, 1), (4, 2), (5, 2), (5, 3)])
def test_the_atlas_is_the_brute_force(n, dof):
    brute = brute_force(n, dof)
    atlas = gear_atlas(n, dof)
    assert len(atlas) == len(brute)
    ours = {_canonical(n, e.gears): e.fractionated for e in atlas}
    assert ours == brute
    assert atlas.count_non_fractionated == sum(not f for f in brute.values())


def test_published_counts_small():
    # one freedom: 1, 2, 6 (Buchsbaum and Freudenstein 1970; Tsai 1987), 27 at six links
    # (Yang and Ding 2019, where earlier atlases give 26); two freedoms, non-fractionated:
    # none up to five links, 2 of six (Tsai and Lin 1989)
    assert [len(gear_atlas(n, 1)) for n in (3, 4, 5, 6)] == [1, 2, 6, 27]
    assert [gear_atlas(n, 2).count_non_fractionated for n in (4, 5, 6)] == [0, 0, 2]


@pytest.mark.slow
def test_published_counts_seven_links():
    # Yang and Ding 2019: 152 rotation graphs of 7 links, one freedom
    seven = gear_atlas(7, 1)
    assert len(seven) == 152 and seven.count_non_fractionated == 152


def test_every_entry_keeps_the_rules_and_one_dof_never_fractionates():
    for n, dof in [(4, 1), (5, 1), (6, 1), (5, 2), (6, 2), (6, 3)]:
        atlas = gear_atlas(n, dof)
        for e in atlas:
            assert train_verdict(n, e.turning, e.gears, dof=dof) is None
            assert len(e.turning) == n - 1 and len(e.gears) == n - 1 - dof
            assert len(e.levels) == n - 1
            assert e.fractionated == fractionated(n, e.gears)
            assert 1 <= e.inversions <= n and e.arrangements >= 1
            if dof == 1:
                assert not e.fractionated
        assert len({e.key for e in atlas}) == len(atlas)


def test_the_key_ignores_numbering_and_tells_trains_apart():
    rng = random.Random(3)
    atlas = gear_atlas(6, 1)
    keys = [train_key(6, (), e.gears)[0] for e in atlas]
    assert len(set(keys)) == len(keys)
    for e, key in zip(atlas, keys):
        for _ in range(5):
            p = list(range(6))
            rng.shuffle(p)
            moved = [(p[a], p[b], p[c]) for a, b, c in e.gears]
            assert train_key(6, (), moved)[0] == key
            moved_tree = [(p[a], p[b]) for a, b in e.turning]
            assert train_verdict(6, moved_tree, moved, dof=1) is None


def test_rules_refuse_what_they_should():
    star = [(0, 1), (0, 2), (0, 3)]
    assert train_verdict(4, star, [(1, 2, 0), (2, 3, 0)], dof=1) is None
    assert "tree" in train_verdict(4, star[:2], [(1, 2, 0)])
    assert "same two links" in train_verdict(4, star, [(1, 2, 0), (2, 1, 0)])
    assert "path" in train_verdict(4, star, [(1, 2, 3), (2, 3, 0)])
    # three gears all in mesh on one carrier: bound together (rigid)
    assert "rigid" in train_verdict(4, star, [(1, 2, 0), (2, 3, 0), (1, 3, 0)])
    # a link that neither meshes nor carries: a freedom of its own
    assert "neither" in train_verdict(5, star + [(0, 4)], [(1, 2, 0), (2, 3, 0)])
    # a gear pair whose carrier holds one of the gears coaxially with the other
    path = [(0, 1), (1, 2), (2, 3)]
    assert "axes" in train_verdict(4, path, [(0, 2, 1), (0, 3, 1), (1, 3, 2)])
    with pytest.raises(ValueError):
        train_levels(4, path, [(0, 2, 1), (0, 3, 1), (1, 3, 2)])


@pytest.mark.parametrize("links, dof", [(2, 1), (3, 2), (9, 1), (5, 0)])
def test_sizes_without_trains_are_refused(links, dof):
    with pytest.raises(AtlasSizeError):
        gear_atlas(links, dof)


@pytest.mark.parametrize("name, dof", [("simple", 1), ("compound", 1), ("reverted", 1),
                                       pytest.param("differential", 2,
                                                    marks=pytest.mark.slow)])
def test_the_textbooks_trains_are_in_the_atlas(name, dof):
    links, turning, gears = chain_graph(load(catalog_path(f"{name}-gear-train")))
    n = len(links)
    assert train_verdict(n, turning, gears, dof=dof) is None
    key = train_key(n, (), gears)[0]
    assert key in {train_key(n, (), e.gears)[0] for e in gear_atlas(n, dof)}


def test_the_housed_epicyclic_train_has_an_idle_housing():
    # sun, planet, annulus and arm turn in a housing that neither meshes nor carries a
    # gear pair: as a train of its own, the housing is a freedom of its own (module text)
    links, turning, gears = chain_graph(load(catalog_path("epicyclic-gear-train")))
    assert "neither meshes nor carries" in train_verdict(len(links), turning, gears)


def test_the_atlas_is_the_same_whatever_order_its_pieces_finish_in():
    """The search split by tree, its pieces finishing last first (as workers may),
    gives the atlas of the serial run: the same trains, in the same order, with the
    same arrangements and inversions."""
    calls = []

    def backwards(fn, tasks, on_result):
        calls.append(len(tasks))
        for i in reversed(range(len(tasks))):
            on_result(i, fn(tasks[i]))
    for links, dof in ((6, 1), (6, 2)):
        assert gear_atlas(links, dof, runner=backwards) == gear_atlas(links, dof)
    assert calls == [6, 6]                      # one task per tree of six vertices
