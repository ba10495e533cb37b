"""Random chains, for property tests and benchmarks.

Like networkx's graph generators: plain functions that return a new chain from a few
numbers and a seed.
"""

from __future__ import annotations

import random

from chaingraph.model.chain import Chain, Joint

__all__ = ["random_chain"]


def random_chain(links: int, joints: int | None = None, *, ternary: int = 0,
                 sliding: int = 0, seed: int | random.Random | None = None) -> Chain:
    """A random connected chain of R and P joints.

    Parameters
    ----------
    links : int
        Number of links (at least 2).
    joints : int, optional
        Number of binary-joint equivalents J; by default ``3 * links // 2 - 2`` (the
        one-degree-of-freedom count, rounded down), at least ``links - 1``.
    ternary : int
        How many of the joints are ternary (each counts as two binary equivalents).
    sliding : int
        How many binary joints are P joints (guide on a random side).
    seed : int or random.Random, optional

    Returns
    -------
    Chain
        A connected chain: links ``"L0"``, ``"L1"``...; joints ``"J0"``, ``"J1"``...
        It may be degenerate or locked: nothing but connectivity is promised.

    Examples
    --------
    >>> c = random_chain(8, seed=1)
    >>> len(c.links), sum(j.order - 1 for j in c.joints)
    (8, 10)
    """
    rng = seed if isinstance(seed, random.Random) else random.Random(seed)
    if links < 2:
        raise ValueError("a chain needs at least two links")
    if joints is None:
        joints = max(links - 1, 3 * links // 2 - 2)
    names = [f"L{i}" for i in range(links)]
    order = names[:]
    rng.shuffle(order)
    groups = []
    for i in range(1, links):          # a random spanning tree keeps the chain connected
        groups.append([order[i], order[rng.randrange(i)]])
    count = links - 1
    while count < joints:
        size = 3 if ternary > 0 and count + 2 <= joints and links >= 3 else 2
        ternary -= size == 3
        groups.append(rng.sample(names, size))
        count += size - 1
    rng.shuffle(groups)
    binary = [i for i, g in enumerate(groups) if len(g) == 2]
    slides = set(rng.sample(binary, min(sliding, len(binary))))
    result = []
    for i, g in enumerate(groups):
        if i in slides:
            result.append(Joint(f"J{i}", "P", tuple(rng.sample(g, 2))))
        else:
            result.append(Joint(f"J{i}", "R", tuple(g)))
    return Chain(f"random chain ({links} links)", tuple(result))
