"""The solve plan of an inversion: which links are found from which, in what order.

Built once per (chain, fixed link, inputs) and immutable. Coordinates: every link
carries a rigid motion (x, y, phi) from its drawn pose, so a point p of the drawing
moves to ``R(phi) p + (x, y)``; the drawn pose is all zeros. Constraints:

* an R joint of links a, b at point P: a's P and b's P coincide (a joint of k links
  gives k - 1 such pairs, each against the fixed link, else the first);
* a P joint of guide g and block b at point A with direction u: equal rotations, and
  b's A stays on the line through g's A along g's u (the same line with either link
  as guide, since their rotations are equal);
* an *input* joint adds one equation that prescribes its relative motion: the rotation
  of its second link relative to its first (R), or the block's slide along the guide
  (P), as the input's value ``delta`` (radians or length units from the drawn pose).

The inputs move along a line in their own space, parameterized by one path parameter
``tau`` (in "degrees": an R input's angle itself; a P input's slide over the size, as an
angle in degrees), so that the tracking of assembly modes and the grids work alike
whatever the inputs: ``delta_i = c_i + k_i tau``.

Steps, in the order the graph allows: a *single* link joined to known links by two
constraints (RR, RP, PP) or welded to a known link by an input joint (WR, WP); a *dyad*
of two links, each joined to known links by one constraint and to each other by one
(RRR, RRP, PRR, RPR, PRP, RPP, PPR), both solved in closed form; what is left is one
*group* (an Assur group of higher class, such as the triad of Stephenson's third
inversion, or links welded by an input between two moving links), solved by Newton's
method.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, fields, replace

import networkx as nx
import numpy as np
from numpy.typing import ArrayLike

from chaingraph._util.disjoint import DisjointSets
from chaingraph.errors import MechanismError
from chaingraph.kinematics.higher import (HIGHER_KINDS, Derived, derived_inputs,
                                          derived_options, not_derived)
from chaingraph.model.chain import Chain, Input, chosen_inputs
from chaingraph.model.snap import check_link_sizes, size_of

__all__ = ["Constraint", "Step", "InputJoint", "Plan", "build_plan"]


@dataclass(frozen=True)
class Constraint:
    """One R pair (links a, b) or P joint (a the guide, b the block) at ``point``;
    ``drive`` names the input (its key in pose and rate tables) that prescribes the
    pair's relative motion, if it is an input.

    In a plan of a drawn chain every link's frame is the drawing, so the joint is at
    ``point`` on both links and a P joint's links turn together. The assembly from
    lengths places links drawn each in its own frame: there ``point_b`` is the joint
    on b (``point`` on a) and ``turn`` a P joint's rotation of b less a's (radians).
    The position kernel (closed forms, group equations) reads both; the rates and the
    summary are asked of drawn chains only."""

    kind: str
    joint: str
    a: str
    b: str
    point: tuple[float, float]
    axis: float | None = None
    drive: str | None = None
    point_b: tuple[float, float] | None = None
    turn: float = 0.0

    def other(self, link: str) -> str:
        return self.b if link == self.a else self.a

    def at(self, link: str) -> tuple[float, float]:
        """The joint's point in ``link``'s frame."""
        return self.point if self.point_b is None or link == self.a else self.point_b


@dataclass(frozen=True)
class Step:
    """Links solved together: ``constraints`` lists attachments to known links first."""

    kind: str                 # "single", "dyad" or "group"
    links: tuple[str, ...]
    constraints: tuple[Constraint, ...]
    pattern: str


@dataclass(frozen=True)
class InputJoint:
    """An input of the plan: joint ``joint`` of kind R or P between links ``a`` (the
    fixed link for an R joint on it, the joint's first link, or the guide) and ``b``.
    ``value0`` is its value in the drawn pose (degrees for R, 0 slide for P);
    ``sweep`` the (from, to) asked for, or None."""

    joint: str
    kind: str
    a: str
    b: str
    value0: float
    sweep: tuple[float, float] | None = None

    @property
    def key(self) -> str:
        """The input's entry in pose and rate tables (never a link's name)."""
        return "@input:" + self.joint


@dataclass(frozen=True)
class Plan:
    """How to solve one inversion with its inputs."""

    chain: Chain
    fixed: str
    driver: str | None        # the input link, when the input is an R joint on the fixed link
    inputs: tuple[InputJoint, ...]
    lead: int                 # the input that ``tau`` measures (the first that moves)
    line: tuple[tuple[float, float], ...]   # per input (c, k): delta = c + k tau
    theta0: float | None      # tau at the drawn pose, None if the line misses it
    steps: tuple[Step, ...]
    constraints: tuple[Constraint, ...]
    size: float               # the mechanism's size (for tolerances)
    mobility: int             # Kutzbach
    numeric_mobility: int     # coordinates minus rank of the joints' constraint Jacobian
    origin: tuple[float, float] = (0.0, 0.0)   # the drawing's centre: see ``local``
    from_driver: bool = False  # given as ``driver = LINK`` (the CSV keeps ``theta`` first)
    #: the joints that higher pairs (cams, gears) move as functions of the inputs, in
    #: the order they follow from them (:mod:`chaingraph.kinematics.higher`)
    derived: tuple[Derived, ...] = ()

    def __hash__(self) -> int:
        """The fields' hash, as the dataclass's, worked out once: the plan keys the
        caches of its cycle and anchor, looked up several times a solve, and hashing
        the chain and the steps again each time costs more than the look-up."""
        found = self.__dict__.get("_hash")
        if found is None:
            found = hash(tuple(getattr(self, f.name) for f in fields(self)))
            object.__setattr__(self, "_hash", found)
        return found

    def reference_radians(self, link: str) -> float:
        """The drawn direction (radians) a link's angle is measured by
        (:meth:`Chain.reference_direction`), worked out once per plan and link."""
        known = self.__dict__.setdefault("_reference_radians", {})
        found = known.get(link)
        if found is None:
            found = known[link] = math.radians(self.chain.reference_direction(link))
        return found

    def __getstate__(self) -> dict:
        # (a string's hash differs from one process to the next: not pickled)
        return {k: v for k, v in self.__dict__.items() if k != "_hash"}

    @property
    def moving(self) -> tuple[str, ...]:
        return tuple(x for x in self.chain.links if x != self.fixed)

    def local(self, p: Sequence[float]) -> tuple[float, float]:
        """A drawn point in the plan's frame, centred on the drawing (so that precision
        does not depend on where the mechanism is drawn): the constraints and every
        pose are in this frame."""
        return (p[0] - self.origin[0], p[1] - self.origin[1])

    @property
    def moving_inputs(self) -> int:
        """How many inputs move along the sweep (the others are held)."""
        return sum(k != 0 for _, k in self.line)

    @property
    def rate_scale(self) -> float:
        """d(delta of the lead input)/d(tau): the lead's native units per degree of tau."""
        return self.line[self.lead][1]

    def deltas(self, tau: ArrayLike) -> list[np.ndarray]:
        """Each input's delta (radians or length) at the path parameters ``tau``."""
        tau = np.asarray(tau, dtype=float)
        return [c + k * tau for c, k in self.line]

    def values(self, tau: ArrayLike) -> list[np.ndarray]:
        """Each input's value (degrees for R, slide for P) at ``tau``."""
        out = []
        for n, (item, delta) in enumerate(zip(self.inputs, self.deltas(tau))):
            if n == self.lead and item.kind == "R":
                out.append(np.asarray(tau, dtype=float))   # tau is the lead's angle itself
            else:
                out.append(item.value0 + (np.degrees(delta) if item.kind == "R" else delta))
        return out

    def value(self, tau: ArrayLike) -> np.ndarray:
        """The lead input's value at ``tau`` (what the summary is expressed in)."""
        if self.inputs[self.lead].kind == "R":
            return np.asarray(tau, dtype=float)     # (tau is its angle: as values says)
        return self.values(tau)[self.lead]

    def tau(self, value: float) -> float:
        """The path parameter at which the lead input has ``value``."""
        item = self.inputs[self.lead]
        if item.kind == "R":
            return float(value)
        c, k = self.line[self.lead]
        return (value - item.value0 - c) / k

    def describe(self) -> str:
        """The input in words, for messages: the driver or the input joints."""
        if self.from_driver:
            return f"the driver {self.driver!r}"
        names = ", ".join(repr(i.joint) for i in self.inputs)
        return f"the input {names}" if len(self.inputs) == 1 else f"the inputs {names}"

    @property
    def lead_unit(self) -> str:
        """The unit word of the lead input's values."""
        return "degrees" if self.inputs[self.lead].kind == "R" else \
            (self.chain.units or "length units")


