"""Instantaneous centres of a mechanism, found as the textbook finds them.

Every pair of the L links has an instantaneous centre (L(L-1)/2 in all), the point
where the two links have the same velocity. The primary ones come from the joints: an
R joint is the centre of every pair of its links, a P joint's is at infinity,
perpendicular to the sliding line. The others follow by Kennedy's theorem (the three
centres of any three links lie on one line): the centre of links i and j is where the
line through I_ik and I_kj meets the line through I_im and I_mj. The construction uses
positions only; velocities are needed only where Kennedy's theorem leaves a centre
indeterminate (in mechanisms of several inputs, whose centres depend on the inputs'
rates, and in some linkages of higher class): those are found from the links'
velocity fields and said so.

Points are handled in homogeneous coordinates (x, y, w), so that a centre at infinity
(w = 0, the direction of (x, y)) takes part in the construction like any other: the line
through two points is their cross product, and so is the point where two lines meet.

With the centres, angular velocities follow from the input's speed alone (the angular
velocity ratio theorem, solved for every link at once), and the velocity of any point
from its link's angular velocity and its distance from the link's centre relative to
the fixed link.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from chaingraph.geometry import Vec, normalised, perp
from chaingraph.kinematics.pose import AtOneValue, PoseMotion, pose_motion
from chaingraph.model.chain import Chain

#: a line of Kennedy's theorem: the two link pairs whose centres it passes through
Line = tuple[tuple[str, str], tuple[str, str]]

__all__ = ["Centre", "InstantCentres", "instant_centres"]

#: lines or points whose (unit) cross product is below this are taken as coincident
_COINCIDENT = 1e-9
#: a centre farther than this many times the mechanism's size is at infinity
_FAR = 1e12


@dataclass(frozen=True)
class Centre:
    """One instantaneous centre.

    ``links`` the two links (the lower number first), ``numbers`` their numbers (the
    fixed link is 1); ``at`` (x, y), or None when the centre is at infinity, where
    ``direction`` (degrees in [0, 180)) is the direction in which it lies; ``found``
    how it was found: ``"joint J"``, or the two lines of Kennedy's theorem that met,
    each a pair of link pairs (the centres it passes through), or ``"velocities"``
    (where Kennedy's theorem leaves it indeterminate), or ``"indeterminate"``."""

    links: tuple[str, str]
    numbers: tuple[int, int]
    at: tuple[float, float] | None
    direction: float | None
    found: str | tuple[Line, Line]
    homogeneous: tuple[float, float, float]   # (x, y, w) in the plan's frame scaled by the size, unit norm

    @property
    def name(self) -> str:
        """The textbook's name: I13 for links 1 and 3 (I1,13 past nine links)."""
        a, b = self.numbers
        return f"I{a}{b}" if max(a, b) < 10 else f"I{a},{b}"

    @property
    def primary(self) -> bool:
        """Whether a joint gives it."""
        return isinstance(self.found, str) and self.found.startswith("joint ")

    @property
    def at_infinity(self) -> bool:
        """Whether it lies at infinity (then ``direction`` says where)."""
        return self.at is None and self.direction is not None

    def found_text(self, numbers: Mapping[str, int] | None = None) -> str:
        """How it was found, in words: "joint B", or with the links' ``numbers``
        "I12-I23 x I14-I34" (the two lines of Kennedy's theorem that met)."""
        if isinstance(self.found, str):
            return self.found

        def centre(pair: tuple[str, str]) -> str:
            if numbers is None:
                return "(" + ", ".join(pair) + ")"
            a, b = sorted(numbers[x] for x in pair)
            return f"I{a}{b}" if b < 10 else f"I{a},{b}"
        (p, q), (r, s) = self.found
        return f"{centre(p)}-{centre(q)} x {centre(r)}-{centre(s)}"

    def to_dict(self) -> dict[str, Any]:
        """The centre in ``chaingraph centres --json``."""
        found: str | list[list[list[str]]] = self.found if isinstance(self.found, str) else \
            [[list(p), list(q)] for p, q in self.found]
        return {"links": list(self.links), "name": self.name,
                "at": None if self.at is None else [self.at[0], self.at[1]],
                "direction": self.direction, "from": found}


@dataclass(frozen=True, eq=False)
class InstantCentres(AtOneValue):
    """All the instantaneous centres of a mechanism at one input value (a result).

    Attributes
    ----------
    centres : tuple of Centre
        By link numbers: I12, I13, ..., I23, ...
    numbers : dict
        link -> its number (the fixed link 1, the input links next, then the others
        along the chain: :func:`link_numbers`).
    angular_velocities : dict
        link -> angular velocity (rad/s) found through the centres from the input's
        speed (None at a dead centre, where the input does not determine them).
    state : PoseMotion
        The solved pose (the solver's velocities, to compare).
    """

    centres: tuple[Centre, ...]
    numbers: dict[str, int]
    angular_velocities: dict[str, float | None]
    translations: dict[str, tuple[float, float]]
    state: PoseMotion

    def centre(self, a: str, b: str) -> Centre:
        """The centre of links ``a`` and ``b`` (names, either order)."""
        key = frozenset((a, b))
        for c in self.centres:
            if frozenset(c.links) == key:
                return c
        raise KeyError(f"no instantaneous centre of {a!r} and {b!r}")

    def velocity(self, name: str) -> tuple[float, float] | None:
        """A joint's or point's velocity found through the centres: its link's angular
        velocity times its distance from the link's centre relative to the fixed link,
        perpendicular to the line to that centre (a translating link's, the common
        velocity of its points). None where the centres do not determine it."""
        state = self.state
        link = state.link_of(name)
        if link == state.fixed:
            return (0.0, 0.0)
        w = self.angular_velocities.get(link)
        if w is None:
            return None
        centre = self.centre(state.fixed, link)
        if centre.at is None:
            return self.translations[link]
        p = state.positions[name]
        r = (p[0] - centre.at[0], p[1] - centre.at[1])
        return (-w * r[1], w * r[0])

    def rows(self) -> list[list[str]]:
        """The centres as text rows: name, links, x, y, how found (for tables)."""
        size = self.state.plan.size

        def coordinate(value: float) -> str:
            return "0" if abs(value) < 1e-12 * size else f"{value:.6g}"
        out = []
        for c in self.centres:
            if c.at is not None:
                where = [coordinate(c.at[0]), coordinate(c.at[1])]
            elif c.direction is not None:
                where = ["at infinity", f"direction {c.direction:.6g} degrees"]
            else:
                where = ["-", "-"]
            out.append([c.name, ", ".join(c.links), *where, c.found_text(self.numbers)])
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON of ``chaingraph centres --json``."""
        out: dict[str, Any] = {"name": self.state.name, "fixed": self.state.fixed,
               "input": self.state.input}
        if self.state.inputs:
            out["inputs"] = [{"joint": j, "value": v} for j, v in self.state.inputs.items()]
        out["numbers"] = dict(self.numbers)
        out["centres"] = [c.to_dict() for c in self.centres]
        out["angular_velocities"] = dict(self.angular_velocities)
        return out



def link_numbers(chain: Chain, fixed: str, inputs: Iterable[str] = ()) -> dict[str, int]:
    """The textbook's numbering: the fixed link 1, then the input links (``inputs``: the
    moving links the inputs turn or slide), then the rest along the chain (breadth
    first from the inputs, ties in the file's order); but a link whose name ends in a
    number ("2", "link 2", "wheel 2", "slider 3") has that number, so that no name
    says another number than the centres' (I12 is then wheel 1 and wheel 2), and the
    others take the numbers left, in that order.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> chain = chaingraph.load(catalog_path("stephenson-iii-mechanism"))
    >>> link_numbers(chain, "frame", ["crank"])
    {'frame': 1, 'crank': 2, 'ternary link': 3, 'left link': 4, 'right link': 5, 'rocker': 6}
    >>> chain = chaingraph.load(catalog_path("stephenson-i-mechanism"))
    >>> link_numbers(chain, "frame", ["crank"])
    {'frame': 1, 'crank': 2, 'coupler': 3, 'rocker': 4, 'link 5': 5, 'link 6': 6}
    """
    count = len(chain.links)
    own: dict[str, int] = {}
    for link in chain.links:
        word = link.split()[-1] if link.split() else ""
        if word.isdigit() and 1 <= int(word) <= count:
            own[link] = int(word)
    taken = [n for n in own.values()]
    own = {link: n for link, n in own.items() if taken.count(n) == 1}
    rank = {link: k for k, link in enumerate(chain.links)}
    order = [fixed] + [x for x in dict.fromkeys(inputs) if x != fixed]
    queue = list(order[1:]) or [fixed]
    while queue:
        here = queue.pop(0)
        near = sorted({x for j in chain.joints if here in j.links for x in j.links},
                      key=rank.__getitem__)
        for x in near:
            if x not in order:
                order.append(x)
                queue.append(x)
    order += [x for x in chain.links if x not in order]     # pieces not joined to the rest
    free = iter(n for n in range(1, count + 1) if n not in own.values())
    numbers = {link: own[link] if link in own else next(free) for link in order}
    return dict(sorted(numbers.items(), key=lambda item: item[1]))




def _finish(h: np.ndarray, state: PoseMotion,
            ) -> tuple[tuple[float, float] | None, float | None]:
    """(at, direction) of a homogeneous point in the scaled frame."""
    plan = state.plan
    x, y, w = h
    if abs(w) * _FAR <= math.hypot(x, y):
        direction = math.degrees(math.atan2(y, x)) % 180.0
        return None, (0.0 if direction >= 180.0 - 1e-12 else direction)
    ox, oy = plan.origin
    return (float(x / w * plan.size + ox), float(y / w * plan.size + oy)), None


def _scaled(state: PoseMotion, p: Vec) -> tuple[float, float]:
    """A point in the construction's frame: the plan's, over the mechanism's size."""
    plan = state.plan
    return ((p[0] - plan.origin[0]) / plan.size, (p[1] - plan.origin[1]) / plan.size)


def _field(state: PoseMotion, link: str) -> tuple[np.ndarray, float]:
    """A link's velocity field v(p) = c + omega k x p in the scaled frame: (c, omega)."""
    plan = state.plan
    m = state.links[link]
    o = _scaled(state, m.point)
    v = (m.velocity[0] / plan.size, m.velocity[1] / plan.size)
    c = (v[0] + m.omega * o[1], v[1] - m.omega * o[0])
    return np.array(c), m.omega


def _from_velocities(state: PoseMotion, a: str, b: str) -> np.ndarray | None:
    """The centre of a and b from their velocity fields: where c_a + w_a k x p equals
    c_b + w_b k x p, i.e. (k x (c_a - c_b), w_a - w_b) in homogeneous coordinates."""
    ca, wa = _field(state, a)
    cb, wb = _field(state, b)
    dc = ca - cb
    h = np.array([-dc[1], dc[0], wa - wb])
    scale = max(abs(wa), abs(wb), float(np.abs(ca).max()), float(np.abs(cb).max()))
    if not np.isfinite(h).all() or np.linalg.norm(h) <= 1e-12 * scale:
        return None                               # no relative motion (or a dead centre)
    return normalised(h)


def _primary(state):
    """The centres the joints give: (pair -> (homogeneous point, "joint J"))."""
    known: dict[Any, Any] = {}
    for j in state.chain.joints:
        if j.kind == "cam":             # its centre is on the common normal: not a point
            continue
        if j.kind in ("R", "gear"):     # a gear pair's centre is its pitch point
            h = normalised(np.array((*_scaled(state, state.positions[j.id]), 1.0)))
        else:
            u = state.slides[j.id].axis
            h = np.array([-u[1], u[0], 0.0])
        for a, b in itertools.combinations(j.links, 2):
            known.setdefault(frozenset((a, b)), (h, f"joint {j.id}"))
    return known


def _kennedy(links, known):
    """Secondary centres by Kennedy's theorem, round by round: in each round every
    centre that two lines through known centres fix (the best conditioned pair of
    lines) is added. Returns the centres found."""
    known = dict(known)
    while True:
        found = {}
        for a, b in itertools.combinations(links, 2):
            pair = frozenset((a, b))
            if pair in known:
                continue
            lines = []
            for k in links:
                if k in pair:
                    continue
                ak, kb = frozenset((a, k)), frozenset((k, b))
                if ak in known and kb in known:
                    line = np.cross(known[ak][0], known[kb][0])
                    n = float(np.linalg.norm(line))
                    if n > _COINCIDENT:
                        lines.append((line / n, ((a, k), (k, b))))
            best, how = None, None
            for (l1, w1), (l2, w2) in itertools.combinations(lines, 2):
                p = np.cross(l1, l2)
                n = float(np.linalg.norm(p))
                if n > _COINCIDENT and (best is None or n > best[1]):
                    best, how = (p / n, n), (w1, w2)
            if best is not None:
                found[pair] = (best[0], how)
        if not found:
            return known
        known.update(found)


def _angular_velocities(state, centres, numbers):
    """Every link's angular velocity (and a translating link's velocity) from the
    centres and the inputs' rates alone: each link's velocity field is a rotation about
    its centre relative to the fixed link (or a translation across the direction of
    that centre at infinity) of unknown size; each relative centre says where two links'
    fields agree, and each input fixes a relative rate. Solved for all links at once."""
    plan, fixed = state.plan, state.fixed
    if not state.finite_rates:                    # a dead centre: the input decides nothing
        return None, None
    moving = [x for x in numbers if x != fixed]
    index = {x: n for n, x in enumerate(moving)}
    shapes = {fixed: (np.zeros(2), 0.0)}         # link -> (c per unit, omega per unit)
    for link in moving:
        absolute = centres[frozenset((fixed, link))]
        if absolute.found == "indeterminate":
            return None, None
        x, y, w = absolute.homogeneous
        if absolute.at is None:
            shapes[link] = (np.array([-y, x]), 0.0)          # translation across d
        else:
            q = (x / w, y / w)
            shapes[link] = (np.array([q[1], -q[0]]), 1.0)    # rotation about q
    rows, rhs = [], []

    def row(coeffs, value):
        r = np.zeros(len(moving))
        for link, c in coeffs:
            if link != fixed:
                r[index[link]] += c
        rows.append(r)
        rhs.append(value)
    for pair, centre in centres.items():
        if fixed in pair or centre.found == "indeterminate":
            continue
        a, b = sorted(pair, key=numbers.get)
        (ca, wa), (cb, wb) = shapes[a], shapes[b]
        x, y, w = centre.homogeneous
        if centre.at is None:                     # same rotation, relative velocity across d
            d = np.array([x, y])
            row([(a, wa), (b, -wb)], 0.0)
            row([(a, ca @ d), (b, -(cb @ d))], 0.0)
        else:
            p = np.array([x / w, y / w])
            kp = np.array(perp(p))
            for axis in (0, 1):
                row([(a, ca[axis] + wa * kp[axis]), (b, -(cb[axis] + wb * kp[axis]))], 0.0)
    tau_rate = state.omega / plan.rate_scale
    for item, (_, k) in zip(plan.inputs, plan.line):
        rate = k * tau_rate
        if item.kind == "R":
            row([(item.b, shapes[item.b][1]), (item.a, -shapes[item.a][1])], rate)
        else:
            s = state.slides[item.joint]
            kp = np.array(perp(_scaled(state, s.at)))
            u = np.array(s.axis)
            row([(link, sign * ((shapes[link][0] + shapes[link][1] * kp) @ u))
                 for link, sign in ((s.block, 1.0), (s.guide, -1.0))], rate / plan.size)
    a = np.array(rows)
    b = np.array(rhs)
    solution, *_ = np.linalg.lstsq(a, b, rcond=None)
    scale = max(1.0, float(np.abs(solution).max()))
    if np.linalg.matrix_rank(a, tol=1e-9 * max(1.0, float(np.abs(a).max()))) < len(moving) \
            or float(np.abs(a @ solution - b).max()) > 1e-8 * scale:
        return None, None
    omegas, translations = {fixed: 0.0}, {}
    for link in moving:
        c, w = shapes[link]
        s = float(solution[index[link]])
        omegas[link] = s * w + 0.0             # (no -0.0)
        if w == 0.0:
            translations[link] = (float(c[0] * s * plan.size), float(c[1] * s * plan.size))
    return omegas, translations


def instant_centres(chain: Chain, *, at: float | Sequence[float] | None = None,
                    fixed: str | None = None, driver: str | None = None,
                    inputs: Sequence[Any] | None = None, omega: float | None = None,
                    ) -> InstantCentres:
    """All the instantaneous centres of a mechanism at one input value.

    Parameters
    ----------
    chain : Chain
        A mechanism with dimensions (a drawn pose, or lengths).
    at : float or sequence of float, optional
        The input value (the driver's angle in degrees, as ``solve``'s ``theta``); with
        several inputs the first's value or one per input. By default the drawn pose.
    fixed, driver, inputs, omega
        As for :func:`chaingraph.solve`.

    Returns
    -------
    InstantCentres
        L(L-1)/2 centres, each with its position (or direction at infinity) and how it
        was found; the angular velocities found through them.

    Raises
    ------
    MechanismError
        No mechanism, no dimensions, a bad input value (exit status 2).
    AssemblyError
        An input value outside the range that can be assembled (exit status 1).

    Examples
    --------
    A four-bar: the coupler's centre I13 is where the crank's line meets the rocker's.

    >>> import chaingraph
    >>> from chaingraph import Chain, Joint, Mechanism
    >>> four_bar = Chain("four-bar", joints=(
    ...     Joint("O2", "R", ("frame", "crank"), at=(0.0, 0.0)),
    ...     Joint("A", "R", ("crank", "coupler"), at=(0.0, 2.0)),
    ...     Joint("B", "R", ("coupler", "rocker"), at=(4.0, 3.0)),
    ...     Joint("O4", "R", ("rocker", "frame"), at=(5.0, 0.0))),
    ...     mechanism=Mechanism(fixed="frame", driver="crank"))
    >>> centres = chaingraph.instant_centres(four_bar)
    >>> c = centres.centre("frame", "coupler")
    >>> c.name, [round(x, 9) for x in c.at], c.found_text(centres.numbers)
    ('I13', [0.0, 15.0], 'I12-I23 x I14-I34')
    >>> centres.centre("crank", "rocker").at        # I24: O2O4 meets AB
    (-8.0, 0.0)
    >>> round(centres.angular_velocities["rocker"], 6)   # omega2 I12I24 / I14I24 = 8/13
    0.615385
    """
    state = pose_motion(chain, at=at, fixed=fixed, driver=driver, inputs=inputs,
                        omega=omega)
    return centres_of(state)


def centres_of(state: PoseMotion) -> InstantCentres:
    """The instantaneous centres of a solved pose (see :func:`instant_centres`)."""
    plan = state.plan
    moving = [x for item in plan.inputs for x in (item.a, item.b) if x != state.fixed]
    numbers = link_numbers(state.chain, state.fixed, moving)
    links = list(numbers)
    known = _kennedy(links, _primary(state))
    centres = {}
    for a, b in itertools.combinations(links, 2):
        pair = frozenset((a, b))
        if pair in known:
            h, how = known[pair]
        else:
            h = _from_velocities(state, a, b)
            how = "velocities" if h is not None else "indeterminate"
        if h is None:
            at, direction, h = None, None, np.full(3, np.nan)
        else:
            h = h if h[2] >= 0 else -h
            at, direction = _finish(h, state)
        if not isinstance(how, str):              # name each line's centres low first
            how = tuple(tuple(tuple(sorted(p, key=numbers.__getitem__)) for p in line)
                        for line in how)
        centres[pair] = Centre((a, b), (numbers[a], numbers[b]), at, direction, how,
                               (float(h[0]), float(h[1]), float(h[2])))
    omegas, translations = _angular_velocities(state, centres, numbers)
    if omegas is None:
        omegas = {link: None for link in links}
        omegas[state.fixed] = 0.0
        translations = {}
    return InstantCentres(centres=tuple(centres.values()), numbers=numbers,
                          angular_velocities=omegas, translations=translations, state=state)
