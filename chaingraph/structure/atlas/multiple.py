"""The atlas with multiple joints: every chain of N links and F degrees of freedom whose
turning pairs may each join more than two links (a compound hinge; a joint of d links
counts as d - 1 simple joints), as link-joint bipartite graphs.

A chain with multiple joints becomes a chain of simple joints when each multiple joint
is spread into d - 1 simple joints along a tree of its links (the pins then at distinct
places); so the chains are found by merging, in the chains of simple joints, sets of
joints that form trees into one pin each (two merged pins may share a link). The chains
of simple joints used are the atlas's own, without rigid sub-chains: a spread that has
one would be overconstrained, and coincident pins only add constraints' coincidences, so
the chain with multiple joints would be too. ``tests/structure/test_multiple.py`` checks
this against a direct enumeration of every set of joints on N links up to 7 links (an
enumeration that merged only vertex-disjoint trees missed a chain of 7 links whose two
ternary joints share a link). A merged chain is kept when every link has two joints or
more, no two joints join the same two links, and it has F freedoms with no joint
locked (:mod:`~chaingraph.structure.atlas.admissibility`: admitted by an exact
evaluation, rejected by Whiteley's count of bodies and pins). Chains are told apart by
canonical forms of their link-joint graphs (nauty where installed), and their
inversion classes are the orbits of their links.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

from chaingraph._util.disjoint import DisjointSets
from chaingraph.model.chain import Chain, Joint
from chaingraph.structure.atlas.admissibility import verdicts
from chaingraph.structure.atlas.sliding import Entries
from chaingraph.structure.isomorphism import automorphism_orbits, canonical_form

__all__ = ["MultipleEntry", "MultipleAtlas", "multiple_atlas"]


@dataclass(frozen=True)
class MultipleEntry:
    """One chain with multiple joints: ``joints``, each the tuple of the (0-based)
    links it joins; ``links`` how many; its inversion classes; ``multiple`` how many of
    its joints join three links or more."""

    id: int
    joints: tuple
    links: int
    inversion_classes: int

    @property
    def multiple(self) -> int:
        return sum(len(j) > 2 for j in self.joints)

    def chain(self, dof=None) -> Chain:
        joints = tuple(Joint(f"J{i + 1}", "R", tuple(f"L{x + 1}" for x in links))
                       for i, links in enumerate(self.joints))
        name = (f"chain {self.id} of {self.links} links" + (f", {dof} dof" if dof else "")
                + f", {self.multiple} multiple joint{'s' if self.multiple != 1 else ''}")
        return Chain(name, joints, family="atlas")

    def to_dict(self) -> dict:
        orders = {}
        for x in range(self.links):
            k = sum(x in j for j in self.joints)
            orders[k] = orders.get(k, 0) + 1
        return {"id": self.id, "joints": [list(j) for j in self.joints],
                "link_joints": {str(k): v for k, v in sorted(orders.items())},
                "inversion_classes": self.inversion_classes}


@dataclass(frozen=True)
class MultipleAtlas(Entries):
    """The chains with multiple joints of one size (those with only simple joints
    included), and the merged candidates rejected by reason."""

    links: int
    dof: int
    entries: tuple
    rejected: dict

    @property
    def count_by_multiple(self) -> dict:
        out = {}
        for e in self.entries:
            out[e.multiple] = out.get(e.multiple, 0) + 1
        return dict(sorted(out.items()))



def _partitions(items):
    """Every partition of the list ``items`` into blocks."""
    if not items:
        yield []
        return
    first, rest = items[0], items[1:]
    for part in _partitions(rest):
        yield [[first]] + part
        for i in range(len(part)):
            yield part[:i] + [[first] + part[i]] + part[i + 1:]


def _connected(edges):
    seen, todo = {edges[0][0]}, [edges[0][0]]
    while todo:
        x = todo.pop()
        for a, b in edges:
            for u, v in ((a, b), (b, a)):
                if u == x and v not in seen:
                    seen.add(v)
                    todo.append(v)
    return all(a in seen for a, _ in edges)


def _merges(links, edges):
    """Every way of merging sets of the simple joints ``edges`` into pins: each set a
    tree of two edges or more (several sets may share a link), its links then on one
    pin. Yields the chains' joints (tuples of links) with every link keeping two joints
    or more and no two joints on the same two links."""
    m = len(edges)
    for mask in range(1 << m):
        chosen = [edges[i] for i in range(m) if mask >> i & 1]
        if len(chosen) == 1:
            continue
        trees = DisjointSets(links)
        if not all(trees.join(a, b) for a, b in chosen):
            continue                                   # a loop: not a forest
        components = {}
        for e in chosen:
            components.setdefault(trees.find(e[0]), []).append(e)
        options = []
        for part in components.values():
            ways = [[tuple(sorted({x for e in block for x in e})) for block in blocks]
                    for blocks in _partitions(part)
                    if all(len(block) >= 2 and _connected(block) for block in blocks)]
            if not ways:
                break
            options.append(ways)
        else:
            rest = [e for i, e in enumerate(edges) if not mask >> i & 1]
            for choice in itertools.product(*options):
                joints = [j for groups in choice for j in groups] + rest
                if any(sum(x in j for j in joints) < 2 for x in range(links)):
                    continue
                if any(len(set(a) & set(b)) > 1 for a, b in itertools.combinations(joints, 2)):
                    continue
                yield tuple(sorted(joints))


def multiple_atlas(base) -> MultipleAtlas:
    """The chains with multiple joints made from the simple-joint chains of ``base``
    (an :class:`~chaingraph.structure.atlas.run.Atlas`).

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> six = multiple_atlas(atlas_graphs(6, 1))
    >>> six.count_by_multiple
    {0: 2, 1: 1, 2: 1}
    """
    seen, found, rejected = set(), [], {"mobility": 0, "locked": 0}
    for entry in base:
        edges = [tuple(e) for e in entry.edges]
        candidates = []
        for joints in _merges(entry.links, edges):
            if joints in seen:
                continue
            seen.add(joints)
            candidates.append(joints)
        if not candidates:
            continue
        for joints, reason in zip(candidates, verdicts(entry.links, candidates,
                                                       dof=base.dof)):
            if reason is not None:
                rejected[reason] += 1
                continue
            found.append(joints)
    forms, entries = set(), []
    for joints in found:
        made = MultipleEntry(0, joints, base.links, 0)
        chain = made.chain()
        form = canonical_form(chain, oriented=False)
        if form in forms:
            continue
        forms.add(form)
        entries.append(MultipleEntry(len(entries) + 1, joints, base.links,
                                     len(automorphism_orbits(chain, oriented=False))))
    return MultipleAtlas(base.links, base.dof, tuple(entries), rejected)