def _constraints(chain, fixed, inputs, origin, derived=()):
    def local(p):
        return (p[0] - origin[0], p[1] - origin[1])
    driven = {i.joint: i for i in (*inputs, *derived)}
    out = []
    for j in sorted(chain.joints, key=lambda j: j.id):
        item = driven.get(j.id)
        if j.kind in HIGHER_KINDS:         # a higher pair: its derived joint's input
            continue
        on_joint = [i for i in (*inputs, *derived) if i.joint == j.id]
        if j.kind == "R" and len(on_joint) > 1:
            out.extend(_shared_joint(j, on_joint, fixed, local(j.at)))
        elif j.kind == "R":
            ref = item.a if item else fixed if fixed in j.links else j.links[0]
            for x in j.links:
                if x == ref:
                    continue
                drive = item.key if item and x == item.b else None
                out.append(Constraint("R", j.id, ref, x, local(j.at), drive=drive))
        else:
            out.append(Constraint("P", j.id, j.links[0], j.links[1], local(j.at), j.axis,
                                  drive=item.key if item else None))
    return out


def _shared_joint(j, items, fixed, point):
    """The pairs of an R joint of several links that several inputs or derived joints
    drive (the arm on the frame an input and the sun on the arm a gear's, at one
    pivot): one constraint per driven pair, then each link not yet held by them
    pinned to the first link (the fixed link when it is on the joint)."""
    held = DisjointSets(j.links)
    out = []
    for i in items:
        if held.join(i.a, i.b):
            out.append(Constraint("R", j.id, i.a, i.b, point, drive=i.key))
    ref = fixed if fixed in j.links else j.links[0]
    for x in j.links:
        if held.join(ref, x):
            out.append(Constraint("R", j.id, ref, x, point))
    return out


