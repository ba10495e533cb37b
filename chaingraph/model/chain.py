"""The chain model: links and joints as a bipartite networkx graph.

A chain is an immutable value. Its joints are the data; its links are named by the
joints that use them. The link-joint graph has a node for every link and every joint,
and an edge between a joint and each link it connects, so a ternary or quaternary joint
(several links on one pin) is a single node, not a triangle of binary joints. The
link-adjacency multigraph and the contracted graph are views derived from it.

Nodes of the link-joint graph are tuples ``("link", name)`` and ``("joint", id)``, so
a link and a joint may share a name.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property

import networkx as nx

from chaingraph._util.numbers import tidy
from chaingraph.errors import ChainFileError
from chaingraph.model.cams import Cam
from chaingraph.model.gears import GearPair, check_gears, pitch_point
from chaingraph.model.pairs import PAIR_KINDS, PairKind

__all__ = ["Joint", "Point", "Input", "Mechanism", "Chain", "LinkMass", "Load", "link_node",
           "joint_node", "mass_centre",
           "chosen_inputs", "line_direction"]

SPACES = ("planar", "spatial")
CLOSURES = ("form", "force")


def link_node(name: str) -> tuple[str, str]:
    """The link-joint graph node of a link."""
    return ("link", name)


def joint_node(joint_id: str) -> tuple[str, str]:
    """The link-joint graph node of a joint."""
    return ("joint", joint_id)


@dataclass(frozen=True)
class Joint:
    """A joint (kinematic pair) joining two or more links.

    Attributes
    ----------
    id : str
        Unique joint name.
    kind : str
        A key of :data:`chaingraph.model.pairs.PAIR_KINDS` (``"R"``, ``"P"``, ``"cam"``...).
    links : tuple of str
        The links it joins. For a P joint the first link carries the guide and the
        second is the block that slides in it.
    at : tuple of float, optional
        Position in the drawn pose (for a P joint, a point of the sliding line and the
        block's reference point).
    axis : float, optional
        For a P joint, the direction of sliding in the drawn pose, degrees CCW from +x.
    closure : str, optional
        For a higher pair, ``"form"`` (closed pair) or ``"force"`` (unclosed pair).
    friction : float, optional
        For a P joint, the coefficient of Coulomb friction between block and guide (the
        friction force opposes the sliding velocity; ``chaingraph forces``).
    """

    id: str
    kind: str
    links: tuple[str, ...]
    at: tuple[float, float] | None = None
    axis: float | None = None
    closure: str | None = None
    friction: float | None = None

    @property
    def order(self) -> int:
        """Number of links on the joint: 2 binary, 3 ternary, 4 quaternary."""
        return len(self.links)

    @property
    def pair(self) -> PairKind:
        """The joint's :class:`~chaingraph.model.pairs.PairKind`."""
        return PAIR_KINDS[self.kind]

    @property
    def guide(self) -> str | None:
        """For a P joint, the link that carries the guide; else None."""
        return self.links[0] if self.kind == "P" else None

    @property
    def block(self) -> str | None:
        """For a P joint, the link that slides in the guide; else None."""
        return self.links[1] if self.kind == "P" else None

    @property
    def closed(self) -> bool:
        """True for a closed pair (held mechanically); lower pairs always are."""
        return self.pair.lower or self.closure != "force"


@dataclass(frozen=True)
class Point:
    """A tracer point (coupler point, tool tip, pen) carried by a link."""

    id: str
    link: str
    at: tuple[float, float] | None     # None until placed: a file given by its lengths


@dataclass(frozen=True)
class LinkMass:
    """A link's mass properties (``[[links]]`` of a chain file): ``mass`` (kg),
    ``centre`` (the centre of mass in the drawn pose, in the file's units; None: the
    mean of the link's joints and points) and ``inertia`` (kg m^2 about the centre)."""

    link: str
    mass: float
    centre: tuple[float, float] | None = None
    inertia: float = 0.0


@dataclass(frozen=True)
class Load:
    """An external load on one link (``[[loads]]``).

    Constant in the fixed frame: a ``force`` (N) whose line passes through the joint or
    point ``at`` of the link, and a ``torque`` (N m, counter-clockwise positive);
    ``torque = "mean"`` is the steady resisting torque equal to the mean effort over the
    cycle (the machine's load: the net mean effort is zero).

    Following the motion: a force along the axis of the P joint ``along`` (positive:
    the axis direction) through ``at``, interpolated linearly in ``table`` ((x, N)
    pairs) or ``pressure`` ((x, Pa) pairs, times ``area`` m^2: an indicator diagram),
    against the slide of ``along`` from the drawn pose (file units) or, ``against =
    "input"``, against the R input's value (radians), periodic over ``cycle``
    (radians; 2 pi unless given, 4 pi for a four-stroke engine); ``stroke`` "out" or
    "in" holds it only while the slide moves out (its speed positive) or in. A
    ``resist`` force (N) always opposes the velocity of ``at``, with ``stroke``
    "forward" or "return" only during that stroke of the input (the forward stroke: the
    longer in input angle, a quick-return mechanism's cutting stroke).
    """

    on: str
    at: str | None = None
    force: tuple[float, float] | None = None
    torque: float | str = 0.0
    along: str | None = None
    table: tuple[tuple[float, float], ...] | None = None
    pressure: tuple[tuple[float, float], ...] | None = None
    area: float | None = None
    against: str = "slide"
    cycle: float | None = None
    stroke: str | None = None
    resist: float | None = None

    def __post_init__(self):
        # tables given as lists (from Python) kept as tuples, so that a load is a value
        for key in ("table", "pressure"):
            rows = getattr(self, key)
            if isinstance(rows, list | tuple):
                object.__setattr__(self, key, tuple(
                    tuple(r) if isinstance(r, list | tuple) else r for r in rows))
        if isinstance(self.force, list):
            object.__setattr__(self, "force", tuple(self.force))

    @property
    def mean_torque(self) -> bool:
        """The steady resisting torque equal to the mean effort (``torque = "mean"``)."""
        return self.torque == "mean"

    @property
    def follows(self) -> bool:
        """A force along a P joint's axis, read off a table or an indicator diagram."""
        return self.table is not None or self.pressure is not None

    @property
    def period(self) -> float:
        """The period of a table against the input (radians)."""
        return self.cycle if self.cycle is not None else 2.0 * math.pi

    def values(self) -> tuple[tuple[float, ...], tuple[float, ...]]:
        """The table's abscissae and its forces (N; pressure times area)."""
        rows = self.table if self.table is not None else self.pressure or ()
        scale = 1.0 if self.table is not None else float(self.area or 0.0)
        return tuple(r[0] for r in rows), tuple(r[1] * scale for r in rows)


@dataclass(frozen=True)
class Input:
    """An input of a mechanism: a joint whose relative motion is prescribed, swept from
    ``start`` to ``stop`` (degrees for an R joint, length units of slide for a P joint),
    or held at its drawn value when neither is given.

    ``at`` is a P input's value in the drawn pose, where its values are not measured
    from the drawn pose itself: a file given by lengths places the block ``at`` along
    the guide from the guide's origin, and its sweep, its ``input:`` column and its
    values are measured from that origin too (one reference)."""

    joint: str
    start: float | None = None
    stop: float | None = None
    at: float | None = None


@dataclass(frozen=True)
class Mechanism:
    """What makes a chain a mechanism: the fixed link, the inputs and the output.

    ``driver`` is the short form of the commonest input (a link turning about its R
    joint with the fixed link); ``inputs`` names input joints, one per degree of
    freedom, and takes precedence when both are given."""

    fixed: str
    driver: str | None = None
    omega: float = 1.0
    output: str | None = None
    inputs: tuple[Input, ...] = ()


@dataclass(frozen=True)
class Chain:
    """A kinematic chain (or, with ``mechanism``, one inversion of it).

    Build one with :func:`chaingraph.load` from a file, or directly; both validate the
    same way and raise :class:`~chaingraph.errors.ChainFileError` naming the joint, point
    or key at fault.

    Examples
    --------
    >>> from chaingraph.model.chain import Chain, Joint
    >>> four_bar = Chain("four-bar", (
    ...     Joint("A", "R", ("frame", "crank")), Joint("B", "R", ("crank", "coupler")),
    ...     Joint("C", "R", ("coupler", "rocker")), Joint("D", "R", ("rocker", "frame"))))
    >>> four_bar.links
    ('frame', 'crank', 'coupler', 'rocker')
    >>> four_bar.graph.degree[("link", "crank")]
    2
    >>> four_bar.link_graph.number_of_edges()
    4
    """

    name: str
    joints: tuple[Joint, ...]
    family: str | None = None
    units: str | None = None
    space: str = "planar"
    notes: str | None = None
    points: tuple[Point, ...] = ()
    mechanism: Mechanism | None = None
    source: str | None = field(default=None, compare=False)
    naming: str | None = None   # a catalog mechanism's name: "structure", "behaviour", "example"
    masses: tuple[LinkMass, ...] = ()           # [[links]]: the links that have mass
    gravity: tuple[float, float] | None = None  # [forces] gravity, m/s^2
    loads: tuple[Load, ...] = ()                # [[loads]]
    cams: tuple[Cam, ...] = ()                  # [[cams]]: disc cams and followers
    # [task]: what a synthesised mechanism was designed to do (kept, written back, shown
    # by the drawings and the report; the solver ignores it)
    task: dict | None = field(default=None, compare=False)
    # [[gears]]: gear pairs, each also a joint of kind "gear" (a higher pair) in joints
    gears: tuple[GearPair, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "gears", tuple(self.gears))
        object.__setattr__(self, "joints", _with_gear_joints(tuple(self.joints), self.gears))
        object.__setattr__(self, "points", tuple(self.points))
        object.__setattr__(self, "masses", tuple(self.masses))
        object.__setattr__(self, "loads", tuple(self.loads))
        object.__setattr__(self, "cams", tuple(self.cams))
        _validate(self)

    # -- identity -------------------------------------------------------------------
    @cached_property
    def links(self) -> tuple[str, ...]:
        """Link names, in order of first appearance in the joints."""
        return tuple(dict.fromkeys(name for j in self.joints for name in j.links))

    @cached_property
    def _joint_index(self) -> dict[str, Joint]:
        return {j.id: j for j in self.joints}

    def joint(self, joint_id: str) -> Joint:
        """The joint called ``joint_id``."""
        return self._joint_index[joint_id]

    def freedom(self, joint: Joint) -> int:
        """A joint's relative freedom in the chain's space (validation refuses a pair
        that has no form in it)."""
        f = joint.pair.freedom(self.space)
        assert f is not None, f"a {joint.kind} pair has no {self.space} form"
        return f

    def point(self, point_id: str) -> Point:
        """The tracer point called ``point_id``."""
        return {p.id: p for p in self.points}[point_id]

    def joints_of(self, link: str) -> tuple[Joint, ...]:
        """The joints on a link, in id order."""
        return tuple(sorted((j for j in self.joints if link in j.links), key=lambda j: j.id))

    def reference_direction(self, link: str, *, joint: str | None = None) -> float:
        """The drawn direction (degrees) of the line a link's angle is measured by.

        The line runs from ``joint`` (by default the link's first joint by id order) to
        the link's first other joint by id order that is drawn at another place; when
        every joint of the link is at one place, along the link's first sliding pair;
        0 (the +x axis) when the link has no such pair. The CSV's ``angle:LINK`` and an
        input's angle are both measured by it. A figure within rounding of a round
        number is that number (1.4e-14 degrees is a drawing's 0).

        Examples
        --------
        >>> from chaingraph.model.chain import Chain, Joint
        >>> chain = Chain("bar", (Joint("A", "R", ("frame", "bar"), at=(0.0, 0.0)),
        ...                       Joint("B", "R", ("bar", "frame"), at=(0.0, 2.0))))
        >>> chain.reference_direction("bar"), chain.reference_direction("bar", joint="B")
        (90.0, -90.0)
        """
        joints = self.joints_of(link)
        start = self.joint(joint) if joint is not None else (joints[0] if joints else None)
        if start is None or start.at is None:
            return 0.0
        turn = line_direction([(j.id, j.at) for j in joints], start.id)
        if turn is not None:
            return tidy(math.degrees(turn), 360.0)
        axes = [j.axis for j in joints if j.kind == "P" and j.axis is not None]
        return float(axes[0]) if axes else 0.0

    @property
    def has_pose(self) -> bool:
        """True when every joint and point has a position in the drawn pose (a file
        given by its lengths has them once assembled)."""
        return all(j.at is not None for j in self.joints) and \
            all(p.at is not None for p in self.points)

    def positions(self) -> dict[str, tuple[float, float]]:
        """Every joint's and point's position in the drawn pose by id, joints first
        (those that have one: all of them when :attr:`has_pose`)."""
        out = {j.id: j.at for j in self.joints if j.at is not None}
        out.update({p.id: p.at for p in self.points if p.at is not None})
        return out

    # -- graphs ---------------------------------------------------------------------
    @cached_property
    def graph(self) -> nx.Graph:
        """The link-joint graph (frozen).

        Link nodes ``("link", name)`` carry ``part="link"``, ``bipartite=0``; joint
        nodes ``("joint", id)`` carry ``part="joint"``, ``bipartite=1``, ``kind``,
        ``order``, ``at``, ``axis`` and ``guide`` (the link carrying a P joint's
        guide). Each edge carries ``role``: ``"guide"`` or ``"block"`` on a P joint,
        ``"pin"`` otherwise.
        """
        g = nx.Graph(name=self.name)
        for link in self.links:
            g.add_node(link_node(link), part="link", bipartite=0, name=link)
        for j in self.joints:
            g.add_node(joint_node(j.id), part="joint", bipartite=1, name=j.id, kind=j.kind,
                       order=j.order, at=j.at, axis=j.axis, guide=j.guide,
                       closure=j.closure)
            for i, link in enumerate(j.links):
                role = ("guide" if i == 0 else "block") if j.kind == "P" else "pin"
                g.add_edge(joint_node(j.id), link_node(link), role=role)
        return nx.freeze(g)

    @cached_property
    def link_graph(self) -> nx.MultiGraph:
        """The link-adjacency multigraph (frozen).

        One node per link; one edge, keyed by the joint id, for every pair of links that
        share a joint. A joint of k links gives k(k-1)/2 edges, so this view cannot tell
        a ternary joint from three binary joints in a triangle: use :attr:`graph` for
        that.
        """
        g = nx.MultiGraph(name=self.name)
        g.add_nodes_from(self.links)
        for j in self.joints:
            for a in range(j.order):
                for b in range(a + 1, j.order):
                    g.add_edge(j.links[a], j.links[b], key=j.id, kind=j.kind)
        return nx.freeze(g)

    @cached_property
    def contracted_graph(self) -> nx.MultiGraph:
        """The contracted graph: runs of binary links and binary joints collapsed.

        Its nodes are the nodes of the link-joint graph whose degree is not 2 (links
        with one or three or more joints, joints of three or more links). Each edge
        stands for a run of degree-2 nodes between two of them and carries ``links``,
        the binary links along it, and ``joints``, the binary joints. A chain with no
        such node (a single loop) contracts to one node, its first link, with a
        self-loop carrying the whole loop.
        """
        g = self.graph
        branch = [n for n in g if g.degree(n) != 2] or [link_node(self.links[0])]
        c = nx.MultiGraph(name=self.name)
        c.add_nodes_from(branch)
        branch_set = set(branch)
        seen_edges = set()
        for start in branch:
            for first in g[start]:
                if frozenset((start, first)) in seen_edges:
                    continue
                path = [start, first]
                seen_edges.add(frozenset((start, first)))
                while path[-1] not in branch_set:
                    prev, here = path[-2], path[-1]
                    nxt = next(n for n in g[here] if n != prev)
                    seen_edges.add(frozenset((here, nxt)))
                    path.append(nxt)
                inner = path[1:-1]
                c.add_edge(start, path[-1],
                           links=tuple(n[1] for n in inner if n[0] == "link"),
                           joints=tuple(n[1] for n in inner if n[0] == "joint"))
        return nx.freeze(c)

    @cached_property
    def pieces(self) -> tuple[tuple[str, ...], ...]:
        """The links of each connected piece (one piece for a connected chain)."""
        order = {name: i for i, name in enumerate(self.links)}
        comps = []
        for comp in nx.connected_components(self.graph):
            links = sorted((n[1] for n in comp if n[0] == "link"), key=order.__getitem__)
            comps.append(tuple(links))
        return tuple(sorted(comps, key=lambda c: order[c[0]]))

    # -- new chains from this one ---------------------------------------------------
    def relabelled(self, links: dict[str, str] | None = None,
                   joints: dict[str, str] | None = None,
                   points: dict[str, str] | None = None) -> "Chain":
        """A copy with links, joints and points renamed (names not given are kept)."""
        lk, jt, pt = links or {}, joints or {}, points or {}
        ren = lambda m, x: m.get(x, x)  # noqa: E731
        new_joints = tuple(replace(j, id=ren(jt, j.id), links=tuple(ren(lk, x) for x in j.links))
                           for j in self.joints)
        new_points = tuple(replace(p, id=ren(pt, p.id), link=ren(lk, p.link)) for p in self.points)
        mech = self.mechanism
        if mech is not None:
            out = mech.output
            out = ren(lk, out) if out in self.links else ren(pt, out)
            mech = replace(mech, fixed=ren(lk, mech.fixed),
                           driver=None if mech.driver is None else ren(lk, mech.driver),
                           output=out,
                           inputs=tuple(replace(i, joint=ren(jt, i.joint))
                                        for i in mech.inputs))
        masses = tuple(replace(m, link=ren(lk, m.link)) for m in self.masses)
        loads = tuple(replace(x, on=ren(lk, x.on),
                              at=None if x.at is None else
                              ren(jt, x.at) if x.at in self._joint_index else ren(pt, x.at),
                              along=None if x.along is None else ren(jt, x.along))
                      for x in self.loads)
        cams = tuple(replace(c, id=ren(jt, c.id), cam=ren(lk, c.cam),
                             follower=ren(lk, c.follower)) for c in self.cams)
        gears = tuple(replace(g, id=ren(jt, g.id), links=tuple(ren(lk, x) for x in g.links),
                              carrier=ren(lk, g.carrier)) for g in self.gears)
        return replace(self, joints=new_joints, points=new_points, mechanism=mech,
                       masses=masses, loads=loads, cams=cams, gears=gears)

    def with_mechanism(self, fixed: str, driver: str | None = None, *,
                       omega: float | None = None, output: str | None = None) -> "Chain":
        """The inversion with ``fixed`` fixed and ``driver`` as input.

        Output and input speed are kept from the chain's own mechanism unless given;
        its inputs are kept when neither the fixed link nor the driver changes.
        """
        old = self.mechanism
        if omega is None:
            omega = old.omega if old else 1.0
        if output is None and old is not None:
            output = old.output
        inputs = old.inputs if old and old.fixed == fixed and driver is None else ()
        return replace(self, mechanism=Mechanism(fixed, driver, omega, output, inputs))

    def __repr__(self):
        m = self.mechanism
        tail = ""
        if m is not None:
            inputs = [i.joint for i in m.inputs]
            tail = f", fixed={m.fixed!r}" + (f", inputs={inputs!r}" if inputs
                                              else f", driver={m.driver!r}")
        return (f"Chain({self.name!r}, links={len(self.links)}, joints={len(self.joints)}"
                f"{tail})")

    def __str__(self):
        return self.name


def _with_gear_joints(joints: tuple[Joint, ...], gears: tuple[GearPair, ...]
                      ) -> tuple[Joint, ...]:
    """The joints with a ``"gear"`` joint for each gear pair that has none yet (a chain
    rebuilt by :func:`dataclasses.replace` has them already, perhaps placed)."""
    have = {j.id: j for j in joints}
    extra = []
    for g in gears:
        joint = have.get(g.id)
        if joint is None or joint.kind != "gear" or joint.links != tuple(g.links):
            extra.append(Joint(g.id, "gear", tuple(g.links), at=pitch_point(g, joints)))
    return joints + tuple(extra)


def _is_finite_pair(value) -> bool:
    return (isinstance(value, tuple) and len(value) == 2
            and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                    and math.isfinite(v) for v in value))


