"""The atlas of epicyclic gear trains: every train of N links and F degrees of freedom as
Buchsbaum and Freudenstein's graph, once up to isomorphism.

A gear train's graph has the links as vertices and two kinds of edge: the turning pairs
(a link journalled on another) and the gear pairs, each labelled with its *transfer
vertex*, the carrier that holds both gears' axes. The rules (Buchsbaum and Freudenstein
1970; Tsai 1987; Tsai, *Mechanism Design*, 2001, ch. 7):

* the turning pairs form a spanning tree: J_t = N - 1 (a link turns on one other);
* with every pair of turning one freedom and every gear pair taking one (the rotations
  alone: F = (N - 1) - J_g), there are J_g = N - 1 - F gear pairs, so each closes one
  fundamental circuit with the tree, and two gear pairs never join the same two links;
* every fundamental circuit has exactly one transfer vertex: the carrier c of the gear
  pair (a, b) is an inner vertex of the tree's path from a to b, the turning pairs from
  a to c all about one axis (a's axis on the carrier) and those from c to b about another
  (b's): the pairs' axes (*levels*) must be assignable so, for every circuit at once;
* no degenerate train: with the gear ratios generic, the Willis equation of every pair,
  ``(w_a - w_c) + k (w_b - w_c) = 0``, is independent of the others (else a sub-train is
  overconstrained and the train has fewer freedoms than counted), no two links are bound
  to turn together (a rigid sub-train, one link in effect), and every link meshes in a
  gear pair or carries one (a link in no equation turns freely, a freedom of its own).

A train is *fractionated* when one link splits its gear pairs' equations in two (two
trains joined at that link: Tsai and Lin's count leaves them out); a train of one
freedom never is. Two trains are the same when a renumbering of the links maps their
gear pairs, with their carriers, onto each other: the *rotation graph* of the literature
(the "r-graphs" of Yang and Ding), which fixes every ratio of speeds. The trees of
turning pairs that carry one rotation graph (which link is journalled on which: coaxial
links allow several) are its *arrangements*, counted up to isomorphism of the whole
graph. The keys are nauty's certificates of the graphs with each edge subdivided by a
node of its kind, a gear pair's node tied to its carrier through a node of a third
kind.

Method: for each tree on N vertices (up to isomorphism), the gear pairs are chosen one
at a time among the (a, b, c) the tree allows, in increasing order, each kept only
while the levels stay assignable (union-find: equal along each side, different across
the carrier), the equations independent and no two links bound together (exact
elimination modulo the prime 2^61 - 1 with random ratios: rank and rigidity are then
the generic ones but for a chance of the links' number over 2^61 at each test, by
Schwartz and Zippel); the complete sets are keyed by their rotation graph and kept
once. ``tests/structure/test_gear_atlas.py`` checks it against a brute force over every
labelled graph to five links (isomorphism by every permutation of the links) and the
published counts.
"""

from __future__ import annotations

import random
from collections.abc import Hashable, Iterator, Sequence
from dataclasses import dataclass
from fractions import Fraction
from typing import Any

import networkx as nx

from chaingraph._util.disjoint import DisjointSets
from chaingraph._util.parallel import Runner, serial
from chaingraph.errors import AtlasSizeError
from chaingraph.model.chain import Chain

__all__ = ["GearEntry", "GearAtlas", "gear_atlas", "gear_trains", "train_key",
           "train_levels", "train_verdict", "gear_atlas_dict", "MAX_GEAR_LINKS",
           "chain_graph", "fractionated", "check_gear_size", "rotation_key",
           "gear_axes", "drivers"]

#: the largest train enumerated (8 links take minutes here; 9, hours)
MAX_GEAR_LINKS = 8

_PRIME = (1 << 61) - 1

Gear = tuple[int, int, int]                      # (gear a, gear b, carrier c), a < b