def _parallel(c1, c2):
    return abs(math.sin(math.radians(c1.axis - c2.axis))) < 1e-9


def _steps(chain, fixed, constraints, closed_form=True, needs=None):
    """The plan's steps; ``needs`` maps a derived joint's key to the links its value
    is read from (a higher pair driven through the linkage): its joint places a link
    only once those are placed."""
    known = {fixed}
    remaining = list(constraints)
    steps = []
    order = list(chain.links)
    needs = needs or {}
    while len(known) < len(order):
        unknown = [x for x in order if x not in known]

        def attachments(u):
            return [c for c in remaining if u in (c.a, c.b) and c.other(u) in known
                    and needs.get(c.drive, frozenset()) <= known]
        step = None
        for u in unknown:
            att = attachments(u)
            # (without closed forms: only the weld of a pair driven through the linkage)
            welded = [c for c in att if c.drive is not None
                      and (closed_form or needs.get(c.drive))]
            if welded:
                step = Step("single", (u,), (welded[0],), "W" + welded[0].kind)
                break
            if not closed_form:
                continue
            if len(att) >= 2 and not (att[0].kind == att[1].kind == "P"
                                      and _parallel(att[0], att[1])):
                if att[0].kind == "P" and att[1].kind == "R":
                    att = [att[1], att[0]] + att[2:]
                step = Step("single", (u,), tuple(att), att[0].kind + att[1].kind)
                break
        if step is None:
            for a in (unknown if closed_form else []):
                att_a = attachments(a)
                if not att_a:
                    continue
                for c in remaining:
                    if a not in (c.a, c.b) or c.other(a) in known or c.drive is not None:
                        continue
                    b = c.other(a)
                    att_b = attachments(b)
                    pattern = att_a[0].kind + c.kind + att_b[0].kind if att_b else ""
                    if att_b and pattern != "PPP":
                        step = Step("dyad", (a, b), (att_a[0], att_b[0], c), pattern)
                        break
                if step is not None:
                    break
        if step is None:
            # (without closed forms every link but those a pair driven through the
            # linkage places after it)
            group = _smallest_group(unknown, known, remaining) if closed_form else \
                [u for u in unknown if not any(needs.get(c.drive) and u in (c.a, c.b)
                                               and u not in needs[c.drive] for c in remaining)]
            if not group:
                return None
            inside = set(group) | known
            cons = tuple(c for c in remaining if (c.a in group or c.b in group)
                         and c.a in inside and c.b in inside)
            step = Step("group", tuple(group), cons, "group of %d links" % len(group))
            if any(not needs.get(c.drive, frozenset()) <= known for c in cons):
                return None       # a pair's driving member placed only with its joint
        steps.append(step)
        known |= set(step.links)
        used = set(step.constraints)
        remaining = [c for c in remaining if c not in used]
    return tuple(steps)


