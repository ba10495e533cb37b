"""The atlas with sliding pairs: every chain of N links and F degrees of freedom whose
simple joints are K sliding (P) pairs and the rest turning (R) pairs.

A chain with sliding pairs is a chain of the (turning-pair) atlas with K of its joints
made P. Such an assignment is admissible when the chain keeps F degrees of freedom and
no joint is locked (moves in no motion of the chain; a rigid sub-chain locks the joints
inside it). Two causes are seen in the structure of the P joints alone:

* the links' rotations are tied only by P joints (the two links of a P joint turn
  together), so a *loop of P joints only* leaves its loop's rotation equation empty:
  the chain gets one freedom more than its joints allow (rejected: ``"mobility"``);
* an R joint whose two links are joined by a path of P joints cannot turn (the path
  keeps them parallel): it is *locked* (rejected: ``"locked"``).

The rest is decided with proofs (:mod:`~chaingraph.structure.atlas.admissibility`):
an admission by one exact evaluation of the velocity equations, a rejection by forests
(the rows split into three forests of the link graph exactly when they are independent
at a generic pose). Forests find what the structure of the P joints alone does not:
two binary links between two links that a path of P joints keeps parallel (Stephenson's
chain with the path P-P-P between its ternary links) make a rigid sub-chain that locks
their four R joints. ``tests/structure/test_sliding.py`` checks the verdicts against a
floating-point rank at random poses for every assignment of every chain up to 8
links.

Two chains are the same when an isomorphism of their link graphs maps P joints to P
joints; with ``oriented``, also the link that carries each guide to the link that
carries the guide. The assignments are taken one per orbit of the chain's
automorphisms, so each chain is counted once without a canonical form per candidate.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import TYPE_CHECKING, Any, Literal, overload

import json
from dataclasses import dataclass
from itertools import combinations
from pathlib import Path

from chaingraph._util.atomic import withdraw, write_atomic
from chaingraph._util.disjoint import DisjointSets
from chaingraph.errors import AtlasSizeError
from chaingraph.model.chain import Chain, Joint
from chaingraph.model.chainfile import dumps
from chaingraph.structure.atlas.admissibility import REASONS, admissible, verdicts
from chaingraph.structure.atlas.entry import chain_file_name, order_counts
from chaingraph.structure.atlas.generic import generic_verdicts
from chaingraph.structure.classification import order_name
from chaingraph.structure.isomorphism import (
    automorphism_generators,
)

if TYPE_CHECKING:       # the atlas with multiple joints builds on this module's Entries
    from chaingraph.structure.atlas.multiple import MultipleAtlas
    from chaingraph.structure.atlas.run import Atlas

__all__ = ["SlidingEntry", "SlidingAtlas", "SlidingCounts", "sliding_atlas",
           "sliding_chains", "prismatic_counts", "sliding_dict", "write_sliding"]

@dataclass(frozen=True)
class SlidingEntry:
    """One chain with sliding pairs: its link graph ``edges`` (0-based link pairs; with
    ``oriented``, a P joint's first link carries its guide), each joint's ``kind``
    ("R" or "P", in the order of ``edges``), the number of ``links``, its inversion
    classes (orbits of its links under its automorphisms), whether it is
    fractionated, and ``base``, the id of the turning-pair chain it comes from."""

    id: int
    edges: tuple[tuple[int, ...], ...]
    kinds: tuple[str, ...]
    links: int
    inversion_classes: int
    fractionated: bool
    base: int
    oriented: bool = False
    multiple: bool = False      # from the atlas with multiple joints: "joints", not "edges"

    @property
    def prismatic(self) -> int:
        """How many of its joints are sliding pairs."""
        return self.kinds.count("P")

    @property
    def link_orders(self) -> dict[str, int]:
        """How many links of each order (``{"binary": 4, ...}``)."""
        if self.multiple:
            return _orders([sum(x in j for j in self.edges) for x in range(self.links)])
        return order_counts(self.edges, self.links)

    def chain(self, dof: int | None = None) -> Chain:
        """The chain (links L1..LN, joints J1..; a P joint's first link carries its
        guide)."""
        joints = tuple(Joint(f"J{i + 1}", k, tuple(f"L{x + 1}" for x in links))
                       for i, (links, k) in enumerate(zip(self.edges, self.kinds)))
        name = (f"chain {self.id} of {self.links} links" + (f", {dof} dof" if dof else "")
                + f", {self.prismatic} sliding pair{'s' if self.prismatic != 1 else ''}")
        return Chain(name, joints, family="atlas")

    def to_dict(self) -> dict[str, Any]:
        """The chain's record in the atlas's JSON."""
        return {"id": self.id, ("joints" if self.multiple else "edges"):
                [list(e) for e in self.edges],
                "kinds": list(self.kinds), "link_orders": self.link_orders,
                "inversion_classes": self.inversion_classes,
                "fractionated": self.fractionated}


class Entries:
    """What the atlases' result classes share: their ``entries`` in order, counted and
    iterated, and the sum of their inversion classes."""

    entries: Sequence[Any]

    def __len__(self) -> int:
        return len(self.entries)

    def __iter__(self) -> Iterator[Any]:
        return iter(self.entries)

    @property
    def distinct_inversions(self) -> int:
        """The inversion classes of every chain, summed."""
        return sum(e.inversion_classes for e in self.entries)


@dataclass(frozen=True)
class SlidingAtlas(Entries):
    """The chains with sliding pairs of one size: ``entries`` in order (by the
    turning-pair chain they come from, then by their P joints), ``rejected``
    ``{reason: assignments}`` (one per orbit), and what was asked."""

    links: int
    dof: int
    prismatic: tuple[int, ...]
    oriented: bool
    entries: tuple[SlidingEntry, ...]
    rejected: dict[str, int]

    def __iter__(self) -> Iterator[SlidingEntry]:
        return iter(self.entries)

    @property
    def count_by_prismatic(self) -> dict[int, int]:
        """Chains by their number of sliding pairs (every number asked for)."""
        out = {k: 0 for k in self.prismatic}
        for e in self.entries:
            out[e.prismatic] += 1
        return out

    @property
    def count_non_fractionated(self) -> int:
        """The chains that are not fractionated."""
        return sum(1 for e in self.entries if not e.fractionated)

    @property
    def count_by_multiple(self) -> dict[int, int] | None:
        """Chains by how many of their joints join three links or more; None when no
        chain comes from the atlas with multiple joints."""
        if not any(e.multiple for e in self.entries):
            return None
        out: dict[int, int] = {}
        for e in self.entries:
            k = _multiple_joints(e)
            out[k] = out.get(k, 0) + 1
        return dict(sorted(out.items()))

    def without_fractionated(self) -> SlidingAtlas:
        """The non-fractionated chains alone (ids kept)."""
        return SlidingAtlas(self.links, self.dof, self.prismatic, self.oriented,
                            tuple(e for e in self.entries if not e.fractionated),
                            dict(self.rejected))


class SlidingCounts:
    """The counts of an atlas with sliding pairs whose chains were counted as they were
    found, not kept (what ``--summary`` prints; the chains of 10 links, oriented, would
    take gigabytes): the same counts as :class:`SlidingAtlas`, by K, by multiple joints,
    fractionated or not.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> counts = sliding_atlas(atlas_graphs(6, 1), prismatic=range(8), keep=False)
    >>> kept = sliding_atlas(atlas_graphs(6, 1), prismatic=range(8))
    >>> (len(counts), counts.distinct_inversions) == (len(kept), kept.distinct_inversions)
    True
    """

    def __init__(self, links: int, dof: int, prismatic: tuple[int, ...], oriented: bool,
                 rejected: dict[str, int]) -> None:
        self.links, self.dof, self.prismatic, self.oriented = links, dof, prismatic, oriented
        self.rejected = rejected
        # (fractionated, K, multiple joints) -> [chains, distinct inversions]
        self.tally: dict[tuple[bool, int, int], list[int]] = {}
        self.multiple = False

    def add(self, entry: SlidingEntry) -> None:
        """Count one more chain."""
        key = (entry.fractionated, entry.prismatic, _multiple_joints(entry))
        row = self.tally.setdefault(key, [0, 0])
        row[0] += 1
        row[1] += entry.inversion_classes
        self.multiple = self.multiple or entry.multiple

    def __len__(self) -> int:
        return sum(row[0] for row in self.tally.values())

    @property
    def distinct_inversions(self) -> int:
        """The inversion classes of every chain counted, summed."""
        return sum(row[1] for row in self.tally.values())

    @property
    def count_non_fractionated(self) -> int:
        """The chains counted that are not fractionated."""
        return sum(row[0] for key, row in self.tally.items() if not key[0])

    @property
    def count_by_prismatic(self) -> dict[int, int]:
        """Chains by their number of sliding pairs (every number asked for)."""
        out = {k: 0 for k in self.prismatic}
        for (_, k, _), row in self.tally.items():
            out[k] += row[0]
        return out

    @property
    def count_by_multiple(self) -> dict[int, int] | None:
        """Chains by how many of their joints join three links or more; None when no
        chain comes from the atlas with multiple joints."""
        if not self.multiple:
            return None
        out: dict[int, int] = {}
        for (_, _, k), row in self.tally.items():
            out[k] = out.get(k, 0) + row[0]
        return dict(sorted(out.items()))

    def without_fractionated(self) -> SlidingCounts:
        """The counts of the non-fractionated chains alone."""
        out = SlidingCounts(self.links, self.dof, self.prismatic, self.oriented,
                            dict(self.rejected))
        out.tally = {key: list(row) for key, row in self.tally.items() if not key[0]}
        out.multiple = self.multiple
        return out


def _multiple_joints(entry: SlidingEntry) -> int:
    """How many of a chain's joints join three links or more."""
    return sum(len(j) > 2 for j in entry.edges)


def prismatic_counts(links: int, dof: int, joints: int,
                     prismatic: int | Sequence[int] | str | None, oriented: bool = False,
                     ) -> tuple[int, ...] | None:
    """The numbers of sliding pairs asked for (``prismatic``: a number, a sequence of
    them, or "all") as a tuple, for chains of ``joints`` joints; AtlasSizeError naming
    the parameter for a number that is not one.

    >>> prismatic_counts(4, 1, 4, "all")
    (0, 1, 2, 3, 4)
    >>> prismatic_counts(4, 1, 4, 5)
    Traceback (most recent call last):
    ...
    chaingraph.errors.AtlasSizeError: prismatic 5: a chain of 4 links and 1 dof has 4 joints, so at most 4 of them can be sliding pairs
    """
    if prismatic is None:
        if oriented:
            raise AtlasSizeError("oriented tells chains apart by which link carries each "
                                 "sliding pair's guide: give prismatic too", links=links,
                                 dof=dof, parameter="oriented")
        return None
    if prismatic == "all":
        return tuple(range(joints + 1))
    asked: Sequence[Any] = ((prismatic,) if not isinstance(prismatic, (list, tuple, range))
                            else prismatic)    # each checked below
    for k in asked:
        if isinstance(k, bool) or not isinstance(k, int) or k < 0:
            raise AtlasSizeError(f"prismatic must be a whole number of sliding pairs, 0 or "
                                 f"more, or 'all', got {k!r}", links=links, dof=dof,
                                 parameter="prismatic")
        if k > joints:
            raise AtlasSizeError(f"prismatic {k}: a chain of {links} links and {dof} dof has "
                                 f"{joints} joints, so at most {joints} of them can be "
                                 "sliding pairs", links=links, dof=dof, parameter="prismatic")
    return tuple(sorted(set(asked)))


def _edge_maps(chain, gens):
    """Each automorphism (link-joint graph node map) as (link permutation, edge
    permutation) over indices."""
    links = {name: int(name[1:]) - 1 for name in chain.links}      # L1.. are links 0..
    joints = {j.id: i for i, j in enumerate(chain.joints)}
    out = []
    for g in gens:
        perm = [0] * len(links)
        for name, i in links.items():
            perm[i] = links[g[("link", name)][1]]
        eperm = [0] * len(joints)
        for jid, i in joints.items():
            eperm[i] = joints[g[("joint", jid)][1]]
        out.append((tuple(perm), tuple(eperm)))
    return out


def _group(generators, n, m):
    """Every element of the group the (link, edge) permutations generate."""
    identity = (tuple(range(n)), tuple(range(m)))
    seen, todo = {identity}, [identity]
    while todo:
        p, e = todo.pop()
        for gp, ge in generators:
            q = (tuple(gp[x] for x in p), tuple(ge[x] for x in e))
            if q not in seen:
                seen.add(q)
                todo.append(q)
    return list(seen)


def _orbit_representatives(states, act):
    """The least state of each orbit of ``states`` (ints) under the maps in ``act``."""
    orbits = DisjointSets(states)
    for f in act:
        for s in states:
            orbits.join(s, f(s))
    return sorted(orbits.blocks())


def _permute_mask(mask: int, eperm: Sequence[int]) -> int:
    out = 0
    for i, j in enumerate(eperm):
        if mask >> i & 1:
            out |= 1 << j
    return out


def _link_orbits(n: int, elements: Iterable[tuple[Sequence[int], Sequence[int]]]) -> int:
    """How many orbits the links fall into under ``elements``."""
    orbits = DisjointSets(n)
    for perm, _ in elements:
        for x in range(n):
            orbits.join(x, perm[x])
    return orbits.count


@overload
def sliding_atlas(base: Atlas | MultipleAtlas, *, prismatic: int | Iterable[int],
                  oriented: bool = ..., keep: Literal[True] = ...) -> SlidingAtlas: ...


@overload
def sliding_atlas(base: Atlas | MultipleAtlas, *, prismatic: int | Iterable[int],
                  oriented: bool = ..., keep: Literal[False]) -> SlidingCounts: ...


@overload
def sliding_atlas(base: Atlas | MultipleAtlas, *, prismatic: int | Iterable[int],
                  oriented: bool = ..., keep: bool) -> SlidingAtlas | SlidingCounts: ...


def sliding_atlas(base: Atlas | MultipleAtlas, *, prismatic: int | Iterable[int],
                  oriented: bool = False, keep: bool = True) -> SlidingAtlas | SlidingCounts:
    """The chains with sliding pairs made from the turning-pair chains of ``base`` (an
    :class:`~chaingraph.structure.atlas.run.Atlas`), with ``prismatic`` sliding pairs
    (an int, or a sequence of them).

    Each turning-pair chain's automorphism group is listed once; the assignments are
    taken one per orbit of it, and a chain's own automorphisms (for its inversion
    classes, and the orbits of its guides' orientations) are the elements that keep
    its sliding pairs (and their guides) in place.

    ``keep=False`` counts the chains as they are found instead of keeping them, and
    returns :class:`SlidingCounts` (memory stays flat whatever the size).

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> four = sliding_atlas(atlas_graphs(4, 1), prismatic=range(5))
    >>> four.count_by_prismatic, four.rejected
    ({0: 1, 1: 1, 2: 2, 3: 0, 4: 0}, {'mobility': 1, 'locked': 1})
    >>> sliding_atlas(atlas_graphs(4, 1), prismatic=2, oriented=True).count_by_prismatic
    {2: 5}
    """
    wanted = (prismatic,) if isinstance(prismatic, int) else tuple(sorted(set(prismatic)))
    rejected = {reason: 0 for reason in REASONS}
    chains = sliding_chains(base, prismatic=wanted, oriented=oriented, rejected=rejected)
    if keep:
        entries = tuple(chains)
        return SlidingAtlas(base.links, base.dof, wanted, oriented, entries, rejected)
    counts = SlidingCounts(base.links, base.dof, wanted, oriented, rejected)
    for entry in chains:
        counts.add(entry)
    return counts


def sliding_chains(base: Atlas | MultipleAtlas, *, prismatic: int | Iterable[int],
                   oriented: bool = False, rejected: dict[str, int] | None = None,
                   ) -> Iterator[SlidingEntry]:
    """Yield the chains of :func:`sliding_atlas` one by one, in its order, adding the
    assignments rejected (one per orbit) to ``rejected`` (a dict by reason) as it goes.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> refused = {}
    >>> [e.kinds for e in sliding_chains(atlas_graphs(4, 1), prismatic=2, rejected=refused)]
    [('P', 'P', 'R', 'R'), ('R', 'P', 'P', 'R')]
    >>> refused
    {'mobility': 0, 'locked': 0}
    """
    wanted = (prismatic,) if isinstance(prismatic, int) else tuple(sorted(set(prismatic)))
    rejected = {} if rejected is None else rejected
    for reason in REASONS:
        rejected.setdefault(reason, 0)
    for reason, n in getattr(base, "rejected", {}).items():    # link-joint graphs
        rejected[reason] += n
    count = 0
    for base_id, entry in enumerate(base, start=1):
        for found in _chain_assignments(base, base_id, entry, wanted, oriented, rejected):
            count += 1
            yield SlidingEntry(count, *found)


def _chain_assignments(base, base_id, entry, wanted, oriented, rejected):
    """The admissible assignments of one turning-pair chain, one per orbit (and
    orientation), as the fields of its :class:`SlidingEntry` after its id."""
    multiple = hasattr(entry, "joints")
    edges = [tuple(e) for e in (entry.joints if multiple else entry.edges)]
    n, m = entry.links, len(edges)
    simple = [i for i, e in enumerate(edges) if len(e) == 2]
    chain = entry.chain()
    gens = _edge_maps(chain, automorphism_generators(chain, oriented=False))
    group = _group(gens, n, m)
    masks = sorted(sum(1 << i for i in chosen) for k in wanted
                   for chosen in combinations(simple, k))
    acts = [lambda s, e=eperm: _permute_mask(s, e) for _, eperm in gens]
    reps = _orbit_representatives(masks, acts)
    # the structure of the P joints first; the rest drawn in one batch, then proven
    found = {s: admissible(n, edges, _kinds(s, m)) for s in reps}
    left = [s for s in reps if found[s] is None]
    drawn = generic_verdicts(n, edges, left) if left else None
    found.update(zip(left, verdicts(n, [tuple(edges)] * len(left),
                                    kinds=[_kinds(s, m) for s in left],
                                    dof=base.dof, drawn=drawn)))
    fractionated = bool(getattr(entry, "fractionated", False))
    for mask in reps:
        reason = found[mask]
        if reason is not None:
            rejected[reason] += 1
            continue
        kinds = _kinds(mask, m)
        own = [g for g in group if _permute_mask(mask, g[1]) == mask]
        for oriented_edges, keep in _orientations(edges, kinds, own, oriented):
            yield (oriented_edges, kinds, n, _link_orbits(n, keep), fractionated, base_id,
                   oriented, multiple)


def _orders(degree: Iterable[int]) -> dict[str, int]:
    """The link orders' counts (as the atlas words them) of links with these numbers of
    joints."""
    counts: dict[str, int] = {}
    for d in sorted(degree):
        counts[order_name(d)] = counts.get(order_name(d), 0) + 1
    return counts


def _kinds(mask: int, m: int) -> tuple[str, ...]:
    return tuple("P" if mask >> i & 1 else "R" for i in range(m))


def _orientations(edges, kinds, own, oriented):
    """``(edges, automorphisms)`` of the chain as listed (unoriented), or of one chain
    per orbit of the orientations of its P joints (a P edge's first link carries the
    guide) under the chain's automorphisms ``own``, with the automorphisms that keep
    each guide on its link."""
    sliding = [i for i, k in enumerate(kinds) if k == "P"]
    if not oriented or not sliding:
        return [(tuple(edges), own)]
    position = {i: k for k, i in enumerate(sliding)}

    def image(bits, perm, eperm):
        out = 0
        for k, i in enumerate(sliding):
            guide = edges[i][1] if bits >> k & 1 else edges[i][0]
            j = eperm[i]
            if perm[guide] == edges[j][1]:
                out |= 1 << position[j]
        return out
    states = range(1 << len(sliding))
    reps = _orbit_representatives(states, [lambda b, p=p, e=e: image(b, p, e) for p, e in own])
    out = []
    for bits in reps:
        flipped = list(edges)
        for k, i in enumerate(sliding):
            if bits >> k & 1:
                flipped[i] = edges[i][::-1]
        keep = [(p, e) for p, e in own if image(bits, p, e) == bits]
        out.append((tuple(flipped), keep))
    return out


def sliding_dict(result: SlidingAtlas | SlidingCounts, *,
                 prismatic: int | Sequence[int] | str | None = None, chains: bool = True,
                 names: Callable[[Chain], Any] | None = None) -> dict[str, Any]:
    """The JSON object of ``chaingraph atlas --prismatic K`` (``chains=False``:
    ``--summary``, of a :class:`SlidingAtlas` or :class:`SlidingCounts`): the counts, the rejected assignments by reason, the count by K
    when every K was asked for (``prismatic="all"``), and each chain with ``"kinds"``
    and, given ``names`` (a function of a chain), its ``"names"``.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> d = sliding_dict(sliding_atlas(atlas_graphs(4, 1), prismatic=1))
    >>> d["count"], d["rejected"], d["chains"][0]["kinds"]
    (1, {'mobility': 0, 'locked': 0}, ['P', 'R', 'R', 'R'])
    """
    by_multiple = result.count_by_multiple
    out: dict[str, Any] = {"links": result.links, "dof": result.dof,
           "prismatic": prismatic if prismatic is not None else (
               result.prismatic[0] if len(result.prismatic) == 1 else list(result.prismatic)),
           "oriented": result.oriented, "count": len(result),
           **({"multiple": True, "count_by_multiple": {
               str(k): v for k, v in by_multiple.items()}}
              if by_multiple is not None else {}),
           "count_non_fractionated": result.count_non_fractionated,
           "distinct_inversions": result.distinct_inversions,
           "rejected": dict(result.rejected)}
    if prismatic == "all" or len(result.prismatic) > 1:
        out["count_by_prismatic"] = {str(k): v for k, v in result.count_by_prismatic.items()}
    if chains:
        if not isinstance(result, SlidingAtlas):
            raise TypeError("the chains of counts were not kept: give chains=False")
        out["chains"] = [e.to_dict() for e in result]
        if names is not None:
            for record, e in zip(out["chains"], result):
                record["names"] = names(e.chain(result.dof))
    return out


def write_sliding(result: SlidingAtlas, out_dir: str | os.PathLike[str], *,
                  record: dict[str, Any] | None = None, chain_files_up_to: int = 10_000,
                  ) -> dict[str, Any]:
    """Write ``atlas.json`` (``record``, else :func:`sliding_dict`) and, up to
    ``chain_files_up_to`` chains, one chain file per chain under ``chains/``. An
    ``index.html`` of earlier pages is removed first (the pages, when drawn, write a
    new one last)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    withdraw(out)          # the old pages' index, until new pages are written
    path = write_atomic(out / "atlas.json",
                        json.dumps(record or sliding_dict(result), indent=1) + "\n")
    chain_dir = out / "chains"
    written: list[Path] = []
    if len(result) <= chain_files_up_to:
        chain_dir.mkdir(exist_ok=True)
        for e in result:
            file = chain_dir / chain_file_name(e.id, len(result))
            file.write_text(dumps(e.chain(result.dof)), encoding="utf-8")
            written.append(file)
    return {"json": path, "chain_dir": chain_dir, "chains": written}
