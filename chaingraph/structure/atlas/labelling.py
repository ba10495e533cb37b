"""Canonical labelling for the atlas: nauty (through ``pynauty``) when it is installed,
the project's own search (:mod:`chaingraph.structure.isomorphism`) otherwise.

Both give, for a simple graph, a canonical relabelling (isomorphic graphs get the same
edge list) and the number of orbits of its automorphism group on the nodes; for a
contracted multigraph (loops and parallel edges), a canonical key and its node
automorphism group. The two labellings differ (each is canonical on its own), so the
atlas is always made with one of them; the tests compare the graphs of one with the
other through the project's own canonical form.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable, Sequence

import numpy as np
import numpy.typing as npt

from chaingraph.structure.isomorphism import orbits_of, refine_search

try:                                          # nauty: the field's canonical labelling
    import pynauty as _nauty
    from pynauty import nautywrap as _nautywrap
except ImportError:                           # pragma: no cover - pynauty is a dependency
    _nauty = _nautywrap = None

__all__ = ["graph_form", "graph_forms", "multigraph_key", "multigraph_automorphisms",
           "link_joint_keys", "link_joint_form", "BACKENDS", "default_backend"]

BACKENDS = ("nauty", "own")


def default_backend() -> str:
    """``"nauty"`` when pynauty is importable, else ``"own"``."""
    return "nauty" if _nauty is not None else "own"


def _check(backend: str) -> None:
    if backend not in BACKENDS:
        raise ValueError(f"unknown labelling {backend!r}: one of {', '.join(BACKENDS)}")
    if backend == "nauty" and _nauty is None:
        raise ImportError("the nauty labelling needs the pynauty package")


def graph_form(n: int, edges: Iterable[tuple[int, int]], *, backend: str = "nauty",
               ) -> tuple[tuple[tuple[int, int], ...], int]:
    """Canonical edge list and link orbit count of a simple graph on ``n`` nodes.

    Returns ``(edges, orbits)``: the edges as sorted pairs ``(i, j)``, ``i < j``, in the
    canonical labels, sorted; ``orbits`` the number of node orbits of the automorphism
    group (the chain's distinct inversions).

    Examples
    --------
    >>> graph_form(4, [(0, 1), (1, 2), (2, 3), (3, 0)], backend="own")
    (((0, 1), (0, 2), (1, 3), (2, 3)), 1)
    """
    canonical, orbits = graph_forms(n, [list(edges)], backend=backend)
    return tuple(map(tuple, canonical[0].tolist())), int(orbits[0])


def graph_forms(n: int, edges: npt.ArrayLike, *, backend: str = "nauty",
                ) -> tuple[npt.NDArray[np.uint8], npt.NDArray[np.int32]]:
    """:func:`graph_form` of many graphs at once: ``edges`` an integer array (m, J, 2).

    Returns ``(canonical, orbits)``: an array (m, J, 2) of uint8 (each graph's edges in
    its canonical labels, as sorted pairs, sorted) and an array (m,) of orbit counts.

    Examples
    --------
    >>> import numpy as np
    >>> square = np.array([[(0, 1), (1, 2), (2, 3), (3, 0)]])
    >>> canonical, orbits = graph_forms(4, square, backend="own")
    >>> canonical.tolist(), orbits.tolist()
    ([[[0, 1], [0, 2], [1, 3], [2, 3]]], [1])
    """
    _check(backend)
    edges = np.asarray(edges, dtype=np.int64)
    m, joints = len(edges), edges.shape[1]
    orders = np.empty((m, n), dtype=np.int64)
    orbits = np.empty(m, dtype=np.int32)
    if backend == "nauty":
        g = _nauty.Graph(n)                     # one graph object, its adjacency swapped
        for i, chain in enumerate(edges.tolist()):
            adjacency: dict[int, list[int]] = {v: [] for v in range(n)}
            for a, b in chain:
                adjacency[a].append(b)
            g._adjacency_dict = adjacency       # skips pynauty's per-call validation
            orders[i] = _nautywrap.graph_canonlab(g)
            orbits[i] = _nautywrap.graph_autgrp(g)[4]
    else:
        for i, chain in enumerate(edges.tolist()):
            labels = [("link",)] * n
            adj: list[list[tuple[int, int]]] = [[] for _ in range(n)]
            for a, b in chain:
                adj[a].append((b, 0))
                adj[b].append((a, 0))
            _, order, gens, _ = refine_search(labels, adj)
            orders[i] = order
            orbits[i] = len(set(orbits_of(gens, n)))
    position = np.empty_like(orders)
    np.put_along_axis(position, orders, np.arange(n)[None, :].repeat(m, axis=0), axis=1)
    relabelled = np.take_along_axis(position, edges.reshape(m, -1), axis=1).reshape(m, joints, 2)
    low, high = relabelled.min(axis=2), relabelled.max(axis=2)
    keys = np.sort(low * n + high, axis=1)
    canonical = np.stack([keys // n, keys % n], axis=2).astype(np.uint8)
    return canonical, orbits


def _incidence(k: int, edges: Sequence[Sequence[int]]) -> dict[int, list[int]]:
    """The multigraph as a simple coloured graph: its nodes, then one node per edge
    joined to the edge's ends (a loop's node to its one end)."""
    adjacency: dict[int, list[int]] = {v: [] for v in range(k + len(edges))}
    for e, (a, b) in enumerate(edges):
        adjacency[k + e].append(a)
        if b != a:
            adjacency[k + e].append(b)
    return adjacency


def multigraph_key(k: int, edges: Sequence[Sequence[int]], *, backend: str = "nauty",
                  ) -> Hashable:
    """A key equal for two multigraphs (loops allowed) on ``k`` nodes exactly when they
    are isomorphic."""
    _check(backend)
    if backend == "nauty":
        g = _nauty.Graph(k + len(edges), adjacency_dict=_incidence(k, edges),
                         vertex_coloring=[set(range(k)), set(range(k, k + len(edges)))])
        return _nauty.certificate(g)
    labels, adj = _weighted(k, edges)
    cert, order, _, _ = refine_search(labels, adj)
    return (tuple(labels[v] for v in order), cert)


def _weighted(k: int, edges: Iterable[Sequence[int]],
              ) -> tuple[list[tuple[str, int, int]], list[list[tuple[int, int]]]]:
    """A multigraph as a labelled simple graph: a node's label is its degree and number
    of loops, an edge's label its multiplicity."""
    loops, degree = [0] * k, [0] * k
    mult: dict[tuple[int, int], int] = {}
    for a, b in edges:
        degree[a] += 1
        degree[b] += 1
        if a == b:
            loops[a] += 1
        else:
            mult[(a, b)] = mult.get((a, b), 0) + 1
    labels = [("node", degree[i], loops[i]) for i in range(k)]
    adj: list[list[tuple[int, int]]] = [[] for _ in range(k)]
    for (a, b), m in mult.items():
        adj[a].append((b, m))
        adj[b].append((a, m))
    return labels, adj


