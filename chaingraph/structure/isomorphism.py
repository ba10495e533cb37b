"""Exact isomorphism of chains: canonical forms, automorphisms and orbits.

Two chains are the same by structure when a bijection of their link-joint graphs maps
links to links, joints to joints of the same kind, and keeps which link of each P joint
carries the guide. (``oriented=False`` forgets that last part: a sliding pair's relative
motion is the same whichever link carries the guide.)

Method: individualization and refinement, as nauty does. Colour refinement splits the
nodes by kind and then by the colours of their neighbours until nothing changes; when
cells of equal colour remain, one node of a cell is individualized and the search
branches over the cell's nodes. Each leaf (every node alone in its cell) is an ordering
of the nodes; its certificate is the sorted edge list in that ordering, and the least
certificate is the canonical form. Two leaves with equal certificates give an
automorphism; automorphisms found so far prune branches that are images of ones
already searched (orbit pruning at every node, and a jump back when a leaf repeats the
first one). The automorphisms found generate the whole group, so link orbits, and
orbits of (fixed, input) pairs, come from them by union-find. Invariants alone never
decide: the canonical form is a complete invariant.
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass
from functools import lru_cache
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from chaingraph._util.disjoint import DisjointSets
from chaingraph.errors import ChainStructureError
from chaingraph.model.chain import Chain

__all__ = ["Canon", "canonical", "canonical_form", "is_isomorphic", "isomorphism",
           "automorphism_orbits", "automorphism_generators", "pair_orbits",
           "link_joint_orbits"]

#: a node of the link-joint graph: ("link", name) or ("joint", id)
_Node = tuple[str, str]
#: a search's certificate: the sorted (position, position, edge label) list
_Certificate = tuple[tuple[int, int, int], ...]
#: the nodes' labels, each ("link",) or ("joint", kind); their adjacency lists
_Labels = list[tuple[str, ...]]
_Adjacency = Sequence[Sequence[tuple[int, int]]]

_EDGE = {"pin": 0, "guide": 1, "block": 2}


@dataclass(frozen=True)
class Canon:
    """The result of canonical labelling.

    Attributes
    ----------
    form : tuple
        Hashable; equal for two chains exactly when they are isomorphic.
    order : tuple
        The link-joint graph's nodes in canonical order (position i of one chain
        corresponds to position i of any isomorphic chain).
    generators : tuple of dict
        Automorphisms (node to node) that generate the automorphism group.
    group_size : int
        Order of the automorphism group.
    """

    form: tuple[tuple[tuple[str, ...], ...], tuple[tuple[int, int, int], ...]]
    order: tuple[tuple[str, str], ...]
    generators: tuple[dict[tuple[str, str], tuple[str, str]], ...]
    group_size: int


def _structure(chain: Chain, oriented: bool) -> tuple[list[_Node], _Labels, _Adjacency]:
    nodes = list(chain.graph.nodes)
    index = {n: i for i, n in enumerate(nodes)}
    labels: _Labels = []
    for n in nodes:
        data = chain.graph.nodes[n]
        labels.append(("link",) if n[0] == "link" else ("joint", data["kind"]))
    adj: list[list[tuple[int, int]]] = [[] for _ in nodes]
    for u, v, data in chain.graph.edges(data=True):
        e = _EDGE[data["role"]] if oriented else min(_EDGE[data["role"]], 1)
        adj[index[u]].append((index[v], e))
        adj[index[v]].append((index[u], e))
    return nodes, labels, adj


def _refine(colors: list[int], adj: _Adjacency) -> list[int]:
    """Colour refinement to the coarsest equitable partition finer than ``colors``."""
    n_colors = len(set(colors))
    while True:
        sig = [(colors[v], tuple(sorted((e, colors[u]) for u, e in adj[v])))
               for v in range(len(colors))]
        ranks = {s: i for i, s in enumerate(sorted(set(sig)))}
        new = [ranks[s] for s in sig]
        if len(ranks) == n_colors:
            return new
        colors, n_colors = new, len(ranks)


def _individualize(colors: list[int], v: int) -> list[int]:
    keyed = [(c, 0 if u == v else 1) for u, c in enumerate(colors)]
    ranks = {k: i for i, k in enumerate(sorted(set(keyed)))}
    return [ranks[k] for k in keyed]


def orbits_of(generators: Iterable[Sequence[int]], n: int,
              fixing: Iterable[int] = ()) -> list[int]:
    """Each of the ``n`` nodes' orbit (a representative) under the permutations of
    ``generators`` that fix every node of ``fixing``."""
    blocks = DisjointSets(n)
    for g in generators:
        if all(g[p] == p for p in fixing):
            for x in range(n):
                blocks.join(x, g[x])
    return [blocks.find(x) for x in range(n)]


def refine_search(labels: Sequence[Any], adj: _Adjacency,
                  ) -> tuple[_Certificate, list[int], list[list[int]], int]:
    """Canonical labelling by individualization and refinement: the least
    certificate, the nodes in canonical order, generators of the automorphisms (as
    permutations of node indices) and the group's order."""
    n = len(labels)
    label_rank = {lab: i for i, lab in enumerate(sorted(set(labels)))}
    root = _refine([label_rank[lab] for lab in labels], adj)
    state: dict[str, Any] = {"first": None, "best": None}
    generators: list[list[int]] = []
    first_path: list[int] = []

    def certificate(colors: list[int]) -> _Certificate:
        edges = sorted((min(colors[v], colors[u]), max(colors[v], colors[u]), e)
                       for v in range(n) for u, e in adj[v] if v < u)
        return tuple(edges)

    def leaf(colors: list[int], path: list[int]) -> int | None:
        cert = certificate(colors)
        perm = colors  # node -> position
        if state["first"] is None:
            state["first"] = (cert, perm)
            state["best"] = (cert, perm)
            first_path.extend(path)
            return None
        for key in ("first", "best"):
            ref_cert, ref_perm = state[key]
            if cert == ref_cert:
                inverse = [0] * n
                for node, pos in enumerate(ref_perm):
                    inverse[pos] = node
                generators.append([inverse[perm[x]] for x in range(n)])
                if key == "first":
                    k = 0
                    while k < len(path) and k < len(first_path) and path[k] == first_path[k]:
                        k += 1
                    return k
                return None
        if cert < state["best"][0]:
            state["best"] = (cert, perm)
        return None

    def dfs(colors: list[int], path: list[int]) -> int | None:
        cells: dict[int, list[int]] = {}
        for v, c in enumerate(colors):
            cells.setdefault(c, []).append(v)
        if len(cells) == n:
            return leaf(colors, path)
        target = min((len(vs), c) for c, vs in cells.items() if len(vs) > 1)[1]
        explored: list[int] = []
        for v in cells[target]:
            if explored:
                orbit = orbits_of(generators, n, fixing=path)
                if any(orbit[v] == orbit[w] for w in explored):
                    continue
            explored.append(v)
            jump = dfs(_refine(_individualize(colors, v), adj), path + [v])
            if jump is not None and jump < len(path):
                return jump
        return None

    dfs(root, [])
    # group order from the stabilizer chain along the first path
    size = 1
    for depth in range(len(first_path)):
        orbit = orbits_of(generators, n, fixing=first_path[:depth])
        size *= sum(1 for x in range(n) if orbit[x] == orbit[first_path[depth]])
    best_cert, best_perm = state["best"]
    order = [0] * n
    for node, pos in enumerate(best_perm):
        order[pos] = node
    return best_cert, order, generators, size


