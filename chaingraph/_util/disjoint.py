"""Disjoint sets (union-find), the one home of the partitions the atlas, the
isomorphism code and the assembly grow by joining elements."""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

__all__ = ["DisjointSets"]


class DisjointSets:
    """Elements (0..n-1 for an int ``n``, else the given hashables) in blocks, merged by
    :meth:`join`; each block is named by its least member (so the names do not depend
    on the order of the joins).

    Examples
    --------
    >>> d = DisjointSets(5)
    >>> d.join(3, 1), d.join(1, 3), d.join(4, 0)
    (True, False, True)
    >>> [d.find(x) for x in range(5)], d.count
    ([0, 1, 2, 1, 0], 3)
    >>> DisjointSets("abc").blocks()
    {'a': ['a'], 'b': ['b'], 'c': ['c']}
    """

    def __init__(self, elements: int | Iterable[Any]) -> None:
        self.parent: Any
        self.parent = list(range(elements)) if isinstance(elements, int) else \
            {x: x for x in elements}
        self.count = len(self.parent)

    def find(self, x: Any) -> Any:
        """The name of ``x``'s block."""
        parent = self.parent
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    def join(self, x: Any, y: Any) -> bool:
        """Merge the blocks of ``x`` and ``y``; False if they were one already."""
        a, b = self.find(x), self.find(y)
        if a == b:
            return False
        if b < a:
            a, b = b, a
        self.parent[b] = a
        self.count -= 1
        return True

    def blocks(self) -> dict[Any, list[Any]]:
        """Block name -> its members, in the elements' order."""
        out: dict[Any, list[Any]] = {}
        members = range(len(self.parent)) if isinstance(self.parent, list) else self.parent
        for x in members:
            out.setdefault(self.find(x), []).append(x)
        return out
