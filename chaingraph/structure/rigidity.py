"""Rigid sub-chains: the test for degenerate (partly locked) chains.

A sub-chain is a set S of links with the joints among them: a joint of k links of
which k_S are in S joins them as k_S - 1 binary equivalents. Its own Kutzbach mobility
is ``f(S) = d (|S| - 1) - sum over joints of w (k_S - 1)`` (the sum over joints with
``k_S >= 1``), with d = 3 in plane motion (6 in space) and ``w = d - f`` the pair's
constraints; joints on the same links are one joint whose constraints add. S is
*rigid* when ``f(S) <= 0``. A chain is degenerate when a proper sub-chain (at least two
links, not all of them) is rigid: part of it is a structure and the rest has more
freedom than the count says. The *smallest* rigid sub-chains are the minimal rigid
proper sub-chains: rigid, with no rigid sub-chain of two links or more inside.

Three answers are given (:func:`rigid_parts`), the first two always in polynomial
time, a few maximum flows per link:

* whether the chain is degenerate, with one smallest rigid sub-chain as the witness
  (:func:`one_rigid_subchain`);
* its rigid regions (:func:`rigid_regions`): the largest sets of links that are rigid
  as one body, every smallest rigid sub-chain inside one of them;
* the list of every smallest rigid sub-chain (:func:`rigid_subchains`), by a search
  whose cost cannot be polynomial (there can be exponentially many), so
  :func:`rigid_parts` bounds it by a budget of work and says when it stopped short.

Facts used (all of them follow from the definition; ``g = d (|S| - 1) - f`` counts
constraints, and the links are numbered 0 ... n - 1 in chain order):

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
4. The sets of least ``f`` between T and B are the minimum cuts of a network
   (Picard-Ratliff): ``f(S) + d`` is ``d |S|`` less ``w`` for each binary joint held
   whole (the product of two link variables) and ``w (k_S - 1)`` for each multiple one
   (one auxiliary node per joint, the pin as a body of its own, as in Whiteley's
   body-and-pin count); every term is a cut term. After a maximum flow, the links the
   source reaches in the residual network are the least minimiser; the links that
   cannot reach the sink, the greatest.
5. *Is there a rigid set?* Let ``G_y`` be the greatest minimiser of ``f`` over the sets
   between ``{y}`` and ``P_y = {0, ..., y}``. A rigid set whose last link is y exists
   exactly when ``G_y`` has two links or more: ``f({y}) = 0``, so the least value is
   at most 0 and a minimiser other than ``{y}`` is rigid; a rigid set with last link y
   has a value at most 0, so it is a minimiser and lies in ``G_y``. Sweeping y = 0, 1,
   ... to the first such y (n flows at most) finds a rigid set ``G = G_y``, and every
   rigid set inside ``P_y`` holds y. If G is not the whole chain, the chain is
   degenerate. If it is (then y = n - 1), the chain is degenerate exactly when for
   some link x before y the greatest minimiser between ``{y}`` and all links but x has
   two links or more, since a proper rigid set misses some x (n - 1 flows more).
6. *One smallest rigid set* (polynomial): start from a rigid set S of fact 5 (every
   rigid set inside it holds y) and try each other link x of S once: when the greatest
   minimiser between ``{y}`` and ``S - x`` has two links or more, S becomes it. After
   the pass S is minimal: a link x still in S lies in every rigid set inside S (there
   was none inside ``S - x`` when x was tried, and S has only shrunk since), so a rigid
   part of S of two links or more is all of S. At most ``|S|`` flows.
7. *Rigid regions.* Call S (two links or more) a *body* when ``f(S) <= sum f(S_i)``
   for every partition of S into parts ``S_i``: however S is cut, the constraints across
   the cut hold the parts together (``g(S) - sum g(S_i) >= d (p - 1)`` for p parts,
   Tay's count for a body-and-bar framework to be rigid). A body is rigid (the parts
   single links, f 0 each). A rigid set need not be a body, nor need two rigid sets that
   share a link have a rigid union: two links pinned twice (f = -1) with a third link
   pinned once to one of them is rigid (f = 0) although the third link turns, and with
   a fourth link pinned likewise the four have f = 1. Bodies behave:

   a. A minimal rigid set is a body: its parts are single links (f = 0) or proper
      parts of two links or more (f >= 1), and ``f(S) <= 0``.
   b. Two bodies A and B that share a link have a body as their union. Take a
      partition of ``A | B``, and let ``U_1 ... U_a`` be its parts that meet A. Adding
      them to A one at a time, fact 1 (each meets what is there already, in
      ``U_i & A``) gives ``f(A | U_1 | ... | U_a) <= f(A) + sum (f(U_i) - f(U_i & A))
      <= sum f(U_i)``, since the ``U_i & A`` partition the body A: merging the parts
      that meet a body into one does not raise the sum. Merge the parts meeting A, then
      those meeting B (the merged part is one of them, through ``A & B``): one part is
      left, ``A | B``, and ``f(A | B) <= `` the sum over the partition.

   So the maximal bodies, the *rigid regions*, share no link, and each smallest rigid
   sub-chain lies in one (a, b). They are found by contraction. With the links
   partitioned into bodies ``B_i`` (or single links), the chain with each ``B_i`` made
   one node (a joint counted once per body it meets) has, for a set X of nodes,
   ``f'(X) = f(union of X) - sum over X of f(B_i)`` (the constraints inside the bodies
   are what is left out). Sweep the nodes as in fact 5, with ``f'``: at the first node
   y whose ``G_y`` has two nodes or more, ``G_y`` is a body of the contracted chain
   (in a partition of it, the part through y lies between ``{y}`` and ``P_y`` so has
   ``f'`` at least ``f'(G_y)``, and the other parts lie in ``P_{y-1}``, which holds no
   rigid set, so have ``f' >= 0``), and the union of its bodies is a body of the chain
   (merge the parts of a partition that meet each ``B_i``, as in b; what is left is a
   partition of the nodes, whose sum is at least ``f'(G_y) + sum f(B_i)``). It is made
   one node, in y's place, and tried again; otherwise the sweep goes on to y + 1. Each
   flow moves the sweep on or removes a node: 2 n flows at most. At the end the
   contracted chain has no rigid set, so the bodies are maximal: a body Z of the chain
   meeting two of them would, with the bodies it meets (b), make a body W whose nodes
   have ``f' = f(W) - sum f(B_i) <= 0`` (the partition of W into its ``B_i``).

Listing every smallest rigid sub-chain: rigid pairs are read off the joints. Larger
minimal rigid sets are enumerated by a binary partition over connected link sets,
within each rigid region, each set from its first link r in chain order: a node holds
links T kept and links B allowed (``T <= S <= B`` for every set it may still yield), T
with no rigid part. At a node, B shrinks to the least minimiser over ``[T, B]`` (fact
3; a minimum above 0 ends the node) and loses the links that bear at most d
constraints within B (fact 2). Each link y of B joined to T is then classified by the
sets through y inside ``T + y`` (minimum cuts over ``[{y, z}, T + y]`` for each z of T
joined to y): ``T + y`` has a rigid proper part (y is dropped from B), is itself
minimal rigid (reported; dropped), or has no rigid part (a child node with y, and y
dropped from B after it). Every minimal rigid set is yielded exactly once (the
partition is by inclusion of one link at a time, and nothing cut away can hold one), so
the answer is the one of the exhaustive search over all ``2**L`` link sets,
:func:`rigid_subchains_by_subsets`, kept as the reference the tests compare against.

Each node costs a few maximum flows (polynomial). The number of nodes is not: minimal
rigid sets can be exponentially many (a link pinned to every node of a grid of links,
joined by binary links, makes one with each cycle of the grid), so no method lists them
all in polynomial time; where many link sets extend to rigid sets that are not minimal
(a heavily overconstrained part with loose links round it) the search may also visit
many nodes per set found. :func:`rigid_parts` (what ``classify`` reports) therefore
lists only on a degenerate chain, region by region (every smallest rigid sub-chain lies
in one): a region small enough (``SCAN_CELLS`` link set and joint pairs, about a dozen
links) by the scan of its link sets, which is faster there; a larger one by the search,
within a budget of ``SEARCH_BUDGET`` work units for all of them (an arc of a flow
network scanned in a phase of a maximum flow, a joint read for a mobility or a
bearing: a count, so the answer does not depend on the machine or its load; about a
second here). When the budget runs out it returns the sets found so far, the witness of
fact 6 among them, marked incomplete; which ones those are depends on the order of the
links.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from chaingraph.errors import ChainStructureError
from chaingraph.model.chain import Chain

__all__ = ["RigidParts", "rigid_parts", "rigid_subchains", "one_rigid_subchain",
           "rigid_regions", "rigid_subchains_by_subsets", "subchain_mobility",
           "MAX_LINKS", "SEARCH_BUDGET", "SCAN_CELLS"]

#: links the exhaustive reference search takes at most
MAX_LINKS = 26
#: subset-joint pairs evaluated at once (bounds the memory: 8 bytes each)
_BLOCK_CELLS = 1 << 23
#: subset-joint pairs the exhaustive search may take in all (under a minute here)
MAX_WORK = 1 << 31
#: work units (arcs scanned by the maximum flows' phases) the listing of every smallest
#: rigid sub-chain may take in :func:`rigid_parts` (about a second here)
SEARCH_BUDGET = 1_500_000
#: link set and joint pairs up to which :func:`rigid_parts` lists by the scan (faster
#: than the search on chains of a dozen links)
SCAN_CELLS = 1 << 16
_DEAD, _SPARSE, _MINIMAL = 0, 1, 2


def _incidence(chain: Chain) -> tuple[dict[str, int], int, dict[int, int]]:
    """Link index, d, and the joints as (link mask, constraint weight), joints that join
    the same links merged (their weights add: a bundle of parallel joints costs one)."""
    index = {name: i for i, name in enumerate(chain.links)}
    d = 3 if chain.space == "planar" else 6
    merged: dict[int, int] = {}
    for j in chain.joints:
        mask = sum(1 << index[x] for x in j.links)
        merged[mask] = merged.get(mask, 0) + d - chain.freedom(j)
    return index, d, merged


def subchain_mobility(chain: Chain, links: Iterable[str]) -> int:
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


def _bits(mask: int) -> list[int]:
    """The indices of the set bits of ``mask``, lowest first."""
    out = []
    while mask:
        low = mask & -mask
        out.append(low.bit_length() - 1)
        mask ^= low
    return out


class _MaxFlow:
    """Dinic's maximum flow on a small network; :meth:`cut` gives the least or the
    greatest minimum cut's source side. ``work`` counts the arcs its phases scan."""

    def __init__(self, nodes):
        self.head: list[list[int]] = [[] for _ in range(nodes)]
        self.to, self.cap = [], []
        self.work = 0

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

    def cut(self, s, t, *, greatest=False):
        """A maximum flow, then the source side of the least minimum cut (what ``s``
        reaches in the residual network) or of the greatest (what cannot reach ``t``)."""
        while True:
            self.work += len(self.to)
            level = self._levels(s)
            if level[t] < 0:
                break
            self._push(s, t, level)
        if not greatest:
            return [x >= 0 for x in level]
        reaches = [False] * len(self.head)
        reaches[t] = True
        todo = [t]
        while todo:
            v = todo.pop()
            for e in self.head[v]:           # e runs v -> u; e ^ 1 runs u -> v
                u = self.to[e]
                if not reaches[u] and self.cap[e ^ 1] > 0:
                    reaches[u] = True
                    todo.append(u)
        return [not r for r in reaches]


