"""Inversions: fix each link in turn, group them by structure, name them.

The inversions that are the same mechanism by the chain's structure alone are the
orbits of links under the automorphisms of the link-joint graph (joint kinds and P
orientation respected; see :mod:`chaingraph.structure.isomorphism`). With an input link as well,
the classes are the orbits of (fixed, input) pairs.

Names come from the catalog's mechanism files through isomorphisms, never from link
names: a catalog mechanism names an inversion when an isomorphism of the two chains
maps its fixed link onto the inversion's fixed link and, where both have dimensions,
they behave alike: the same Grashof category for a four-bar (so a dimensioned
four-bar's crank-rocker inversion is a beam engine, its double crank the coupling rod
of a locomotive and its double rocker Watt's indicator), the links that turn fully
relative to the fixed link mapped onto each other for other chains. When no catalog mechanism matches with P orientation respected, a
dimensioned inversion is matched again with it forgotten (a sliding pair's relative
motion is the same whichever link carries the guide), the full turns deciding.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Any

import networkx as nx
from networkx.algorithms.isomorphism import GraphMatcher

from chaingraph._util.text import short_list
from chaingraph.errors import ChainStructureError
from chaingraph.kinematics.behaviour import (
    behaviour,
    behaviour_cost,
    behaviour_key,
    turning_links,
)
from chaingraph.model.chain import Chain
from chaingraph.naming.catalog import bundled_catalog
from chaingraph.structure.isomorphism import (
    automorphism_orbits,
    canonical_form,
    pair_orbits,
)

__all__ = ["Inversion", "InputClass", "Inversions", "Match", "inversions", "catalog_matches",
           "naming_matches",
           "link_isomorphisms", "require_connected"]


@dataclass(frozen=True)
class InputClass:
    """A choice of input link for an inversion, with its (fixed, input) class."""

    driver: str
    class_: int

    def to_dict(self) -> dict[str, Any]:
        return {"driver": self.driver, "class": self.class_}


@dataclass(frozen=True)
class Inversion:
    """One inversion: the chain with ``fixed`` fixed."""

    fixed: str
    class_: int
    names: tuple[str, ...]
    behaviour: str | None
    full_turns: tuple[str, ...] | None = None
    inputs: tuple[InputClass, ...] | None = None
    note: str | None = None    # why a catalog name is missing, where one is

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"fixed": self.fixed, "class": self.class_, "names": list(self.names),
             "behaviour": self.behaviour,
             "full_turns": None if self.full_turns is None else list(self.full_turns),
             "note": self.note}
        if self.inputs is not None:
            d["inputs"] = [i.to_dict() for i in self.inputs]
        return d


@dataclass(frozen=True)
class Inversions:
    """Every inversion of a chain; :meth:`to_dict` is the JSON of ``chaingraph inversions``."""

    name: str
    links: int
    classes: int
    inversions: tuple[Inversion, ...]
    classes_with_input: int | None = None

    def __repr__(self) -> str:
        return (f"Inversions({self.name!r}, links={self.links}, classes={self.classes}, "
                f"fixed={short_list([i.fixed for i in self.inversions])})")

    def rows(self) -> list[tuple[str | int, ...]]:
        """The inversions as table rows, the first the header: fixed link, class, (the
        inputs and their classes, where designated), behaviour, names ("-" for none), as
        the command line, the report and a notebook show them.

        Examples
        --------
        >>> import chaingraph
        >>> from chaingraph.naming.catalog import catalog_path
        >>> chain = chaingraph.load(catalog_path("four-bar-chain"))
        >>> chaingraph.inversions(chain).rows()[:2]
        [('fixed', 'class', 'behaviour', 'names'), ('frame', 1, 'crank-rocker', 'Beam engine (crank and lever mechanism)')]
        """
        designated = self.classes_with_input is not None
        header = ("fixed", "class") + (("inputs (class)",) if designated else ()) + (
            "behaviour", "names")
        rows: list[tuple[str | int, ...]] = [header]
        for i in self.inversions:
            inputs = ((", ".join(f"{x.driver} ({x.class_})" for x in i.inputs or ()) or "-",)
                      if designated else ())
            rows.append((i.fixed, i.class_) + inputs
                        + (i.behaviour or "-", "; ".join(i.names) or "-"))
        return rows

    def inversion(self, fixed: str) -> Inversion:
        """The inversion with ``fixed`` fixed."""
        return next(i for i in self.inversions if i.fixed == fixed)

    def to_dict(self) -> dict[str, Any]:
        d: dict[str, Any] = {"name": self.name, "links": self.links, "classes": self.classes,
             "inversions": [i.to_dict() for i in self.inversions]}
        if self.classes_with_input is not None:
            d["classes_with_input"] = self.classes_with_input
        return d


def require_connected(chain: Chain) -> None:
    """Raise ChainStructureError unless the chain is one connected piece."""
    if len(chain.pieces) > 1:
        pieces = "; ".join("{" + ", ".join(p) + "}" for p in chain.pieces)
        raise ChainStructureError(
            f"the chain is in {len(chain.pieces)} pieces that share no joint: {pieces}; "
            "inversions need one connected chain", chain=chain.source or chain.name,
            pieces=chain.pieces)


def _labelled(chain, oriented, marks):
    g = nx.Graph()
    for n, data in chain.graph.nodes(data=True):
        label = ("link", marks.get(n[1])) if n[0] == "link" else ("joint", data["kind"])
        g.add_node(n, label=label)
    for u, v, data in chain.graph.edges(data=True):
        role = data["role"] if oriented else ("pin" if data["role"] == "pin" else "slide")
        g.add_edge(u, v, role=role)
    return g


def link_isomorphisms(a: Chain, b: Chain, *, oriented: bool = True,
                      marks_a: dict[str, str] | None = None,
                      marks_b: dict[str, str] | None = None) -> Iterator[dict[str, str]]:
    """Every isomorphism of chain ``a`` onto chain ``b``, as dicts of links.

    ``marks_a`` and ``marks_b`` tag links (for example ``{fixed: "fixed"}``) that only
    equally tagged links may map onto.
    """
    if canonical_form(a, oriented=oriented) != canonical_form(b, oriented=oriented):
        return
    ga = _labelled(a, oriented, marks_a or {})
    gb = _labelled(b, oriented, marks_b or {})
    matcher = GraphMatcher(ga, gb, node_match=lambda x, y: x["label"] == y["label"],
                           edge_match=lambda x, y: x["role"] == y["role"])
    for mapping in matcher.isomorphisms_iter():
        yield {u[1]: v[1] for u, v in mapping.items() if u[0] == "link"}


def _output_maps(chain, output, entry, mapping) -> bool:
    """Whether ``mapping`` takes the chain's output onto the entry's: a link onto its
    link, a point onto a point of the same link, a joint onto a joint of the same links."""
    def kind(c, name):
        if name in c.links:
            return "link", frozenset((name,))
        if name in c._joint_index:
            return "joint", frozenset(c.joint(name).links)
        return "point", frozenset((c.point(name).link,))
    mine, theirs = kind(chain, output), kind(entry, entry.mechanism.output)
    return mine[0] == theirs[0] and frozenset(mapping[x] for x in mine[1]) == theirs[1]


def _alike(key, entry_key, mapping) -> bool:
    if key[0] != entry_key[0]:
        return False
    if key[0] == "full turns":
        return frozenset(mapping[x] for x in key[1]) == entry_key[1]
    return key == entry_key


@dataclass(frozen=True)
class Match:
    """A catalog mechanism that is a chain with a given link fixed.

    ``mapping`` maps the chain's links onto the entry's; ``score`` counts 2 when the
    drivers correspond and 1 when the outputs do; ``oriented`` is False when P
    orientation had to be forgotten; ``alike`` is True when both have dimensions and
    behave alike, False when they behave differently, None when either has none."""

    score: int
    entry: Chain
    mapping: dict[str, str]
    oriented: bool
    alike: bool | None

    @property
    def structural(self) -> bool:
        """Whether the entry's name is one of structure (holds for any dimensions)."""
        return self.entry.naming == "structure"