@dataclass(frozen=True)
class GearEntry:
    """One gear train of the atlas: ``gears`` its gear pairs ``(a, b, carrier)`` (links
    numbered from 0 in canonical order; ``a < b``) and ``turning`` the turning pairs of
    its simplest arrangement (a tree); ``key`` the gear pairs as text, equal for two
    trains exactly when they are isomorphic; ``inversions`` the orbits of the links
    under the train's automorphisms (the distinct choices of the fixed link);
    ``fractionated`` whether one link joins two trains; ``arrangements`` how many
    trees of turning pairs (up to isomorphism) carry these gear pairs."""

    id: int
    links: int
    turning: tuple[tuple[int, int], ...]
    gears: tuple[Gear, ...]
    key: str
    inversions: int
    fractionated: bool
    arrangements: int = 1

    @property
    def levels(self) -> tuple[int, ...]:
        """The axis (level) of each turning pair, 0, 1, ...: pairs share one where a
        circuit makes them coaxial (the finest assignment the rules allow)."""
        return train_levels(self.links, self.turning, self.gears)

    def to_dict(self) -> dict[str, Any]:
        """The train's record in ``atlas --gears --json`` (links numbered from 0)."""
        return {"id": self.id, "turning": [list(t) for t in self.turning],
                "gears": [list(g) for g in self.gears], "levels": list(self.levels),
                "inversions": self.inversions, "fractionated": self.fractionated,
                "arrangements": self.arrangements, "key": self.key}


@dataclass(frozen=True)
class GearAtlas:
    """The gear trains of ``links`` links and ``dof`` degrees of freedom."""

    links: int
    dof: int
    entries: tuple[GearEntry, ...]

    def __len__(self) -> int:
        return len(self.entries)

    def __iter__(self) -> Iterator[GearEntry]:
        return iter(self.entries)

    def __getitem__(self, i: int) -> GearEntry:
        return self.entries[i]

    @property
    def count_non_fractionated(self) -> int:
        """The trains no link separates (the count of Tsai and Lin for F > 1)."""
        return sum(not e.fractionated for e in self.entries)

    @property
    def arrangements(self) -> int:
        """The trees of turning pairs over every train (graphs with their turning
        pairs, up to isomorphism)."""
        return sum(e.arrangements for e in self.entries)


def check_gear_size(links: int, dof: int) -> int:
    """The number of gear pairs of a train of ``links`` links and ``dof`` freedoms;
    :class:`~chaingraph.errors.AtlasSizeError` for a size with no train or too large."""
    if dof < 1:
        raise AtlasSizeError(f"'dof' must be 1 or more for a gear train, got {dof}",
                             links=links, dof=dof, parameter="dof")
    if links < dof + 2:
        raise AtlasSizeError(f"a gear train of {dof} degree(s) of freedom has at least "
                             f"{dof + 2} links (one gear pair), got links = {links}",
                             links=links, dof=dof, parameter="links")
    if links > MAX_GEAR_LINKS:
        raise AtlasSizeError(f"'links' is at most {MAX_GEAR_LINKS} for gear trains here "
                             f"(8 links of one freedom take about two minutes), got "
                             f"{links}", links=links, dof=dof, parameter="links")
    return links - 1 - dof


def _paths(tree: nx.Graph) -> dict[tuple[int, int], list[int]]:
    return {(a, b): path for a, rest in nx.all_pairs_shortest_path(tree)
            for b, path in rest.items() if a < b}


