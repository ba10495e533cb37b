"""The atlas with multiple joints: every chain of N links and F degrees of freedom whose
turning pairs may each join more than two links (a compound hinge; a joint of d links
counts as d - 1 simple joints), as link-joint bipartite graphs.

The chains with a multiple joint are enumerated directly, as link-joint graphs, so that
the atlas is complete by construction. A chain's joints are fixed by its *joint
pattern*: the degrees d_j of its joints, with sum (d_j - 1) = (3 (N - 1) - F) / 2 (the
Kutzbach count) and sum d_j >= 2 N (every link on two joints or more). For each pattern
with a joint of three links or more, the joints are added one at a time in the
pattern's order (largest first), in every way on the N links, and the sets of joints
found are told apart by nauty's canonical form of their link-joint graph at each step
(:func:`~chaingraph.structure.atlas.labelling.link_joint_keys`), so each is kept once
and extended in every way. A set of joints is dropped, with everything that would
extend it, when

* some set S of two links or more holds 3 |S| - 3 rows or more, a joint counting
  2 (d_S - 1) for the d_S links of S it holds: Whiteley's count
  (:mod:`~chaingraph.structure.atlas.pins`) then proves the chain, and every chain with
  more joints, dependent (more than 3 |S| - 3: overbraced) or locked (exactly
  3 |S| - 3: S is rigid, so a weld of a joint inside it overbraces it), since adding a
  joint only adds rows. Two joints on the same two links are such a set (4 rows on 2
  links), so a pair of links is joined once at most;
* the joints its links hold beyond two each, summed, already exceed what the pattern
  leaves (sum d_j - 2 N): some link would end on fewer than two joints.

Every set of joints that completes its pattern, connected, is then decided by the
atlas's own verdict (:func:`~chaingraph.structure.atlas.admissibility.verdicts`: an
exact evaluation admits, Whiteley's count rejects); the count the search prunes by is
the one the verdict rejects by, so none is rejected there (``rejected`` counts them by
reason should one be). The chains of simple joints are the atlas's own (``base``),
found by contracted graphs. ``tests/structure/test_multiple.py`` checks the whole
against a brute force over every link-joint graph to 8 links. The inversion classes
are the orbits of the links under the link-joint graph's automorphisms.
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Hashable, Sequence
from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from chaingraph._util.disjoint import DisjointSets
from chaingraph.model.chain import Chain, Joint
from chaingraph.structure.atlas.admissibility import REASONS, verdicts
from chaingraph.structure.atlas.labelling import (
    default_backend,
    link_joint_form,
    link_joint_keys,
)
from chaingraph.structure.atlas.run import Atlas
from chaingraph.structure.atlas.sliding import Entries

__all__ = ["MultipleEntry", "MultipleAtlas", "multiple_atlas", "joint_patterns",
           "link_joint_graphs"]


@dataclass(frozen=True)
class MultipleEntry:
    """One chain with multiple joints: ``joints``, each the tuple of the (0-based)
    links it joins; ``links`` how many; its inversion classes; whether it is
    fractionated (a link or a joint whose removal splits it); ``multiple`` how many of
    its joints join three links or more."""

    id: int
    joints: tuple[tuple[int, ...], ...]
    links: int
    inversion_classes: int
    fractionated: bool = False

    @property
    def multiple(self) -> int:
        """How many of its joints join three links or more."""
        return sum(len(j) > 2 for j in self.joints)

    @property
    def degrees(self) -> tuple[int, ...]:
        """How many links each multiple joint joins, largest first."""
        return tuple(sorted((len(j) for j in self.joints if len(j) > 2), reverse=True))

    def chain(self, dof: int | None = None) -> Chain:
        """The chain (links L1..LN, joints J1..)."""
        joints = tuple(Joint(f"J{i + 1}", "R", tuple(f"L{x + 1}" for x in links))
                       for i, links in enumerate(self.joints))
        name = (f"chain {self.id} of {self.links} links" + (f", {dof} dof" if dof else "")
                + f", {self.multiple} multiple joint{'s' if self.multiple != 1 else ''}")
        return Chain(name, joints, family="atlas")

    def to_dict(self) -> dict[str, Any]:
        """The chain's record in the atlas's JSON."""
        orders: dict[int, int] = {}
        for x in range(self.links):
            k = sum(x in j for j in self.joints)
            orders[k] = orders.get(k, 0) + 1
        return {"id": self.id, "joints": [list(j) for j in self.joints],
                "link_joints": {str(k): v for k, v in sorted(orders.items())},
                "inversion_classes": self.inversion_classes}


@dataclass(frozen=True)
class MultipleAtlas(Entries):
    """The chains with multiple joints of one size (those with only simple joints
    first, in the atlas's order), and the complete link-joint graphs the verdict
    rejected, by reason."""

    links: int
    dof: int
    entries: tuple[MultipleEntry, ...]
    rejected: dict[str, int]

    @property
    def count_by_multiple(self) -> dict[int, int]:
        """Chains by how many of their joints join three links or more."""
        out: dict[int, int] = {}
        for e in self.entries:
            out[e.multiple] = out.get(e.multiple, 0) + 1
        return dict(sorted(out.items()))

    @property
    def count_by_degrees(self) -> dict[tuple[int, ...], int]:
        """Chains by the degrees of their multiple joints (a tuple, largest first;
        ``()`` for simple joints only)."""
        out: dict[tuple[int, ...], int] = {}
        for e in self.entries:
            out[e.degrees] = out.get(e.degrees, 0) + 1
        return dict(sorted(out.items(), key=lambda kv: (len(kv[0]), [-d for d in kv[0]])))


def joint_patterns(links: int, dof: int) -> list[tuple[int, ...]]:
    """The joint patterns of chains of ``links`` links and ``dof`` degrees of freedom:
    each the degrees of its joints, largest first, with the Kutzbach count of ``dof``
    and at least two joints per link by count (sum of the degrees >= 2 links).

    Examples
    --------
    >>> joint_patterns(6, 1)
    [(4, 2, 2, 2, 2), (3, 3, 2, 2, 2), (3, 2, 2, 2, 2, 2), (2, 2, 2, 2, 2, 2, 2)]
    """
    rows = 3 * (links - 1) - dof
    if rows < 0 or rows % 2:
        return []
    out: list[tuple[int, ...]] = []

    def grow(pattern: list[int], left: int) -> None:
        if not left:
            if sum(pattern) >= 2 * links:
                out.append(tuple(pattern))
            return
        for d in range(min(pattern[-1] if pattern else links, left + 1), 1, -1):
            grow(pattern + [d], left - (d - 1))
    grow([], rows // 2)
    return out


@functools.lru_cache(maxsize=64)
def _candidates(links: int, degree: int) -> tuple[list[int], np.ndarray]:
    """Every joint of ``degree`` links on ``links`` links (bit masks), and the rows it
    puts on each set of links (a row per set, sets as bit masks): 2 (d_S - 1) for the
    d_S links of S it holds."""
    masks = [sum(1 << x for x in c) for c in itertools.combinations(range(links), degree)]
    sets = np.arange(1 << links)
    held = sum(((sets[None, :] >> x) & 1) * np.array([[m >> x & 1] for m in masks])
               for x in range(links))
    return masks, (2 * np.maximum(held - 1, 0)).astype(np.int16)


@functools.lru_cache(maxsize=16)
def _capacity(links: int) -> np.ndarray:
    """The rows each set S of links may hold without a rigid or overbraced set:
    3 |S| - 4 for two links or more (no bound for fewer)."""
    size = np.array([s.bit_count() for s in range(1 << links)])
    return np.where(size >= 2, 3 * size - 4, np.iinfo(np.int16).max).astype(np.int16)


def _fractionated(links: int, joints: Sequence[int]) -> bool:
    """Whether a link or a joint (a bit mask of links) separates the link-joint graph
    (every side of it then closed: its every node is on two others or more)."""
    g = nx.Graph((links + k, x) for k, mask in enumerate(joints)
                 for x in range(links) if mask >> x & 1)
    return not nx.is_biconnected(g)


def _connected(links: int, joints: Sequence[int]) -> bool:
    parts = DisjointSets(links)
    for mask in joints:
        members = [x for x in range(links) if mask >> x & 1]
        for x in members[1:]:
            parts.join(members[0], x)
    return parts.count == 1


def link_joint_graphs(links: int, pattern: Sequence[int], *, backend: str | None = None,
                      ) -> list[tuple[int, ...]]:
    """Every connected link-joint graph on ``links`` links with joints of the degrees
    ``pattern`` (largest first) whose every link is on two joints or more and no set S
    of two links or more holds 3 |S| - 3 rows (module text), once up to isomorphism:
    each a tuple of joints as bit masks of their links (bit ``x`` for link ``x``), in
    the order of ``pattern``. ``backend``: the canonical labelling (nauty by default).

    Examples
    --------
    >>> [[bin(m) for m in g] for g in link_joint_graphs(6, (3, 3, 2, 2, 2))]
    [['0b111', '0b111000', '0b1001', '0b10010', '0b100100']]
    """
    backend = backend or default_backend()
    capacity = _capacity(links)
    spare = sum(pattern) - 2 * links                 # joints beyond two, over all links
    rows_of: dict[int, np.ndarray] = {}         # a joint's rows on each set of links
    # a set of joints: (joints, links on a joint, links on two joints or more, joints
    # beyond two over all links); its rows are summed where it is extended
    level: list[tuple[tuple[int, ...], int, int, int]] = [((), 0, 0, 0)]
    for degree in pattern:
        masks, rows = _candidates(links, degree)
        rows_of.update(zip(masks, rows))
        children: list[tuple[int, ...]] = []
        made: list[int] = []
        for k, (joints, once, twice, beyond) in enumerate(level):
            free = capacity - sum((rows_of[m] for m in joints), np.zeros_like(capacity))
            for i in np.nonzero((rows <= free).all(axis=1))[0].tolist():
                if beyond + (masks[i] & twice).bit_count() <= spare:
                    children.append(joints + (masks[i],))
                    made.append(k)
        kept: dict[Hashable, tuple[tuple[int, ...], int, int, int]] = {}
        for key, child, k in zip(link_joint_keys(links, children, backend=backend),
                                 children, made):
            if key not in kept:
                _, once, twice, beyond = level[k]
                mask = child[-1]
                kept[key] = (child, once | mask, twice | (once & mask),
                             beyond + (mask & twice).bit_count())
        level = list(kept.values())
    return [joints for joints, *_ in level if _connected(links, joints)]


def multiple_atlas(base: Atlas) -> MultipleAtlas:
    """The chains with multiple joints of the size of ``base`` (an
    :class:`~chaingraph.structure.atlas.run.Atlas`: the chains of simple joints, which
    come first), the chains with a multiple joint then by their number, their degrees
    and their canonical joints.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> six = multiple_atlas(atlas_graphs(6, 1))
    >>> six.count_by_multiple
    {0: 2, 1: 1, 2: 1}
    >>> eight = multiple_atlas(atlas_graphs(8, 1))
    >>> len(eight), eight.count_by_degrees      # doctest: +NORMALIZE_WHITESPACE
    (60, {(): 16, (4,): 2, (3,): 20, (4, 4): 1, (4, 3): 1, (3, 3): 16, (3, 3, 3): 3,
          (3, 3, 3, 3): 1})
    """
    links, dof = base.links, base.dof
    backend = getattr(base, "labelling", None) or default_backend()
    found = [graph for pattern in joint_patterns(links, dof) if pattern[0] > 2
             for graph in link_joint_graphs(links, pattern, backend=backend)]
    candidates = [tuple(tuple(x for x in range(links) if mask >> x & 1) for mask in g)
                  for g in found]
    rejected = {reason: 0 for reason in REASONS}
    admitted = []
    for graph, reason in zip(found, verdicts(links, candidates, dof=dof)):
        if reason is None:
            admitted.append(link_joint_form(links, graph, backend=backend))
        else:
            rejected[reason] += 1
    admitted.sort(key=lambda form: (sum(len(j) > 2 for j in form[0]),
                                    sorted((-len(j) for j in form[0] if len(j) > 2)),
                                    form[0]))
    entries = [MultipleEntry(i, tuple(map(tuple, e.edges)), links, e.inversion_classes,
                             bool(e.fractionated))
               for i, e in enumerate(base, start=1)]
    for joints, orbits in admitted:
        masks = [sum(1 << x for x in j) for j in joints]
        entries.append(MultipleEntry(len(entries) + 1, joints, links, orbits,
                                     _fractionated(links, masks)))
    return MultipleAtlas(links, dof, tuple(entries), rejected)