# the behaviour of every inversion solves each one's whole cycle (a few seconds for 30
# links, growing as the cube of the links): beyond this, only where a name needs it
BEHAVIOUR_LINKS = 40

#: the inversions' behaviours solved in all, in estimated seconds of one core
#: (:func:`~chaingraph.kinematics.behaviour.behaviour_cost`): the cheapest first, the
#: others only where a name needs them (a chain of dyads fixed at an outer link is an
#: Assur group of up to 24 links, whose cycle takes seconds to trace: 20 and 30 links
#: took minutes in all)
BEHAVIOUR_SECONDS = 8.0


def _behaviours_solved(chain, needed, *, budget=BEHAVIOUR_SECONDS):
    """The fixed links whose behaviour :func:`inversions` solves: those in ``needed``
    (a catalog name needs it), and the others, the cheapest first, while the least
    each takes (:func:`behaviour_cost`: its first driver's cycle) keeps the estimated
    seconds spent (counted as each is solved, every driver it tried) within ``budget``
    (so past it by one inversion's drivers at most); and each unsolved one's least
    estimate."""
    if len(chain.links) > BEHAVIOUR_LINKS:
        return set(needed), {}
    least = {x: behaviour_cost(chain, x) for x in chain.links}
    solved, spent = set(), 0.0
    for x in list(needed) + sorted(chain.links, key=lambda x: (least[x],
                                                                chain.links.index(x))):
        if x in solved or (x not in needed and spent + least[x] > budget):
            continue
        behaviour(chain, x)
        spent += behaviour_cost(chain, x, spent=True)
        solved.add(x)
    return solved, {x: c for x, c in least.items() if x not in solved}


