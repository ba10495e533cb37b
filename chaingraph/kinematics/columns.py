"""A sweep's motion as typed arrays, and the CSV's columns as a view of them.

From the solver's poses and rates (:class:`LinkStates`), :meth:`Trajectories.of_states`
builds every link's angle and rates (:class:`LinkMotion`), every joint's and point's
position, velocity and acceleration (:class:`PointMotion`) and every P joint's slide
(:class:`SlideMotion`): radians inside, degrees only where a name says so
(``LinkMotion.angle_deg``). :attr:`Trajectories.columns` is the CSV's view of them: its
column names (``"angle:crank"`` in degrees, ``"x:B"``...), their order and their values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, fields, replace
from typing import Any, Self

import numpy as np

from chaingraph.geometry import turn_by
from chaingraph.kinematics.higher import cam_contact
from chaingraph.kinematics.plan import Plan
from chaingraph.model.chain import Chain, Joint

__all__ = ["LinkStates", "LinkMotion", "PointMotion", "SlideMotion", "Trajectories",
           "reference_link", "slide_rates", "csv_columns", "link_of_states",
           "point_of_states", "slide_of_states"]


@dataclass(frozen=True)
class LinkStates:
    """Every link's pose and rates at the solved steps, as the solver holds them: the
    path parameters ``tau``, ``pose`` (link -> (x, y, phi, cos, sin) about the plan's
    origin), and ``velocity`` and ``acceleration`` (link -> (vx, vy, omega), (ax, ay,
    alpha) of its frame's origin; each input's rate under its key) at the input speed
    ``speed`` (1 for a sweep's: they scale with omega and omega squared).

    ``points``: the points the rates' solve went through, by (link, point in the plan's
    frame): (x, y, vx, vy, ax, ay) about the plan's origin (a dyad's joints), so that a
    joint's motion is not worked out twice (:func:`chaingraph.kinematics.rates.rates`)."""

    tau: np.ndarray
    pose: dict
    velocity: dict
    acceleration: dict
    speed: float = 1.0
    points: dict = field(default_factory=dict, compare=False, repr=False)


@dataclass(frozen=True, eq=False)
class LinkMotion:
    """A link over a sweep: ``angle`` its direction (radians, counter-clockwise from +x,
    continuous over the sweep, the first in (-pi, pi]), ``omega`` (rad/s) and ``alpha``
    (rad/s^2); ``angle_deg`` the direction in degrees (the CSV's ``angle:LINK``)."""

    name: str
    angle: np.ndarray
    omega: np.ndarray
    alpha: np.ndarray

    @property
    def angle_deg(self) -> np.ndarray:
        """The link's direction in degrees."""
        return np.degrees(self.angle)


@dataclass(frozen=True, eq=False)
class PointMotion:
    """A joint or point over a sweep: its position ``x``, ``y``, velocity ``vx``,
    ``vy`` and acceleration ``ax``, ``ay`` (length units, per second, per second
    squared); a P joint's is its block's reference point."""

    name: str
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    ax: np.ndarray
    ay: np.ndarray


@dataclass(frozen=True, eq=False)
class SlideMotion:
    """A P joint over a sweep: ``s`` the block's slide along its guide from the drawn
    pose, ``v`` its rate and ``a`` its acceleration."""

    name: str
    s: np.ndarray
    v: np.ndarray
    a: np.ndarray


#: the fields that are rates, by order: proportional to the input speed, to its square
_FIRST = {LinkMotion: ("omega",), PointMotion: ("vx", "vy"), SlideMotion: ("v",)}
_SECOND = {LinkMotion: ("alpha",), PointMotion: ("ax", "ay"), SlideMotion: ("a",)}
#: the CSV's columns of a link (column kind -> field), of a point, of a slide
_LINK_COLUMNS = {"angle": "angle_deg", "omega": "omega", "alpha": "alpha"}
_POINT_COLUMNS = ("x", "y", "vx", "vy", "ax", "ay")
_SLIDE_COLUMNS = ("s", "v", "a")