def mass_centre(chain: Chain, mass: LinkMass) -> tuple[float, float]:
    """A link's centre of mass in the drawn pose: its ``centre``, else the mean of the
    link's joints and points (a :class:`LinkMass` of ``chain``)."""
    if mass.centre is not None:
        return mass.centre
    where = chain.positions()
    pts = [where[j.id] for j in chain.joints if mass.link in j.links] + \
          [where[p.id] for p in chain.points if p.link == mass.link]
    return (sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts))


def _finite(value) -> bool:
    return (isinstance(value, (int, float)) and not isinstance(value, bool)
            and math.isfinite(value))


def _validate_forces(chain, fail, links, point_ids):
    """Masses, gravity, loads and friction: what ``chaingraph forces`` reads."""
    for j in chain.joints:
        if j.friction is None:
            continue
        if j.kind != "P":
            fail(f"'friction' is only for P joints (a {j.kind} joint here has no sliding "
                 "velocity to oppose)", f"joint {j.id!r}")
        if not _finite(j.friction) or j.friction < 0:
            fail(f"'friction' must be a finite coefficient >= 0, got {j.friction!r}",
                 f"joint {j.id!r}")
    named = set()
    for i, m in enumerate(chain.masses):
        where = f"[[links]] #{i + 1}"
        if m.link not in links:
            fail(f"'name' names no link of the chain: {m.link!r} "
                 f"(links: {', '.join(chain.links)})", where)
        where = f"[[links]] {m.link!r}"
        if m.link in named:
            fail("the link's mass is given twice", where)
        named.add(m.link)
        if not _finite(m.mass) or m.mass < 0:
            fail(f"'mass' must be a finite number of kg >= 0, got {m.mass!r}", where)
        if not _finite(m.inertia) or m.inertia < 0:
            fail(f"'inertia' must be a finite number of kg m^2 >= 0, got {m.inertia!r}",
                 where)
        if m.centre is not None and not _is_finite_pair(m.centre):
            fail("'centre' must be two finite numbers [x, y]", where)
    if chain.gravity is not None and not _is_finite_pair(chain.gravity):
        fail("'gravity' must be two finite numbers [gx, gy] (m/s^2)", "[forces]")
    for i, load in enumerate(chain.loads):
        _validate_load(chain, load, f"[[loads]] #{i + 1}", fail, links, point_ids)