class _OutOfBudget(Exception):
    pass


class _Links:
    """A chain as masks: links are bits, a joint is (mask, constraints). ``work`` adds
    up the maximum flows' work; past ``limit`` (when set) :meth:`minimiser` stops the
    search with _OutOfBudget."""

    def __init__(self, n, d, merged):
        self.n, self.d = n, d
        self.joints = list(merged.items())
        self.members = [(_bits(mask), w) for mask, w in self.joints]
        self.at: list[list[int]] = [[] for _ in range(n)]          # joints on each link
        self.near = [0] * n                       # links sharing a joint with each link
        for k, (mask, _) in enumerate(self.joints):
            for x in _bits(mask):
                self.at[x].append(k)
                self.near[x] |= mask & ~(1 << x)
        self.work, self.limit = 0, None

    def mobility(self, s):
        self.work += len(self.joints)
        held = sum(w * (c - 1) for mask, w in self.joints if (c := (mask & s).bit_count()) > 1)
        return self.d * (s.bit_count() - 1) - held

    def bearing(self, x, s):
        """Constraints on link ``x`` from joints it shares with links of ``s``."""
        self.work += len(self.at[x])
        return sum(self.joints[k][1] for k in self.at[x] if self.joints[k][0] & s & ~(1 << x))

    def minimiser(self, keep, allowed, *, greatest=False):
        """The least (or greatest) set S with ``keep <= S <= allowed`` of least
        mobility (fact 4)."""
        if self.limit is not None and self.work > self.limit:
            raise _OutOfBudget
        links = _bits(allowed)
        node = {x: i + 2 for i, x in enumerate(links)}
        unary = dict.fromkeys(links, self.d)
        terms, aux = [], 2 + len(links)
        for members, w in self.members:
            inside = [x for x in members if allowed >> x & 1]
            if len(inside) == 2:              # -w x_u x_v = -w x_u + w x_u (1 - x_v)
                unary[inside[0]] -= w
                terms.append((node[inside[0]], node[inside[1]], w))
            elif len(inside) > 2:             # an auxiliary node y: w y - w sum x + cuts
                terms.append((aux, 1, w))
                for x in inside:
                    unary[x] -= w
                    terms.append((node[x], aux, w))
                aux += 1
        flow = _MaxFlow(aux)
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
        side = flow.cut(0, 1, greatest=greatest)
        self.work += flow.work
        return sum(1 << x for x in links if side[node[x]])

    def rigid_through(self, y, allowed):
        """For ``allowed`` whose rigid sets all hold ``y`` (the callers' case, facts 5
        to 7): the greatest set of least mobility through y inside ``allowed`` when
        a rigid set lies there (then it is one, of two links or more), else 0. A
        smallest rigid set inside ``allowed`` then holds y, so y bears d constraints
        or more within ``allowed`` (fact 2): no flow is run when it bears fewer."""
        if self.bearing(y, allowed) < self.d:
            return 0
        s = self.minimiser(1 << y, allowed, greatest=True)
        return s if s.bit_count() >= 2 else 0

    def first_rigid(self):
        """(y, G) of fact 5: the first link y that ends a rigid set, and the greatest
        such set inside ``P_y``; None when no set of two links or more is rigid."""
        for y in range(self.n):
            s = self.rigid_through(y, (2 << y) - 1)
            if s:
                return y, s
        return None

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
            m = self.minimiser(1 << y | 1 << z, whole)
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
                            self.minimiser(1 << y | 1 << z, whole & ~(1 << u))) <= 0:
                        return _DEAD
        return _MINIMAL

    def grow(self, kept, allowed, found):
        """Add to ``found`` every minimal rigid set S of three links or more with
        ``kept <= S <= allowed`` (``kept`` connected, with no rigid part)."""
        status = {}
        while True:
            allowed = self.reach(kept, allowed)
            if kept.bit_count() >= 2:
                allowed = self.minimiser(kept, allowed)
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