@dataclass(frozen=True, eq=False)
class Trajectories:
    """What a sweep moves, as typed arrays (one value per step).

    ``theta`` the lead input's value (a driver's angle in degrees, or an input's value:
    degrees, or length units of slide); ``values`` each input joint's value when the
    mechanism is moved by inputs (empty with a driver); ``links``, ``joints``,
    ``points`` and ``slides`` each link's :class:`LinkMotion`, each joint's and point's
    :class:`PointMotion` and each P joint's :class:`SlideMotion`, by name, in the
    chain's order. ``self["x:B"]`` and :attr:`columns` are the CSV's view of them.
    """

    theta: np.ndarray
    values: dict[str, np.ndarray]
    links: dict[str, LinkMotion]
    joints: dict[str, PointMotion]
    points: dict[str, PointMotion]
    slides: dict[str, SlideMotion]

    @classmethod
    def of_states(cls, plan: Plan, states: LinkStates, /, **more: Any) -> Self:
        """The trajectories of the solver's ``states`` (``more``: the other fields of a
        subclass)."""
        chain, theta = plan.chain, states.tau
        values = {}
        if not plan.from_driver:
            for item, value in zip(plan.inputs, plan.values(theta)):
                values[item.joint] = np.array(np.broadcast_to(value, theta.shape), dtype=float)
        return cls(
            theta=theta if plan.from_driver else np.asarray(plan.value(theta), dtype=float),
            values=values,
            links={x: link_of_states(plan, states, x) for x in chain.links},
            joints={j.id: point_of_states(plan, states, j.id) for j in chain.joints},
            points={p.id: point_of_states(plan, states, p.id) for p in chain.points},
            slides={j.id: slide_of_states(plan, states, j.id)
                    for j in chain.joints if j.kind == "P"},
            **more)

    @property
    def columns(self) -> dict[str, np.ndarray]:
        """The CSV's columns, in its order: each input's value (``input:J``), ``theta``,
        each link's ``angle`` (degrees), ``omega``, ``alpha``, each joint's then each
        point's ``x``, ``y``, ``vx``, ``vy``, ``ax``, ``ay``, each P joint's ``s``,
        ``v``, ``a``."""
        out = {f"input:{joint}": v for joint, v in self.values.items()}
        out["theta"] = self.theta
        for link in self.links.values():
            out.update((f"{kind}:{link.name}", getattr(link, name))
                       for kind, name in _LINK_COLUMNS.items())
        for p in (*self.joints.values(), *self.points.values()):
            out.update((f"{kind}:{p.name}", getattr(p, kind)) for kind in _POINT_COLUMNS)
        for s in self.slides.values():
            out.update((f"{kind}:{s.name}", getattr(s, kind)) for kind in _SLIDE_COLUMNS)
        return out

    def __getitem__(self, key: str) -> np.ndarray:
        """The CSV's column ``key`` (``"theta"``, ``"input:J"``, ``"angle:LINK"`` in
        degrees, ``"x:B"``, ``"s:S"``...), from the typed fields."""
        kind, _, name = key.partition(":")
        try:
            if key == "theta":
                return self.theta
            if kind == "input":
                return self.values[name]
            if kind in _LINK_COLUMNS:
                return getattr(self.links[name], _LINK_COLUMNS[kind])
            if kind in _POINT_COLUMNS:
                return getattr(self.joints[name] if name in self.joints
                               else self.points[name], kind)
            if kind in _SLIDE_COLUMNS:
                return getattr(self.slides[name], kind)
        except KeyError:
            pass
        raise KeyError(key)

    def _each(self, change) -> Self:
        """A copy whose links, joints, points and slides are each ``change(item)``."""
        def each(group):
            return {k: change(v) for k, v in group.items()}
        return replace(self, links=each(self.links), joints=each(self.joints),
                       points=each(self.points), slides=each(self.slides))

    def scaled(self, omega: float) -> Self:
        """The trajectories at input speed ``omega``, from these at unit speed."""
        if omega == 1.0:
            return self
        square = omega * omega

        def at_speed(item):
            kind = type(item)
            return replace(item, **{f: getattr(item, f) * omega for f in _FIRST[kind]},
                           **{f: getattr(item, f) * square for f in _SECOND[kind]})
        return self._each(at_speed)

    def rates_unknown_at(self, steps: np.ndarray) -> Self:
        """A copy with NaN rates at ``steps`` (a mask): where the inputs do not
        determine them (a limit of the range, a fold). What is fixed keeps its zeros."""
        def unknown(item):
            kind = type(item)
            rates = [f for f in _FIRST[kind] + _SECOND[kind]
                     if np.any(getattr(item, f) != 0)]
            return replace(item, **{f: np.where(steps, np.nan, getattr(item, f))
                                    for f in rates})
        return self._each(unknown)

    def joined(self, *others: Trajectories) -> Self:
        """These trajectories' steps followed by each of ``others``' (of the same
        mechanism); a subclass's other fields are this one's."""
        parts: tuple[Trajectories, ...] = (self, *others)

        def join(group):
            def one(key):
                items = [getattr(p, group)[key] for p in parts]
                return replace(items[0], **{f.name: np.concatenate([getattr(i, f.name)
                                                                    for i in items])
                                            for f in fields(items[0]) if f.name != "name"})
            return {key: one(key) for key in getattr(self, group)}
        return replace(self, theta=np.concatenate([p.theta for p in parts]),
                       values={k: np.concatenate([p.values[k] for p in parts])
                               for k in self.values},
                       links=join("links"), joints=join("joints"), points=join("points"),
                       slides=join("slides"))