def _validate_load(chain, load, where, fail, links, point_ids):
    """One load: its link and point, and what kind of load it is."""
    if load.on not in links:
        fail(f"'on' names no link of the chain: {load.on!r} "
             f"(links: {', '.join(chain.links)})", where)
    if load.force is not None and not _is_finite_pair(load.force):
        fail("'force' must be two finite numbers [Fx, Fy] (N)", where)
    if not load.mean_torque and not _finite(load.torque):
        fail(f"'torque' must be a finite number (N m) or \"mean\" (a steady resisting "
             f"torque equal to the mean effort), got {load.torque!r}", where)
    needs_at = load.force is not None or load.follows or load.resist is not None
    if needs_at and load.at is None:
        fail("a load with a force needs 'at': a joint or point of its link that the "
             "force's line passes through", where)
    if load.at is not None:
        on_link = ({j.id for j in chain.joints if load.on in j.links}
                   | {p.id for p in chain.points if p.link == load.on})
        if load.at not in on_link:
            what = ("is not on link " + repr(load.on) if load.at in point_ids
                    or any(j.id == load.at for j in chain.joints)
                    else "names no joint or point of the chain")
            fail(f"'at' {what}: {load.at!r} (on {load.on!r}: "
                 f"{', '.join(sorted(on_link)) or 'none'})", where)
    _validate_following(chain, load, where, fail)