def _contracted(groups, d, merged):
    """The chain with each group of links (a mask) made one node (fact 7)."""
    node = {}
    for i, g in enumerate(groups):
        for x in _bits(g):
            node[x] = i
    joints: dict[Any, Any] = {}
    for mask, w in merged.items():
        m = 0
        for x in _bits(mask):
            m |= 1 << node[x]
        if m.bit_count() >= 2:
            joints[m] = joints.get(m, 0) + w
    return _Links(len(groups), d, joints)


def _regions(n, d, merged):
    """The rigid regions (fact 7), link masks in order of their first link, and fact 5's
    (y, G) on the chain itself (the sweep's first find, before any contraction)."""
    groups = [1 << x for x in range(n)]
    links, first, y = _Links(n, d, merged), None, 0
    while y < len(groups):
        s = links.rigid_through(y, (2 << y) - 1)
        if not s:
            y += 1
            continue
        if first is None:
            first = (y, s)
        kept = [groups[i] for i in range(y) if not s >> i & 1]
        body = 0
        for i in _bits(s):
            body |= groups[i]
        groups = kept + [body] + groups[y + 1:]
        y = len(kept)
        links = _contracted(groups, d, merged)
    regions = sorted((g for g in groups if g.bit_count() >= 2), key=lambda g: g & -g)
    return regions, first