def train_levels(links: int, turning: Sequence[tuple[int, int]],
                 gears: Sequence[Gear]) -> tuple[int, ...]:
    """The finest assignment of axes (levels) to the turning pairs that the gear pairs
    allow, numbered 0, 1, ... in the order of ``turning``; ValueError when none does.

    Examples
    --------
    >>> train_levels(4, [(0, 1), (0, 2), (0, 3)], [(1, 2, 0), (2, 3, 0)])
    (0, 1, 2)
    >>> train_levels(4, [(0, 1), (1, 2), (2, 3)], [(0, 3, 1), (0, 2, 1)])
    (0, 1, 1)
    """
    index = {frozenset(t): i for i, t in enumerate(turning)}
    tree = nx.Graph(list(turning))
    tree.add_nodes_from(range(links))
    paths = _paths(tree)
    gears = [(min(a, b), max(a, b), c) for a, b, c in gears]
    if any(c not in paths[(a, b)][1:-1] for a, b, c in gears):
        raise ValueError("a carrier is not on the turning pairs' path between its gears")
    blocks = _level_blocks(len(turning), index, paths, gears)
    if blocks is None:
        raise ValueError("no assignment of axes makes every gear pair's carrier hold both "
                         "its gears")
    names: dict[int, int] = {}
    return tuple(names.setdefault(blocks.find(i), len(names)) for i in range(len(turning)))


def _sides(gear: Gear, index: dict[frozenset[int], int],
           paths: dict[tuple[int, int], list[int]]) -> tuple[list[int], list[int]]:
    """The turning pairs of a gear pair's circuit from a to the carrier, and from the
    carrier to b (indices into the tree's pairs)."""
    a, b, c = gear
    path = paths[(a, b)]
    k = path.index(c)
    edges = [index[frozenset(p)] for p in zip(path, path[1:])]
    return edges[:k], edges[k:]


def _level_blocks(edges: int, index: dict[frozenset[int], int],
                  paths: dict[tuple[int, int], list[int]], gears: Sequence[Gear],
                  ) -> DisjointSets | None:
    """The turning pairs joined into axes as the gear pairs' circuits ask, or None when
    some circuit's two sides would be on one axis (or a side is empty)."""
    return _axes(edges, [_sides(g, index, paths) for g in gears])


def _axes(edges: int, sides: Sequence[tuple[list[int], list[int]]]) -> DisjointSets | None:
    blocks = DisjointSets(edges)
    for left, right in sides:
        if not left or not right:
            return None
        for side in (left, right):
            for e in side[1:]:
                blocks.join(side[0], e)
    if any(blocks.find(left[0]) == blocks.find(right[0]) for left, right in sides):
        return None
    return blocks


class _Equations:
    """The Willis equations of chosen gear pairs, row-reduced modulo a prime with
    random generic ratios: the rank, and whether two links are bound together."""

    def __init__(self, links: int, ratios: dict[tuple[int, int], int]) -> None:
        self.links, self.ratios = links, ratios
        self.rows: list[tuple[int, list[int]]] = []         # (pivot, row), pivot 1

    def reduce(self, v: list[int]) -> list[int]:
        v = list(v)
        for pivot, row in self.rows:
            f = v[pivot]
            if f:
                v = [(x - f * y) % _PRIME for x, y in zip(v, row)]
        return v

    def with_gear(self, gear: Gear) -> _Equations | None:
        """These equations and the gear pair's, or None when it depends on them."""
        a, b, c = gear
        k = self.ratios[(a, b)]
        v = [0] * self.links
        v[a], v[b], v[c] = 1, k, (-1 - k) % _PRIME
        return self.with_row(v)

    def with_row(self, v: list[int]) -> _Equations | None:
        """These equations and ``v`` (its coefficients on the links' speeds), or None
        when it depends on them."""
        v = self.reduce(v)
        pivot = next((i for i, x in enumerate(v) if x), None)
        if pivot is None:
            return None
        inverse = pow(v[pivot], _PRIME - 2, _PRIME)
        v = [x * inverse % _PRIME for x in v]
        rows = [(p, [(x - r[pivot] * y) % _PRIME for x, y in zip(r, v)]) if r[pivot]
                else (p, r) for p, r in self.rows]
        out = _Equations(self.links, self.ratios)
        out.rows = rows + [(pivot, v)]
        return out

    def bound(self) -> bool:
        """Whether two links are bound to turn together (a rigid sub-train): the rows
        are reduced, so each link's speed is a form in the free links' speeds (its own,
        or minus its row's entries), and two links are bound when their forms agree."""
        pivots = dict(self.rows)
        free = [x for x in range(self.links) if x not in pivots]
        seen = set()
        for x in range(self.links):
            form = (tuple(-pivots[x][f] % _PRIME for f in free) if x in pivots
                    else tuple(int(f == x) for f in free))
            if form in seen:
                return True
            seen.add(form)
        return False