def _validate_following(chain, load, where, fail):
    """A load that follows the motion: its table, its P joint, its cycle and stroke."""
    kinds = [k for k, given in (("force", load.force is not None),
                                ("table", load.table is not None),
                                ("pressure", load.pressure is not None),
                                ("resist", load.resist is not None)) if given]
    if len(kinds) > 1:
        fail(f"a load is one kind of force: it gives {' and '.join(map(repr, kinds))} "
             "(write one [[loads]] for each)", where)
    if load.follows:
        if load.along is None:
            fail("a 'table' or 'pressure' load needs 'along': the P joint along whose "
                 "axis it acts", where)
        rows = load.table if load.table is not None else load.pressure
        key = "table" if load.table is not None else "pressure"
        if (not rows or any(len(r) != 2 or not _is_finite_pair(r) for r in rows)):
            fail(f"'{key}' must be a list of [x, value] pairs of finite numbers", where)
        xs = [r[0] for r in rows]
        bad = next((k for k in range(1, len(xs)) if xs[k] <= xs[k - 1]), None)
        if bad is not None:
            fail(f"'{key}' must be increasing in its first column: row {bad + 1} "
                 f"({xs[bad]:g}) does not exceed row {bad} ({xs[bad - 1]:g})", where)
        if load.pressure is not None and load.area is None:
            fail("a 'pressure' load needs 'area': the piston's area (m^2)", where)
    elif load.along is not None:
        fail("'along' is for a 'table' or 'pressure' load (a force along a P joint's "
             "axis)", where)
    if load.area is not None and (load.pressure is None or not _finite(load.area)
                                  or load.area <= 0):
        fail("'area' must be a positive number of m^2, with 'pressure'", where)
    if load.along is not None:
        joint = next((j for j in chain.joints if j.id == load.along), None)
        if joint is None or joint.kind != "P":
            what = "names no joint" if joint is None else f"is a {joint.kind} joint"
            fail(f"'along' must name a P joint (the force acts along its axis): "
                 f"{load.along!r} {what}", where)
    if load.against not in ("slide", "input"):
        fail(f"'against' must be \"slide\" (the slide of 'along') or \"input\" (the input's "
             f"value, degrees), got {load.against!r}", where)
    if load.cycle is not None:
        turns = load.cycle / (2 * math.pi) if _finite(load.cycle) else 0.0
        if load.against != "input" or turns < 0.5 or abs(turns - round(turns)) > 1e-9:
            got = (f"{math.degrees(load.cycle):g}" if _finite(load.cycle)
                   else repr(load.cycle))
            fail(f"'cycle' must be a whole number of turns of the input (360 or 720 "
                 f"degrees), with against = \"input\", got {got}", where)
    if load.resist is not None and (not _finite(load.resist) or load.resist < 0):
        fail(f"'resist' must be a finite force >= 0 (N), got {load.resist!r}", where)
    if load.stroke is not None:
        ok = (("out", "in") if load.follows else ("forward", "return")
              if load.resist is not None else ())
        if load.stroke not in ok:
            fail(f"'stroke' {load.stroke!r}: a table load takes \"out\" or \"in\" (its "
                 "slide's), a 'resist' load \"forward\" or \"return\" (the input's)", where)