def _witness(links, first):
    """One minimal rigid proper set (a mask) from fact 5's (y, G), or 0 when the chain
    is not degenerate (facts 5 and 6)."""
    if first is None:
        return 0
    y, s = first
    full = (1 << links.n) - 1
    if s == full:
        s = next((g for x in range(y) if (g := links.rigid_through(y, full & ~(1 << x)))), 0)
    for x in _bits(s & ~(1 << y)):
        if s >> x & 1:
            s = links.rigid_through(y, s & ~(1 << x)) or s
    return s


def _listing(links, regions, witness, budget, *, scan):
    """The minimal rigid proper sets (masks) of a degenerate chain, region by region: by
    the scan where a region costs it at most ``SCAN_CELLS`` (when ``scan``), else by
    the search; and whether the searches ended within ``budget`` work units (None: no
    bound) in all. A search cut short keeps what it found, ``witness`` among them."""
    found, full = {witness}, (1 << links.n) - 1
    for u in range(links.n):
        for v in _bits(links.near[u] >> (u + 1) << (u + 1)):
            if links.mobility(1 << u | 1 << v) <= 0:
                found.add(1 << u | 1 << v)
    searched = []
    for region in regions:
        inside: dict[Any, Any] = {}
        for mask, w in links.joints:
            if (mask & region).bit_count() >= 2:
                inside[mask & region] = inside.get(mask & region, 0) + w
        if scan and (1 << region.bit_count()) * max(1, len(inside)) <= SCAN_CELLS:
            found |= _scan(region, links.d, inside, proper=region == full)
        else:
            searched.append(region)
    links.limit = None if budget is None else links.work + budget
    complete = True
    try:
        for region in searched:
            allowed = links.peel(region, 0)
            for r in _bits(allowed):
                links.grow(1 << r, allowed & ~((1 << r) - 1), found)
    except _OutOfBudget:
        complete = False
    links.limit = None
    found.discard(full)
    return found, complete