def canonical(chain: Chain, *, oriented: bool = True) -> Canon:
    """Canonical labelling of a chain's link-joint graph; see :class:`Canon`.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> canonical(chaingraph.load(catalog_path("four-bar-chain"))).group_size
    8
    """
    if len(chain.links) > MAX_LINKS:
        raise ChainStructureError(
            f"canonical labelling (for isomorphism, inversions and identify) takes chains of "
            f"at most {MAX_LINKS:,} links, which it labels in seconds; this one has "
            f"{len(chain.links):,}", chain=chain.name)
    return canonical_cached(chain, oriented)


#: the most links a chain may have for canonical labelling: polynomial in practice,
#: seconds up to here, but very symmetric graphs of many thousands take minutes
MAX_LINKS = 2000


#: link-joint graphs of more nodes than this are labelled by nauty (the search here is
#: exact at any size, but nauty's is much faster on large, very symmetric graphs);
#: isomorphic chains have as many nodes, so they are always labelled the same way
NAUTY_FROM = 160


def _search_nauty(labels: Sequence[Any], adj: _Adjacency,
                  ) -> tuple[_Certificate, list[int], list[list[int]], int]:
    """:func:`refine_search` by nauty. Edges of the most common label join their ends
    directly; an edge of another label becomes a node of its own colour between its
    ends. The colour classes are ordered by label, the graph's nodes first, so the
    canonical order of the nodes is the first ``n`` of nauty's; the certificate is the
    sorted labelled edge list in that order, as :func:`refine_search` makes it."""
    import pynauty
    n = len(labels)
    kinds = sorted(set(labels))
    edges = [(v, u, e) for v in range(n) for u, e in adj[v] if v < u]
    counts: dict[int, int] = {}
    for _, _, e in edges:
        counts[e] = counts.get(e, 0) + 1
    common = max(sorted(counts), key=counts.__getitem__) if counts else 0
    others = [(v, u, e) for v, u, e in edges if e != common]
    adjacency: dict[int, list[int]] = {v: [] for v in range(n + len(others))}
    for v, u, e in edges:
        if e == common:
            adjacency[v].append(u)
    for i, (v, u, _) in enumerate(others):
        adjacency[n + i] = [v, u]
    colouring = [{v for v in range(n) if labels[v] == k} for k in kinds]
    colouring += [{n + i for i, (_, _, e) in enumerate(others) if e == k}
                  for k in sorted({e for _, _, e in others})]
    g = pynauty.Graph(n + len(others), adjacency_dict=adjacency, vertex_coloring=colouring)
    order = list(pynauty.canon_label(g)[:n])
    generators, size1, size2, _, _ = pynauty.autgrp(g)
    size = int(round(size1 * 1e6)) * 10 ** size2 // 10 ** 6
    position = [0] * n
    for i, v in enumerate(order):
        position[v] = i
    cert = tuple(sorted((min(position[v], position[u]), max(position[v], position[u]), e)
                        for v, u, e in edges))
    return cert, order, [list(p[:n]) for p in generators], size


