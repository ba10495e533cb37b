"""Rigid sub-chains: the test for degenerate (partly locked) chains.

A sub-chain is a set S of links with the joints among them: a joint of k links of
which k_S are in S joins them as k_S - 1 binary equivalents. Its own Kutzbach mobility
is ``d (|S| - 1) - sum over joints of (d - f) (k_S - 1)`` with d = 3 in plane motion
(6 in space) and f the pair's relative freedom. S is rigid when that is <= 0. A chain
is degenerate when a proper sub-chain (at least two links, not all of them) is rigid:
part of it is a structure and the rest has more freedom than the count says.

Method: every subset of links is a bit mask; all 2**L masks are evaluated at once with
numpy (joint incidence by ``bitwise_and``, link counts by ``bitwise_count``), in blocks
of 2**20. This is exact, finds rigid sets of any shape (a triangle, or a K(2,3) of five
links and six joints with no triangle), and takes well under a millisecond for twelve
links. The cost doubles with each link, so chains of more than ``MAX_LINKS`` links are
refused rather than left to run for hours. The inclusion-minimal rigid sets are then
picked smallest first: a rigid set is minimal unless it contains one already picked.
"""

from __future__ import annotations

import numpy as np

from chaingraph.errors import ChainStructureError

__all__ = ["rigid_subchains", "subchain_mobility", "MAX_LINKS"]

MAX_LINKS = 26
#: subset-joint pairs evaluated at once (bounds the memory: 8 bytes each)
_BLOCK_CELLS = 1 << 23
#: subset-joint pairs a search may take in all (under a minute here); more is refused
MAX_WORK = 1 << 31


def _incidence(chain):
    """Link index, d, and the joints as (link mask, constraint weight), joints that join
    the same links merged (their weights add: a bundle of parallel joints costs one)."""
    index = {name: i for i, name in enumerate(chain.links)}
    d = 3 if chain.space == "planar" else 6
    merged = {}
    for j in chain.joints:
        mask = sum(1 << index[x] for x in j.links)
        merged[mask] = merged.get(mask, 0) + d - j.pair.freedom(chain.space)
    masks = np.array(list(merged), dtype=np.int64)
    weights = np.array(list(merged.values()), dtype=np.int64)
    return index, d, masks, weights


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
    index, d, masks, weights = _incidence(chain)
    s = sum(1 << index[x] for x in links)
    return int(_mobility(np.array([s], dtype=np.int64), d, masks, weights)[0])


def _mobility(subsets, d, masks, weights):
    size = np.bitwise_count(subsets).astype(np.int64)
    k = np.bitwise_count(subsets[:, None] & masks[None, :]).astype(np.int64)
    constraint = (np.maximum(k - 1, 0) * weights[None, :]).sum(axis=1)
    return d * (size - 1) - constraint


def rigid_subchains(chain) -> list[tuple[str, ...]]:
    """The smallest rigid proper sub-chains of a chain.

    Parameters
    ----------
    chain : Chain

    Returns
    -------
    list of tuple of str
        The inclusion-minimal sets of at least two links, not the whole chain, whose
        own mobility is <= 0; links in chain order, sets smallest first.

    Raises
    ------
    ChainStructureError
        For a chain of more than ``MAX_LINKS`` links.

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
    n_links = len(chain.links)
    if n_links > MAX_LINKS:
        raise ChainStructureError(
            f"the rigid sub-chain search is exhaustive over link sets and takes chains of "
            f"at most {MAX_LINKS} links; this one has {n_links}", chain=chain.name)
    _, d, masks, weights = _incidence(chain)
    total = 1 << n_links
    if total * max(1, len(masks)) > MAX_WORK:
        raise ChainStructureError(
            f"the rigid sub-chain search is exhaustive over link sets: {n_links} links and "
            f"{len(masks)} distinct joints make {total * len(masks):.2g} subset-joint "
            f"checks, more than the {MAX_WORK:.2g} it may take (about a minute)",
            chain=chain.name)
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