def _trains_on(tree: nx.Graph, links: int, gears: int, rng: random.Random,
               ) -> Iterator[tuple[Gear, ...]]:
    """Every admissible set of ``gears`` gear pairs on ``tree`` (labelled: the tree's
    automorphisms give each train several times)."""
    turning = sorted(tuple(sorted(e)) for e in tree.edges)
    index = {frozenset(t): i for i, t in enumerate(turning)}
    paths = _paths(tree)
    candidates = [(a, b, c) for (a, b), path in sorted(paths.items()) if len(path) > 2
                  for c in path[1:-1]]
    ratios = {(a, b): rng.randrange(2, _PRIME - 1) for a, b, _ in candidates}
    sides = [_sides(g, index, paths) for g in candidates]

    def grow(start: int, chosen: list[Gear], equations: _Equations,
             pairs: set[tuple[int, int]], circuits: list[tuple[list[int], list[int]]],
             ) -> Iterator[tuple[Gear, ...]]:
        if len(chosen) == gears:
            if {x for g in chosen for x in g} == set(range(links)):
                yield tuple(chosen)
            return
        for i in range(start, len(candidates)):
            if len(candidates) - i < gears - len(chosen):
                return
            g = candidates[i]
            if g[:2] in pairs:
                continue
            if _axes(len(turning), circuits + [sides[i]]) is None:
                continue
            more = equations.with_gear(g)
            if more is None or more.bound():
                continue
            yield from grow(i + 1, chosen + [g], more, pairs | {g[:2]},
                            circuits + [sides[i]])

    yield from grow(0, [], _Equations(links, ratios), set(), [])


def _coloured(links: int, turning: Sequence[tuple[int, int]], gears: Sequence[Gear],
              ) -> tuple[dict[int, list[int]], list[set[int]]]:
    """The train as a simple coloured graph: links, a node per turning pair on its two
    links, a node per gear pair on its two gears, and a node joining each gear pair's
    node to its carrier."""
    adjacency: dict[int, list[int]] = {v: [] for v in range(links)}
    t0 = links
    g0 = t0 + len(turning)
    m0 = g0 + len(gears)
    for i, (a, b) in enumerate(turning):
        adjacency[t0 + i] = [a, b]
    for i, (a, b, c) in enumerate(gears):
        adjacency[g0 + i] = [a, b]
        adjacency[m0 + i] = [g0 + i, c]
    colours = [set(range(links)), set(range(t0, g0)), set(range(g0, m0)),
               set(range(m0, m0 + len(gears)))]
    return adjacency, colours


def train_key(links: int, turning: Sequence[tuple[int, int]], gears: Sequence[Gear],
              ) -> tuple[Hashable, list[int], int]:
    """nauty's certificate of a train's graph (equal exactly for isomorphic trains), its
    links in canonical order, and the number of orbits of the links under its
    automorphisms."""
    import pynauty

    adjacency, colours = _coloured(links, turning, gears)
    g = pynauty.Graph(sum(len(c) for c in colours), adjacency_dict=adjacency,
                      vertex_coloring=colours)
    order = [v for v in pynauty.canon_label(g) if v < links]
    orbits = len(set(pynauty.autgrp(g)[3][:links]))
    return pynauty.certificate(g), order, orbits


def _text_key(gears: Sequence[Gear]) -> str:
    """The canonical gear pairs as text: ``a-b/c`` each, links from 1."""
    return " ".join(f"{a + 1}-{b + 1}/{c + 1}" for a, b, c in gears)