@lru_cache(maxsize=4096)
def canonical_cached(chain: Chain, oriented: bool) -> Canon:
    """:func:`canonical` without the size check, cached by chain."""
    nodes, labels, adj = _structure(chain, oriented)
    search = refine_search
    if len(nodes) > NAUTY_FROM:
        if importlib.util.find_spec("pynauty") is not None:     # a dependency
            search = _search_nauty
    cert, order, gens, size = search(labels, adj)
    form = (tuple(labels[v] for v in order), cert)
    generators = tuple({nodes[x]: nodes[g[x]] for x in range(len(nodes))} for g in gens)
    return Canon(form=form, order=tuple(nodes[v] for v in order), generators=generators,
                 group_size=size)


def canonical_form(chain: Chain, *, oriented: bool = True,
                   ) -> tuple[tuple[tuple[str, ...], ...], tuple[tuple[int, int, int], ...]]:
    """A hashable form, equal for two chains exactly when they are isomorphic.

    Link and joint names, the order of the joints and the drawn pose play no part;
    joint kinds, and (with ``oriented``) which link carries each P joint's guide, do.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> watt = chaingraph.load(catalog_path("watt-six-bar-chain"))
    >>> steph = chaingraph.load(catalog_path("stephenson-six-bar-chain"))
    >>> canonical_form(watt) == canonical_form(steph)
    False
    >>> renamed = watt.relabelled(links={"t1": "ternary link", "b1": "binary link"})
    >>> canonical_form(watt) == canonical_form(renamed)
    True
    """
    return canonical(chain, oriented=oriented).form