def _validate(chain: Chain) -> None:
    """Check a chain's semantics; raise ChainFileError naming what is wrong and where."""
    def fail(problem, where=None):
        raise ChainFileError(problem, source=chain.source, where=where)

    if not isinstance(chain.name, str) or not chain.name.strip():
        fail("'name' must be a non-empty string", "key 'name'")
    if chain.space not in SPACES:
        fail(f"unknown space {chain.space!r} (expected 'planar' or 'spatial')", "key 'space'")
    if not chain.joints:
        fail("the chain has no joints (add [[joints]] tables)", "key 'joints'")
    if chain.gears:                  # before the joints: a pair's own words for its faults
        gear_ids = {g.id for g in chain.gears}
        check_gears(chain.gears, [j.links for j in chain.joints if j.kind == "R"],
                    {x for j in chain.joints if not (j.kind == "gear" and j.id in gear_ids)
                     for x in j.links},
                    fail)
    seen = set()
    for j in chain.joints:
        if not isinstance(j.id, str) or not j.id:
            fail("a joint id must be a non-empty string", "joint")
        if j.id in seen:
            if any(g.id == j.id for g in chain.gears):
                fail("the id is a joint's too (gear pairs and joints share one "
                     "namespace)", f"gear pair {j.id!r}")
            fail("duplicate joint id", f"joint {j.id!r}")
        seen.add(j.id)
        _validate_joint(chain, j, fail)
    links = set(chain.links)
    point_ids = _validate_points(chain, fail, links, seen)
    if chain.naming is not None and chain.naming not in ("structure", "behaviour", "example"):
        fail(f"'naming' must be \"structure\" (the name holds for any dimensions), "
             f"\"behaviour\" (it needs the catalog's behaviour) or \"example\" (a worked "
             f"example: as behaviour, and a general name is preferred to it), "
             f"got {chain.naming!r}", "key 'naming'")
    _validate_forces(chain, fail, links, point_ids)
    if chain.mechanism is not None:
        _validate_mechanism(chain, fail, links, point_ids)


