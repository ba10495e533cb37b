"""One piece of the atlas: every chain that shrinks to one contracted graph.

A chain is its contracted graph with binary links strung along the edges. Two ways of
stringing them (distributions: how many binary links each edge carries) give isomorphic
chains exactly when an automorphism of the contracted graph maps one onto the other (an
isomorphism of chains maps binary links to binary links, so it induces one of the
contracted graph), and chains from different contracted graphs are never isomorphic. So
a piece keeps one distribution per orbit, and the pieces never overlap: no chain is
labelled twice, no table of canonical forms is kept across pieces.

Everything before the canonical labelling works on all distributions of a piece at once,
as numpy arrays:

- **distributions**: every way to put the binary links on the edges (a loop needs three
  at least: two would close a rigid triangle), parallel edges and loops at one node
  listed in non-increasing order (they are interchangeable);
- **one per orbit**: a distribution is kept when no automorphism of the contracted graph
  maps it to a lexicographically larger one;
- **no rigid sub-chain**: a sub-chain's mobility ``3 (n - 1) - 2 j`` adds up over the
  contracted nodes it holds and, edge by edge, over the binary links it takes. For a set
  ``T`` of contracted nodes the least mobility of a sub-chain holding exactly ``T`` is
  ``3 |T| - 3 + sum h(c_e)`` over the edges with both ends in ``T``, where an edge with
  ``c`` binary links adds ``h(0) = -2`` (a joint), ``h(1) = -1`` (a link and two joints)
  and nothing otherwise (a string of two or more adds ``c - 2 >= 0`` and is left out).
  A sub-chain of only binary links is never rigid, nor is one contracted node alone
  with parts of strings. So the chain is degenerate exactly when some ``T`` of two or
  more nodes has that sum ``<= 0`` (the whole chain has mobility F > 0, so such a
  sub-chain is proper); only the sets ``T`` that hold enough edges to reach it are tried.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence

import networkx as nx
import numpy as np
import numpy.typing as npt

from chaingraph.structure.atlas.labelling import graph_forms, multigraph_automorphisms

__all__ = ["piece", "piece_work", "Piece"]

#: rows of distributions handled at once (bounds a piece's memory)
BLOCK = 1 << 16

#: a piece's job: its contracted graph's node degrees, its sorted edges, the binary links
_Job = tuple[Sequence[int], Sequence[Sequence[int]], int]
_Edge = tuple[int, ...]
_Rows = npt.NDArray[np.int16]


class Piece:
    """What one piece found: ``edges`` (m, J, 2) uint8 canonical link graphs, ``orbits``
    (m,) the distinct inversions of each, ``fractionated`` whether they are (all of a
    piece's chains are, or none: it depends on the contracted graph alone)."""

    __slots__ = ("edges", "orbits", "fractionated")

    def __init__(self, edges: npt.NDArray[np.uint8], orbits: npt.NDArray[np.int32],
                 fractionated: bool) -> None:
        self.edges, self.orbits, self.fractionated = edges, orbits, fractionated

    def __len__(self) -> int:
        return len(self.orbits)


def piece_work(job: _Job) -> int:
    """The number of distributions a piece looks at (its share of the work)."""
    degrees, edges, binaries = job
    spare = binaries - 3 * sum(a == b for a, b in edges)
    if spare < 0:
        return 1
    return math.comb(spare + len(edges) - 1, len(edges) - 1) + 1


_CACHE: dict[tuple[int, int], _Rows] = {}
#: compositions kept for reuse: small tables only (bounds a worker's memory)
_CACHE_ROWS = 4096


def _compositions(total: int, parts: int) -> _Rows:
    """Every way to write ``total`` as ``parts`` ordered non-negative parts, as rows."""
    key = (total, parts)
    if key in _CACHE:
        return _CACHE[key]
    if parts == 1:
        out = np.array([[total]], dtype=np.int16)
    else:
        blocks = []
        for first in range(total, -1, -1):
            rest = _compositions(total - first, parts - 1)
            blocks.append(np.hstack([np.full((len(rest), 1), first, dtype=np.int16), rest]))
        out = np.vstack(blocks)
    out.flags.writeable = False
    if len(out) <= _CACHE_ROWS:
        _CACHE[key] = out
    return out


def _distribution_blocks(total: int, parts: int, limit: int = BLOCK) -> Iterator[_Rows]:
    """The compositions of :func:`_compositions` in blocks of about ``limit`` rows."""
    if parts == 1 or math.comb(total + parts - 1, parts - 1) <= limit:
        yield _compositions(total, parts)
        return
    for first in range(total, -1, -1):
        for rest in _distribution_blocks(total - first, parts - 1, limit):
            yield np.hstack([np.full((len(rest), 1), first, dtype=np.int16), rest])


def _bundles(edges: Sequence[_Edge]) -> list[tuple[_Edge, int, int]]:
    """Runs of equal edges (parallel edges, or loops at one node) in the sorted list."""
    runs: list[tuple[_Edge, int, int]] = []
    start = 0
    for e in range(1, len(edges) + 1):
        if e == len(edges) or edges[e] != edges[start]:
            runs.append((edges[start], start, e))
            start = e
    return runs


def _images(k: int, edges: Sequence[_Edge], automorphisms: Sequence[tuple[int, ...]],
            ) -> list[npt.NDArray[np.intp]]:
    """For each automorphism but the identity, the column order that maps a
    distribution to its image (bundles carried onto bundles, order kept inside)."""
    runs = _bundles(edges)
    where = {edge: (start, stop) for edge, start, stop in runs}
    images = []
    for p in automorphisms:
        if list(p) == list(range(k)):
            continue
        source = np.empty(len(edges), dtype=np.intp)
        for (a, b), start, stop in runs:
            target = tuple(sorted((p[a], p[b])))
            t0, _ = where[target]
            source[t0:t0 + stop - start] = np.arange(start, stop)
        images.append(source)
    return images


def _candidate_sets(k: int, edges: Sequence[_Edge]) -> tuple[_Rows, _Rows]:
    """Sets of two or more contracted nodes that hold enough edges to be rigid, as a
    0/1 matrix over the (non-loop) edges, with their ``3 |T| - 3``."""
    masks = np.arange(1, 1 << k)
    member = (masks[:, None] >> np.arange(k)[None, :]) & 1            # (sets, k)
    ends = np.array([(a, b) for a, b in edges], dtype=np.intp).reshape(len(edges), 2)
    inside = member[:, ends[:, 0]] & member[:, ends[:, 1]] & (ends[:, 0] != ends[:, 1])
    size = member.sum(axis=1)
    base = 3 * size - 3
    possible = (size >= 2) & (base - 2 * inside.sum(axis=1) <= 0)
    return inside[possible].astype(np.int16), base[possible].astype(np.int16)


def _keep(block: _Rows, runs: Sequence[tuple[_Edge, int, int]],
          images: Sequence[npt.NDArray[np.intp]], inside: _Rows, base: _Rows) -> _Rows:
    """Rows of ``block`` (distributions) that are orbit representatives and rigid-free."""
    keep = np.ones(len(block), dtype=bool)
    for (a, b), start, stop in runs:
        if stop - start > 1:                  # interchangeable: non-increasing order
            keep &= np.all(block[:, start:stop - 1] >= block[:, start + 1:stop], axis=1)
            if a != b:                         # two direct joints between two links
                keep &= (block[:, start:stop] == 0).sum(axis=1) <= 1
    rows = block[keep]
    index = np.flatnonzero(keep)
    for source in images:
        if not len(rows):
            break
        diff = rows[:, source] - rows
        nonzero = diff != 0
        first = nonzero.argmax(axis=1)
        larger = nonzero.any(axis=1) & (diff[np.arange(len(rows)), first] > 0)
        rows, index = rows[~larger], index[~larger]
    if len(base) and len(rows):
        # integer products: exact, and no BLAS threads competing with the workers
        h = np.where(rows == 0, -2, np.where(rows == 1, -1, 0)).astype(np.int16)
        rigid = np.zeros(len(rows), dtype=bool)
        step = max(1, (1 << 22) // len(base))
        for s in range(0, len(rows), step):
            mobility = h[s:s + step] @ inside.T + base
            rigid[s:s + step] = (mobility <= 0).any(axis=1)
        rows = rows[~rigid]
    return rows


def _expand(k: int, edges: Sequence[_Edge], counts: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """The link graphs of many distributions at once: contracted nodes 0..k-1, then the
    binary links edge by edge; ``counts`` (R, E) gives an integer array (R, J, 2)."""
    counts = np.asarray(counts, dtype=np.int64)
    rows, n_edges = counts.shape
    segments = counts + 1                                  # joints along each edge
    joints = int(segments[0].sum()) if rows else 0
    ends = np.array(edges, dtype=np.int64).reshape(n_edges, 2)
    first_binary = k + np.cumsum(counts, axis=1) - counts  # number of each edge's first
    flat = segments.ravel()
    which = np.repeat(np.arange(rows * n_edges), flat)     # (row, edge) of each joint
    step = np.arange(len(which)) - np.repeat(np.cumsum(flat) - flat, flat)
    edge = which % n_edges
    c = counts.ravel()[which]
    start = first_binary.ravel()[which]
    tail = np.where(step == 0, ends[edge, 0], start + step - 1)
    head = np.where(step == c, ends[edge, 1], start + step)
    return np.stack([tail, head], axis=1).reshape(rows, joints, 2)


def _fractionated(n: int, edges: list[list[int]]) -> bool:
    """Whether a link graph has a separating link (cut vertex) or joint (bridge)."""
    g = nx.Graph(edges)
    g.add_nodes_from(range(n))
    return not nx.is_biconnected(g)


def piece(job: _Job, *, backend: str = "nauty") -> Piece:
    """Every chain of one contracted graph, as canonical link graphs.

    Parameters
    ----------
    job : tuple
        ``(degrees, edges, binaries)``: the contracted graph's node degrees, its sorted
        edges ``(i, j)`` (loops ``(i, i)``), and the number of binary links to string.
    backend : {"nauty", "own"}
        The canonical labelling (:mod:`chaingraph.structure.atlas.labelling`).

    Examples
    --------
    >>> # two ternary links joined by three strings of four binary links in all:
    >>> # Watt's chain (2, 2 and 0 binary links) and Stephenson's (2, 1 and 1)
    >>> p = piece(((3, 3), ((0, 1), (0, 1), (0, 1)), 4), backend="own")
    >>> len(p), p.orbits.tolist(), p.fractionated
    (2, [2, 3], False)
    """
    degrees, given, binaries = job
    edges = [tuple(e) for e in given]
    k = len(degrees)
    minimum = np.array([3 if a == b else 0 for a, b in edges], dtype=np.int16)
    spare = binaries - int(minimum.sum())
    joints = len(edges) + binaries
    found_edges: list[npt.NDArray[np.uint8]] = []
    found_orbits: list[npt.NDArray[np.int32]] = []
    fractionated = False
    if spare >= 0:
        runs = _bundles(edges)
        images = _images(k, edges, multigraph_automorphisms(k, edges, backend=backend))
        inside, base = _candidate_sets(k, edges)
        for block in _distribution_blocks(spare, len(edges)):
            kept = _keep(block + minimum, runs, images, inside, base)
            if not len(kept):
                continue
            expanded = _expand(k, edges, kept)
            if not found_edges:
                fractionated = _fractionated(k + binaries, expanded[0].tolist())
            canonical, orbits = graph_forms(k + binaries, expanded, backend=backend)
            found_edges.append(canonical)
            found_orbits.append(orbits)
    if not found_edges:
        return Piece(np.zeros((0, joints, 2), np.uint8), np.zeros(0, np.int32), False)
    return Piece(np.concatenate(found_edges), np.concatenate(found_orbits), fractionated)
