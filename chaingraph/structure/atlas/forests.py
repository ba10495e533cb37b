"""Generic mobility of a chain with turning and sliding pairs, decided by forests: a
combinatorial test, exact, with no pose drawn.

Why forests. A link's velocity is its twist ``(omega, vx, vy)``; a joint between links
``a`` and ``b`` gives rows ``l (x) (e_a - e_b)``, a 3-vector ``l`` on the difference of
their twists. An R joint at ``p`` gives the two rows that annihilate the turn about
``p``: their span is a generic plane of 3-space when ``p`` is generic, the span of two
generic vectors. A P joint gives the turn row ``(1, 0, 0)``, the same for every P
joint, and the no-slip row across its guide, a generic vector (its pin and normal are
free). So the rows are generic vectors, except the P joints' turn rows, which are fixed.

Expand a maximal minor by the three column blocks (Laplace): each term assigns every
row to one coordinate, omega, x or y, and is a product of minors of the link graph's
incidence matrix, one per coordinate, times the monomial of the chosen entries of the
generic rows. A minor of an incidence matrix is nonzero exactly when its edges form a
forest; a fixed turn row has a nonzero entry under omega only; and two assignments
that differ on a generic row give different monomials, so no terms cancel. Hence a set
of rows is independent at a generic pose exactly when it splits into three forests of
the link graph, the fixed rows in the first (Whiteley's d-frames, "The union of
matroids and the rigidity of frameworks", 1988, with rows at infinity as in
Lee-St.John and Sidman's body-and-cad frameworks). The split is found by Edmonds'
matroid partition (shortest augmenting paths), so the test is exact and polynomial.

What the atlas asks follows:

* the chain's generic mobility is ``3 (links - 1) - rank``; with as many rows as its
  joints allow (``2 j``), the mobility is ``F`` exactly when the rows are independent;
* an R joint is locked when its relative turn, one more fixed row on its links, adds
  nothing to the rank; a P joint is locked when its slide, one more generic row on its
  links, adds nothing (a rigid sub-chain locks every joint inside it, so it is found
  this way too).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Sequence
from typing import Any

__all__ = ["Forests", "forest_verdicts"]

OMEGA, ANY = 0b001, 0b111      # the coordinates a row may be assigned to


class Forests:
    """Rows split into three forests of a link graph (omega, x, y): Edmonds' matroid
    partition. A row is ``(a, b, allowed)``: the links it joins and a bit mask of the
    forests it may join (``OMEGA`` for a fixed turn row, ``ANY`` for a generic row).

    >>> f = Forests(2)
    >>> [f.add(0, 1, ANY) for _ in range(4)]      # two links: three rows at most
    [True, True, True, False]
    """

    def __init__(self, links: int) -> None:
        self.links = links
        self.rows: list[tuple[int, int, int]] = []      # (a, b, allowed)
        self.where: list[int] = []  # the forest each kept row is in (-1: not kept)
        self.rank = 0
        # each forest rooted, until a row joins or leaves it
        self._up: list[list[Any] | None] = [None] * 3

    def _rooted_now(self, k: int) -> list[Any]:
        up = self._up[k]
        if up is None:
            up = self._up[k] = self._rooted(k)
        return up

    def _rooted(self, k: int) -> list[Any]:
        """Forest ``k`` rooted: each link's (parent link, row to it, depth, root)."""
        adjacent: list[list[tuple[int, int]]] = [[] for _ in range(self.links)]
        for i, w in enumerate(self.where):
            if w == k:
                x, y, _ = self.rows[i]
                adjacent[x].append((y, i))
                adjacent[y].append((x, i))
        up: list[Any] = [None] * self.links
        for start in range(self.links):
            if up[start] is not None:
                continue
            up[start] = (-1, -1, 0, start)
            todo = [start]
            while todo:
                x = todo.pop()
                depth = up[x][2] + 1
                for y, i in adjacent[x]:
                    if up[y] is None:
                        up[y] = (x, i, depth, start)
                        todo.append(y)
        return up

    @staticmethod
    def _path(up: list[Any], a: int, b: int) -> list[int] | None:
        """The rows on a rooted forest's path from ``a`` to ``b``, or None when they
        are not joined."""
        if up[a][3] != up[b][3]:
            return None
        out = []
        while a != b:
            if up[a][2] >= up[b][2]:
                out.append(up[a][1])
                a = up[a][0]
            else:
                out.append(up[b][1])
                b = up[b][0]
        return out

    def add(self, a: int, b: int, allowed: int = ANY) -> bool:
        """Add a row; whether it raised the rank (False: it depends on the rows kept,
        and it is not kept)."""
        s = len(self.rows)
        self.rows.append((a, b, allowed))
        self.where.append(-1)
        if a == b:
            return False
        label: dict[int, Any] = {s: None}   # row -> (row that takes its place, forest)
        todo = deque([s])
        while todo:
            u = todo.popleft()
            x, y, mask = self.rows[u]
            for k in range(3):
                if not mask >> k & 1 or self.where[u] == k:
                    continue
                cycle = self._path(self._rooted_now(k), x, y)
                if cycle is None:                   # room in forest k: augment
                    v, into = u, k
                    while v is not None:
                        was = self.where[v]
                        self.where[v] = into
                        self._up[into] = None
                        if was >= 0:
                            self._up[was] = None
                        if label[v] is None:
                            break
                        v, into = label[v][0], was
                    self.rank += 1
                    return True
                for r in cycle:
                    if r not in label:
                        label[r] = (u, k)
                        todo.append(r)
        return False

    def adds(self, a: int, b: int, allowed: int = ANY) -> bool:
        """Whether one more row would raise the rank (the forests are left as they
        are)."""
        trial = Forests(self.links)
        trial.rows, trial.where, trial.rank = list(self.rows), list(self.where), self.rank
        trial._up = list(self._up)
        return trial.add(a, b, allowed)