def _equations(c):
    """The links whose coordinates each scalar equation of constraint ``c`` involves,
    by coordinate (0, 1, 2 for x, y, phi): an R pair's two equations involve every
    coordinate of both links; a P joint's equal rotations only the angles, its line
    (and, for an input, its slide) every coordinate; an R input's rotation the angles."""
    every: tuple[int, ...] = (0, 1, 2)
    angles: tuple[int, ...] = (2,)
    if c.kind == "R":
        out = [every, every] + ([angles] if c.drive is not None else [])
    else:
        out = [angles, every] + ([every] if c.drive is not None else [])
    return [[(x, k) for x in (c.a, c.b) for k in coords] for coords in out]


def _smallest_group(unknown, known, remaining):
    """The fewest of the ``unknown`` links that the constraints among them and the
    ``known`` links determine (an Assur group, found where no single link or dyad is
    left): from a matching of every unknown coordinate to an equation, a link needs
    the links its coordinates' equations involve (the Dulmage-Mendelsohn order); the
    least such closed set, when its equations have full rank at a generic placement,
    else every unknown link (one group, as before).

    Solving the least group first and going on with closed forms keeps each Newton
    system small: a 20-link chain of dyads with one of its outer links fixed was one
    group of 18 links, which took minutes to trace."""
    unknown_set = set(unknown)
    graph = nx.Graph()
    scalars = [(x, k) for x in unknown for k in range(3)]
    graph.add_nodes_from(scalars)
    involved = {}
    for n, c in enumerate(remaining):
        if c.a not in unknown_set and c.b not in unknown_set:
            continue
        if not (c.a in unknown_set or c.a in known) or not (c.b in unknown_set or c.b in known):
            continue
        for m, support in enumerate(_equations(c)):
            node = ("equation", n, m)
            involved[node] = {x for x, _ in support if x in unknown_set}
            graph.add_edges_from((node, (x, k)) for x, k in support if x in unknown_set)
    matching = nx.bipartite.hopcroft_karp_matching(graph, top_nodes=scalars)
    if any(v not in matching for v in scalars):
        return tuple(unknown)
    needs = nx.DiGraph()
    needs.add_nodes_from(unknown)
    for x, k in scalars:
        needs.add_edges_from((x, y) for y in involved[matching[(x, k)]] if y != x)
    closures = sorted(({x} | nx.descendants(needs, x) for x in unknown),
                      key=lambda group: (len(group), min(unknown.index(x) for x in group)))
    order = {x: i for i, x in enumerate(unknown)}
    for group in closures:
        if len(group) == len(unknown):
            break
        cons = [c for c in remaining if (c.a in group or c.b in group)
                and c.a in group | known and c.b in group | known]
        if _freedom(sorted(group, key=order.__getitem__), cons, 1.0, with_inputs=True,
                    generic=True) == 0:
            return tuple(sorted(group, key=order.__getitem__))
    return tuple(unknown)


def _slide_origin(chain, item):
    """A P input's value in the drawn pose: 0 (slides measured from the drawn pose), or
    its ``at`` where the file gives one (a file by lengths: from the guide's origin),
    also when the input is named again without it (``--input S``)."""
    if item.at is not None:
        return float(item.at)
    m = chain.mechanism
    same = [i.at for i in (m.inputs if m else ()) if i.joint == item.joint]
    return float(same[0]) if same and same[0] is not None else 0.0


