"""Which chains the atlas admits, every verdict proven.

A chain is admissible when its generic mobility is the one its joints allow (its
velocity rows are independent at a generic pose), no joint is locked (moves in no
motion) and so no sub-chain is rigid (a rigid sub-chain locks the joints inside it).

Each verdict carries a proof, not a sampled pose's judgement:

* **the structure of the sliding pairs** (:func:`admissible`): a loop of P joints only
  leaves a turn row dependent; a turning pair whose links a path of P joints keeps
  parallel cannot turn;
* **an admission** is proven by one exact evaluation of the velocity rows
  (:mod:`~chaingraph.structure.atlas.generic`): independent rows that lock no joint
  at one pose, modulo a prime, are independent at a generic pose;
* **a rejection** is proven by forests (:mod:`~chaingraph.structure.atlas.forests`),
  a theorem for chains of simple joints, turning and sliding, and by Whiteley's count
  (:mod:`~chaingraph.structure.atlas.pins`), a theorem for chains of turning pairs
  with pins of several links; either bound proves a chain with pins and sliding pairs
  overbraced or locked.

A chain with both pins and sliding pairs is admitted when an evaluation proves it and
rejected when a bound does: forests with each pin spread over points of its own (the
chain is a special case of that one, so its rank is no higher), or the count, which
takes a path of sliding pairs outside a set of links as the one turn row it adds to it.
Neither is known to be a theorem there, but together they decide every such chain of
the atlas to 10 links with one degree of freedom and 9 with two (a path of sliding pairs
keeping two links parallel, with a pin, makes the rigid sub-chains that only the
count's path row sees). Should some chain
escape both, it is rejected when :data:`DRAWS` independent exact evaluations all find
it dependent or locked: a minor of degree at most twice the joints vanishes at a random
point modulo the prime 2**31 - 1 with probability below 1e-8, so four evaluations that
all miss an admissible chain have probability below 1e-31. That verdict alone would not
be a proof; none is made to those sizes.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from chaingraph._util.disjoint import DisjointSets
from chaingraph._util.text import freedom
from chaingraph.errors import ChainStructureError
from chaingraph.structure.atlas.forests import forest_verdicts
from chaingraph.structure.atlas.generic import joint_verdicts
from chaingraph.structure.atlas.pins import pin_verdicts

__all__ = ["REASONS", "DRAWS", "admissible", "decide", "verdicts"]

#: why an assignment of sliding pairs is rejected, in the order they are tested
REASONS = {"mobility": "a generic mobility other than asked (a loop of sliding pairs only "
                       "has one freedom more than its joints allow)",
           "locked": "a locked joint (a turning pair whose two links are joined by sliding "
                     "pairs only cannot turn; a rigid sub-chain locks its joints)"}

#: exact evaluations that must all find a chain dependent or locked when no bound proves
#: it (a chain with pins and sliding pairs only)
DRAWS = 4

_UNDECIDED = "undecided"


def admissible(links: int, edges: Sequence[Sequence[int]], kinds: Sequence[str]) -> str | None:
    """What the structure of the P joints alone says of an assignment of ``kinds``
    ("R"/"P") to the joints ``edges``: ``"mobility"`` for a loop of P joints only,
    ``"locked"`` for an R joint whose links are joined by P joints, else None (then
    :func:`decide` decides).

    Examples
    --------
    >>> ring = [(0, 1), (1, 2), (2, 3), (3, 0)]
    >>> [admissible(4, ring, k) for k in ("RRRR", "RRRP", "RRPP", "RPRP", "RPPP", "PPPP")]
    [None, None, None, None, 'locked', 'mobility']
    """
    slides = DisjointSets(links)
    for j, k in zip(edges, kinds):
        if k == "P" and not slides.join(*j):
            return "mobility"
    for j, k in zip(edges, kinds):
        if k == "R" and len({slides.find(x) for x in j}) < len(j):
            return "locked"
    return None


def decide(links: int, joints: Sequence[Sequence[int]], kinds: Sequence[str] | None = None,
           *, independent: bool = False) -> str | None:
    """The proven verdict on a chain (``joints``: tuples of links; ``kinds``: "R"/"P"
    per joint) by forests and counts: None (admissible), ``"mobility"`` or
    ``"locked"``; ``"undecided"`` where neither bound proves a chain with pins and
    sliding pairs either way. ``independent``: its rows are already proven independent
    (by an evaluation), so a rate the bounds find dependent proves a lock.

    Examples
    --------
    >>> stephenson = [(0, 1), (0, 4), (1, 5), (2, 4), (2, 5), (3, 4), (3, 5)]
    >>> decide(6, stephenson, "PPPRRRR")     # links 4 and 5 kept parallel: rigid
    'locked'
    >>> decide(4, [(0, 1, 2), (1, 3), (2, 3), (0, 3)])      # a pin of three: rigid
    'mobility'
    """
    kinds = kinds or "R" * len(joints)
    pins, sliding = any(len(j) > 2 for j in joints), "P" in kinds
    if pins and not sliding:                             # Whiteley's count: a theorem
        dependent, stuck = pin_verdicts(links, [joints])
        return "mobility" if dependent[0] else "locked" if stuck[0] else None
    rank, locked = forest_verdicts(links, joints, kinds)
    rows = 2 * sum(len(j) - 1 for j in joints)
    if not pins:                                         # forests: a theorem
        return "mobility" if rank < rows else "locked" if locked else None
    dependent, welded = pin_verdicts(links, [joints], kinds=[kinds])
    if rank < rows or dependent[0]:
        return "mobility"
    if independent and (locked or welded[0]):
        return "locked"
    return _UNDECIDED


def verdicts(links: int, candidates: Sequence[Sequence[Sequence[int]]], *,
             kinds: Sequence[Sequence[str] | None] | None = None, dof: int,
             drawn: tuple[npt.NDArray[np.int64], npt.NDArray[np.bool_]] | None = None,
             ) -> list[str | None]:
    """For each candidate (a tuple of joints, each a tuple of links, as many as ``dof``
    degrees of freedom allow; ``kinds``: each one's joint kinds, all R by default),
    None when it is admissible, else its reason (a key of :data:`REASONS`). ``drawn``:
    the candidates' ``(mobility, locked)`` at the first pose, where a caller has them.
    A candidate with other than the joints ``dof`` allows is a ChainStructureError.

    Examples
    --------
    >>> ring = ((0, 1), (1, 2), (2, 3), (3, 0))
    >>> verdicts(4, [ring] * 4, kinds=["RRRR", "RRPP", "RPPP", "PPPP"], dof=1)
    [None, None, 'locked', 'mobility']
    """
    count = len(candidates)
    each: list[Sequence[str]] = [k or "R" * len(c)
                                 for k, c in zip(kinds or [None] * count, candidates)]
    for c in candidates:
        counted = 3 * (links - 1) - 2 * sum(len(j) - 1 for j in c)
        if counted != dof:
            raise ChainStructureError(f"the joints {list(c)} on {links} links leave "
                                      f"{freedom(counted)} by their count, not "
                                      f"{dof}")
    out = [admissible(links, c, k) for c, k in zip(candidates, each)]
    todo = [i for i in range(count) if out[i] is None]
    for draw in range(DRAWS):
        if not todo:
            break
        if draw == 0 and drawn is not None:
            mobility, locked = (drawn[0][todo], drawn[1][todo])
        else:
            mobility, locked = joint_verdicts(links, [candidates[i] for i in todo],
                                              kinds=[each[i] for i in todo], draw=draw)
        left = []
        for i, free, stuck in zip(todo, mobility, locked):
            if free == dof and not stuck:
                out[i] = None                             # proven by the evaluation
                continue
            reason = decide(links, candidates[i], each[i], independent=free == dof)
            if reason == _UNDECIDED:
                left.append(i)
                # what every evaluation so far says, should none admit it
                out[i] = "mobility" if free != dof else "locked"
            else:
                out[i] = reason
        todo = left
    return out