def _validate_joint(chain, j, fail):
    """One joint: its kind in the chain's space, its links, its position and axis, its
    closure."""
    where = f"joint {j.id!r}"
    if j.kind not in PAIR_KINDS:
        fail(f"unknown kind {j.kind!r} (expected one of {', '.join(PAIR_KINDS)})", where)
    pair = PAIR_KINDS[j.kind]
    if pair.freedom(chain.space) is None:
        other = "spatial" if chain.space == "planar" else "planar"
        fail(f"a {pair.name} ({j.kind}) has no {chain.space} form; "
             f"it belongs in a chain with space = {other!r}", where)
    if any(not isinstance(x, str) or not x for x in j.links):
        fail("link names must be non-empty strings", where)
    if len(j.links) < 2:
        fail(f"a joint needs at least two links, got {len(j.links)}", where)
    if len(set(j.links)) != len(j.links):
        dup = next(x for x in j.links if j.links.count(x) > 1)
        fail(f"link {dup!r} is named twice in one joint", where)
    if j.kind != "R" and len(j.links) != 2:
        fail(f"a {pair.name} ({j.kind}) joins exactly two links, got {len(j.links)}; "
             "only R joints may be multiple", where)
    if j.at is not None and not _is_finite_pair(j.at):
        fail("'at' must be two finite numbers [x, y]", where)
    if j.kind == "P":
        _validate_axis(j, fail, where)
    elif j.axis is not None:
        fail("'axis' is only for P joints", where)
    if j.closure is not None:
        if j.closure not in CLOSURES:
            fail(f"unknown closure {j.closure!r} (expected 'form' or 'force')", where)
        if pair.lower and j.closure == "force":
            fail("a lower pair is a closed pair; closure = 'force' is only for "
                 "higher pairs", where)