def multigraph_automorphisms(k: int, edges: Sequence[Sequence[int]], *,
                             backend: str = "nauty") -> list[tuple[int, ...]]:
    """Every automorphism of a multigraph as a permutation of its nodes (a tuple ``p``:
    node ``v`` goes to ``p[v]``), the identity included.

    Examples
    --------
    >>> sorted(multigraph_automorphisms(2, [(0, 1), (0, 1), (0, 1)], backend="own"))
    [(0, 1), (1, 0)]
    """
    _check(backend)
    if backend == "nauty":
        g = _nauty.Graph(k + len(edges), adjacency_dict=_incidence(k, edges),
                         vertex_coloring=[set(range(k)), set(range(k, k + len(edges)))])
        generators = [tuple(p[:k]) for p in _nauty.autgrp(g)[0]]
    else:
        labels, adj = _weighted(k, edges)
        generators = [tuple(p) for p in refine_search(labels, adj)[2]]
    identity = tuple(range(k))
    group, frontier = {identity}, [identity]
    while frontier:
        new = []
        for p in frontier:
            for g in generators:
                q = tuple(g[p[v]] for v in range(k))
                if q not in group:
                    group.add(q)
                    new.append(q)
        frontier = new
    return sorted(group)


def _link_joint_adjacency(n: int, joints: Iterable[int],
                          members: dict[int, list[int]] | None = None) -> dict[int, list[int]]:
    """A link-joint graph's adjacency: links 0..n-1, then one node per joint (a bit mask
    of its links) joined to its links (``members``: a dict of masks' links, filled as
    it goes, for many graphs)."""
    members = {} if members is None else members
    adjacency: dict[int, list[int]] = {v: [] for v in range(n)}
    for k, mask in enumerate(joints, start=n):
        links = members.get(mask)
        if links is None:
            links = members[mask] = [x for x in range(n) if mask >> x & 1]
        adjacency[k] = links
    return adjacency