def fractionated(links: int, gears: Sequence[Gear]) -> bool:
    """Whether one link splits the gear pairs' equations into two sets that share no
    other link (two trains joined at that link; Tsai and Lin's fractionated train).

    Examples
    --------
    >>> fractionated(5, [(0, 3, 4), (1, 2, 4)]), fractionated(4, [(0, 1, 3), (0, 2, 3)])
    (True, False)
    """
    incidence = nx.Graph((("pair", i), x) for i, g in enumerate(gears) for x in g)
    incidence.add_nodes_from(range(links))
    return any(not isinstance(x, tuple) for x in nx.articulation_points(incidence))


def gear_trains(links: int, dof: int = 1, *, seed: int = 39) -> Iterator[
        tuple[tuple[tuple[int, int], ...], tuple[Gear, ...]]]:
    """Every admissible labelled train on each tree of ``links`` vertices (the trees up
    to isomorphism), as (turning pairs, gear pairs): the same train several times over;
    :func:`gear_atlas` keeps each once. Each tree draws its random ratios from its own
    stream (``seed`` and the tree's place), so a tree's trains do not depend on which
    trees were searched before it (the atlas is split by tree over workers)."""
    gears = check_gear_size(links, dof)
    for i, tree in enumerate(nx.nonisomorphic_trees(links)):
        turning = tuple(sorted(tuple(sorted(e)) for e in tree.edges))
        for chosen in _tree_trains(tree, links, gears, i, seed):
            yield turning, chosen


def _tree_trains(tree: nx.Graph, links: int, gears: int, index: int, seed: int
                 ) -> Iterator[tuple[Gear, ...]]:
    """The admissible trains on the ``index``-th tree, its random ratios drawn from its
    own stream (``seed`` and the tree's place)."""
    return _trains_on(tree, links, gears, random.Random(f"{seed}-{index}"))


def _tree_task(task: tuple[int, int, int, tuple[tuple[int, int], ...], int],
               ) -> dict[Hashable, dict[str, Any]]:
    """One piece of the atlas: the trains on one tree (``(links, dof, index, tree's
    edges, seed)``), each once by its rotation graph's key, with its canonical gear
    pairs, its links' orbits, the canonical trees that carry it and the keys of those
    arrangements."""
    links, dof, index, edges, seed = task
    tree = nx.Graph(list(edges))
    tree.add_nodes_from(range(links))
    found: dict[Hashable, dict[str, Any]] = {}
    for chosen in _tree_trains(tree, links, check_gear_size(links, dof), index, seed):
        cert, order, orbits = train_key(links, (), chosen)
        at = {v: i for i, v in enumerate(order)}
        item = found.setdefault(cert, {"gears": tuple(sorted(
            (*sorted((at[a], at[b])), at[c]) for a, b, c in chosen)), "orbits": orbits,
            "trees": set(), "layouts": set()})
        item["trees"].add(tuple(sorted(tuple(sorted((at[a], at[b]))) for a, b in edges)))
        item["layouts"].add(train_key(links, edges, chosen)[0])
    return found


def _simplest(links: int, trees: set[tuple[tuple[int, int], ...]],
              ) -> tuple[tuple[int, int], ...]:
    """The tree drawn for a train: the one whose busiest link holds most (links
    journalled on the carriers rather than on one another), then the least pairs."""
    def rank(t: tuple[tuple[int, int], ...]) -> Any:
        holds = sorted((sum(x in p for p in t) for x in range(links)), reverse=True)
        return ([-h for h in holds], t)
    return min(trees, key=rank)