@dataclass(frozen=True)
class RigidParts:
    """A chain's rigid parts: whether it is degenerate, its smallest rigid sub-chains
    (all of them when ``complete``), and its rigid regions; links in chain order."""

    degenerate: bool
    smallest: tuple[tuple[str, ...], ...]
    complete: bool
    regions: tuple[tuple[str, ...], ...]


def rigid_parts(chain: Chain, *, budget: int | None = SEARCH_BUDGET) -> RigidParts:
    """Whether a chain is degenerate, its smallest rigid sub-chains and its rigid
    regions (the module's text says how, and why each is right).

    Parameters
    ----------
    chain : Chain
    budget : int or None, optional
        Work units (arcs scanned by maximum flows) the listing of every smallest rigid
        sub-chain may take; None for no bound. The verdict, the regions and one
        smallest rigid sub-chain are found whatever the budget, in polynomial time.

    Returns
    -------
    RigidParts
        ``smallest`` as :func:`rigid_subchains` gives it, or, when the listing ran out
        of budget on a chain too large to scan, the sets it had found (one at least),
        with ``complete`` False.

    Examples
    --------
    A triangle of links on a four-bar, and a dyad hung on two links of the triangle
    (rigid with it, though in no smallest rigid sub-chain):

    >>> from chaingraph.model.chain import Chain, Joint
    >>> R = lambda i, a, b: Joint(i, "R", (a, b))
    >>> c = Chain("x", (R("A", "1", "2"), R("B", "2", "3"), R("C", "3", "4"),
    ...                 R("D", "4", "1"), R("E", "2", "5"), R("F", "5", "6"),
    ...                 R("G", "6", "2"), R("H", "5", "7"), R("I", "7", "8"),
    ...                 R("K", "8", "6")))
    >>> parts = rigid_parts(c)
    >>> parts.degenerate, parts.smallest, parts.complete, parts.regions
    (True, (('2', '5', '6'),), True, (('2', '5', '6', '7', '8'),))
    """
    return _rigid_parts(chain, budget, scan=True)