def _validate_axis(j, fail, where):
    """A P joint's 'at' and 'axis' go together: a chain written for its structure alone
    needs neither."""
    if j.at is not None and j.axis is None:
        fail("a P joint with 'at' needs 'axis' (direction of sliding, degrees); "
             "a chain written for its structure alone needs neither", where)
    if j.axis is not None and j.at is None:
        fail("a P joint with 'axis' needs 'at' (a point of the sliding line); "
             "a chain written for its structure alone needs neither", where)
    if j.axis is not None and (isinstance(j.axis, bool)
                               or not isinstance(j.axis, (int, float))
                               or not math.isfinite(j.axis)):
        fail("'axis' must be a finite number of degrees", where)


def _validate_points(chain, fail, links, joint_ids):
    """The points: ids unique beside the joints', on a link of the chain, placed;
    returns their ids."""
    point_ids = set()
    for p in chain.points:
        where = f"point {p.id!r}"
        if not isinstance(p.id, str) or not p.id:
            fail("a point id must be a non-empty string", "point")
        if p.id in point_ids or p.id in joint_ids:
            fail("duplicate id (points and joints share one namespace)", where)
        point_ids.add(p.id)
        if p.link not in links:
            fail(f"'link' names no link of the chain: {p.link!r}", where)
        if not _is_finite_pair(p.at):
            fail("'at' must be two finite numbers [x, y]", where)
    return point_ids