def _own_link_joint(n: int, joints: Sequence[int],
                    ) -> tuple[Hashable, list[int], list[list[int]]]:
    """:func:`refine_search` of a link-joint graph: its certificate, node order and
    automorphism generators."""
    adjacency = _link_joint_adjacency(n, joints)
    adj: list[list[tuple[int, int]]] = [[] for _ in adjacency]
    for v, ends in adjacency.items():
        for x in ends:
            adj[v].append((x, 0))
            adj[x].append((v, 0))
    labels = [("link",)] * n + [("joint",)] * len(joints)
    cert, order, generators, _ = refine_search(labels, adj)
    return (tuple(labels[v] for v in order), cert), order, generators


def link_joint_keys(n: int, graphs: Iterable[Sequence[int]], *, backend: str = "nauty",
                    ) -> list[Hashable]:
    """A key for each link-joint graph of ``graphs``, equal for two graphs on ``n``
    links with as many joints exactly when they are isomorphic (links to links, joints
    to joints). Each graph is a sequence of joints, each a bit mask of its links (bit
    ``x`` for link ``x``).

    Examples
    --------
    >>> a, b, c = link_joint_keys(4, [(0b0111, 0b1010, 0b1100, 0b1001),
    ...                               (0b1110, 0b0101, 0b0011, 0b1001),
    ...                               (0b0011, 0b0110, 0b1100, 0b1001)], backend="own")
    >>> a == b, a == c
    (True, False)
    """
    _check(backend)
    if backend == "own":
        return [_own_link_joint(n, joints)[0] for joints in graphs]
    keys: list[Hashable] = []
    members: dict[int, list[int]] = {}
    g = None
    for joints in graphs:
        nodes = n + len(joints)
        if g is None or g.number_of_vertices != nodes:
            g = _nauty.Graph(nodes, vertex_coloring=[set(range(n)), set(range(n, nodes))])
        g._adjacency_dict = _link_joint_adjacency(n, joints, members)   # unvalidated
        keys.append(_nautywrap.graph_cert(g))
    return keys


def link_joint_form(n: int, joints: Sequence[int], *, backend: str = "nauty",
                    ) -> tuple[tuple[tuple[int, ...], ...], int]:
    """A link-joint graph's joints in canonical labels, and its link orbits.

    Returns ``(joints, orbits)``: each joint (``joints`` as in :func:`link_joint_keys`)
    a sorted tuple of links renumbered canonically (isomorphic graphs get the same
    tuple), the tuple sorted; ``orbits`` the number of orbits of the links under the
    graph's automorphisms (the chain's distinct inversions).

    Examples
    --------
    >>> link_joint_form(4, (0b0111, 0b1010, 0b1100, 0b1001), backend="own")
    (((0, 1, 2), (0, 3), (1, 3), (2, 3)), 2)
    """
    _check(backend)
    if backend == "own":
        _, order, generators = _own_link_joint(n, joints)
        orbits = len(set(orbits_of(generators, n + len(joints))[:n]))
    else:
        g = _nauty.Graph(n + len(joints), adjacency_dict=_link_joint_adjacency(n, joints),
                         vertex_coloring=[set(range(n)), set(range(n, n + len(joints)))])
        order = _nauty.canon_label(g)
        orbits = len(set(_nauty.autgrp(g)[3][:n]))
    position = {v: i for i, v in enumerate(v for v in order if v < n)}
    canonical = sorted(tuple(sorted(position[x] for x in range(n) if mask >> x & 1))
                       for mask in joints)
    return tuple(canonical), orbits