def _input_joints(chain, fixed, driver, inputs, name):
    """The plan's inputs from ``driver`` (a link) or ``inputs`` (Input items)."""
    if inputs:
        out = []
        for item in inputs:
            try:
                j = chain.joint(item.joint)
            except KeyError:
                j = None
            if j is None:
                raise MechanismError(f"the input {item.joint!r} is not a joint of the chain "
                                     f"(joints: {', '.join(sorted(x.id for x in chain.joints))})",
                                     mechanism=name)
            if j.kind == "R":
                if fixed in j.links:
                    a, b = fixed, next(x for x in j.links if x != fixed)
                    value0 = chain.reference_direction(b, joint=j.id)
                else:
                    a, b = j.links[0], j.links[1]
                    value0 = math.remainder(chain.reference_direction(b, joint=j.id)
                                            - chain.reference_direction(a, joint=j.id),
                                            360.0)
            else:
                a, b = j.links
                value0 = _slide_origin(chain, item)
            sweep = None if item.start is None else (float(item.start), float(item.stop))
            out.append(InputJoint(j.id, j.kind, a, b, value0, sweep))
        if len({i.joint for i in out}) < len(out):
            raise MechanismError("an input joint is named twice", mechanism=name)
        return tuple(out)
    if driver is None:
        raise MechanismError("no driver or input: name the driver link or the input joints "
                             "([mechanism] driver or inputs)", mechanism=name)
    if driver not in chain.links:
        raise MechanismError(f"the driver link {driver!r} is not a link of the chain "
                             f"(links: {', '.join(chain.links)})", mechanism=name)
    if fixed == driver:
        raise MechanismError("the driver is the fixed link", mechanism=name)
    pivots = sorted(j.id for j in chain.joints
                    if j.kind == "R" and fixed in j.links and driver in j.links)
    if not pivots:
        raise MechanismError(f"the driver {driver!r} is not pinned to the fixed link "
                             f"{fixed!r} by an R joint, so it cannot be turned as the input",
                             mechanism=name)
    pivot = chain.joint(pivots[0])
    if len(chain.joints_of(driver)) < 2:
        raise MechanismError(f"the driver {driver!r} has no joint besides its pivot",
                             mechanism=name)
    return (InputJoint(pivot.id, "R", fixed, driver,
                       chain.reference_direction(driver, joint=pivot.id)),)


def _line(inputs, size):
    """(lead, line, tau at the drawn pose or None) for inputs moving together."""
    def moves(i):
        return i.sweep is not None and i.sweep[0] != i.sweep[1]
    lead = next((n for n, i in enumerate(inputs) if moves(i)),
                next((n for n, i in enumerate(inputs) if i.sweep is not None), 0))
    m = inputs[lead]
    # the lead's own parameter: its angle (R) or its slide as an angle over the size (P)
    k_m = math.pi / 180.0 if m.kind == "R" else size * math.pi / 180.0
    c_m = -math.radians(m.value0) if m.kind == "R" else 0.0
    b_m = 1.0 if m.kind == "R" else k_m          # value = b_m tau, in the lead's units
    line = []
    for n, item in enumerate(inputs):
        if n == lead:
            line.append((c_m, k_m))
            continue
        f = math.pi / 180.0 if item.kind == "R" else 1.0
        if item.sweep is None:
            line.append((0.0, 0.0))
        elif not moves(m) or not moves(item):
            line.append((f * (item.sweep[0] - item.value0), 0.0))
        else:
            (f_i, t_i), (f_m, t_m) = item.sweep, m.sweep
            r = (t_i - f_i) / (t_m - f_m)
            line.append((f * (f_i - r * f_m - item.value0), f * r * b_m))
    tau0 = m.value0 if m.kind == "R" else 0.0     # where the lead's delta is 0
    scale = [1.0 if i.kind == "R" else size for i in inputs]
    through = all(abs(c + k * tau0) <= 1e-12 * s for (c, k), s in zip(line, scale))
    return lead, tuple(line), (tau0 if through else None)