#: the isomorphisms tried per catalog entry, looking for one whose behaviour is alike
#: (after the one that keeps driver and output): a chain with a symmetric group of
#: links, seven cylinders on one crank pin, has 7! = 5,040, alike or not alike together
MAX_MAPPINGS = 720


def catalog_matches(chain: Chain, fixed: str, catalog: Sequence[Chain], *,
                    driver: str | None = None, output: str | None = None) -> list[Match]:
    """The catalog mechanisms that are this chain with ``fixed`` fixed, by structure.

    Each entry is matched with P orientation respected, else with it forgotten (a
    sliding pair's relative motion is the same whichever link carries the guide: the
    textbook's crank and slotted lever is its slider crank chain's inversion only so).
    Where both have dimensions, ``alike`` says whether they behave alike (the Grashof
    category of a four-bar; otherwise which links turn fully). :func:`naming_matches`
    says which of them name the inversion.

    Returns
    -------
    list of Match, those with orientation respected first, each in catalog order
    """
    keys = {}

    def file_key():
        # the inversion's behaviour is solved only where a catalog mechanism of its
        # structure needs it for a name (a large chain has none: nothing is solved)
        if "file" not in keys:
            keys["file"] = behaviour_key(chain, fixed)
        return keys["file"]
    found, seen = [], set()
    for oriented in (True, False):
        for entry in catalog:
            m = entry.mechanism
            if m is None or len(entry.links) != len(chain.links) or id(entry) in seen:
                continue
            best = None
            # first the mappings that also take driver and output onto the entry's (a
            # symmetric chain, the seven cylinders, has thousands of others), then any
            marked = (_marks(chain, fixed, driver, output), _marks(entry, m.fixed, m.driver, m.output))
            first = next(link_isomorphisms(chain, entry, oriented=oriented, marks_a=marked[0],
                                           marks_b=marked[1]), None)
            candidates = itertools.chain([] if first is None else [first], link_isomorphisms(
                chain, entry, oriented=oriented, marks_a={fixed: "fixed"},
                marks_b={m.fixed: "fixed"}))
            for mapping in itertools.islice(candidates, MAX_MAPPINGS):
                entry_key = behaviour_key(entry, m.fixed)
                compare = entry_key is not None and file_key() is not None
                alike = _alike(file_key(), entry_key, mapping) if compare else None
                score = 0
                if driver and m.driver and mapping[driver] == m.driver:
                    score += 2
                if output and m.output and _output_maps(chain, output, entry, mapping):
                    score += 1
                rank = (alike is not False, score)
                if best is None or rank > best[0]:
                    best = (rank, Match(score, entry, mapping, oriented, alike))
                top = 2 * bool(driver and m.driver) + bool(output and m.output)
                if rank == (True, top):
                    # none better: a symmetric chain (seven cylinders) has thousands
                    break
            if best is not None:
                found.append(best[1])
                seen.add(id(entry))
    return found


def _marks(chain, fixed, driver, output):
    """Tags of the fixed link, the driver and the output's links, for matching."""
    marks = {fixed: "fixed"}
    if driver and driver != fixed:
        marks[driver] = "driver"
    if output:
        if output in chain.links:
            links = (output,)
        elif output in chain._joint_index:
            links = chain.joint(output).links
        else:
            links = (chain.point(output).link,)
        for link in links:
            marks.setdefault(link, "output")
    return marks


def naming_matches(matches: Sequence[Match]) -> list[Match]:
    """Which catalog matches name the inversion: those that behave alike (where both
    have dimensions); failing those, the names of structure (Watt I, the slider crank's
    inversions: they hold whatever the dimensions) and the names that cannot be
    checked (no dimensions on one side), with P orientation respected if any, else
    forgotten. A name of behaviour whose behaviour differs never names it."""
    alike = [x for x in matches if x.alike is True]
    if alike:
        return alike
    for oriented in (True, False):
        named = [x for x in matches if x.oriented == oriented
                 and (x.structural or x.alike is None)]
        if named:
            return named
    return []


