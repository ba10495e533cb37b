"""Rigid sub-chains: the test for degenerate (partly locked) chains.

A sub-chain is a set S of links with the joints among them: a joint of k links of
which k_S are in S joins them as k_S - 1 binary equivalents. Its own Kutzbach mobility
is ``f(S) = d (|S| - 1) - sum over joints of w (k_S - 1)`` (the sum over joints with
``k_S >= 1``), with d = 3 in plane motion (6 in space) and ``w = d - f`` the pair's
constraints; joints on the same links are one joint whose constraints add. S is
*rigid* when ``f(S) <= 0``. A chain is degenerate when a proper sub-chain (at least two
links, not all of them) is rigid: part of it is a structure and the rest has more
freedom than the count says. What is reported is the family of *minimal* rigid proper
sub-chains: rigid, with no rigid sub-chain of two links or more inside.

Facts used (all of them follow from the definition; ``g = d (|S| - 1) - f`` counts
constraints):

1. ``f`` is submodular on sets that meet: ``f(A | B) + f(A & B) <= f(A) + f(B)`` when
   ``A & B`` is not empty (``g`` adds ``w (k_S - 1)`` per joint, and ``max(k - 1, 0)``
   of the links a set holds of a joint is supermodular).
2. A minimal rigid set S is connected (two parts that no joint joins have
   ``f(S) = f(S1) + f(S2) + d``, so one part would be rigid already), and every link
   ``x`` of S bears ``delta_S(x) >= d + 1`` constraints from joints it shares with the
   rest of S when ``|S| >= 3`` (``f(S) = f(S - x) + d - delta_S(x)``, and
   ``f(S - x) >= 1``); two links are a minimal rigid set when the joints between them
   bear ``d`` constraints or more.
3. If S is minimal rigid, ``T <= S <= B`` with ``|T| >= 2``, and M minimises ``f``
   over the sets between T and B, then ``S <= M``: ``f(S & M) <= f(S) + f(M) -
   f(S | M) <= f(S)`` since ``S | M`` is between T and B, so ``S & M`` is a rigid part
   of S of two links or more, hence S itself.
4. The least minimiser of ``f`` over the sets between T and B is a minimum cut
   (Picard-Ratliff): ``f(S) + d`` is ``d |S|`` less ``w`` for each binary joint held
   whole (the product of two link variables) and ``w (k_S - 1)`` for each multiple one
   (one auxiliary node per joint, the pin as a body of its own, as in Whiteley's
   body-and-pin count); every term is a cut term, and the links the source reaches in
   the residual network of a maximum flow are the least minimiser.

Method: rigid pairs are read off the joints. Larger minimal rigid sets are enumerated
by a binary partition over connected link sets, each set from its first link r in
chain order: a node holds links T kept and links B allowed (``T <= S <= B`` for every
set it may still yield), T with no rigid part. At a node, B shrinks to the least
minimiser over ``[T, B]`` (fact 3; a minimum above 0 ends the node) and loses the links
that bear at most d constraints within B (fact 2). Each link y of B joined to T is then
classified by the sets through y inside ``T + y`` (minimum cuts over ``[{y, z}, T + y]``
for each z of T joined to y): ``T + y`` has a rigid proper part (y is dropped from B),
is itself minimal rigid (reported; dropped), or has no rigid part (a child node with y,
and y dropped from B after it). Every minimal rigid set is yielded exactly once (the
partition is by inclusion of one link at a time, and nothing cut away can hold one), so
the answer is the one of the exhaustive search over all ``2**L`` link sets,
:func:`rigid_subchains_by_subsets`, kept as the reference the tests compare against.

Each node costs a few maximum flows on a network of the links and multiple joints
(polynomial). The number of nodes is not: minimal rigid sets can be exponentially many
(a link pinned to every node of a grid of links, joined by binary links, makes one with
each cycle of the grid), so no method lists them all in polynomial time. For a chain
whose rigid parts are few and small the pruning ends most nodes at once (a 100-link
chain of four-bar loops, with or without a rigid part buried in it, takes a fraction of
a second); where many link sets extend to rigid sets that are not minimal (a heavily
overconstrained part with loose links round it), it may visit many nodes per set found. A search past
``MAX_FLOWS`` maximum flows (about a minute) hands a chain small enough for the scan
(``MAX_LINKS`` links) to the scan, so that no chain the scan took is refused, and refuses
a larger one with the count it reached.
"""

from __future__ import annotations

from collections import deque

import numpy as np

from chaingraph.errors import ChainStructureError

__all__ = ["rigid_subchains", "rigid_subchains_by_subsets", "subchain_mobility",
           "MAX_LINKS", "MAX_FLOWS"]