def build_plan(chain: Chain, fixed: str | None = None, driver: str | None = None, *,
               inputs: Sequence[Input] | None = None, closed_form: bool = True) -> Plan:
    """Check that an inversion can be solved with its inputs and plan how.

    Parameters
    ----------
    chain : Chain
        A chain with a drawn pose.
    fixed, driver : str, optional
        The fixed link and the input link (turning about its R joint with the fixed
        link); by default the chain's ``[mechanism]``.
    inputs : sequence of Input, optional
        Input joints instead of a driver (R or P, between any two links), one per
        degree of freedom, each with its sweep or none.
    closed_form : bool
        ``False`` solves every link by Newton's method in one group (slower; the tests
        use it to check the closed forms and Newton against each other).

    Raises
    ------
    MechanismError
        For a spatial joint, a higher pair without its [[cams]] or [[gears]] table or
        that no input drives (a cam or gear pair moves its follower's or driven gear's
        joint as an input derived from its driving joint's: :mod:`.higher`), a joint
        without a position, a driver not
        pinned to the fixed link by an R joint, an input that is not an R or P joint
        of the chain, or as many inputs as there are not degrees of freedom (the
        mobility found is said).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> engine = chaingraph.load(catalog_path("reciprocating-engine"))
    >>> plan = build_plan(engine, inputs=[chaingraph.Input("S")])
    >>> [(s.pattern, s.links) for s in plan.steps]
    [('WP', ('crosshead',)), ('RRR', ('crank', 'connecting rod'))]
    """
    name = chain.source or chain.name
    fixed, driver, inputs = chosen_inputs(chain, fixed, driver, inputs)
    fixed = _check_solvable(chain, fixed, inputs, name)
    inputs = tuple(inputs or ())
    items = _input_joints(chain, fixed, driver, inputs, name)
    from_driver = not inputs
    lone = items[0] if len(items) == 1 and items[0].kind == "R" and items[0].a == fixed else None
    where = chain.positions()       # all of them: _check_solvable refused one unplaced
    size = size_of(where)
    xs, ys = [p[0] for p in where.values()], [p[1] for p in where.values()]
    origin = (0.5 * (max(xs) + min(xs)), 0.5 * (max(ys) + min(ys)))
    derived, constraints, steps = _placed(chain, fixed, items, origin, name, closed_form)
    # Kutzbach: a lower pair takes 2 freedoms, a higher pair (cam, gear) 1
    mobility = 3 * (len(chain.links) - 1) - sum((3 - (j.pair.planar_freedom or 1))
                                                * (j.order - 1) for j in chain.joints)
    numeric = _numeric_mobility(chain, fixed, constraints, size, with_inputs=False,
                                derived=derived)
    _check_inputs_hold(chain, fixed, items, constraints, size, mobility=mobility,
                       numeric=numeric, driver=driver, from_driver=from_driver)
    if steps is None:
        raise _refuse_unplaced(chain, derived, name)
    lead, line, tau0 = _line(items, size)
    return Plan(chain=chain, fixed=fixed, driver=lone.b if lone else None, inputs=items,
                lead=lead, line=line, theta0=tau0, steps=steps, constraints=constraints,
                size=size, mobility=mobility, numeric_mobility=numeric, origin=origin,
                from_driver=from_driver, derived=derived)


def _needs(derived):
    """Each derived joint's key: the links its value is read from (none for a joint
    the inputs alone drive)."""
    out: dict[str, frozenset[str]] = {}
    for d in derived:
        out[d.key] = frozenset(d.after) if d.after is not None else out.get(d.by, frozenset())
    return out


def _placed(chain, fixed, items, origin, name, closed_form):
    """The higher pairs' derived joints, the constraints and the steps: the first way
    of driving the pairs (:func:`~chaingraph.kinematics.higher.derived_options`) whose
    pairs driven through the linkage each place their driven link after the links they
    are read from. Refuses a pair that no way drives."""
    options = derived_options(chain, [(i.joint, i.key, i.a, i.b) for i in items], name)
    if not options:     # the pair the inputs cannot drive, said as before (it raises)
        derived_inputs(chain, [(i.joint, i.key, i.a, i.b) for i in items], name)
    first = None
    for derived in options:
        constraints = tuple(_constraints(chain, fixed, items, origin, derived))
        steps = _steps(chain, fixed, constraints, closed_form, _needs(derived))
        if steps is not None:
            return derived, constraints, steps
        first = first or (derived, constraints)
    assert first is not None, "derived_inputs refuses a chain with no way to drive it"
    return (*first, None)


def _refuse_unplaced(chain, derived, name):
    """The refusal of a plan whose pairs driven through the linkage cannot be placed."""
    late = next(d for d in derived if d.after is not None)
    pair = next(p for p in (*chain.gears, *chain.cams) if p.id == late.pair)
    return not_derived(pair, name, loop=True)


