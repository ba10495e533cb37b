"""Number synthesis and contracted graphs: the first two stages of the atlas.

A link assortment says how many links of each order a chain has; a contracted graph is
what is left of a chain when each string of binary links is shrunk to one edge: a
connected multigraph on the links of order 3 or more (parallel edges, and loops for a
string that leaves a link and comes back to it), with the links' orders as degrees.
"""

from __future__ import annotations

from collections.abc import Hashable, Sequence

from chaingraph._util.text import freedom
from chaingraph.errors import AtlasSizeError
from chaingraph.structure.atlas.labelling import multigraph_key

__all__ = ["joints_for", "assortments", "contracted_graphs"]


def joints_for(links: int, dof: int) -> int:
    """J for a chain of ``links`` links and ``dof`` degrees of freedom, or AtlasSizeError.

    Examples
    --------
    >>> joints_for(8, 1)
    10
    """
    for name, value in (("links", links), ("dof", dof)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise AtlasSizeError(f"{name} must be a positive whole number, got {value!r}",
                                 links=links, dof=dof, parameter=name)
    twice = 3 * (links - 1) - dof
    if twice % 2:
        raise AtlasSizeError(
            f"no chain has {links} links and {freedom(dof)}: 3(N - 1) - F = "
            f"{twice} is odd, and simple revolute joints remove two freedoms each",
            links=links, dof=dof)
    joints = twice // 2
    if joints < links:
        raise AtlasSizeError(
            f"no closed chain has {links} links and {freedom(dof)}: it would "
            f"have {joints} joints, fewer than its {links} links (the fewest links is "
            f"{dof + 3}, a single loop)", links=links, dof=dof)
    return joints


def assortments(links: int, joints: int) -> list[tuple[int, ...]]:
    """Link assortments: tuples (n2, n3, ...) with sum n = links, sum k n_k = 2 joints.

    Examples
    --------
    >>> assortments(6, 7)
    [(4, 2, 0), (5, 0, 1)]
    """
    # each independent loop through a link adds at most two of its joints (a link shared
    # by the loops of a fractionated chain has order twice their number)
    loops = joints - links + 1
    top = min(links - 1, 2 * loops)
    out: list[tuple[int, ...]] = []

    def rec(order: int, left_links: int, left_ends: int, acc: list[int]) -> None:
        if order > top:
            if left_links == 0 and left_ends == 0:
                out.append(tuple(acc))
            return
        for count in range(left_links + 1):
            if count * order > left_ends:
                break
            rec(order + 1, left_links - count, left_ends - count * order, acc + [count])
    rec(2, links, 2 * joints, [])
    return out


def contracted_graphs(degrees: Sequence[int], *, backend: str = "nauty",
                      ) -> list[tuple[tuple[int, int], ...]]:
    """Connected multigraphs with loops on nodes of the given degrees (non-increasing),
    up to isomorphism, each as a sorted tuple of edges ``(i, j)``, ``i <= j``, in the
    order they are first met.

    Examples
    --------
    >>> contracted_graphs((3, 3), backend="own")        # the theta and the dumb-bell
    [((0, 0), (0, 1), (1, 1)), ((0, 1), (0, 1), (0, 1))]
    """
    k = len(degrees)
    found: dict[Hashable, tuple[tuple[int, int], ...]] = {}
    remaining = list(degrees)
    edges: list[tuple[int, int]] = []

    def rec(i: int) -> None:
        if i == k:
            if _connected(k, edges):
                key = multigraph_key(k, edges, backend=backend)
                if key not in found:
                    found[key] = tuple(sorted(edges))
            return
        if remaining[i] == 0:
            rec(i + 1)
            return
        # node i's stubs go to nodes j >= i, in non-decreasing order of j; of the nodes
        # not yet touched, those of one degree are interchangeable: only the first is
        # tried (the others would give the same graphs relabelled)
        last = edges[-1][1] if edges and edges[-1][0] == i else i
        tried_fresh = set()
        for j in range(last, k):
            if j > i and remaining[j] == degrees[j]:
                if degrees[j] in tried_fresh:
                    continue
                tried_fresh.add(degrees[j])
            if j == i:
                if remaining[i] >= 2:
                    remaining[i] -= 2
                    edges.append((i, i))
                    rec(i)
                    edges.pop()
                    remaining[i] += 2
            elif remaining[j] >= 1:
                remaining[i] -= 1
                remaining[j] -= 1
                edges.append((i, j))
                rec(i)
                edges.pop()
                remaining[i] += 1
                remaining[j] += 1
    rec(0)
    return sorted(found.values())


def _connected(k: int, edges: Sequence[tuple[int, int]]) -> bool:
    """Whether the multigraph on ``k`` nodes is connected (bit masks)."""
    neighbours = [1 << v for v in range(k)]
    for a, b in edges:
        neighbours[a] |= 1 << b
        neighbours[b] |= 1 << a
    reached, frontier = 1, 1
    while frontier:
        grown = reached
        v = 0
        while frontier:
            if frontier & 1:
                grown |= neighbours[v]
            frontier >>= 1
            v += 1
        frontier = grown & ~reached
        reached = grown
    return reached == (1 << k) - 1
