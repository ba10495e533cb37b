"""Mechanism families for path synthesis: a parametrised chain and the link that carries
the tracing point.

A family's parameters are the *drawn pose* of its chain: the position of every joint
of its template, in the template's order, then the tracing point's (x, y pairs, one row
of ``2 * (joints + 1)`` numbers per mechanism). So a similarity of the plane (the task's
own frame, :class:`~chaingraph.synthesis.optimiser.TaskFrame`) moves a mechanism by
moving its parameters as points, lengths follow from positions, the assembly mode is
the drawn one, and the input's value at the drawn pose (the first target) is read off
the drawing, as the solver reads it. A family supplies, vectorised over many mechanisms:

* :meth:`Family.positions`: where the tracing point is at given input values (NaN where
  the chain cannot be assembled), tracking the drawn assembly;
* :meth:`Family.transmission`: the transmission angle there (degrees), and
  :meth:`Family.rotation` how far the carrier has turned from its drawn pose (radians);
* :meth:`Family.first_input`: the input's value (radians) at the drawn pose, and
  :meth:`Family.posed` the mechanisms drawn at other input values;
* :meth:`Family.sample`: random mechanisms of the family that can turn their input fully,
  about the origin at about unit size;
* :meth:`Family.chain`: one mechanism as a :class:`~chaingraph.model.chain.Chain` with
  its ``[mechanism]`` (output: the tracing point), to be certified from its file.

:class:`FourBar` is the four-bar's (closed form); a six-bar family plugs into the same
optimiser (:mod:`chaingraph.synthesis.optimiser`) by giving these seven.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from chaingraph.geometry import angle_between, circle_circle, circle_line, line_by_two_distances
from chaingraph.kinematics.equations import newton_step
from chaingraph.model.chain import Chain, Input, Joint, Mechanism, Point

__all__ = ["Family", "FourBar", "FOUR_BAR", "AtlasFamily", "LoopFamily", "DyadStep", "dyad_plan",
           "DYADS", "driven_about_fixed", "input_kind", "CylinderFamily",
           "CylinderDyads", "cylinder_joints", "cylinder_plan"]


class Family(ABC):
    """A parametrised chain (see the module): ``template`` (its joints' ids and the
    links they join; positions are the parameters), ``carrier`` (the link that carries
    the tracing point ``point``), ``fixed`` and ``driver`` (the input turns about its
    joint with the fixed link)."""

    name: str
    family_name: str
    template: tuple[Joint, ...]
    carrier: str
    fixed: str
    driver: str
    point: str = "P"
    #: whether the input is a sliding pair on the fixed link (its value a slide, in the
    #: parameters' units, not an angle): its path is open, swept over the slides that
    #: assemble (:meth:`sweep`)
    sliding: bool = False

    @property
    def title(self) -> str:
        """The family's name as a designed chain's name begins: its first letter a
        capital, the rest as written (a catalog name keeps its capitals)."""
        return self.name[:1].upper() + self.name[1:]

    @property
    def size(self) -> int:
        """The number of parameters."""
        return 2 * (len(self.template) + 1)

    @abstractmethod
    def positions(self, params: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray,
                                                                         np.ndarray]:
        """The tracing point (x, y) of each mechanism (rows of ``params``, (M, size)) at
        input values ``theta`` (radians, (M, K)), in the drawn assembly; NaN where it
        cannot be assembled."""

    @abstractmethod
    def transmission(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The transmission angle (degrees, (M, K)) at ``theta``; NaN where unassembled."""

    @abstractmethod
    def rotation(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """How far the carrier has turned (radians, (M, K)) at ``theta`` from its drawn
        pose; NaN where unassembled."""

    @abstractmethod
    def first_input(self, params: np.ndarray) -> np.ndarray:
        """The input's value (radians, (M,); a sliding input's: its slide) at the drawn
        pose."""

    def sweep(self, params: np.ndarray, steps: int) -> np.ndarray:
        """The input values (M, steps) a mechanism's path is sampled at: a turn from the
        drawn pose (the last sample one step short of it), or for a :attr:`sliding`
        input the slides that assemble about the drawn pose, limit to limit, both ends
        included (NaN rows where the drawn pose itself does not assemble)."""
        params = np.atleast_2d(params)
        return self.first_input(params)[:, None] + np.linspace(0.0, 2 * math.pi, steps,
                                                               endpoint=False)

    @abstractmethod
    def posed(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The same mechanisms drawn at input values ``theta`` (radians, (M,)) instead,
        in the drawn assembly (NaN where they cannot be)."""

    @abstractmethod
    def sample(self, rng: np.random.Generator, count: int) -> np.ndarray:
        """``count`` random mechanisms whose input turns fully, about the origin, their
        tracing point's path about unit size."""

    def slide_direction(self, params: np.ndarray) -> np.ndarray:
        """The direction (radians, (M,)) in which a sliding input on the fixed link
        moves its block as its value grows; NaN for other inputs."""
        return np.full(len(np.atleast_2d(params)), np.nan)

    def link_ratio(self, params: np.ndarray) -> np.ndarray:
        """The longest link (the distance between two joints of one link) over the
        shortest, per mechanism ((M,))."""
        joints = np.asarray(params)[..., :-2].reshape(len(params), -1, 2)
        index = {j.id: k for k, j in enumerate(self.template)}
        spans = []
        for link in sorted({x for j in self.template for x in j.links}):
            on = [index[j.id] for j in self.template if link in j.links]
            for a in range(len(on)):
                for b in range(a + 1, len(on)):
                    spans.append(np.hypot(*(joints[:, on[a]] - joints[:, on[b]]).T))
        s = np.stack(spans, axis=1)
        with np.errstate(all="ignore"):
            return s.max(axis=1) / s.min(axis=1)

    def chain(self, params: npt.ArrayLike, *, name: str, units: str, notes: str,
              task: dict | None = None, span: tuple[float, float] | None = None) -> Chain:
        """The mechanism of one row of parameters, drawn at its pose, its output the
        tracing point; a sliding input swept over ``span`` (slides from the drawn pose,
        file units) when given."""
        p = [float(v) for v in np.asarray(params, dtype=float)]
        return Chain(name, self._drawn_joints(p), family=self.family_name, units=units, notes=notes,
                     points=(Point(self.point, self.carrier, (p[-2], p[-1])),),
                     mechanism=self.mechanism(span), task=task)

    def mechanism(self, span: tuple[float, float] | None = None) -> Mechanism:
        """The ``[mechanism]`` of the family's chains: its fixed link, its input (the
        driver turning about the fixed link) and the tracing point as the output."""
        return Mechanism(self.fixed, self.driver, 1.0, self.point)

    def _drawn_joints(self, p: list[float]) -> tuple[Joint, ...]:
        """The template's joints drawn where one row of parameters puts them."""
        return tuple(Joint(j.id, j.kind, j.links, at=(p[2 * k], p[2 * k + 1]))
                     for k, j in enumerate(self.template))

    @abstractmethod
    def dimensions(self, params: np.ndarray) -> dict[str, float]:
        """One mechanism's lengths (and the tracing point's place on its link) by name."""


class FourBar(Family):
    """The four-bar: crank A-B about A, coupler B-C carrying the point P, rocker C-D
    about D. Parameters: A, B, C, D, P at the drawn pose (10 numbers)."""

    name = "four-bar"
    family_name = "four-bar chain"
    template = (Joint("A", "R", ("frame", "crank")), Joint("B", "R", ("crank", "coupler")),
                Joint("C", "R", ("coupler", "rocker")), Joint("D", "R", ("rocker", "frame")))
    carrier, fixed, driver = "coupler", "frame", "crank"

    @staticmethod
    def _unpack(params):
        p = np.asarray(params, dtype=float)
        a, b, c, d, pt = (p[:, 2 * k:2 * k + 2].T[..., None] for k in range(5))
        crank = np.hypot(b[0] - a[0], b[1] - a[1])
        coupler = np.hypot(c[0] - b[0], c[1] - b[1])
        rocker = np.hypot(c[0] - d[0], c[1] - d[1])
        # the drawn assembly: C left (+1) or right (-1) of the line from B to D
        mode = np.where((d[0] - b[0]) * (c[1] - b[1]) - (d[1] - b[1]) * (c[0] - b[0]) >= 0,
                        1.0, -1.0)
        with np.errstate(all="ignore"):
            ex, ey = (c[0] - b[0]) / coupler, (c[1] - b[1]) / coupler
        along = (pt[0] - b[0]) * ex + (pt[1] - b[1]) * ey
        across = -(pt[0] - b[0]) * ey + (pt[1] - b[1]) * ex
        return a, d, crank, coupler, rocker, mode, along, across

    def _joints(self, params, theta):
        a, d, crank, coupler, rocker, mode, along, across = self._unpack(params)
        theta = np.asarray(theta, dtype=float)
        bx, by = a[0] + crank * np.cos(theta), a[1] + crank * np.sin(theta)
        with np.errstate(all="ignore"):
            (mx, my), (nx, ny), raw = circle_circle((bx, by), coupler, (d[0], d[1]), rocker)
            root = mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
        cx, cy = mx + root * nx, my + root * ny
        return (bx, by), (cx, cy), d, coupler, along, across

    def positions(self, params: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray,
                                                                         np.ndarray]:
        (bx, by), (cx, cy), _, coupler, along, across = self._joints(params, theta)
        with np.errstate(all="ignore"):
            ex, ey = (cx - bx) / coupler, (cy - by) / coupler
        return bx + along * ex - across * ey, by + along * ey + across * ex

    def transmission(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        (bx, by), (cx, cy), d, _, _, _ = self._joints(params, theta)
        return angle_between((bx - cx, by - cy), (d[0] - cx, d[1] - cy))

    def posed(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        p = np.asarray(params, dtype=float)
        th = np.asarray(theta, dtype=float)[:, None]
        (bx, by), (cx, cy), _, _, _, _ = self._joints(p, th)
        x, y = self.positions(p, th)
        return np.concatenate([p[:, 0:2], bx, by, cx, cy, p[:, 6:8], x, y], axis=1)

    def first_input(self, params: np.ndarray) -> np.ndarray:
        p = np.asarray(params, dtype=float)
        return np.arctan2(p[:, 3] - p[:, 1], p[:, 2] - p[:, 0])

    def rotation(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        p = np.asarray(params, dtype=float)
        (bx, by), (cx, cy), _, _, _, _ = self._joints(p, theta)
        drawn = np.arctan2(p[:, 5] - p[:, 3], p[:, 4] - p[:, 2])[:, None]
        return np.arctan2(cy - by, cx - bx) - drawn

    def sample(self, rng: np.random.Generator, count: int) -> np.ndarray:
        """Grashof crank-rockers (the crank the shortest link, so that it turns fully),
        in either assembly, at a random crank angle, the coupler point anywhere within
        about the coupler's length of it, turned and scaled so that the point's path is
        about unit size about the origin."""
        drawn = 4 * count + 16
        frame = np.ones(drawn)
        coupler = rng.uniform(0.3, 2.5, drawn)
        rocker = rng.uniform(0.3, 2.5, drawn)
        crank = rng.uniform(0.08, 0.8, drawn) * np.minimum(np.minimum(coupler, rocker), 1.0)
        longest = np.maximum(np.maximum(frame, coupler), rocker)
        # Grashof, the crank shortest (s + l < p + q): its input turns fully
        ok = (crank + 2 * longest < frame + coupler + rocker - 1e-3) & (longest <= 15 * crank)
        keep = np.nonzero(ok)[0][:count]
        while keep.size < count:        # (about a third pass; never in practice)
            keep = np.concatenate([keep, keep[:count - keep.size]])
        crank, coupler, rocker, frame = (v[keep] for v in (crank, coupler, rocker, frame))
        theta = rng.uniform(0.0, 2 * math.pi, count)
        mode = rng.choice([-1.0, 1.0], count)
        a = np.zeros((2, count))
        d = np.stack([frame, np.zeros(count)])
        b = a + crank * np.stack([np.cos(theta), np.sin(theta)])
        (mx, my), (nx, ny), raw = circle_circle(b, coupler, d, rocker)
        root = mode * np.sqrt(np.maximum(raw, 0.0))
        c = np.stack([mx + root * nx, my + root * ny])
        e = (c - b) / coupler
        along = rng.uniform(-0.5, 1.5, count) * coupler
        across = rng.uniform(-1.0, 1.0, count) * coupler
        pt = b + along * e + across * np.stack([-e[1], e[0]])
        params = np.concatenate([a, b, c, d, pt]).T
        return _centred_unit(self, params)

    def dimensions(self, params: np.ndarray) -> dict[str, float]:
        a, d, crank, coupler, rocker, _, along, across = self._unpack(np.atleast_2d(params))
        frame = np.hypot(d[0] - a[0], d[1] - a[1])
        return {"crank": float(crank[0, 0]), "coupler": float(coupler[0, 0]),
                "rocker": float(rocker[0, 0]), "frame": float(frame[0, 0]),
                "point along": float(along[0, 0]), "point across": float(across[0, 0])}


#: the four-bar family
FOUR_BAR = FourBar()

_CURVE = 64       # samples of the tracing point's path when sampling a family


def _centred_unit(family: Family, params: np.ndarray) -> np.ndarray:
    """Mechanisms moved and scaled so that their tracing point's path (over a turn of
    the input) is centred on the origin, its largest extent 1."""
    theta = family.sweep(params, _CURVE)
    x, y = family.positions(params, theta)
    with np.errstate(all="ignore"):
        cx, cy = np.nanmean(x, axis=1), np.nanmean(y, axis=1)
        extent = np.maximum(np.nanmax(x, axis=1) - np.nanmin(x, axis=1),
                            np.nanmax(y, axis=1) - np.nanmin(y, axis=1))
    extent = np.where(np.isfinite(extent) & (extent > 0), extent, 1.0)
    pts = params.reshape(len(params), -1, 2)
    pts = (pts - np.stack([cx, cy], axis=1)[:, None, :]) / extent[:, None, None]
    return pts.reshape(len(params), -1)


# -- any chain of the atlas, solved dyad by dyad -----------------------------------------
#: the dyads solved in closed form (the kinds of the first outer, middle and second outer
#: joints): every dyad of a 1-dof chain (three sliding pairs would leave it free to slide)
DYADS = ("RRR", "RRP", "PRR", "RPR", "PRP", "RPP", "PPR")


@dataclass(frozen=True)
class DyadStep:
    """One dyad of a :class:`DyadPlan`: the unknown links ``first`` and ``second`` joined
    by ``middle``; ``first`` joins the known link ``first_known`` at ``first_joint``,
    ``second`` joins ``second_known`` at ``second_joint``; ``pattern`` the three joints'
    kinds (first, middle, second: one of :data:`DYADS`)."""

    first: str
    second: str
    middle: str
    first_joint: str
    second_joint: str
    first_known: str
    second_known: str
    pattern: str = "RRR"


def dyad_plan(chain: Chain, fixed: str, driver: str) -> tuple[DyadStep, ...] | None:
    """The order in which the links of ``chain`` are found, two at a time, once ``fixed``
    and ``driver`` (turning about the fixed link) are known: each step a dyad (RRR, or
    with sliding pairs RRP, PRR, RPR, PRP, RPP, PPR: :data:`DYADS`) whose outer joints
    are on known links (an Assur group of class II). ``driver`` turns or slides on the
    fixed link (:func:`input_kind`). None when the chain is not solved so (a joint of
    three links, a driver not on the fixed link by one turning or sliding pair, or a
    group of higher class: a triad).

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas
    >>> watt, stephenson = atlas(links=6)
    >>> [(s.first, s.second) for s in dyad_plan(watt, "L1", "L2")]
    [('L5', 'L6'), ('L3', 'L4')]
    >>> dyad_plan(stephenson, "L1", "L2") is None     # Stephenson III: a triad after L2
    True
    >>> slider_crank, = atlas(links=4, prismatic=1)
    >>> [(s.first, s.second, s.pattern) for s in dyad_plan(slider_crank, "L1", "L3")]
    [('L2', 'L4', 'PRR')]
    """
    if input_kind(chain, fixed, driver) is None:
        return None
    known = {fixed, driver}
    steps: list[DyadStep] = []
    while len(known) < len(chain.links):
        step = _next_dyad(chain, known)
        if step is None or step.pattern not in DYADS:
            return None
        steps.append(step)
        known |= {step.first, step.second}
    return tuple(steps)


def driven_about_fixed(chain: Chain, fixed: str, driver: str) -> bool:
    """Whether every joint of ``chain`` is a turning or sliding pair of two links and
    ``driver`` turns about ``fixed`` on one turning pair (both family classes also take
    a driver sliding on ``fixed``: :func:`input_kind`)."""
    return input_kind(chain, fixed, driver) == "R"


def input_kind(chain: Chain, fixed: str, driver: str) -> str | None:
    """``"R"`` when ``driver`` turns about ``fixed`` on one turning pair, ``"P"`` when it
    slides on it on one sliding pair (a linear actuator, a slider driving the rest),
    every joint of ``chain`` a turning or sliding pair of two links; else None.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas
    >>> slider_crank, = atlas(links=4, prismatic=1)
    >>> input_kind(slider_crank, "L1", "L3"), input_kind(slider_crank, "L1", "L2")
    ('R', 'P')
    """
    if not all(j.kind in ("R", "P") and len(j.links) == 2 for j in chain.joints):
        return None
    kinds = [j.kind for j in chain.joints if set(j.links) == {fixed, driver}]
    return kinds[0] if len(kinds) == 1 else None


def cylinder_joints(chain: Chain, fixed: str) -> list[str]:
    """The sliding pairs of ``chain`` between two links other than ``fixed`` (each a
    possible cylinder input: :class:`CylinderFamily`), every joint a turning or sliding
    pair of two links; else none.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas
    >>> slider_crank, = atlas(links=4, prismatic=1)
    >>> [j.links for j in slider_crank.joints if j.kind == "P"]
    [('L1', 'L2')]
    >>> cylinder_joints(slider_crank, "L3"), cylinder_joints(slider_crank, "L1")
    (['J1'], [])
    """
    if not all(j.kind in ("R", "P") and len(j.links) == 2 for j in chain.joints):
        return []
    return [j.id for j in chain.joints if j.kind == "P" and fixed not in j.links]


def _next_dyad(chain: Chain, known: set[str]) -> DyadStep | None:
    """The first dyad (in joint order) of two unknown links whose other ends are known."""
    def outer(link, middle):
        return next(((j, x) for j in chain.joints_of(link) if j.id != middle.id
                     for x in j.links if x != link and x in known), None)
    for m in chain.joints:
        u, v = m.links
        if u in known or v in known:
            continue
        a, b = outer(u, m), outer(v, m)
        if a is not None and b is not None:
            return DyadStep(u, v, m.id, a[0].id, b[0].id, a[1], b[1],
                            a[0].kind + m.kind + b[0].kind)
    return None


class AtlasFamily(Family):
    """A chain of the atlas as a mechanism family: ``fixed`` link, ``driver`` turning
    about it, the tracing point on ``carrier``; the joints' positions solved dyad by dyad
    (:func:`dyad_plan`: RRR, and with sliding pairs RRP, PRR, RPR, PRP) in closed form,
    vectorised over mechanisms and input values (a screen: every answer is certified by
    the kernel's solver from its written file). Parameters: every joint's drawn position
    in the chain's joint order, then for each sliding pair (in that order) a second
    point of its line (its direction: a similarity of the plane moves it as it moves
    the line), then the point's. ``name`` is the mechanism's (a catalog name where there
    is one)."""

    def __init__(self, chain: Chain, fixed: str, driver: str, carrier: str, *,
                 name: str | None = None) -> None:
        plan = dyad_plan(chain, fixed, driver)
        if plan is None:
            raise ValueError(f"{chain.name} with {fixed} fixed and {driver} driving is not "
                             "solved dyad by dyad")
        self.plan = plan
        self._setup(chain, fixed, driver, carrier, name)
        frames = {fixed: None, driver: (self._pivot, self._pivot)}
        for s in plan:
            frames[s.first] = (s.first_joint, s.middle)
            frames[s.second] = (s.second_joint, s.middle)
        self._carrier_frame = frames[carrier]

    def _setup(self, chain: Chain, fixed: str, driver: str, carrier: str,
               name: str | None, pivot: str | None = None) -> None:
        """What every family of a chain keeps: its template, links, pivot (the input's
        joint: by default the driver's with the fixed link) and the input's reference
        line, the sliding pairs' parameter rows."""
        self.template = tuple(Joint(j.id, j.kind, j.links) for j in chain.joints)
        self.fixed, self.driver, self.carrier = fixed, driver, carrier
        self.name = name or f"{chain.name}, {fixed} fixed"
        self.family_name = chain.family or chain.name
        self._index = {j.id: k for k, j in enumerate(self.template)}
        self._pivot = pivot or next(j.id for j in chain.joints
                                    if set(j.links) == {fixed, driver})
        on = sorted(j.id for j in chain.joints if driver in j.links and j.id != self._pivot)
        # the solver's input: the line from the pivot to the driver's first other joint;
        # a sliding input's: that joint's place along the guide (the block's slide)
        self._reference = (self._pivot, on[0])
        pair = chain.joint(self._pivot)
        self.sliding = pair.kind == "P"
        if self.sliding and fixed in pair.links:
            self.name += f", driven by its sliding pair {self._pivot}"
        # a slide of the block (the pair's second link) along the guide (its first)
        self._sign = 1.0 if pair.links[1] == driver else -1.0
        self._links = sorted({x for j in self.template for x in j.links})
        slides = [j.id for j in self.template if j.kind == "P"]
        self._axis_row = {jid: len(self.template) + k for k, jid in enumerate(slides)}
        self._last: tuple | None = None

    @property
    def size(self) -> int:
        """The number of parameters (a second point for each sliding pair's line)."""
        return 2 * (len(self.template) + len(self._axis_row) + 1)

    def _drawn(self, params):
        """The joints' drawn positions (M, J, 2)."""
        p = np.asarray(params, dtype=float)
        return p[:, :2 * len(self.template)].reshape(len(p), -1, 2)

    def _axis(self, params, jid):
        """A sliding pair's drawn direction (unit x, y, each (M, 1))."""
        p = np.asarray(params, dtype=float)
        k, r = 2 * self._index[jid], 2 * self._axis_row[jid]
        dx, dy = p[:, r] - p[:, k], p[:, r + 1] - p[:, k + 1]
        n = np.hypot(dx, dy)
        return (dx / n)[:, None], (dy / n)[:, None]

    def _motions(self, params, theta):
        """:meth:`_solve`, every link's motion NaN where any link's is (the chain
        assembles only where all of it does: a dyad that does not carry the point
        limits the input as the solver finds), the last answer kept: a fit asks for the
        points, the transmission angles and the turns of the same mechanisms at the
        same inputs."""
        p = np.ascontiguousarray(params, dtype=float)
        th = np.ascontiguousarray(theta, dtype=float)
        key = (p.shape, p.tobytes(), th.shape, th.tobytes())
        if self._last is None or self._last[0] != key:
            self._last = (key, _assembled(self._solve(p, th)))
        return self._last[1]

    def _solve(self, params, theta):
        """Every link's rigid motion from its drawn pose at ``theta``: link -> (c, s,
        (px, py), (qx, qy)) meaning x -> p + R(c, s) (x - q) ((M, K) arrays; None: fixed)."""
        drawn = self._drawn(params)
        theta = np.asarray(theta, dtype=float)
        turn = theta - self.first_input(params)[:, None]
        k = self._index[self._pivot]
        pivot = drawn[:, k, 0][:, None], drawn[:, k, 1][:, None]
        if self.sliding:        # the driver slides along the fixed guide, turning not
            ex, ey = self._axis(params, self._pivot)
            d = self._sign * turn
            driven = (np.ones_like(turn), np.zeros_like(turn),
                      (pivot[0] + d * ex, pivot[1] + d * ey), pivot)
        else:
            driven = (np.cos(turn), np.sin(turn), pivot, pivot)
        motions: dict[str, tuple | None] = {self.fixed: None, self.driver: driven}
        for s in self.plan:
            with np.errstate(all="ignore"):
                motions.update(self._dyad(s, params, motions))
        return motions

    def _dyad(self, s: DyadStep, params, motions) -> dict[str, tuple]:
        """One dyad's two motions (see :data:`DYADS`), in the drawn assembly mode."""
        drawn = self._drawn(params)

        def d(jid):
            k = self._index[jid]
            return drawn[:, k, 0][:, None], drawn[:, k, 1][:, None]
        s = _mirrored(s)
        a0, b0, m0 = d(s.first_joint), d(s.second_joint), d(s.middle)
        ka, kb = motions[s.first_known], motions[s.second_known]
        if s.pattern == "RPR":
            c, sn = _rpr_turn(_moved(ka, a0), _moved(kb, b0), a0, b0,
                              self._axis(params, s.middle))
            return {s.first: (c, sn, _moved(ka, a0), a0),
                    s.second: (c, sn, _moved(kb, b0), b0)}
        if s.pattern == "PRP":
            m = _lines_meet(_slide_line(ka, a0, m0, self._axis(params, s.first_joint)),
                            _slide_line(kb, b0, m0, self._axis(params, s.second_joint)))
            return {s.first: (*_turn_of(ka), m, m0), s.second: (*_turn_of(kb), m, m0)}
        if s.pattern == "RPP":          # both links turn with the second's guide
            turn = _turn_of(kb)
            a = _moved(ka, a0)
            first = (*turn, a, a0)
            m = _lines_meet(_slide_line(first, m0, m0, self._axis(params, s.middle)),
                            _slide_line(kb, b0, m0, self._axis(params, s.second_joint)))
            return {s.first: first, s.second: (*turn, m, m0)}
        a = _moved(ka, a0)
        r1 = np.hypot(m0[0] - a0[0], m0[1] - a0[1])
        if s.pattern == "RRR":
            b = _moved(kb, b0)
            r2 = np.hypot(m0[0] - b0[0], m0[1] - b0[1])
            mode = np.where((b0[0] - a0[0]) * (m0[1] - a0[1])
                            - (b0[1] - a0[1]) * (m0[0] - a0[0]) >= 0, 1.0, -1.0)
            (mx, my), (nx, ny), raw = circle_circle(a, r1, b, r2)
            root = mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
            m = (mx + root * nx, my + root * ny)
            return {s.first: _rigid(a0, m0, a, m), s.second: _rigid(b0, m0, b, m)}
        # RRP: the middle joint on the circle about a and on the second link's line
        ex, ey = self._axis(params, s.second_joint)
        base, (ux, uy) = _slide_line(kb, b0, m0, (ex, ey))
        mode = np.where((m0[0] - a0[0]) * ex + (m0[1] - a0[1]) * ey >= 0, 1.0, -1.0)
        (fx, fy), _, raw = circle_line(a, r1, base, (ux, uy))
        root = mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
        m = (fx + root * ux, fy + root * uy)
        return {s.first: _rigid(a0, m0, a, m), s.second: (*_turn_of(kb), m, m0)}

    def positions(self, params: np.ndarray, theta: np.ndarray) -> tuple[np.ndarray,
                                                                       np.ndarray]:
        motions = self._motions(params, theta)
        p = np.asarray(params, dtype=float)
        return _moved(motions[self.carrier], (p[:, -2][:, None], p[:, -1][:, None]))

    def rotation(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        c, s, _, _ = self._motions(params, theta)[self.carrier]
        return np.arctan2(s, c)

    def posed(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        p = np.asarray(params, dtype=float)
        th = np.asarray(theta, dtype=float)[:, None]
        motions = self._motions(p, th)
        drawn = self._drawn(p)
        out, axes = [], []
        for k, j in enumerate(self.template):
            # a sliding pair's place is its block's point (on the guide's line)
            link = j.links[1] if j.kind == "P" else next(
                (x for x in j.links if motions[x] is not None), j.links[0])
            x, y = _moved(motions[link], (drawn[:, k, 0][:, None], drawn[:, k, 1][:, None]))
            out += [x, y]
            if j.kind == "P":
                ex, ey = self._axis(p, j.id)
                c, s = _turn_of(motions[link])
                axes += [x + c * ex - s * ey, y + s * ex + c * ey]
        out += axes
        out += list(_moved(motions[self.carrier], (p[:, -2][:, None], p[:, -1][:, None])))
        return np.concatenate([np.broadcast_to(v, (len(p), 1)) for v in out], axis=1)

    def transmission(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The worst (farthest from 90 degrees) of the dyads' transmission angles: at an
        RRR dyad's middle joint, between its links; with a sliding pair (within [0, 90],
        as the certification measures a slider crank's), between the turning link and
        the guide's normal (RRP), the line between the two pivots and the guide's normal
        (RPR), or the two guides (PRP, RPP)."""
        motions = self._motions(params, theta)
        worst = np.full(np.shape(theta), 90.0)
        for s in self.plan:
            with np.errstate(all="ignore"):
                mu = self._dyad_angle(s, params, motions)
                worst = np.where(np.abs(mu - 90.0) > np.abs(worst - 90.0), mu, worst)
        return worst

    def _dyad_angle(self, s: DyadStep, params, motions) -> np.ndarray:
        """One dyad's transmission angle (see :meth:`transmission`)."""
        drawn = self._drawn(params)

        def at(link, jid):
            k = self._index[jid]
            return _moved(motions[link], (drawn[:, k, 0][:, None], drawn[:, k, 1][:, None]))

        def axis(link, jid):
            c, sn = _turn_of(motions[link])
            ex, ey = self._axis(params, jid)
            return c * ex - sn * ey, sn * ex + c * ey
        s = _mirrored(s)
        if s.pattern in ("PRP", "RPP"):
            first = s.first_joint if s.pattern == "PRP" else s.middle
            (ux, uy), (vx, vy) = axis(s.first, first), axis(s.second, s.second_joint)
            return np.degrees(np.arccos(np.clip(np.abs(ux * vx + uy * vy), 0.0, 1.0)))
        if s.pattern == "RPR":
            (ax, ay), (bx, by) = at(s.first, s.first_joint), at(s.second, s.second_joint)
            return _to_normal((bx - ax, by - ay), axis(s.first, s.middle))
        (ax, ay), (mx, my) = at(s.first, s.first_joint), at(s.first, s.middle)
        if s.pattern == "RRP":
            return _to_normal((ax - mx, ay - my), axis(s.second, s.second_joint))
        bx, by = at(s.second, s.second_joint)
        return angle_between((ax - mx, ay - my), (bx - mx, by - my))

    def first_input(self, params: np.ndarray) -> np.ndarray:
        drawn = self._drawn(params)
        a, b = (self._index[j] for j in self._reference)
        if self.sliding:        # the driver's joint's place along the guide
            ex, ey = self._axis(params, self._pivot)
            return self._sign * (drawn[:, b, 0] * ex[:, 0] + drawn[:, b, 1] * ey[:, 0])
        return np.arctan2(drawn[:, b, 1] - drawn[:, a, 1], drawn[:, b, 0] - drawn[:, a, 0])

    def slide_direction(self, params: np.ndarray) -> np.ndarray:
        """As :meth:`Family.slide_direction`: the guide's axis, its sign the slide's."""
        p = np.atleast_2d(params)
        if not self.sliding or self.fixed not in self.template[self._index[self._pivot]].links:
            return super().slide_direction(p)
        ex, ey = self._axis(p, self._pivot)
        return np.arctan2(self._sign * ey[:, 0], self._sign * ex[:, 0])

    def params_of(self, at: dict[str, tuple[float, float]], axes: dict[str, float],
                  point: tuple[float, float]) -> np.ndarray:
        """One row of parameters from the joints' places ``at`` (by id), the sliding
        pairs' ``axes`` (radians, by id) and the tracing point's place."""
        row = [v for j in self.template for v in at[j.id]]
        for jid, _ in sorted(self._axis_row.items(), key=lambda kv: kv[1]):
            row += [at[jid][0] + math.cos(axes[jid]), at[jid][1] + math.sin(axes[jid])]
        return np.array(row + list(point), dtype=float)

    def sweep(self, params: np.ndarray, steps: int) -> np.ndarray:
        """As :meth:`Family.sweep`; a sliding input's range found by probing
        :data:`_REACH` times the mechanism's spread either way of the drawn slide, the
        run of probes that assemble about it kept and each end refined by bisection
        (:data:`_ENDS` halvings) towards the limit beyond it."""
        p = np.atleast_2d(np.asarray(params, dtype=float))
        if not self.sliding:
            return super().sweep(p, steps)
        probe, ok = self._probed(p)
        half = probe.shape[1] // 2
        rows = np.arange(len(p))
        ends = []
        for side in (1, -1):        # the last probe that assembles, and the next beyond
            run = np.cumprod(ok[:, half::side], axis=1).sum(axis=1)
            last = half + side * np.maximum(run - 1, 0)
            beyond = np.clip(last + side, 0, 2 * half)
            good, bad = probe[rows, last], probe[rows, beyond]
            for _ in range(_ENDS):
                mid = 0.5 * (good + bad)
                with np.errstate(all="ignore"):
                    fine = np.isfinite(self.positions(p, mid[:, None])[0][:, 0])
                good, bad = np.where(fine, mid, good), np.where(fine, bad, mid)
            ends.append(good)
        hi, lo = ends
        theta = lo[:, None] + (hi - lo)[:, None] * np.linspace(0.0, 1.0, steps)
        return np.where(ok[:, half:half + 1], theta, np.nan)

    def _probed(self, p):
        """A sliding input's probes (M, 2 * :data:`_PROBES` + 1: :data:`_REACH` times
        the mechanism's spread either way of the drawn slide, evenly) and where the
        chain assembles there."""
        s0 = self.first_input(p)
        spread = np.max(np.ptp(self._drawn(p), axis=1), axis=1)
        probe = s0[:, None] + _REACH * spread[:, None] * np.linspace(-1.0, 1.0,
                                                                     2 * _PROBES + 1)
        with np.errstate(all="ignore"):
            return probe, np.isfinite(self.positions(p, probe)[0])

    def sample(self, rng: np.random.Generator, count: int) -> np.ndarray:
        """Random mechanisms of the chain that turn their input fully: the joints
        scattered over a unit square, the driver's other joints drawn in towards its
        pivot (a short crank), the sliding pairs' lines in random directions, the point
        near the carrier's joints; those that assemble over a whole turn kept (the draw
        repeated a few times, then the feasible ones repeated), centred and scaled as
        :func:`_centred_unit`."""
        kept: list[np.ndarray] = []
        have = 0
        for _ in range(_DRAWS):
            p = self._scattered(rng, 4 * count + 16)
            with np.errstate(all="ignore"):
                x, y = self.positions(p, self.sweep(p, 48))
                ok = np.all(np.isfinite(x), axis=1) & (self.link_ratio(p) <= 12.0)
                if self.sliding:    # a path, not a point: slides that move it
                    extent = np.maximum(np.ptp(x, axis=1), np.ptp(y, axis=1))
                    ok &= extent > 0.2 * np.max(np.ptp(self._drawn(p), axis=1), axis=1)
            kept.append(p[ok])
            have += int(ok.sum())
            if have >= count:
                break
        params = np.concatenate(kept)[:count]
        if len(params) == 0:
            params = self._scattered(rng, count)
        while len(params) < count:
            params = np.concatenate([params, params[:count - len(params)]])
        return _centred_unit(self, params)

    def _scattered(self, rng, n):
        joints = rng.uniform(-1.0, 1.0, (n, len(self.template), 2))
        pivot = self._index[self._pivot]
        shrink = rng.uniform(0.1, 0.4, (n, 1, 1))
        for k, j in enumerate(self.template):
            if self.driver in j.links and k != pivot and not self.sliding:
                joints[:, k] = joints[:, pivot] + shrink[:, 0] * (joints[:, k] - joints[:, pivot])
        on = [self._index[j.id] for j in self.template if self.carrier in j.links]
        centre = joints[:, on].mean(axis=1)
        point = centre + rng.normal(0.0, 0.5, (n, 2))
        turn = rng.uniform(0.0, 2 * math.pi, (n, len(self._axis_row)))
        axes = [joints[:, self._index[jid]] + 0.5 * np.stack([np.cos(turn[:, i]),
                                                              np.sin(turn[:, i])], axis=1)
                for i, jid in enumerate(self._axis_row)]
        return np.concatenate([joints.reshape(n, -1), *axes, point], axis=1)

    def mechanism(self, span: tuple[float, float] | None = None) -> Mechanism:
        """As :meth:`Family.mechanism`; a sliding input is the sliding pair on the fixed
        link (its value the block's slide along the guide from the drawn pose, in file
        units), swept over ``span`` when given (a slide may run on without a limit)."""
        if self.sliding:
            start, stop = (None, None) if span is None else (float(span[0]), float(span[1]))
            return Mechanism(self.fixed, None, 1.0, self.point,
                             inputs=(Input(self._pivot, start, stop),))
        return super().mechanism()

    def _drawn_joints(self, p: list[float]) -> tuple[Joint, ...]:
        """As :meth:`Family._drawn_joints`, each sliding pair along its line."""
        def axis(jid):
            k, r = 2 * self._index[jid], 2 * self._axis_row[jid]
            return math.degrees(math.atan2(p[r + 1] - p[k + 1], p[r] - p[k]))
        return tuple(Joint(j.id, j.kind, j.links, at=(p[2 * k], p[2 * k + 1]),
                           axis=axis(j.id) if j.kind == "P" else None)
                     for k, j in enumerate(self.template))

    def dimensions(self, params: np.ndarray) -> dict[str, float]:
        p = [float(v) for v in np.asarray(params).reshape(-1)]
        at = {j.id: (p[2 * k], p[2 * k + 1]) for k, j in enumerate(self.template)}
        out = {}
        for link in self._links:
            on = [j.id for j in self.template if link in j.links]
            for i, a in enumerate(on):
                for b in on[i + 1:]:
                    out[f"{a}-{b}"] = math.dist(at[a], at[b])
        for jid, r in self._axis_row.items():
            out[f"{jid} axis"] = math.degrees(math.atan2(p[2 * r + 1] - at[jid][1],
                                                         p[2 * r] - at[jid][0]))
        a, m = self._carrier_frame or (self._pivot, self._pivot)
        if a == m:
            a, m = sorted(j.id for j in self.template if self.carrier in j.links)[:2]
        ex, ey = at[m][0] - at[a][0], at[m][1] - at[a][1]
        length = math.hypot(ex, ey)
        dx, dy = p[-2] - at[a][0], p[-1] - at[a][1]
        out[f"{self.point} along {a}-{m}"] = (dx * ex + dy * ey) / length
        out[f"{self.point} across"] = (-dx * ey + dy * ex) / length
        return out


_DRAWS = 6        # rounds of random mechanisms drawn when sampling an atlas family
_REACH = 3.0      # a sliding input's slides probed either way, in the mechanism's spreads
_PROBES = 48      # probes either way of the drawn slide
_ENDS = 8         # halvings refining each end of a sliding input's range


def _moved(motion, point):
    """A drawn point (x, y) carried by a link's rigid motion (None: the fixed link)."""
    if motion is None:
        return point
    c, s, (px, py), (qx, qy) = motion
    dx, dy = point[0] - qx, point[1] - qy
    return px + c * dx - s * dy, py + s * dx + c * dy


def _assembled(motions: dict[str, tuple | None]) -> dict[str, tuple | None]:
    """Every link's motion (as :meth:`AtlasFamily._solve` gives them) made NaN where
    some link's is not finite."""
    moving = [v for v in motions.values() if v is not None]
    if not moving:
        return motions
    ok = np.ones(np.broadcast_shapes(*(np.shape(v[0]) for v in moving)), dtype=bool)
    for c, s, (px, py), _ in moving:
        ok &= np.isfinite(c) & np.isfinite(s) & np.isfinite(px) & np.isfinite(py)
    if ok.all():
        return motions

    def masked(v):
        return np.where(ok, v, np.nan)
    return {x: None if v is None else (masked(v[0]), masked(v[1]),
                                       (masked(v[2][0]), masked(v[2][1])), v[3])
            for x, v in motions.items()}


def _mirrored(s: DyadStep) -> DyadStep:
    """A PRR or PPR dyad as the RRP or RPP dyad it is, read from its other end."""
    if s.pattern not in ("PRR", "PPR"):
        return s
    return DyadStep(s.second, s.first, s.middle, s.second_joint, s.first_joint,
                    s.second_known, s.first_known, s.pattern[::-1])


def _turn_of(motion):
    """A link's rotation (cos, sin) from its drawn pose (the fixed link: none)."""
    return (1.0, 0.0) if motion is None else (motion[0], motion[1])


def _rigid(a0, m0, a, m):
    """The rigid motion taking drawn points a0, m0 to a, m (the same distance apart)."""
    ux, uy = m0[0] - a0[0], m0[1] - a0[1]
    vx, vy = m[0] - a[0], m[1] - a[1]
    n = ux * ux + uy * uy
    return (ux * vx + uy * vy) / n, (ux * vy - uy * vx) / n, a, a0


def _slide_line(known, b0, m0, axis):
    """The line on which a link sliding on ``known`` at the drawn point ``b0`` (along
    ``axis``, drawn) carries its drawn point ``m0``: (base, unit direction) now."""
    c, s = _turn_of(known)
    bx, by = _moved(known, b0)
    dx, dy = m0[0] - b0[0], m0[1] - b0[1]
    return (bx + c * dx - s * dy, by + s * dx + c * dy), (c * axis[0] - s * axis[1],
                                                          s * axis[0] + c * axis[1])


def _lines_meet(first, second):
    """Where two lines (base, direction) cross."""
    (bx, by), (ux, uy) = first
    (cx, cy), (vx, vy) = second
    det = ux * vy - uy * vx
    t = ((cx - bx) * vy - (cy - by) * vx) / det
    return bx + t * ux, by + t * uy


def _rpr_turn(a, b, a0, b0, axis):
    """An RPR dyad's turn (cos, sin) from its drawn pose: its links turn about ``a`` and
    ``b`` (drawn ``a0``, ``b0``) and slide on each other along ``axis`` (drawn), so
    their common line's normal n, turned, meets ``n . (b - a) = n0 . (b0 - a0)``; the
    root the drawn pose is on."""
    nx, ny = -axis[1], axis[0]
    c = nx * (b0[0] - a0[0]) + ny * (b0[1] - a0[1])
    (ux, uy), ratio, raw = line_by_two_distances(a, b, c)
    (u0x, u0y), _, _ = line_by_two_distances(a0, b0, c)
    mode = np.where(u0x * ny - u0y * nx >= 0, 1.0, -1.0)
    root = mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
    mx, my = ux * ratio - uy * root, uy * ratio + ux * root      # the turned normal
    return nx * mx + ny * my, nx * my - ny * mx


def _to_normal(u, axis):
    """The angle (degrees, [0, 90]) between the vector ``u`` and the normal of the unit
    ``axis``."""
    cos = np.abs(-u[0] * axis[1] + u[1] * axis[0]) / np.hypot(u[0], u[1])
    return np.degrees(np.arccos(np.clip(cos, 0.0, 1.0)))


# -- any chain of turning pairs, its group beyond the driver solved by Newton's method ----
_GRID = 24        # steps of the continuation over a turn of the input
_NEWTON = 6       # Newton iterations per step (and at each asked input)
_CLOSED = 1e-9    # a loop closes when every joint is within this (of the unit size)
_CORRECTION = 0.02  # the largest correction of a continuation step's prediction kept
_HALVINGS = 8     # halvings of a continuation step before a mechanism stops there
_OPEN_HALVINGS = 4  # the same where the step's loop does not close at all
_MARCHES = 400    # steps (kept or halved) of one continuation before it stops
_ENOUGH = 1e-7   # a continuation's nodes closed to this (of the unit size) need no more


def _det_sign(jac: np.ndarray) -> np.ndarray:
    """The signs of stacked square matrices' determinants (0 where singular or not
    finite)."""
    with np.errstate(all="ignore"):
        sign = np.linalg.slogdet(np.nan_to_num(jac, nan=0.0, posinf=0.0, neginf=0.0))[0]
    return np.where(np.isfinite(jac).all(axis=(1, 2)), sign, 0.0)


class LoopFamily(AtlasFamily):
    """A chain of turning pairs whose links beyond the driver are not found dyad by dyad
    (a triad: the Stephenson III, the Stephenson II driven by its binary link): every
    moving link's rigid motion from its drawn pose solved together by Newton's method,
    continued along the input from the drawn pose over a turn (its :data:`_GRID` nodes
    kept, so the drawn circuit is tracked; a sliding input's both ways from the drawn
    slide, as far as :meth:`AtlasFamily.sweep` probes) by a predictor-corrector (see
    :meth:`_marched`: steps as long as the branch allows, shorter where it turns fast or
    another passes near), then continued to each asked input from the node before it
    (nearer the drawn pose) the same way; vectorised over mechanisms.

    A *screen*, not a solver: it scores thousands of candidate mechanisms at once (an
    array row per mechanism, which the kernel's solver, one chain at a time, cannot),
    with its own loop-closure equations (each joint placed alike by its two links'
    motions) but the kernel's Newton step
    (:func:`chaingraph.kinematics.equations.newton_step`, its linear algebra:
    least squares at a fold, NaN where not finite). Nothing it finds is listed on its
    word: every candidate is written as a chain file and certified by the kernel's
    solver from that file (:func:`chaingraph.synthesis.certification.certify`: assembled
    at every target on one circuit, in order, its transmission angle and error
    recomputed), exactly as the dyads' closed form is."""

    def __init__(self, chain: Chain, fixed: str, driver: str, carrier: str, *,
                 name: str | None = None) -> None:
        if input_kind(chain, fixed, driver) is None:
            raise ValueError(f"{chain.name} with {fixed} fixed and {driver} driving is not "
                             "a chain of binary pairs driven on the fixed link")
        self.plan = ()
        self._setup(chain, fixed, driver, carrier, name)
        self._loop_setup([x for x in self._links if x not in (fixed, driver)],
                         [j for j in self.template if j.id != self._pivot],
                         [j for j in self.template if not set(j.links) & {fixed, driver}])

    def _loop_setup(self, unknown: list[str], equations: list[Joint],
                    middles: list[Joint]) -> None:
        """The loop-closure equations' bookkeeping: the ``unknown`` links (three
        unknowns each), the joints that give ``equations`` (two each) and those whose
        angle between their links is a transmission angle (``middles``)."""
        driver = self.driver
        self._kept: tuple | None = None
        self._unknown = unknown
        self._anchor = {x: self._index[next(j.id for j in self.template if x in j.links)]
                        for x in self._unknown}
        self._equations = [(self._index[j.id], j.links) for j in equations]
        self._carrier_frame = None
        col = {x: i for i, x in enumerate(self._links)}
        self._driver_col = col[driver]
        self._unknown_cols = [col[x] for x in self._unknown]
        self._anchor_rows = [self._anchor[x] for x in self._unknown]
        self._joint_rows = [k for k, _ in self._equations]
        self._first = [col[a] for _, (a, _) in self._equations]
        self._second = [col[b] for _, (_, b) in self._equations]
        # a sliding pair's equations: its block's point on the guide's line, no turn
        self._slides = [e for e, (k, _) in enumerate(self._equations)
                        if self.template[k].kind == "P"]
        self._select = tuple(np.array([[1.0 if links[side] == x else 0.0
                                        for x in self._unknown]
                                       for _, links in self._equations])
                             for side in (0, 1))
        self._middles = [(self._index[j.id], [self._index[next(k.id for k in self.template
                                                              if x in k.links and k.id != j.id)]
                                              for x in j.links]) for j in middles]

    @staticmethod
    def _lead(pivot, turn):
        """The driver's rigid motion (c, s, p, q; each (R,) or (R, 2)) from its move:
        ``turn`` (R,) about the ``pivot`` (R, 2), or for a sliding input its
        displacement (R, 2) along the guide."""
        if np.ndim(turn) == 2:
            ones = np.ones(len(turn))
            return ones, 0.0 * ones, pivot + turn, pivot
        return np.cos(turn), np.sin(turn), pivot, pivot

    def _moves(self, params, slide):
        """The driver's moves (:meth:`_lead`) for inputs ``slide`` (M, K) from the drawn
        one: the turns themselves, or a sliding input's displacements (M, K, 2)."""
        if not self.sliding:
            return slide
        ex, ey = self._axis(params, self._pivot)
        return self._sign * np.stack([slide * ex, slide * ey], axis=-1)

    def _state_motions(self, drawn, turn, z):
        """Every link's motion (as :meth:`AtlasFamily._solve`) from the unknowns ``z``
        (rows, 3 per unknown link: its anchor's move and its turn) and the driver's
        ``turn`` (:meth:`_lead`); rows of ``drawn`` (R, J, 2) and ``turn`` (R,) or
        (R, 2)."""
        pivot = drawn[:, self._index[self._pivot]]
        c, sn, p, q = self._lead(pivot, turn)
        out: dict[str, tuple | None] = {
            self.fixed: None,
            self.driver: (c, sn, (p[:, 0], p[:, 1]), (q[:, 0], q[:, 1]))}
        for k, x in enumerate(self._unknown):
            q = drawn[:, self._anchor[x]]
            out[x] = (np.cos(z[:, 3 * k + 2]), np.sin(z[:, 3 * k + 2]),
                      (q[:, 0] + z[:, 3 * k], q[:, 1] + z[:, 3 * k + 1]), (q[:, 0], q[:, 1]))
        return out

    def _closure(self, drawn, turn, z, normals=None):
        """The loop-closure equations' residuals (R, 2E: each turning pair's place by
        its first link less by its second; a sliding pair's block point off the guide's
        line, along its normal (``normals`` (R, S, 2), drawn), and the block's turn less
        the guide's) and their Jacobian (R, 2E, 3U), from the unknowns."""
        rows = len(z)
        unknown = len(self._unknown)
        links = len(self._links)
        d = drawn[:, self._joint_rows]                                   # (R, E, 2)
        # every link's motion (c, s, p, q) once: the fixed link's the identity
        c, s = np.ones((rows, links)), np.zeros((rows, links))
        p, q = np.zeros((rows, links, 2)), np.zeros((rows, links, 2))
        lead = self._lead(drawn[:, self._index[self._pivot]], turn)
        c[:, self._driver_col], s[:, self._driver_col] = lead[0], lead[1]
        p[:, self._driver_col], q[:, self._driver_col] = lead[2], lead[3]
        cols = self._unknown_cols
        q[:, cols] = drawn[:, self._anchor_rows]
        p[:, cols] = q[:, cols] + z.reshape(rows, unknown, 3)[:, :, :2]
        c[:, cols], s[:, cols] = np.cos(z[:, 2::3]), np.sin(z[:, 2::3])
        sides = []
        for side in (self._first, self._second):
            v = d - q[:, side]
            cl, sl = c[:, side], s[:, side]
            moved = np.empty_like(v)
            moved[..., 0] = cl * v[..., 0] - sl * v[..., 1]
            moved[..., 1] = sl * v[..., 0] + cl * v[..., 1]
            sides.append((p[:, side] + moved, moved))
        (pa, ra), (pb, rb) = sides
        f = pa - pb
        jac = np.zeros((rows, len(self._first), 2, unknown, 3))
        sa, sb = self._select
        jac[:, :, 0, :, 0] = jac[:, :, 1, :, 1] = sa - sb
        jac[:, :, 0, :, 2] = -ra[..., 1, None] * sa + rb[..., 1, None] * sb
        jac[:, :, 1, :, 2] = ra[..., 0, None] * sa - rb[..., 0, None] * sb
        if self._slides:
            self._slide_rows(f, jac, (pa, ra, pb, rb), turn, z, normals)
        return f.reshape(rows, -1), jac.reshape(rows, 2 * len(self._first), 3 * unknown)

    def _slide_rows(self, f, jac, sides, turn, z, normals):
        """The sliding pairs' rows of :meth:`_closure` (in place): the block's point off
        the guide's line (along the turned normal n) and the block's turn less the
        guide's."""
        e = self._slides
        pa, ra, pb, rb = (v[:, e] for v in sides)
        angle = np.zeros((len(z), len(self._links)))
        angle[:, self._driver_col] = turn if np.ndim(turn) == 1 else 0.0
        angle[:, self._unknown_cols] = z[:, 2::3]
        ta, tb = angle[:, [self._first[k] for k in e]], angle[:, [self._second[k] for k in e]]
        c, s = np.cos(ta), np.sin(ta)
        nx = c * normals[..., 0] - s * normals[..., 1]
        ny = s * normals[..., 0] + c * normals[..., 1]
        gap = pb - pa
        f[:, e] = np.stack([nx * gap[..., 0] + ny * gap[..., 1], tb - ta], axis=2)
        sa, sb = (m[e][None, :, :] for m in self._select)
        rows = np.zeros((len(z), len(e), 2) + jac.shape[3:])
        rows[:, :, 0, :, 0] = nx[..., None] * (sb - sa)
        rows[:, :, 0, :, 1] = ny[..., None] * (sb - sa)
        along_b = nx * -rb[..., 1] + ny * rb[..., 0]          # n . (d rb / d turn)
        along_a = (-ny * gap[..., 0] + nx * gap[..., 1]) - (nx * -ra[..., 1] + ny * ra[..., 0])
        rows[:, :, 0, :, 2] = along_b[..., None] * sb + along_a[..., None] * sa
        rows[:, :, 1, :, 2] = sb - sa
        jac[:, e] = rows

    def _newton(self, drawn, turn, z, normals=None, *, settled: float = 1e-14,
                enough: float | None = None):
        """Newton's iterations on the loop-closure equations from ``z``, each row's
        until none of its unknowns moves by more than ``settled`` or (when ``enough``
        is given) its equations are within ``enough`` (of the unit size; then with no
        step more): a row that has settled is left as it is, its answer not depending
        on the others'. The unknowns, whether they close (to ``settled`` or
        :data:`_CLOSED`) and the sign of the equations' Jacobian determinant there (a
        branch's, which changes where a step crossed onto another branch)."""
        z = np.array(z, dtype=float)
        size = np.maximum(1.0, np.abs(drawn).max(axis=(1, 2)))
        gap = np.full(len(z), np.nan)
        sign = np.zeros(len(z))
        live = np.arange(len(z))
        stale = []              # the rows stepped since their equations were last found
        for _ in range(_NEWTON):
            if live.size == len(z):
                f, jac = self._closure(drawn, turn, z, normals)
            else:
                f, jac = self._closure(drawn[live], turn[live], z[live],
                                       None if normals is None else normals[live])
            gap[live] = np.max(np.abs(f), axis=1)
            if enough is not None:
                going = ~(gap[live] <= enough * size[live])
                if not going.all():
                    sign[live[~going]] = _det_sign(jac[~going])
                live, f, jac = live[going], f[going], jac[going]
                if not live.size:
                    break
            step = newton_step(jac, f)         # the kernel's step (NaN where not finite)
            z[live] += step
            with np.errstate(invalid="ignore"):
                moving = np.any(np.abs(step) > settled, axis=1)
            stale.append(live[~moving])
            live = live[moving]
            if not live.size:
                break
        stale.append(live)
        last = np.concatenate(stale)
        if last.size:
            f, jac = self._closure(drawn[last], turn[last], z[last],
                                   None if normals is None else normals[last])
            gap[last] = np.max(np.abs(f), axis=1)
            sign[last] = _det_sign(jac)
        return z, gap <= max(settled, _CLOSED) * size, sign

    def _normals(self, params):
        """The sliding pairs' drawn normals (M, S, 2), in :meth:`_closure`'s order."""
        out = []
        for e in self._slides:
            ex, ey = self._axis(params, self.template[self._equations[e][0]].id)
            out.append(np.concatenate([-ey, ex], axis=1))
        return np.stack(out, axis=1) if out else np.zeros((len(params), 0, 2))

    def _nodes(self, params):
        """The continuation over a turn from the drawn pose: the unknowns at
        :data:`_GRID` + 1 even steps of the input (M, G + 1, 3U; NaN past where a
        mechanism stops closing), the prediction's state there (M, G + 1, 6U + 2: see
        :meth:`_marched`) and the sliding pairs' normals. The last mechanisms' are kept:
        a fit asks for their points, transmission angles and turns in turn."""
        p = np.ascontiguousarray(params, dtype=float)
        key = (p.shape, p.tobytes())
        if self._kept is not None and self._kept[0] == key:
            return self._kept[1]
        drawn = self._drawn(p)
        m, n = len(p), 3 * len(self._unknown)
        normals = self._normals(p)
        centre = _GRID if self.sliding else 0       # a slide's both ways from the middle
        nodes = np.full((m, centre + _GRID + 1, n), np.nan)
        nodes[:, centre] = 0.0
        rates = np.full((m, centre + _GRID + 1, 2 * n + 2), np.nan)
        h = self._reach(p) / _GRID if self.sliding else np.full(m, 2 * math.pi / _GRID)
        rates[:, centre] = 0.0
        rates[:, centre, :n], rates[:, centre, -1] = self._rate(p, drawn, normals,
                                                                np.zeros((m, n)), h)
        for way in ((1, -1) if self.sliding else (1,)):
            self._continued(p, drawn, normals, (nodes, rates), way * h, way)
        self._kept = (key, (nodes, rates, normals))
        return nodes, rates, normals

    def _reach(self, params):
        """A sliding input's slides continued either way (M,): as far as
        :meth:`AtlasFamily.sweep` probes."""
        return _REACH * np.max(np.ptp(self._drawn(params), axis=1), axis=1)

    def _probed(self, p):
        """As :meth:`AtlasFamily._probed`, the probes the continuation's nodes (where
        it closes: the run from the drawn slide to a fold, which the solver's range
        ends at too)."""
        nodes, _, _ = self._nodes(p)
        probe = (self.first_input(p)[:, None] + (self._reach(p) / _GRID)[:, None]
                 * np.arange(-_GRID, _GRID + 1))
        return probe, np.all(np.isfinite(nodes), axis=2)

    def _continued(self, params, drawn, normals, table, h, way):
        """The continuation (in place: ``table`` the nodes and the prediction's state
        there) from the node of the drawn pose (the first for a turn, the middle for a
        slide; its state the tangent) through the next :data:`_GRID` nodes, ``h`` (M,)
        of the input apart, ``way`` by ``way`` node (:meth:`_marched`), NaN past where a
        mechanism stops closing."""
        nodes, rates = table
        start = 0 if not self.sliding else _GRID
        stops = h[:, None] * np.arange(1, _GRID + 1)
        z, rate = self._marched(params, drawn, normals, (nodes[:, start], rates[:, start]),
                                np.zeros(len(params)), stops)
        at = start + way * np.arange(1, _GRID + 1)
        nodes[:, at], rates[:, at] = z, rate

    def _rate(self, params, drawn, normals, z, h):
        """The unknowns' rates per unit input (R, 3U) at the drawn pose (``z``, input
        0): the loop-closure equations' tangent, their change with the input by a
        central difference (a millionth of the step ``h`` (R,) either way); and the
        sign of their Jacobian determinant there (R,)."""
        d = 1e-6 * h
        f = [self._closure(drawn, self._moves(params, v[:, None])[:, 0], z, normals)
             for v in (d, -d, 0.0 * d)]
        rate = newton_step(f[2][1], (f[0][0] - f[1][0]) / (2.0 * d[:, None]))
        return np.where(np.isfinite(rate), rate, 0.0), _det_sign(f[2][1])

    def _marched(self, params, drawn, normals, state, u, stops, *, settled=1e-7):
        """Rows' unknowns continued from the input ``u`` (R,; from the drawn pose)
        through ``stops`` (R, K; inputs one way from ``u``). ``state``: the unknowns (R,
        N) and the prediction's state (R, 2N + 2: the unknowns' rate d1 per unit input,
        its change d2, the last step t, so that the unknowns a step s on are predicted
        z + s (d1 + d2 (s + t)): the quadratic through the last three points, or the
        tangent at the drawn pose; and the sign of the equations' Jacobian determinant).
        Each step is predicted so and corrected by :meth:`_newton` (each row to
        ``settled``), kept where the correction is within :data:`_CORRECTION` (radians,
        or of the mechanism's spread) and the determinant keeps its sign, halved where
        not (so a branch passing near another, or turning fast, is not left for it: the
        kernel's trace keeps the sign alike), at most :data:`_HALVINGS` times below the
        way between two stops (:data:`_OPEN_HALVINGS` where the loop does not close: a
        fold, where the mechanism stops, is the usual cause); a kept step's next is
        sized for a correction of half the largest (the correction grows as the step's
        cube), at most doubled; the rows march independently (only those still marching
        computed). Returns the unknowns and the prediction's state at every stop (R, K,
        ...; NaN from where a row stopped)."""
        z, rate = (np.array(v, dtype=float) for v in state)
        rows, k = stops.shape
        n = z.shape[1]
        u = np.array(u, dtype=float)
        bounds = np.concatenate([u[:, None], stops], axis=1)
        spans = np.abs(np.diff(bounds, axis=1))             # (R, K): between stops
        spread = np.max(np.ptp(drawn, axis=1), axis=1)
        scale = np.tile(np.stack([spread, spread, np.ones(rows)], axis=1),
                        (1, len(self._unknown)))
        out = np.full((rows, k, n), np.nan), np.full((rows, k, rate.shape[1]), np.nan)
        step = spans[:, 0].copy()
        at = np.zeros(rows, dtype=int)                      # each row's next stop
        i = np.arange(rows)                                 # the rows still marching
        for _ in range(_MARCHES * k):
            if not i.size:
                break
            left = stops[i, at[i]] - u[i]
            # the step, or the rest of the way in one or two (no short last one)
            reach = np.abs(left) <= step[i] * (1.0 + 1e-9)
            s = np.where(reach, left, np.where(np.abs(left) <= 2.0 * step[i], 0.5 * left,
                                                np.sign(left) * step[i]))
            d1, d2, t = rate[i, :n], rate[i, n:2 * n], rate[i, 2 * n]
            guess = z[i] + s[:, None] * (d1 + d2 * (s + t)[:, None])
            move = self._moves(params[i], (u[i] + s)[:, None])[:, 0]
            zn, conv, sign = self._newton(drawn[i], move, guess, normals[i], settled=settled,
                                          enough=settled if settled >= _ENOUGH else None)
            with np.errstate(invalid="ignore", divide="ignore"):
                fix = np.max(np.abs(zn - guess) / scale[i], axis=1)
                good = conv & (fix <= _CORRECTION) & ~(sign * rate[i, -1] < 0.0)
                grow = np.minimum((0.5 * _CORRECTION / fix[good]) ** (1.0 / 3.0), 2.0)
            a, r, sa = i[good], i[~good], s[good]
            span = sa + t[good]
            with np.errstate(invalid="ignore", divide="ignore"):
                d1n = (zn[good] - z[a]) / sa[:, None]
                d2n = np.where((span != 0.0)[:, None], (d1n - d1[good]) / span[:, None], 0.0)
            rate[a] = np.where((sa != 0.0)[:, None], np.concatenate(
                [d1n, d2n, sa[:, None], sign[good][:, None]], axis=1), rate[a])
            z[a] = zn[good]
            u[a] = np.where(reach[good], stops[a, at[a]], u[a] + sa)
            # a step cut short at a stop does not shorten the next
            step[a] = np.maximum(np.abs(sa) * grow, np.where(reach[good], step[a], 0.0))
            step[r] = 0.5 * np.abs(s[~good])
            stopped = a[reach[good]]
            out[0][stopped, at[stopped]] = z[stopped]
            out[1][stopped, at[stopped]] = rate[stopped]
            at[stopped] += 1
            least = spans[r, at[r]] / 2.0 ** np.where(conv[~good], _HALVINGS, _OPEN_HALVINGS)
            i = np.concatenate([a[at[a] < k], r[step[r] >= least]])
        return out

    def _solve(self, params, theta):
        """As :meth:`AtlasFamily._solve`, by continuation from the drawn pose (see the
        class): from the node at or before each asked input (nearer the drawn pose),
        :meth:`_marched` there; the asked inputs taken modulo a turn."""
        drawn = self._drawn(params)
        theta = np.asarray(theta, dtype=float)
        m, k = theta.shape
        n = 3 * len(self._unknown)
        h = np.full((m, 1), 2 * math.pi / _GRID)
        nodes, rates, normals = self._nodes(params)
        turn = theta - self.first_input(params)[:, None]
        if self.sliding:        # the node at or nearer the drawn slide; none beyond reach
            h = self._reach(params)[:, None] / _GRID
            node = _GRID + np.trunc(turn / h)
            node = np.where(np.abs(node - _GRID) <= _GRID, node, -1).astype(int)
            at = (node - _GRID) * h
            move = self._moves(params, turn)
            move = move.reshape((m * k,) + move.shape[2:])
        else:
            turn = turn % (2 * math.pi)
            node = np.minimum(np.floor(turn / h).astype(int), _GRID)
            at = node * h
            move = turn.reshape(-1)
        start, rate = (np.take_along_axis(v, np.maximum(node, 0)[:, :, None],
                                          axis=1).reshape(m * k, -1) for v in (nodes, rates))
        known = (node >= 0).reshape(-1) & np.all(np.isfinite(start), axis=1)
        rows, params_rows = np.repeat(drawn, k, axis=0), np.repeat(params, k, axis=0)
        normal_rows = np.repeat(normals, k, axis=0)
        z = np.zeros((m * k, n))
        if known.any():
            z[known] = self._marched(
                params_rows[known], rows[known], normal_rows[known],
                (start[known], rate[known]), at.reshape(-1)[known],
                turn.reshape(-1)[known][:, None], settled=1e-14)[0][:, 0]
            known &= np.all(np.isfinite(z), axis=1)
        z = np.where(known[:, None], z, np.nan)
        motions = self._state_motions(rows, move, z)
        return {x: None if v is None else (v[0].reshape(m, k), v[1].reshape(m, k),
                                           (v[2][0].reshape(m, k), v[2][1].reshape(m, k)),
                                           (v[3][0].reshape(m, k), v[3][1].reshape(m, k)))
                for x, v in motions.items()}

    def transmission(self, params: np.ndarray, theta: np.ndarray) -> np.ndarray:
        """The worst (farthest from 90 degrees) of the angles at the joints between two
        links of the group (each link's line to another of its joints)."""
        motions = self._motions(params, theta)
        drawn = self._drawn(params)
        worst = np.full(np.shape(theta), 90.0)
        for k, (i, j) in self._middles:
            with np.errstate(invalid="ignore"):
                mu = self._joint_angle(params, motions, k, (i, j))
                worst = np.where(np.abs(mu - 90.0) > np.abs(worst - 90.0), mu, worst)
        return np.where(np.isfinite(worst), worst, np.nan)

    def _lines(self, params, motions, k, others):
        """The lines (vectors (x, y)) from joint ``k`` to the ``others`` (one joint of
        each of its links, drawn rows), at the motions."""
        drawn = self._drawn(params)
        jt = self.template[k]
        pts = [_moved(motions[x], (drawn[:, o, 0][:, None], drawn[:, o, 1][:, None]))
               for x, o in zip(jt.links, others)]
        mx, my = _moved(motions[jt.links[0]], (drawn[:, k, 0][:, None],
                                               drawn[:, k, 1][:, None]))
        return [(x - mx, y - my) for x, y in pts]

    def _joint_angle(self, params, motions, k, others) -> np.ndarray:
        """The angle (degrees) at joint ``k`` between its two links' lines to
        ``others``."""
        u, v = self._lines(params, motions, k, others)
        return angle_between(u, v)


class CylinderFamily(LoopFamily):
    """A chain driven by a sliding pair between two moving links (a hydraulic cylinder:
    the inverted slider crank driven by its cylinder's extension, a boom lifted by a
    cylinder, a six-bar driven by one): the input ``joint`` (a P pair, neither of whose
    links is ``fixed``), its value the slide of its block (its second link) along its
    guide (its first) from the drawn pose, in the parameters' units, as the solver reads
    it from the file (``inputs = [{joint, from, to}]``). Every moving link is an unknown
    of the loop-closure equations (:class:`LoopFamily`'s, with the input pair's slide as
    one more equation), continued both ways from the drawn slide as a sliding input's;
    the transmission angles those at the joints between two moving links other than the
    cylinder's own. A screen, as :class:`LoopFamily`: every answer is certified by the
    kernel's solver from its written file."""

    def __init__(self, chain: Chain, fixed: str, joint: str, carrier: str, *,
                 name: str | None = None) -> None:
        pair = chain.joint(joint)
        if (pair.kind != "P" or fixed in pair.links
                or not all(j.kind in ("R", "P") and len(j.links) == 2 for j in chain.joints)):
            raise ValueError(f"{joint} of {chain.name} is not a sliding pair of two links "
                             f"other than {fixed} in a chain of binary pairs")
        self.plan = ()
        self._setup(chain, fixed, pair.links[1], carrier, name, pivot=joint)
        self.name += f", driven by its cylinder {joint}"
        self._loop_setup([x for x in self._links if x != fixed], list(self.template),
                         [j for j in self.template if fixed not in j.links and j.id != joint])
        self._input = next(e for e, (k, _) in enumerate(self._equations)
                           if self.template[k].id == joint)
        self._input_slide = self._slides.index(self._input)

    def first_input(self, params: np.ndarray) -> np.ndarray:
        """0: the slide is read from the drawn pose (as the solver reads it)."""
        return np.zeros(len(np.atleast_2d(params)))

    def _moves(self, params, slide):
        """The cylinder's slides themselves (its links are unknowns: no lead)."""
        return np.asarray(slide, dtype=float)

    def _closure(self, drawn, turn, z, normals=None):
        """:meth:`LoopFamily._closure` (every joint's equations, the driver an unknown
        too) and one row more: the block's slide along the guide's turned axis less
        ``turn`` (the asked slide, (R,))."""
        f, jac = super()._closure(drawn, turn, z, normals)
        k, (a, b) = self._equations[self._input]
        placed = []
        for x in (a, b):
            i = self._unknown.index(x)
            q = drawn[:, self._anchor[x]]
            c, s = np.cos(z[:, 3 * i + 2]), np.sin(z[:, 3 * i + 2])
            vx, vy = drawn[:, k, 0] - q[:, 0], drawn[:, k, 1] - q[:, 1]
            rx, ry = c * vx - s * vy, s * vx + c * vy
            placed.append((i, c, s, q[:, 0] + z[:, 3 * i] + rx, q[:, 1] + z[:, 3 * i + 1] + ry,
                           rx, ry))
        (ia, ca, sa, xa, ya, rax, ray), (ib, _, _, xb, yb, rbx, rby) = placed
        n = normals[:, self._input_slide]
        ex, ey = n[:, 1], -n[:, 0]                        # the drawn axis
        tx, ty = ca * ex - sa * ey, sa * ex + ca * ey      # turned with the guide
        gx, gy = xb - xa, yb - ya
        row = np.zeros((len(z), jac.shape[2]))
        row[:, 3 * ib], row[:, 3 * ib + 1] = tx, ty
        row[:, 3 * ia] -= tx
        row[:, 3 * ia + 1] -= ty
        row[:, 3 * ib + 2] += tx * -rby + ty * rbx
        row[:, 3 * ia + 2] += (-ty * gx + tx * gy) - (tx * -ray + ty * rax)
        slide = tx * gx + ty * gy - np.asarray(turn, dtype=float).reshape(len(z))
        return (np.concatenate([f, slide[:, None]], axis=1),
                np.concatenate([jac, row[:, None, :]], axis=1))

    def _joint_angle(self, params, motions, k, others) -> np.ndarray:
        """As :meth:`LoopFamily._joint_angle`; at a joint of a link of the cylinder, the
        angle (within [0, 90]) between the cylinder's axis (the force's line) and the
        other link's line (as the certification measures a boom's)."""
        links = self.template[k].links
        pair = self.template[self._index[self._pivot]]
        if not set(links) & set(pair.links):
            return super()._joint_angle(params, motions, k, others)
        lines = self._lines(params, motions, k, others)
        ux, uy = lines[1] if links[0] in pair.links else lines[0]
        ex, ey = self._axis(params, self._pivot)
        c, s = _turn_of(motions[pair.links[0]])
        tx, ty = c * ex - s * ey, s * ex + c * ey
        cos = np.abs(ux * tx + uy * ty) / np.hypot(ux, uy)
        return np.degrees(np.arccos(np.clip(cos, 0.0, 1.0)))


def cylinder_plan(chain: Chain, fixed: str, joint: str) -> tuple[DyadStep, ...] | None:
    """The dyads that solve ``chain`` driven by the cylinder ``joint`` (a sliding pair of
    two moving links) once its slide is given: its two links one rigid link (named as
    the guide), the rest found two links at a time from ``fixed`` (as
    :func:`dyad_plan`), every dyad of turning pairs (RRR); None when the chain is not
    solved so (a triad, a dyad with a sliding pair, or two joints between the same two
    links once the cylinder's are one).

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas
    >>> slider_crank, = atlas(links=4, prismatic=1)     # L3 fixed: a boom's cylinder
    >>> [(s.first, s.second, s.pattern) for s in cylinder_plan(slider_crank, "L3", "J1")]
    [('L1', 'L4', 'RRR')]
    """
    guide, block = chain.joint(joint).links
    joints = [Joint(j.id, j.kind, tuple(guide if x == block else x for x in j.links))
              for j in chain.joints if j.id != joint]
    if len({frozenset(j.links) for j in joints}) < len(joints):
        return None
    merged = Chain(chain.name, tuple(joints))
    known = {fixed}
    steps: list[DyadStep] = []
    while len(known) < len(merged.links):
        step = _next_dyad(merged, known)
        if step is None or step.pattern != "RRR":
            return None
        steps.append(step)
        known |= {step.first, step.second}
    return tuple(steps)


class CylinderDyads(CylinderFamily):
    """A :class:`CylinderFamily` solved in closed form (:func:`cylinder_plan`): at each
    slide the cylinder's two links move as one link (in its frame, the block's joints
    drawn moved along the axis by the slide), found with the rest dyad by dyad (RRR)
    from the fixed link; vectorised over mechanisms and slides as the atlas's dyad
    families, so searched on their budget."""

    def __init__(self, chain: Chain, fixed: str, joint: str, carrier: str, *,
                 name: str | None = None) -> None:
        super().__init__(chain, fixed, joint, carrier, name=name)
        plan = cylinder_plan(chain, fixed, joint)
        if plan is None:
            raise ValueError(f"{chain.name} driven by its cylinder {joint} with {fixed} "
                             "fixed is not solved dyad by dyad")
        self.plan = plan
        self._guide, self._block = chain.joint(joint).links
        self._on_block = {j.id for j in self.template
                          if self._block in j.links and j.id != joint}

    def _probed(self, p):
        """As :meth:`AtlasFamily._probed`: the closed form at even probes (no
        continuation's nodes)."""
        return AtlasFamily._probed(self, p)

    def _solve(self, params, theta):
        """Every link's motion at the slides ``theta`` ((M, K), from the drawn pose):
        the RRR dyads of :func:`cylinder_plan`, each link's joints where its own frame
        draws them (the merged link's block joints moved along the axis by the slide);
        the block's motion the merged link's after that move."""
        drawn = self._drawn(params)
        slide = np.asarray(theta, dtype=float) - self.first_input(params)[:, None]
        ex, ey = self._axis(params, self._pivot)
        shift = (slide * ex, slide * ey)
        zero = 0.0 * slide

        def d(jid, link, moved=True):
            k = self._index[jid]
            x, y = drawn[:, k, 0][:, None], drawn[:, k, 1][:, None]
            if moved and link == self._guide and jid in self._on_block:
                return x + shift[0], y + shift[1]
            return x + zero, y + zero
        motions: dict[str, tuple | None] = {self.fixed: None}
        for s in self.plan:
            with np.errstate(all="ignore"):
                a = _moved(motions[s.first_known], d(s.first_joint, s.first_known))
                b = _moved(motions[s.second_known], d(s.second_joint, s.second_known))
                a0, m1 = d(s.first_joint, s.first), d(s.middle, s.first)
                b0, m2 = d(s.second_joint, s.second), d(s.middle, s.second)
                # the assembly mode: the drawn pose's (every joint where it is drawn)
                (ax, ay), (bx, by), (mx0, my0) = (d(j, s.first, False) for j in
                                                  (s.first_joint, s.second_joint, s.middle))
                mode = np.where((bx - ax) * (my0 - ay) - (by - ay) * (mx0 - ax) >= 0, 1.0, -1.0)
                (mx, my), (nx, ny), raw = circle_circle(
                    a, np.hypot(m1[0] - a0[0], m1[1] - a0[1]),
                    b, np.hypot(m2[0] - b0[0], m2[1] - b0[1]))
                root = mode * np.sqrt(np.where(raw >= 0, raw, np.nan))
                m = (mx + root * nx, my + root * ny)
                motions[s.first] = _rigid(a0, m1, a, m)
                motions[s.second] = _rigid(b0, m2, b, m)
        guide = motions[self._guide]
        assert guide is not None            # a moving link, found by a dyad
        c, sn, p, q = guide
        motions[self._block] = (c, sn, p, (q[0] - shift[0], q[1] - shift[1]))
        return motions