def csv_columns(plan: Plan, theta: np.ndarray, pose: dict, vel: dict,
                acc: dict) -> dict[str, np.ndarray]:
    """The CSV's columns at the path parameters ``theta`` from the solver's poses and
    rates (a view of :meth:`Trajectories.of_states`)."""
    return Trajectories.of_states(plan, LinkStates(theta, pose, vel, acc)).columns


# -- from the solver's poses -----------------------------------------------------------
def link_of_states(plan: Plan, states: LinkStates, link: str) -> LinkMotion:
    """One link's :class:`LinkMotion` from the solver's ``states`` (what
    :meth:`Trajectories.of_states` holds for it, alone)."""
    pose, n = states.pose, states.tau.size
    direction = plan.reference_radians(link) + pose[link][2]
    return LinkMotion(link, _continuous(direction, n), _array(states.velocity[link][2], n),
                      _array(states.acceleration[link][2], n))


def point_of_states(plan: Plan, states: LinkStates, name: str) -> PointMotion:
    """One joint's or point's :class:`PointMotion` from the solver's ``states``: as the
    rates' solve found it when it went through it, else from its link's motion."""
    chain, n = plan.chain, states.tau.size
    try:
        joint = chain.joint(name)
        if joint.kind == "cam":
            return _follower_point(plan, states, joint)
        link, at = reference_link(joint, plan.fixed, chain=chain), joint.at
    except KeyError:
        point = chain.point(name)
        link, at = point.link, point.at
    # a plan's chain has a drawn pose (build_plan refuses one with a joint unplaced, and
    # a file by its lengths places its points with its joints)
    assert at is not None, f"{name!r} has a position in a solved chain's pose"
    if link == plan.fixed:
        return PointMotion(name, np.full(n, at[0]), np.full(n, at[1]),
                           *(np.zeros(n) for _ in range(4)))
    p = plan.local(at)
    ox, oy = plan.origin
    solved = states.points.get((link, p))
    if solved is not None and all(np.shape(v) == (n,) for v in solved):
        x, y, *rates = solved
        # (copied: a rate the solve passed through unchanged is a link's own array)
        return PointMotion(name, x + ox, y + oy, *(v.copy() for v in rates))
    out = [np.empty(n) for _ in range(6)]
    _point_motion(states.pose, states.velocity, states.acceleration, link, p, out=out,
                  origin=(ox, oy))
    return PointMotion(name, *out)


def _follower_point(plan, states, joint):
    """A cam pair's columns: its follower's reference point (the roller's centre, the
    knife's tip, the flat face's foot on its line), a point of the follower, drawn
    where the drawing's cam (at the start of its program) puts it."""
    cam = next(c for c in plan.chain.cams if c.id == joint.id)
    drawn = cam_contact(plan.chain, cam, np.zeros(1))[2][0]
    out = [np.empty(states.tau.size) for _ in range(6)]
    _point_motion(states.pose, states.velocity, states.acceleration, cam.follower,
                  plan.local(drawn), out=out, origin=plan.origin)
    return PointMotion(joint.id, *out)


def slide_of_states(plan: Plan, states: LinkStates, joint: str) -> SlideMotion:
    """One P joint's :class:`SlideMotion` from the solver's ``states``."""
    j, n = plan.chain.joint(joint), states.tau.size
    assert j.at is not None, "build_plan refuses a chain with a joint unplaced"
    return SlideMotion(joint, *(_array(v, n) for v in slide_rates(
        states.pose, states.velocity, states.acceleration, j, plan.local(j.at))))