def is_isomorphic(a: Chain, b: Chain, *, oriented: bool = True) -> bool:
    """True when chains ``a`` and ``b`` are the same by structure.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> four = chaingraph.load(catalog_path("four-bar-chain"))
    >>> slider = chaingraph.load(catalog_path("single-slider-crank-chain"))
    >>> is_isomorphic(four, slider), is_isomorphic(four, four.relabelled(links={"crank": "x"}))
    (False, True)
    """
    return canonical_form(a, oriented=oriented) == canonical_form(b, oriented=oriented)


def isomorphism(a: Chain, b: Chain, *, oriented: bool = True) -> dict[str, str] | None:
    """A mapping of ``a``'s links to ``b``'s links that is an isomorphism, or None."""
    ca, cb = canonical(a, oriented=oriented), canonical(b, oriented=oriented)
    if ca.form != cb.form:
        return None
    return {x[1]: y[1] for x, y in zip(ca.order, cb.order) if x[0] == "link"}


def automorphism_generators(chain: Chain, *, oriented: bool = True,
                            ) -> tuple[dict[tuple[str, str], tuple[str, str]], ...]:
    """Generators of the automorphism group, each a dict of link-joint graph nodes."""
    return canonical(chain, oriented=oriented).generators


def automorphism_orbits(chain: Chain, *, oriented: bool = True) -> list[tuple[str, ...]]:
    """The orbits of links under the chain's automorphisms.

    Links in one orbit give the same inversion by structure. Orbits are listed in the
    order of their first link in ``chain.links``, links within in chain order.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> automorphism_orbits(chaingraph.load(catalog_path("watt-six-bar-chain")))
    [('t1', 't2'), ('b1', 'b2', 'b3', 'b4')]
    """
    gens = automorphism_generators(chain, oriented=oriented)
    links = chain.links
    return _group([("link", x) for x in links], gens, key=lambda n: n[1])


def pair_orbits(chain: Chain, pairs: Iterable[tuple[str, str]], *, oriented: bool = True) -> list[tuple[tuple[str, str], ...]]:
    """Orbits of ordered link pairs (for example (fixed, input)) under the automorphisms."""
    gens = automorphism_generators(chain, oriented=oriented)
    items = [(("link", a), ("link", b)) for a, b in pairs]
    return _group(items, gens, key=lambda p: (p[0][1], p[1][1]),
                  act=lambda g, p: (g[p[0]], g[p[1]]))


def link_joint_orbits(chain: Chain, *, oriented: bool = True
                      ) -> list[tuple[tuple[str, str], ...]]:
    """Orbits of (link, joint) pairs under the automorphisms: every pair, so that the
    orbits are the whole group's (a pair's orbit under the automorphisms that keep its
    link is the members of its orbit with that link)."""
    gens = automorphism_generators(chain, oriented=oriented)
    items = [(("link", x), ("joint", j.id)) for x in chain.links for j in chain.joints]
    return _group(items, gens, key=lambda p: (p[0][1], p[1][1]),
                  act=lambda g, p: (g[p[0]], g[p[1]]))


def _group(items: Sequence[Any], generators: Iterable[dict[_Node, _Node]], *,
           key: Callable[[Any], Any],
           act: Callable[[dict[_Node, _Node], Any], Any] | None = None) -> list[tuple[Any, ...]]:
    act = act or (lambda g, x: g[x])
    index = {x: i for i, x in enumerate(items)}
    blocks = DisjointSets(len(items))
    for g in generators:
        for x, i in index.items():
            j = index.get(act(g, x))
            if j is not None:
                blocks.join(i, j)
    groups: dict[int, list[Any]] = {}
    for x, i in index.items():
        groups.setdefault(blocks.find(i), []).append(key(x))
    return [tuple(g) for _, g in sorted(groups.items())]