#: links the exhaustive reference search takes at most
MAX_LINKS = 26
#: subset-joint pairs evaluated at once (bounds the memory: 8 bytes each)
_BLOCK_CELLS = 1 << 23
#: subset-joint pairs the exhaustive search may take in all (under a minute here)
MAX_WORK = 1 << 31
#: maximum flows the enumeration may run (about a minute); more is refused
MAX_FLOWS = 40_000
_DEAD, _SPARSE, _MINIMAL = 0, 1, 2


def _incidence(chain):
    """Link index, d, and the joints as (link mask, constraint weight), joints that join
    the same links merged (their weights add: a bundle of parallel joints costs one)."""
    index = {name: i for i, name in enumerate(chain.links)}
    d = 3 if chain.space == "planar" else 6
    merged = {}
    for j in chain.joints:
        mask = sum(1 << index[x] for x in j.links)
        merged[mask] = merged.get(mask, 0) + d - j.pair.freedom(chain.space)
    return index, d, merged


def subchain_mobility(chain, links) -> int:
    """Kutzbach mobility of the sub-chain made of ``links`` and the joints among them.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> watt = chaingraph.load(catalog_path("watt-six-bar-chain"))
    >>> subchain_mobility(watt, watt.links)
    1
    """
    index, d, merged = _incidence(chain)
    return _Links(len(index), d, merged).mobility(sum(1 << index[x] for x in links))


def _bits(mask):
    """The indices of the set bits of ``mask``, lowest first."""
    out = []
    while mask:
        low = mask & -mask
        out.append(low.bit_length() - 1)
        mask ^= low
    return out


class _MaxFlow:
    """Dinic's maximum flow on a small network; :meth:`source_side` is the least
    minimum cut's source side."""

    def __init__(self, nodes):
        self.head = [[] for _ in range(nodes)]
        self.to, self.cap = [], []

    def edge(self, u, v, cap):
        self.head[u].append(len(self.to))
        self.to.append(v)
        self.cap.append(cap)
        self.head[v].append(len(self.to))
        self.to.append(u)
        self.cap.append(0)

    def _levels(self, s):
        level = [-1] * len(self.head)
        level[s] = 0
        todo = deque([s])
        while todo:
            u = todo.popleft()
            for e in self.head[u]:
                if self.cap[e] > 0 and level[self.to[e]] < 0:
                    level[self.to[e]] = level[u] + 1
                    todo.append(self.to[e])
        return level

    def _push(self, s, t, level):
        """One blocking flow, by depth-first paths that keep to the levels."""
        head, to, cap = self.head, self.to, self.cap
        nxt = [0] * len(head)
        pushed = 0
        while True:
            path, u = [], s
            while u != t:
                for k in range(nxt[u], len(head[u])):
                    e = head[u][k]
                    if cap[e] > 0 and level[to[e]] == level[u] + 1:
                        nxt[u] = k
                        path.append(e)
                        u = to[e]
                        break
                else:
                    nxt[u] = len(head[u])
                    level[u] = -1            # a dead end: no path on through u
                    if not path:
                        return pushed
                    e = path.pop()
                    u = to[e ^ 1]
                    nxt[u] += 1
            amount = min(cap[e] for e in path)
            for e in path:
                cap[e] -= amount
                cap[e ^ 1] += amount
            pushed += amount

    def source_side(self, s, t):
        while True:
            level = self._levels(s)
            if level[t] < 0:
                return [x >= 0 for x in level]
            self._push(s, t, level)