def gear_atlas(links: int, dof: int = 1, *, runner: Runner | None = None,
               seed: int = 39) -> GearAtlas:
    """The non-isomorphic epicyclic gear trains of ``links`` links and ``dof`` degrees
    of freedom (module text), by how many carriers they have, then by their canonical
    gear pairs; each with the turning pairs of its simplest arrangement and how many
    arrangements of turning pairs (trees, up to isomorphism) it has. The search is split
    by tree of turning pairs, one task per tree run by ``runner`` (a
    :data:`~chaingraph._util.parallel.Runner`: local processes, a Dask cluster; by
    default here), the pieces merged in the trees' order: the same atlas however run.

    Examples
    --------
    >>> [len(gear_atlas(n, 1)) for n in (3, 4, 5)]
    [1, 2, 6]
    >>> [(e.gears, e.turning) for e in gear_atlas(4, 1)]  # doctest: +NORMALIZE_WHITESPACE
    [(((1, 3, 0), (2, 3, 0)), ((0, 1), (0, 2), (0, 3))),
     (((0, 2, 3), (1, 3, 2)), ((0, 3), (1, 2), (2, 3)))]
    """
    check_gear_size(links, dof)
    tasks = [(links, dof, i, tuple(sorted(tuple(sorted(e)) for e in tree.edges)), seed)
             for i, tree in enumerate(nx.nonisomorphic_trees(links))]
    parts: dict[int, dict[Hashable, dict[str, Any]]] = {}
    (runner or serial)(_tree_task, tasks, parts.__setitem__)
    found: dict[Hashable, dict[str, Any]] = {}
    for i in range(len(tasks)):                       # merged in the trees' order
        for cert, item in parts[i].items():
            have = found.setdefault(cert, {**item, "trees": set(), "layouts": set()})
            have["trees"] |= item["trees"]
            have["layouts"] |= item["layouts"]
    ordered = sorted(found.values(), key=lambda d: (len({g[2] for g in d["gears"]}),
                                                    d["gears"]))
    entries = tuple(GearEntry(i, links, _simplest(links, d["trees"]), d["gears"],
                              _text_key(d["gears"]), d["orbits"],
                              fractionated(links, d["gears"]), len(d["layouts"]))
                    for i, d in enumerate(ordered, start=1))
    return GearAtlas(links, dof, entries)


def train_verdict(links: int, turning: Sequence[tuple[int, int]], gears: Sequence[Gear],
                  *, dof: int | None = None, seed: int = 7) -> str | None:
    """Why a labelled train breaks the rules (module text), or None when it keeps them:
    each rule checked on its own, for tests and for trains read from files."""
    tree = nx.Graph(list(turning))
    tree.add_nodes_from(range(links))
    if len(turning) != links - 1 or not nx.is_tree(tree):
        return "the turning pairs are not a spanning tree"
    if dof is not None and len(gears) != links - 1 - dof:
        return f"{len(gears)} gear pairs, not links - 1 - dof = {links - 1 - dof}"
    if len({frozenset(g[:2]) for g in gears}) != len(gears):
        return "two gear pairs join the same two links"
    paths = _paths(tree)
    norm = [(min(a, b), max(a, b), c) for a, b, c in gears]
    if any(c not in paths[(a, b)][1:-1] for a, b, c in norm):
        return "a carrier is not on the tree's path between its gears"
    index = {frozenset(t): i for i, t in enumerate(turning)}
    if _level_blocks(len(turning), index, paths, norm) is None:
        return "no assignment of axes lets every carrier hold both its gears"
    if {x for g in norm for x in g} != set(range(links)):
        return "a link neither meshes nor carries a gear pair"
    rng = random.Random(seed)
    equations = _Equations(links, {g[:2]: rng.randrange(2, _PRIME - 1) for g in norm})
    for g in norm:
        more = equations.with_gear(g)
        if more is None:
            return "the gear pairs' equations depend on each other (overconstrained)"
        equations = more
    if equations.bound():
        return "two links are bound to turn together (a rigid sub-train)"
    return None