def forest_verdicts(links: int, joints: Sequence[Sequence[int]],
                   kinds: Sequence[str] | None = None) -> tuple[int, bool]:
    """The rank of a chain's velocity rows and whether a joint is locked, by forests:
    ``(rank, locked)``. ``joints`` are tuples of links, ``kinds`` "R"/"P" per joint.

    For simple joints this is exact (module text). A pin of three links or more is
    drawn as a body of its own held by each of its links at a point of its own; the
    chain with the pin is that chain with those points made one, a special case, so
    its rank is at most the drawn chain's less two per pin (the pin's own point), and
    a rate that adds nothing there adds nothing here: then ``rank`` is an upper bound
    and ``locked`` is proven only where the chain's rows are independent.

    Examples
    --------
    >>> ring = ((0, 1), (1, 2), (2, 3), (3, 0))
    >>> [forest_verdicts(4, ring, k) for k in ("RRRR", "RRPP", "RPPP", "PPPP")]
    [(8, False), (8, False), (8, True), (7, False)]
    """
    kinds = kinds or "R" * len(joints)
    forests = Forests(links + sum(len(j) > 2 for j in joints))
    pin = links
    rates: list[tuple[int, int, int]] = []
    for j, kind in zip(joints, kinds):
        if len(j) > 2:
            for x in j:
                forests.add(pin, x)
                forests.add(pin, x)
            pin += 1
        else:
            a, b = j
            forests.add(a, b)
            forests.add(a, b, ANY if kind == "R" else OMEGA)
        # a joint's rates: an R joint's turns (fixed rows), a P joint's slide (generic)
        rates += [(a, b, OMEGA if kind == "R" else ANY)
                  for i, a in enumerate(j) for b in j[i + 1:]]
    rank = forests.rank - 2 * (pin - links)
    return rank, any(not forests.adds(*rate) for rate in rates)