class _Links:
    """A chain as masks: links are bits, a joint is (mask, constraints)."""

    def __init__(self, n, d, merged):
        self.n, self.d = n, d
        self.joints = list(merged.items())
        self.at = [[] for _ in range(n)]          # joints on each link
        self.near = [0] * n                       # links sharing a joint with each link
        for k, (mask, _) in enumerate(self.joints):
            for x in _bits(mask):
                self.at[x].append(k)
                self.near[x] |= mask & ~(1 << x)
        self.flows = 0

    def mobility(self, s):
        held = sum(w * (c - 1) for mask, w in self.joints if (c := (mask & s).bit_count()) > 1)
        return self.d * (s.bit_count() - 1) - held

    def bearing(self, x, s):
        """Constraints on link ``x`` from joints it shares with links of ``s``."""
        return sum(self.joints[k][1] for k in self.at[x] if self.joints[k][0] & s & ~(1 << x))

    def least_minimiser(self, keep, allowed):
        """The least set S with ``keep <= S <= allowed`` of least mobility (fact 4)."""
        self.flows += 1
        if self.flows > MAX_FLOWS:
            raise _TooMany
        links = _bits(allowed)
        node = {x: i + 2 for i, x in enumerate(links)}
        unary = {x: self.d for x in links}
        terms, extra = [], 0
        for mask, w in self.joints:
            inside = _bits(mask & allowed)
            if len(inside) == 2:              # -w x_u x_v = -w x_u + w x_u (1 - x_v)
                unary[inside[0]] -= w
                terms.append((node[inside[0]], node[inside[1]], w))
            elif len(inside) > 2:             # an auxiliary node y: w y - w sum x + cuts
                aux = 2 + len(links) + extra
                extra += 1
                terms.append((aux, 1, w))
                for x in inside:
                    unary[x] -= w
                    terms.append((node[x], aux, w))
        flow = _MaxFlow(2 + len(links) + extra)
        big = 1 + sum(abs(c) for c in unary.values()) + sum(t[2] for t in terms)
        for x in links:
            if keep >> x & 1:
                flow.edge(0, node[x], big)
            if unary[x] > 0:
                flow.edge(node[x], 1, unary[x])
            elif unary[x] < 0:
                flow.edge(0, node[x], -unary[x])
        for u, v, w in terms:
            flow.edge(u, v, w)
        side = flow.source_side(0, 1)
        return sum(1 << x for x in links if side[node[x]])

    def peel(self, allowed, keep):
        """``allowed`` less the links that bear at most d constraints within it, again
        and again (fact 2); None when one of ``keep`` goes."""
        todo = deque(_bits(allowed))
        while todo:
            x = todo.popleft()
            if allowed >> x & 1 and self.bearing(x, allowed) <= self.d:
                if keep >> x & 1:
                    return None
                allowed &= ~(1 << x)
                todo.extend(_bits(self.near[x] & allowed))
        return allowed

    def status(self, kept, y):
        """Whether ``kept + y`` (``kept`` with no rigid part) has a rigid proper part
        (_DEAD), is minimal rigid (_MINIMAL) or has no rigid part (_SPARSE)."""
        whole = kept | 1 << y
        through = _bits(self.near[y] & kept)
        rigid = False
        for z in through:
            m = self.least_minimiser(1 << y | 1 << z, whole)
            if self.mobility(m) <= 0:
                if m != whole:
                    return _DEAD
                rigid = True
        if not rigid:
            return _SPARSE
        if self.mobility(whole) < 0:     # a rigid part of higher mobility may hide inside
            for u in _bits(kept):
                for z in through:
                    if z != u and self.mobility(
                            self.least_minimiser(1 << y | 1 << z, whole & ~(1 << u))) <= 0:
                        return _DEAD
        return _MINIMAL

    def grow(self, kept, allowed, found):
        """Add to ``found`` every minimal rigid set S of three links or more with
        ``kept <= S <= allowed`` (``kept`` connected, with no rigid part)."""
        status = {}
        while True:
            allowed = self.reach(kept, allowed)
            if kept.bit_count() >= 2:
                allowed = self.least_minimiser(kept, allowed)
                if self.mobility(allowed) > 0:
                    return
            allowed = self.peel(allowed, kept)
            if allowed is None:
                return
            ends = _bits(allowed & ~kept & self._around(kept))
            open_ = []
            for y in ends:
                if y not in status:
                    status[y] = (self._pair_status(kept, y) if kept.bit_count() == 1
                                 else self.status(kept, y))
                if status[y] == _MINIMAL:
                    found.add(kept | 1 << y)
                if status[y] != _SPARSE:
                    allowed &= ~(1 << y)
                else:
                    open_.append(y)
            if not open_:
                return
            if len(open_) == len(ends):
                y = max(open_, key=lambda y: (self.bearing(y, kept), -y))
                self.grow(kept | 1 << y, allowed, found)
                allowed &= ~(1 << y)

    def reach(self, start, allowed):
        """The links of ``allowed`` that joints within it connect to ``start`` (a
        connected set S with ``start <= S <= allowed`` lies within them)."""
        seen, todo = start, start
        while todo:
            grown = self._around(todo) & allowed & ~seen
            seen |= grown
            todo = grown
        return seen

    def _around(self, s):
        out = 0
        for x in _bits(s):
            out |= self.near[x]
        return out

    def _pair_status(self, x, y):
        """Two links: a rigid pair is reported on its own (_DEAD here), else _SPARSE."""
        return _DEAD if self.mobility(x | 1 << y) <= 0 else _SPARSE


class _TooMany(Exception):
    pass


