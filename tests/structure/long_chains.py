"""Long chains whose rigid sub-chains are known by construction (tests and
tests/data/make_long_chains.py)."""

import itertools
import random

from chaingraph.model.chain import Chain, Joint


def _chain(name, pairs, kinds=None):
    kinds = kinds or "R" * len(pairs)
    return Chain(name, tuple(Joint(f"J{i}", k, (f"L{a}", f"L{b}"))
                             for i, ((a, b), k) in enumerate(zip(pairs, kinds))))


def ladder_pairs(links):
    """A ladder of four-bar loops: links ``0, 2, 4...`` on one side, ``1, 3, 5...`` on
    the other, each pair a rung. F = 1 for any even number of links, and no rigid part
    (every part of a ladder of loops is a ladder of loops, or has a free end)."""
    pairs = [(i, i + 1) for i in range(0, links, 2)]
    pairs += [(i, i + 2) for i in range(links - 2)]
    return pairs


def ladder(links=100):
    """A chain of ``links // 2 - 1`` four-bar loops in a row: F = 1, not degenerate."""
    return _chain(f"ladder of four-bar loops ({links} links)", ladder_pairs(links))


def k23_pairs(hub, first):
    """A K(2,3) of five links (six pins, F = 0, no triangle) whose link ``hub`` is given
    and the four others are ``first`` ... ``first + 3``."""
    x1, x2, y1, y2, y3 = hub, first, first + 1, first + 2, first + 3
    return [(x, y) for x in (x1, x2) for y in (y1, y2, y3)]


def buried_k23(links=100, at=47):
    """A ladder of ``links - 4`` links with a K(2,3) sharing its link ``at``: F = 1, and the
    K(2,3) is the one minimal rigid sub-chain (a part meeting both shares one link, so
    its mobility is the sum of the two parts', each positive unless it is all of the
    K(2,3) or one link)."""
    base = links - 4
    chain = _chain(f"ladder with a buried K(2,3) ({links} links)",
                   ladder_pairs(base) + k23_pairs(at, base))
    rigid = tuple(f"L{i}" for i in sorted([at, base, base + 1, base + 2, base + 3]))
    return chain, rigid


def random_dyads(links=100, *, seed=0, sliding=10, triangle=False):
    """A four-bar grown by binary dyads (two links, three pins) hung on two different
    links chosen at random, ``sliding`` of the pins made sliding pairs: F = 1 and no
    rigid part (a dyad on two links adds 0 to the mobility of a part holding all three,
    and more to any other), so not degenerate. With ``triangle``, a last dyad is hung
    on both ends of one link: that dyad and link are the one minimal rigid sub-chain.
    Returns the chain, shuffled, and its rigid sub-chains."""
    rng = random.Random(seed)
    pairs = [(0, 1), (1, 2), (2, 3), (3, 0)]
    n = 4
    while n + 2 <= links - 2 * triangle:
        u, v = rng.sample(range(n), 2)
        pairs += [(u, n), (n, n + 1), (n + 1, v)]
        n += 2
    rigid = []
    if triangle:
        u = rng.randrange(n)
        pairs += [(u, n), (n, n + 1), (n + 1, u)]
        rigid = [tuple(f"L{i}" for i in sorted([u, n, n + 1]))]
        n += 2
    kinds = ["R"] * len(pairs)
    for i in rng.sample(range(len(pairs)), sliding):
        kinds[i] = "P"
    order = list(range(len(pairs)))
    rng.shuffle(order)
    chain = _chain(f"random dyads ({n} links)", [pairs[i] for i in order],
                   [kinds[i] for i in order])
    return chain, rigid


def hub_on_grid(k):
    """A hub link pinned to every node link of a 2-by-k grid, whose edges are binary
    links: each cycle of the grid with the hub is a minimal rigid set (F = 0, every
    part of it a path with the hub, F >= 1), and there are no others: k choose 2 of
    them, one per pair of rungs; the whole chain is one rigid region."""
    nodes = [(r, c) for r in range(2) for c in range(k)]
    joints = [Joint(f"H{_node(p)}", "R", ("hub", _node(p))) for p in nodes]
    for i, (p, q) in enumerate(_grid_edges(k)):
        joints += [Joint(f"A{i}", "R", (_node(p), f"y{i}")),
                   Joint(f"B{i}", "R", (f"y{i}", _node(q)))]
    return Chain(f"hub on a 2x{k} grid", tuple(joints))


def _node(p):
    return f"x{p[0]}{p[1]}"


def _grid_edges(k):
    """The rungs, then the rows' edges, of a 2-by-k grid."""
    return ([((0, c), (1, c)) for c in range(k)]
            + [((r, c), (r, c + 1)) for r in range(2) for c in range(k - 1)])


def hub_cycles(k):
    """The minimal rigid sets of :func:`hub_on_grid`, by construction: the hub and
    the cycle between rungs i < j (its node links and edge links)."""
    edges = _grid_edges(k)
    out = set()
    for i, j in itertools.combinations(range(k), 2):
        cycle = [e for e, (p, q) in enumerate(edges)
                 if (p[1] == q[1] and p[1] in (i, j)) or (p[1] != q[1] and i <= p[1] < j)]
        out.add(frozenset(["hub"] + [_node((r, c)) for r in range(2) for c in range(i, j + 1)]
                          + [f"y{e}" for e in cycle]))
    return out