def _rigid_parts(chain, budget, *, scan):
    """:func:`rigid_parts`, listing by the scan where it costs at most ``SCAN_CELLS``
    when ``scan``, else always by the search."""
    index, d, merged = _incidence(chain)
    n = len(index)
    regions, first = _regions(n, d, merged)
    links = _Links(n, d, merged)
    witness = _witness(links, first)
    found, complete = (_listing(links, regions, witness, budget, scan=scan) if witness
                       else (set(), True))
    names = lambda s: tuple(chain.links[i] for i in _bits(s))      # noqa: E731
    return RigidParts(
        degenerate=bool(witness),
        smallest=tuple(names(s) for s in sorted(found, key=lambda s: (s.bit_count(), s))),
        complete=complete, regions=tuple(names(r) for r in regions))


def rigid_subchains(chain: Chain) -> list[tuple[str, ...]]:
    """The smallest rigid proper sub-chains of a chain: all of them, however long the
    search (:func:`rigid_parts` bounds it).

    Parameters
    ----------
    chain : Chain

    Returns
    -------
    list of tuple of str
        The inclusion-minimal sets of at least two links, not the whole chain, whose
        own mobility is <= 0; links in chain order, sets smallest first (sets of one
        size in the order of their last link, then the one before...). There can be
        exponentially many (the module's text).

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
    return list(_rigid_parts(chain, None, scan=False).smallest)


def one_rigid_subchain(chain: Chain) -> tuple[str, ...] | None:
    """One smallest rigid proper sub-chain, or None when the chain is not degenerate:
    a few maximum flows per link (facts 5 and 6 of the module's text).

    Examples
    --------
    >>> from chaingraph.model.chain import Chain, Joint
    >>> R = lambda i, a, b: Joint(i, "R", (a, b))
    >>> one_rigid_subchain(Chain("x", (R("A", "1", "2"), R("B", "2", "3"),
    ...                                 R("C", "3", "4"), R("D", "4", "1"))))
    >>> one_rigid_subchain(Chain("x", (R("A", "1", "2"), R("B", "2", "3"),
    ...                                 R("C", "3", "1"), R("D", "3", "4"),
    ...                                 R("E", "4", "1"))))
    ('1', '2', '3')
    """
    index, d, merged = _incidence(chain)
    links = _Links(len(index), d, merged)
    witness = _witness(links, links.first_rigid())
    return tuple(chain.links[i] for i in _bits(witness)) or None


def rigid_regions(chain: Chain) -> list[tuple[str, ...]]:
    """The rigid regions of a chain: the largest sets of links (two or more) that are
    rigid as one body however they are cut (fact 7 of the module's text); they share no
    link, and every smallest rigid sub-chain lies in one. The whole chain is one when it
    is rigid as a body.

    Examples
    --------
    Two links pinned twice, each with a link pinned once: the pair is the region (the
    other two links turn about it, though the pair with either one counts as rigid):

    >>> from chaingraph.model.chain import Chain, Joint
    >>> R = lambda i, a, b: Joint(i, "R", (a, b))
    >>> rigid_regions(Chain("x", (R("A", "1", "2"), R("B", "1", "2"), R("C", "1", "3"),
    ...                           R("D", "1", "4"))))
    [('1', '2')]
    """
    index, d, merged = _incidence(chain)
    regions, _ = _regions(len(index), d, merged)
    return [tuple(chain.links[i] for i in _bits(r)) for r in regions]


def _mobility(subsets, d, masks, weights):
    size = np.bitwise_count(subsets).astype(np.int64)
    k = np.bitwise_count(subsets[:, None] & masks[None, :]).astype(np.int64)
    constraint = (np.maximum(k - 1, 0) * weights[None, :]).sum(axis=1)
    return d * (size - 1) - constraint


def rigid_subchains_by_subsets(chain: Chain) -> list[tuple[str, ...]]:
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
    total = 1 << n_links
    if total * max(1, len(merged)) > MAX_WORK:
        raise ChainStructureError(
            f"the exhaustive rigid sub-chain search: {n_links} links and {len(merged)} "
            f"distinct joints make {total * len(merged):.2g} subset-joint checks, more "
            f"than the {MAX_WORK:.2g} it may take (about a minute)", chain=chain.name)
    minimal = _scan(total - 1, d, merged, proper=True)
    return [tuple(name for i, name in enumerate(chain.links) if s >> i & 1)
            for s in sorted(minimal, key=lambda s: (s.bit_count(), s))]


def _scan(links, d, merged, *, proper):
    """The minimal rigid sets of two links or more within the link set ``links`` (a
    mask; not all of it when ``proper``), as masks, the joints ``merged`` taken within
    it: every subset of it evaluated at once, in blocks, then the minimal ones picked
    smallest first (a rigid set is minimal unless it holds one already picked)."""
    place = _bits(links)
    n = len(place)
    local: dict[Any, Any] = {}
    for mask, w in merged.items():
        m = sum(1 << i for i, x in enumerate(place) if mask >> x & 1)
        local[m] = local.get(m, 0) + w
    masks = np.array(list(local), dtype=np.int64)
    weights = np.array(list(local.values()), dtype=np.int64)
    total, full = 1 << n, (1 << n) - 1
    found = []
    block = max(1, _BLOCK_CELLS // max(1, len(masks)))
    for start in range(0, total, block):
        subsets = np.arange(start, min(total, start + block), dtype=np.int64)
        mob = _mobility(subsets, d, masks, weights)
        rigid = (mob <= 0) & (np.bitwise_count(subsets) >= 2)
        if proper:
            rigid &= subsets != full
        found.append(subsets[rigid].astype(np.uint32))     # 26 links fit in 32 bits
    candidates = np.concatenate(found).astype(np.int64) if found else np.zeros(0, np.int64)
    order = np.lexsort((candidates, np.bitwise_count(candidates)))
    candidates = candidates[order]
    minimal = set()
    while candidates.size:
        s = candidates[0]
        minimal.add(sum(1 << place[i] for i in _bits(int(s))))
        candidates = candidates[(candidates & s) != s]
    return minimal