def inversions(chain: Chain, *, with_input: bool = False,
               catalog: Sequence[Chain] | None = None,
               behaviour_seconds: float = BEHAVIOUR_SECONDS) -> Inversions:
    """Every inversion of a chain, grouped by structure and named from the catalog.

    Parameters
    ----------
    chain : Chain
    with_input : bool
        Also designate the input: every link joined to the fixed link by an R joint,
        with the classes of (fixed, input) pairs.
    catalog : sequence of Chain, optional
        Where names come from; the bundled catalog by default.
    behaviour_seconds : float
        The estimated seconds of one core that the behaviours of the inversions no
        catalog name needs may take in all (:data:`BEHAVIOUR_SECONDS` by default): the
        cheapest are solved first, past the budget by one inversion at most; the
        others' notes say what each would take.

    Returns
    -------
    Inversions

    Raises
    ------
    ChainStructureError
        For a chain in several pieces.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> result = inversions(chaingraph.load(catalog_path("single-slider-crank-chain")))
    >>> result.classes
    4
    >>> for i in result.inversions:
    ...     print(i.fixed, i.class_, "; ".join(i.names))
    frame 1 Reciprocating engine
    crank 2 Rotary (Gnome) engine; Whitworth quick return mechanism
    rod 3 Crank and slotted lever quick return mechanism; Oscillating cylinder engine
    crosshead 4 Duplex pump; Pendulum pump (bull engine)
    """
    require_connected(chain)
    if catalog is None:
        catalog = bundled_catalog()
    orbits = automorphism_orbits(chain)
    class_of = {x: i + 1 for i, orbit in enumerate(orbits) for x in orbit}
    found = {fixed: catalog_matches(chain, fixed, catalog) for fixed in chain.links}
    solvable, cost = _behaviours_solved(chain, [x for x in chain.links if found[x]],
                                        budget=behaviour_seconds)
    inputs = _input_classes(chain) if with_input else None
    result = tuple(_inversion(chain, fixed, class_of[fixed], found[fixed],
                              solved=fixed in solvable, cost=cost.get(fixed),
                              budget=behaviour_seconds,
                              inputs=None if inputs is None else inputs[fixed])
                   for fixed in chain.links)
    return Inversions(name=chain.name, links=len(chain.links), classes=len(orbits),
                      inversions=result,
                      classes_with_input=None if inputs is None else len(
                          {i.class_ for x in inputs.values() for i in x}))


def _input_classes(chain) -> dict[str, tuple[InputClass, ...]]:
    """For each fixed link, its inputs (every link joined to it by an R joint) with the
    classes of the (fixed, input) pairs."""
    drivers = {fixed: [x for x in chain.links if x != fixed and any(
        j.kind == "R" and fixed in j.links and x in j.links for j in chain.joints)]
        for fixed in chain.links}
    pairs = [(f, d) for f in chain.links for d in drivers[f]]
    pair_class = {p: i + 1 for i, orbit in enumerate(pair_orbits(chain, pairs)) for p in orbit}
    return {f: tuple(InputClass(d, pair_class[(f, d)]) for d in drivers[f])
            for f in chain.links}


def _inversion(chain, fixed, class_, matches, *, solved, cost, budget, inputs) -> Inversion:
    """The inversion with ``fixed`` fixed: its names from the catalog ``matches``, its
    behaviour where ``solved`` (else ``cost``, its least estimate, or None over
    :data:`BEHAVIOUR_LINKS` links, said in its note)."""
    named = naming_matches(matches)
    names = tuple(dict.fromkeys(x.entry.name for x in named))
    differ = [x.entry.name for x in matches if x.alike is False and x.oriented
              and x.entry.name not in names]
    how = behaviour(chain, fixed) if solved else None
    note = None
    if differ:
        note = (f"as dimensioned ({how or 'its own behaviour'}) it is not the catalog's "
                + ", ".join(dict.fromkeys(differ)) + ", whose names need that behaviour")
    elif not names:
        note = "the catalog names no inversion of this structure with this link fixed"
    if not solved and chain.has_pose:        # (a name needs its behaviour: it is solved)
        why = (f"its cycles would take {cost:.2g} s or more, past the {budget:g} s the "
               "inversions' behaviours take in all" if cost is not None else
               f"over {BEHAVIOUR_LINKS} links, every inversion's whole cycle")
        note = f"{note}; its behaviour is not solved ({why}; solve the inversion for it)"
    turning = turning_links(chain, fixed) if solved else None
    order = {x: i for i, x in enumerate(chain.links)}
    return Inversion(
        fixed=fixed, class_=class_, names=names, behaviour=how, note=note,
        full_turns=None if turning is None else tuple(sorted(turning, key=order.__getitem__)),
        inputs=inputs)
