"""Generic mobility of a chain with multiple joints, decided by counting: Whiteley's
count for bodies and pins.

A joint of ``d`` links (a pin at one generic point) puts ``2 (d - 1)`` rows on their
twists, a sliding pair two. Rows on the links of a set ``S`` only are blind to the
three motions that move ``S`` as one body, so they have rank at most ``3 |S| - 3``;
a set whose joints put more rows on it than that, counting a pin by the links of
``S`` it holds (``2 (d_S - 1)`` rows), is *overbraced*: its rows are dependent, and the
chain has a freedom more than its joints allow. For links and pins at generic points
the converse holds too (Whiteley, "A matroid on hypergraphs, with applications in
scene analysis and geometry", Discrete Comput. Geom. 4, 1989): the rows are
independent unless some set is overbraced.

A joint is locked when fixing its rate (the relative turn of two links on a pin, or a
slide) adds nothing to the rank. Fixing it welds its two links into one; the joint's
own two rows and its rate then span all three relative motions, so the rate is
dependent exactly when the welded chain's rows are: a chain is locked when a weld of
one of its joints leaves an overbraced set.

Sliding pairs carry one more condition, on turns alone (their links turn together):
a loop of them leaves a turn row dependent, and a turning pair whose links a path of
them keeps parallel is locked. :func:`~chaingraph.structure.atlas.admissibility.admissible`
tests those before the count. A path of sliding pairs between two links of ``S``
through links outside it also keeps them parallel, and the count takes it as one row
more: take the rows on ``S`` and the turn rows of the paths' sliding pairs outside
``S``, which touch the paths' own links ``O``. Every motion of ``S`` that its rows and
the paths' parallels allow (the three rigid ones at least) extends to ``O``, whose
links the turn rows leave free to translate, so those rows have rank at most
``3 |S| - 3 + |O|``, while a path through ``k`` links of ``O`` brings ``k + 1`` turn
rows: one more than its links. That bound needs no generic pose, so it proves a
rejection wherever it is exceeded; with pins and sliding pairs together it is not
known to be the whole story (:mod:`~chaingraph.structure.atlas.admissibility`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from chaingraph._util.disjoint import DisjointSets

__all__ = ["overbraced", "weld", "pin_verdicts"]


def overbraced(links: int, joints: Sequence[Sequence[int]], kinds: Sequence[str] | None = None,
               ) -> int:
    """The least set of links (a bit mask) on which ``joints`` (tuples of links; ``kinds``
    "R"/"P" per joint, the P joints a forest) put more rows than ``3 |S| - 3``, a path
    of P joints between two of its links through links outside it counting one row (see
    the module's text), or 0 when there is none.

    >>> overbraced(4, [(0, 1), (1, 2), (2, 3), (3, 0)])            # the four-bar
    0
    >>> bin(overbraced(4, [(0, 1, 2), (1, 3), (2, 3), (0, 3)]))     # a pin of three
    '0b1111'

    Links 4 and 5 of Stephenson's chain kept parallel by P joints through 0 and 1, and
    joined by the binary links 2 and 3: a rigid four-link loop, locked, so welding two
    of its links overbraces it:

    >>> joints = [(0, 1), (0, 4), (1, 5), (2, 4), (2, 5), (3, 4), (3, 5)]
    >>> overbraced(6, joints, "PPPRRRR"), bin(overbraced(5, *weld(joints, "PPPRRRR", 2, 4)))
    (0, '0b11100')
    """
    kinds = kinds or "R" * len(joints)
    sets = np.arange(1 << links)
    member = [sets >> x & 1 for x in range(links)]      # whether each set holds link x
    size = sum(member)
    rows = np.zeros(sets.size, dtype=np.int64)
    slides = DisjointSets(links)            # the P joints' components over all links
    for j, kind in zip(joints, kinds):
        inside = sum(member[x] for x in j)
        rows += 2 * np.maximum(inside - 1, 0)
        if kind == "P":
            rows -= inside == 2             # P joints inside S, counted below
            slides.join(*j)
    if "P" in kinds:
        # + |S| - (P joints inside S) - (P components S meets): one row per path outside
        rows += size
        for block in slides.blocks().values():
            rows -= (sets & sum(1 << x for x in block)) != 0
    over = np.nonzero((rows > 3 * size - 3) & (size > 1))[0]
    return int(over[0]) if over.size else 0


def weld(joints: Sequence[Sequence[int]], kinds: Sequence[str] | None, a: int, b: int,
         ) -> tuple[list[tuple[int, ...]], list[str]]:
    """The chain with links ``a`` and ``b`` made one (``b`` becomes ``a``; the links
    above ``b`` move down by one): the joints that keep two links or more, and their
    kinds.

    >>> weld([(0, 1, 2), (1, 3), (2, 3)], "RRR", 1, 2)
    ([(0, 1), (1, 2), (1, 2)], ['R', 'R', 'R'])
    """
    def new(x: int) -> int:
        x = a if x == b else x
        return x - 1 if x > b else x
    out: list[tuple[int, ...]] = []
    out_kinds: list[str] = []
    for j, k in zip(joints, kinds or "R" * len(joints)):
        held = tuple(sorted({new(x) for x in j}))
        if len(held) > 1:
            out.append(held)
            out_kinds.append(k)
    return out, out_kinds


def pin_verdicts(links: int, candidates: Sequence[Sequence[Sequence[int]]], *,
                 kinds: Sequence[Sequence[str] | None] | None = None,
                 ) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
    """For each candidate (a tuple of joints, each a tuple of links; ``kinds`` gives
    each candidate's joint kinds, all R by default), whether its rows are dependent
    (an overbraced set: a freedom more than its joints allow) and whether a joint is
    locked (a weld of it leaves an overbraced set), by the count (module text); a
    dependent candidate is not also called locked.

    Examples
    --------
    >>> four = ((0, 1), (1, 2), (2, 3), (3, 0))
    >>> fan = ((0, 1, 2), (1, 3), (2, 3), (0, 3))
    >>> dependent, locked = pin_verdicts(4, [four, fan])
    >>> dependent.tolist(), locked.tolist()
    ([False, True], [False, False])
    """
    each: list[Sequence[str]] = [k or "R" * len(c) for k, c in zip(
        kinds or [None] * len(candidates), candidates)]
    dependent: list[bool] = []
    locked: list[bool] = []
    for joints, kind in zip(candidates, each):
        dependent.append(bool(overbraced(links, joints, kind)))
        pairs = {(a, b) for j in joints for i, a in enumerate(j) for b in j[i + 1:]}
        locked.append(not dependent[-1] and any(
            overbraced(links - 1, *weld(joints, kind, a, b)) for a, b in sorted(pairs)))
    return np.array(dependent, dtype=bool), np.array(locked, dtype=bool)