def _validate_mechanism(chain, fail, links, point_ids):
    """The ``[mechanism]``: its fixed link, driver, inputs, output and speed."""
    m = chain.mechanism
    if m.fixed not in links:
        fail(f"'fixed' names no link of the chain: {m.fixed!r} "
             f"(links: {', '.join(chain.links)})", "[mechanism]")
    if m.driver is not None:
        if m.driver not in links:
            fail(f"'driver' names no link of the chain: {m.driver!r} "
                 f"(links: {', '.join(chain.links)})", "[mechanism]")
        if m.driver == m.fixed:
            fail("'driver' is the fixed link", "[mechanism]")
    joint_ids = {j.id: j for j in chain.joints}
    named = set()
    for i, item in enumerate(m.inputs):
        where = f"[mechanism] inputs #{i + 1}"
        if item.joint not in joint_ids:
            fail(f"'inputs' names no joint of the chain: {item.joint!r} "
                 f"(joints: {', '.join(sorted(joint_ids))})", where)
        if item.joint in named:
            fail(f"joint {item.joint!r} is named twice in 'inputs'", where)
        named.add(item.joint)
        if joint_ids[item.joint].kind not in ("R", "P"):
            fail(f"an input must be an R or P joint; {item.joint!r} is "
                 f"{joint_ids[item.joint].kind}", where)
        if (item.start is None) != (item.stop is None):
            fail("give both 'from' and 'to', or neither (the input then stays at "
                 "its drawn value)", where)
    if m.output is not None and m.output not in links and m.output not in point_ids \
            and m.output not in joint_ids:
        fail(f"'output' names no link, joint or point of the chain: {m.output!r}",
             "[mechanism]")
    if (isinstance(m.omega, bool) or not isinstance(m.omega, (int, float))
            or not math.isfinite(m.omega) or m.omega == 0):
        fail("'omega' must be a finite non-zero number (rad/s)", "[mechanism]")


def chosen_inputs(chain: Chain, fixed: str | None = None, driver: str | None = None,
                  inputs: Sequence[Input] | None = None
                  ) -> tuple[str | None, str | None, Sequence[Input] | None]:
    """Which inputs a mechanism uses: ``(fixed, driver, inputs)``, those given, else
    the file's ``[mechanism]``: its inputs when it fixes the same link and no driver is
    asked for, else its driver."""
    m = chain.mechanism
    fixed = fixed or (m.fixed if m else None)
    if not inputs and driver is None and m is not None and m.inputs and fixed == m.fixed:
        inputs = m.inputs
    if not inputs:
        driver = driver or (m.driver if m else None)
    return fixed, driver, inputs


def line_direction(features: Sequence[tuple[str, Sequence[float] | None]], start: str, *,
                   tol: float = 0.0, unplaced: Callable[[str], float | None] | None = None
                   ) -> float | None:
    """The rule a link's reference direction follows, over given positions: the
    direction (radians) from ``start`` to the first other of ``features`` (``(id,
    position)`` in id order) that is farther than ``tol`` from it; a feature without a
    position yet (None: a sliding pair's point before it is placed) gives
    ``unplaced(id)``. None when there is none. :meth:`Chain.reference_direction`
    applies it to the drawn pose, the assembly to a link's own frame.

    >>> line_direction([("A", (0.0, 0.0)), ("B", (0.0, 0.0)), ("C", (0.0, 3.0))], "A")
    1.5707963267948966
    """
    here = dict(features)[start]
    assert here is not None, f"the line's start {start!r} has no position"
    for name, at in features:
        if name == start:
            continue
        if at is None:
            return unplaced(name) if unplaced is not None else None
        if math.dist(at, here) > tol:
            return math.atan2(at[1] - here[1], at[0] - here[0])
    return None