def rigid_subchains(chain) -> list[tuple[str, ...]]:
    """The smallest rigid proper sub-chains of a chain.

    Parameters
    ----------
    chain : Chain

    Returns
    -------
    list of tuple of str
        The inclusion-minimal sets of at least two links, not the whole chain, whose
        own mobility is <= 0; links in chain order, sets smallest first (sets of one
        size in the order of their last link, then the one before...).

    Raises
    ------
    ChainStructureError
        When the search would run more than ``MAX_FLOWS`` maximum flows on a chain
        too large for the exhaustive scan (a chain with a great many rigid parts; see
        the module's text).

    Examples
    --------
    A four-bar with a triangle of links hung on it is degenerate:

    >>> from chaingraph.model.chain import Chain, Joint
    >>> R = lambda i, a, b: Joint(i, "R", (a, b))
    >>> c = Chain("x", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "4"),
    ...                 R("D", "4", "1"), R("E", "2", "5"), R("F", "5", "6"),
    ...                 R("G", "6", "2")))
    >>> rigid_subchains(c)
    [('2', '5', '6')]
    """
    index, d, merged = _incidence(chain)
    n = len(index)
    links = _Links(n, d, merged)
    full = (1 << n) - 1
    found = {a | b for a in (1 << x for x in range(n)) for b in (1 << y for y in range(n))
             if a < b and links.near[a.bit_length() - 1] & b and links.mobility(a | b) <= 0}
    try:
        allowed = links.peel(full, 0)
        for r in _bits(allowed):
            links.grow(1 << r, allowed & ~((1 << r) - 1), found)
    except _TooMany:
        if n <= MAX_LINKS and (1 << n) * max(1, len(merged)) <= MAX_WORK:
            return rigid_subchains_by_subsets(chain)      # small enough to scan
        raise ChainStructureError(
            f"the rigid sub-chain search ran {MAX_FLOWS:,} maximum flows and found "
            f"{len(found):,} minimal rigid sub-chains without finishing: this chain has "
            "too many rigid parts to list", chain=chain.name) from None
    found.discard(full)
    return [tuple(chain.links[i] for i in _bits(s))
            for s in sorted(found, key=lambda s: (s.bit_count(), s))]


def _mobility(subsets, d, masks, weights):
    size = np.bitwise_count(subsets).astype(np.int64)
    k = np.bitwise_count(subsets[:, None] & masks[None, :]).astype(np.int64)
    constraint = (np.maximum(k - 1, 0) * weights[None, :]).sum(axis=1)
    return d * (size - 1) - constraint


def rigid_subchains_by_subsets(chain) -> list[tuple[str, ...]]:
    """:func:`rigid_subchains` by evaluating every set of links: the reference.

    Every subset of links is a bit mask; all ``2**L`` masks are evaluated at once with
    numpy (joint incidence by ``bitwise_and``, link counts by ``bitwise_count``), in
    blocks of ``2**20``. The inclusion-minimal rigid sets are then picked smallest
    first: a rigid set is minimal unless it contains one already picked.

    Raises
    ------
    ChainStructureError
        For a chain of more than ``MAX_LINKS`` links, or more than ``MAX_WORK``
        subset-joint checks.

    Examples
    --------
    >>> from chaingraph.model.chain import Chain, Joint
    >>> R = lambda i, a, b: Joint(i, "R", (a, b))
    >>> c = Chain("x", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "4"),
    ...                 R("D", "4", "1"), R("E", "2", "5"), R("F", "5", "6"),
    ...                 R("G", "6", "2")))
    >>> rigid_subchains_by_subsets(c) == rigid_subchains(c)
    True
    """
    n_links = len(chain.links)
    if n_links > MAX_LINKS:
        raise ChainStructureError(
            f"the exhaustive rigid sub-chain search takes chains of at most {MAX_LINKS} "
            f"links; this one has {n_links}", chain=chain.name)
    _, d, merged = _incidence(chain)
    masks = np.array(list(merged), dtype=np.int64)
    weights = np.array(list(merged.values()), dtype=np.int64)
    total = 1 << n_links
    if total * max(1, len(masks)) > MAX_WORK:
        raise ChainStructureError(
            f"the exhaustive rigid sub-chain search: {n_links} links and {len(masks)} "
            f"distinct joints make {total * len(masks):.2g} subset-joint checks, more "
            f"than the {MAX_WORK:.2g} it may take (about a minute)", chain=chain.name)
    full = total - 1
    found = []
    block = max(1, _BLOCK_CELLS // max(1, len(masks)))
    for start in range(0, total, block):
        subsets = np.arange(start, min(total, start + block), dtype=np.int64)
        mob = _mobility(subsets, d, masks, weights)
        rigid = (mob <= 0) & (np.bitwise_count(subsets) >= 2) & (subsets != full)
        found.append(subsets[rigid].astype(np.uint32))     # 26 links fit in 32 bits
    candidates = np.concatenate(found).astype(np.int64) if found else np.zeros(0, np.int64)
    order = np.lexsort((candidates, np.bitwise_count(candidates)))
    candidates = candidates[order]
    minimal = []
    while candidates.size:
        s = candidates[0]
        minimal.append(int(s))
        candidates = candidates[(candidates & s) != s]
    return [tuple(name for i, name in enumerate(chain.links) if s >> i & 1) for s in minimal]