def _check_solvable(chain: Chain, fixed: str | None, inputs: Sequence[Input] | None,
                    name: str) -> str:
    """Refuse what cannot be solved for motion whatever its inputs: no fixed link or
    one not of the chain, a spatial chain, an input or a joint that is not R or P, a
    joint without a position, a chain in pieces, a link of zero length. Returns the
    fixed link."""
    if fixed is None:
        raise MechanismError("no fixed link: name it ([mechanism] fixed in the file, or the "
                             "parameter fixed)", mechanism=name, parameter="fixed")
    if fixed not in chain.links:
        raise MechanismError(f"the fixed link {fixed!r} is not a link of the chain "
                             f"(links: {', '.join(chain.links)})", mechanism=name)
    if chain.space != "planar":
        raise MechanismError("only planar chains can be solved; this one is spatial",
                             mechanism=name)
    for item in inputs or ():
        j = next((x for x in chain.joints if x.id == item.joint), None)
        if j is not None and j.kind not in ("R", "P"):
            raise MechanismError(f"the input {item.joint!r} is a {j.pair.name} ({j.kind}); "
                                 "an input must be an R or P joint", mechanism=name)
    paired = {c.id for c in chain.cams} | {g.id for g in chain.gears}
    for j in chain.joints:
        if j.kind not in ("R", "P") and not (j.kind in HIGHER_KINDS and j.id in paired):
            raise MechanismError(
                f"a {j.pair.name} ({j.kind}) cannot be solved for motion: only R and P "
                "joints can, and cams and gear pairs with their [[cams]] or [[gears]] "
                "tables (classification and inversions take every kind)",
                mechanism=name, where=f"joint {j.id!r}")
    unplaced = [j.id for j in chain.joints if j.at is None]
    if unplaced:
        said = ", ".join(repr(x) for x in unplaced)
        raise MechanismError(
            f"solving needs a drawn pose ('at' of every joint, and 'axis' of every P "
            f"joint): the chain is written for its structure alone; joint"
            f"{'s' if len(unplaced) > 1 else ''} {said} {'have' if len(unplaced) > 1 else 'has'}"
            " no position", mechanism=name)
    if len(chain.pieces) > 1:
        raise MechanismError("the chain is in several pieces that share no joint",
                             mechanism=name)
    check_link_sizes(chain)
    return fixed


def _check_inputs_hold(chain, fixed, items, constraints, size, *, mobility, numeric,
                       driver, from_driver):
    """Refuse inputs that are not one per degree of freedom (``numeric`` at the drawn
    pose, ``mobility`` by Kutzbach's count), or that leave a freedom undriven; the
    message names the ``driver`` when the inputs are ``from_driver``."""
    name = chain.source or chain.name
    count = len(items)
    # a drawn pose at a dead centre or change point loses rank there: that is no reason
    # to refuse a chain whose count says it moves (its range says where it can go)
    if numeric != count and not (mobility == count and numeric > count):
        said = (f"driver {driver!r}" if from_driver else
                f"{count} input{'s' if count > 1 else ''} ({', '.join(i.joint for i in items)})")
        raise MechanismError(
            f"the mobility with {fixed!r} fixed is {numeric} at the drawn pose (Kutzbach: "
            f"{mobility}), so it needs {numeric} input{'s' if numeric != 1 else ''}, one per "
            f"degree of freedom; given the {said}", mechanism=name, mobility=numeric)
    if numeric == count:
        # structurally (at a generic placement of the joints: the drawn pose may be a
        # dead centre of these inputs, which its range will show)
        left = _numeric_mobility(chain, fixed, constraints, size, with_inputs=True,
                                 generic=True)
        if left:
            raise MechanismError(
                f"the inputs {', '.join(i.joint for i in items)} do not determine the "
                f"motion: with them held, {left} degree{'s' if left > 1 else ''} of freedom "
                "remain (two inputs that drive the same freedom?)", mechanism=name,
                mobility=numeric)