def _point_motion(pose, vel, acc, link, p, *, out=None, origin=None):
    """The point ``p`` (drawn, in the plan's frame) of ``link``: its x, y, velocity and
    acceleration; written into the six arrays ``out`` (each of the sweep's length, x
    and y offset by ``origin``) when given, else new arrays."""
    x, y = pose[link][:2]
    vx, vy, w = vel[link]
    ax, ay, al = acc[link]
    rx, ry = turn_by(pose[link], p)
    if out is None:
        return (rx + x, ry + y, vx - w * ry, vy + w * rx,
                ax - al * ry - w * w * rx, ay + al * rx - w * w * ry)
    ox, oy, ovx, ovy, oax, oay = out
    np.add(rx, x, out=ox)
    np.add(ry, y, out=oy)
    if origin is not None:
        ox += origin[0]
        oy += origin[1]
    np.multiply(w, ry, out=ovx)
    np.subtract(vx, ovx, out=ovx)
    np.multiply(w, rx, out=ovy)
    np.add(vy, ovy, out=ovy)
    w2 = w * w
    centripetal = w2 * rx
    np.multiply(al, ry, out=oax)
    np.subtract(ax, oax, out=oax)
    oax -= centripetal
    np.multiply(w2, ry, out=centripetal)
    np.multiply(al, rx, out=oay)
    np.add(ay, oay, out=oay)
    oay -= centripetal
    return out


def reference_link(joint: Joint, fixed: str, *, chain: Chain | None = None) -> str:
    """The link whose motion a joint's CSV columns follow: a P joint's block, an R
    joint's fixed link when it has it, else its first link; with the ``chain``, a gear
    pair's carrier (its pitch point stays on it) and a cam pair's follower (its
    reference point: the roller's centre, the knife's tip, the flat face's foot)."""
    if chain is not None and joint.kind in ("cam", "gear"):
        pair = next((p for p in chain.gears if p.id == joint.id), None)
        if pair is not None:
            return pair.carrier
        cam = next((c for c in chain.cams if c.id == joint.id), None)
        if cam is not None:
            return cam.follower
    if joint.kind == "P":
        return joint.links[1]                   # its block
    return fixed if fixed in joint.links else joint.links[0]


def slide_rates(pose: dict, vel: dict, acc: dict, joint: Joint,
                at: tuple[float, float]) -> tuple[Any, Any, Any]:
    """A P joint's slide, its rate and acceleration; ``at`` its point in the plan's frame."""
    g, b = joint.links
    pg = _point_motion(pose, vel, acc, g, at)
    pb = _point_motion(pose, vel, acc, b, at)
    d = (pb[0] - pg[0], pb[1] - pg[1])
    dd = (pb[2] - pg[2], pb[3] - pg[3])
    ddd = (pb[4] - pg[4], pb[5] - pg[5])
    w, al = vel[g][2], acc[g][2]
    axis = math.radians(joint.axis or 0.0)    # (a P joint's is always given)
    u = turn_by(pose[g], (math.cos(axis), math.sin(axis)))
    pu = (-u[1], u[0])
    du = (w * pu[0], w * pu[1])
    ddu = (al * pu[0] - w * w * u[0], al * pu[1] - w * w * u[1])
    s = d[0] * u[0] + d[1] * u[1]
    v = dd[0] * u[0] + dd[1] * u[1] + d[0] * du[0] + d[1] * du[1]
    a = (ddd[0] * u[0] + ddd[1] * u[1] + 2 * (dd[0] * du[0] + dd[1] * du[1])
         + d[0] * ddu[0] + d[1] * ddu[1])
    return s, v, a


def _continuous(phi, n):
    """Radians (possibly a constant) along the sweep, without jumps of a turn, the first
    value in (-pi, pi]."""
    if np.ndim(phi) == 0:
        return np.full(n, math.remainder(float(phi), 2 * math.pi))
    first = math.remainder(float(phi[0]), 2 * math.pi)
    turns = np.round(np.diff(phi) * (1 / (2 * math.pi)))    # a jump's whole turns
    jumps = np.flatnonzero(turns)
    out = phi + (first - float(phi[0]))
    out[0] = first
    if jumps.size > 16:             # (np.cumsum is dear: only for many jumps)
        out[1:] -= (2 * math.pi) * np.cumsum(turns)
    else:
        for j in jumps:
            out[j + 1:] -= (2 * math.pi) * turns[j]
    return out


def _array(v, n):
    if np.ndim(v):
        return v
    v = float(v)
    # (np.zeros costs a third of np.full; -0.0 kept as it is)
    return np.zeros(n) if v == 0.0 and math.copysign(1.0, v) > 0 else np.full(n, v)