def gear_atlas_dict(atlas: GearAtlas, *, chains: bool = True,
                    no_fractionated: bool = False) -> dict[str, Any]:
    """The JSON object of ``chaingraph atlas --gears --json`` (``chains=False``:
    ``--summary``)."""
    entries = [e for e in atlas if not (no_fractionated and e.fractionated)]
    out: dict[str, Any] = {"links": atlas.links, "dof": atlas.dof,
                           "gear_pairs": atlas.links - 1 - atlas.dof,
                           "count": len(entries),
                           "count_non_fractionated": atlas.count_non_fractionated,
                           "distinct_inversions": sum(e.inversions for e in entries),
                           "arrangements": sum(e.arrangements for e in entries)}
    if chains:
        out["trains"] = [dict(e.to_dict(), id=i) for i, e in enumerate(entries, start=1)]
    return out


def gear_axes(links: int, turning: Sequence[tuple[int, int]], gears: Sequence[Gear],
              ) -> tuple[tuple[int, ...], list[tuple[int, int]]]:
    """The axes of a train: the level of each turning pair (:func:`train_levels`) and,
    for each gear pair ``(a, b, c)``, the levels of a's axis and of b's axis on the
    carrier (the turning pairs from a to c, and from c to b).

    Examples
    --------
    >>> gear_axes(4, [(0, 1), (0, 2), (0, 3)], [(1, 3, 0), (2, 3, 0)])
    ((0, 1, 2), [(0, 2), (1, 2)])
    """
    levels = train_levels(links, turning, gears)
    index = {frozenset(t): i for i, t in enumerate(turning)}
    tree = nx.Graph(list(turning))
    tree.add_nodes_from(range(links))
    paths = _paths(tree)
    out = []
    for a, b, c in gears:
        left, right = _sides((min(a, b), max(a, b), c), index, paths)
        pair = (levels[left[0]], levels[right[0]])
        out.append(pair if a < b else pair[::-1])
    return levels, out


def drivers(links: int, gears: Sequence[Gear], ratios: Sequence[Fraction], fixed: int,
            candidates: Sequence[int]) -> list[int] | None:
    """The first of ``candidates`` whose speeds, with ``fixed`` at rest, fix every
    link's speed through the gear pairs (each ``(a, b, c)`` with its ratio
    ``(w_a - w_c) / (w_b - w_c)``): one per degree of freedom; None when the gear
    pairs' equations depend on each other with these ratios, or two links turn
    together (exact modulo a prime of 61 bits)."""
    ratios_mod = {g[:2]: (-r.numerator * pow(r.denominator, _PRIME - 2, _PRIME)) % _PRIME
                  for g, r in zip(gears, ratios)}
    equations: _Equations | None = _Equations(links, ratios_mod)
    for g in gears:
        equations = equations.with_gear(g) if equations is not None else None
    if equations is None or equations.bound():
        return None

    def unit(v: int) -> list[int]:
        return [int(i == v) for i in range(links)]
    equations = equations.with_row(unit(fixed))
    chosen: list[int] = []
    for v in candidates:
        if equations is None or len(equations.rows) == links:
            break
        more = equations.with_row(unit(v))
        if more is not None:
            equations, chosen = more, chosen + [v]
    if equations is None or len(equations.rows) < links:
        return None
    return chosen


def chain_graph(chain: Chain) -> tuple[list[str], list[tuple[int, int]], list[Gear]]:
    """A chain's gear train as the graph's indices: (links, turning pairs, gear pairs
    with their carriers), a multiple joint giving a turning pair from its first link to
    each other."""
    links = list(chain.links)
    at = {x: i for i, x in enumerate(links)}
    turning = [(at[j.links[0]], at[x]) for j in chain.joints if j.kind == "R"
               for x in j.links[1:]]
    gears = [(at[g.links[0]], at[g.links[1]], at[g.carrier]) for g in chain.gears]
    return links, turning, gears


def rotation_key(links: int, gears: Sequence[Gear]) -> Hashable:
    """The key of a train's rotation graph (its gear pairs with their carriers): equal
    for two trains exactly when the atlas counts them as one."""
    return train_key(links, (), gears)[0]