def _numeric_mobility(chain, fixed, constraints, size, *, with_inputs=False, generic=False,
                      derived=()):
    """Coordinates (3 per moving link) minus the rank of all ``constraints`` (every
    joint's; with ``with_inputs`` the inputs' equations too) at the drawn pose, or, with
    ``generic``, at a random placement of the joints (any placement is the drawn pose of
    some mechanism of this structure, so this is the structure's own count).

    The constraints are about the drawing's centre; the Jacobian is taken in units of
    its size, so that its rank does not depend on where the mechanism is drawn or how
    large it is."""
    return _freedom([x for x in chain.links if x != fixed], constraints, size,
                    with_inputs=with_inputs, generic=generic, derived=derived)


def _freedom(moving, constraints, size, *, with_inputs=False, generic=False, derived=()):
    """The coordinates of the ``moving`` links (3 each) minus the rank of the rows of
    ``constraints`` in them (every other link held): see :func:`_numeric_mobility`.
    Each of the ``derived`` joints is a constraint of the chain, with or without the
    inputs: its value less its slope times the driving joint's, linearised at the
    drawn pose."""
    col = {x: 3 * i for i, x in enumerate(moving)}
    rows = []
    rng = np.random.default_rng(20261122)
    joints = sorted({c.joint for c in constraints})
    placed = {j: tuple(rng.uniform(-1.0, 1.0, 2)) for j in joints}
    turned = {j: float(rng.uniform(0.0, 180.0)) for j in joints}
    drive_rows = {}
    derived_keys = {d.key for d in derived}
    for c in constraints:
        if generic:
            c = replace(c, point=placed[c.joint], axis=None if c.axis is None else turned[c.joint])
            scaled = c.point
        else:
            scaled = (c.point[0] / size, c.point[1] / size)
        for n, coeffs in enumerate(_rows_at_drawn_pose(replace(c, point=scaled),
                                                        with_inputs or c.drive in derived_keys)):
            row = np.zeros(3 * len(moving))
            for link, vec in coeffs.items():
                if link in col:
                    row[col[link]:col[link] + 3] += vec
            if c.drive is not None and n == 2:       # the input's row (R and P alike)
                drive_rows[c.drive] = row
                if c.drive in derived_keys:
                    continue              # added below, with its driving joint's
            rows.append(row)
    for d in derived:
        by = drive_rows.get(d.by)
        if d.after is not None:           # the rotation of one link less another's
            by = np.zeros(3 * len(moving))
            for link, sign in zip(d.after, (-1.0, 1.0)):
                if link in col:
                    by[col[link] + 2] += sign
        elif by is None:                  # an input left out: its row, as drawn
            by = _drive_row(constraints, d.by, col, size, len(moving))
        slope = float(d.slopes(0.0)[0])
        rows.append(drive_rows[d.key] - slope * d.by_sign * by)
    if not rows:
        return 3 * len(moving)
    rank = np.linalg.matrix_rank(np.array(rows), tol=1e-9)
    return 3 * len(moving) - int(rank)


def _drive_row(constraints, key, col, size, n):
    """The input row of the constraint driven by ``key``, at the drawn pose."""
    c = next(c for c in constraints if c.drive == key)
    scaled = replace(c, point=(c.point[0] / size, c.point[1] / size))
    row = np.zeros(3 * n)
    for link, vec in _rows_at_drawn_pose(scaled, True)[-1].items():
        if link in col:
            row[col[link]:col[link] + 3] += vec
    return row


def _rows_at_drawn_pose(c, with_inputs=False):
    px, py = c.point
    driven = with_inputs and c.drive is not None
    if c.kind == "R":
        rows = [{c.a: np.array([1.0, 0.0, -py]), c.b: np.array([-1.0, 0.0, py])},
                {c.a: np.array([0.0, 1.0, px]), c.b: np.array([0.0, -1.0, -px])}]
        if driven:
            rows.append({c.b: np.array([0.0, 0.0, 1.0]), c.a: np.array([0.0, 0.0, -1.0])})
        return rows
    a = math.radians(c.axis)
    rows = [{c.b: np.array([0.0, 0.0, 1.0]), c.a: np.array([0.0, 0.0, -1.0])}]
    # at the drawn pose d = 0, so the guide's rotation term n . perp(R A) cancels out
    for ux, uy in ((-math.sin(a), math.cos(a)),) + (((math.cos(a), math.sin(a)),) if driven else ()):
        perp_b = ux * -py + uy * px
        rows.append({c.b: np.array([ux, uy, perp_b]), c.a: np.array([-ux, -uy, -perp_b])})
    return rows
