"""Velocity and acceleration polygons, as the textbook constructs them, exact.

The polygon is built from the pole (the image of every point of the fixed link) by
relative vectors, each known in size and direction from the links' angular velocities
and accelerations and the slides' rates:

* two points A and B of one link: the velocity of B relative to A is omega x AB,
  perpendicular to AB; its acceleration has a centripetal component omega^2 AB from B
  towards A and a tangential one alpha x AB, perpendicular to AB;
* a block sliding on a guide (a P joint), at the point B of the block and the guide's
  point B' under it: the sliding velocity v along the guide; the acceleration of B
  relative to B' has the sliding component along the guide and the Coriolis component
  2 v omega (omega the guide's angular velocity), perpendicular to the guide, in the
  direction of v turned a quarter turn in the sense of omega.

Each point's image is reached from the pole along a tree of these vectors; every other
vector closes a loop of the polygon, and the sum of the relative vectors around it is
zero (``loops`` gives each loop and how closely it closes).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from chaingraph.geometry import direction_deg, perp
from chaingraph.kinematics.pose import AtOneValue, PoseMotion, pose_motion
from chaingraph.model.chain import Chain

__all__ = ["Component", "Relative", "Image", "Polygons", "velocity_polygon"]




def _floats(v: Sequence[float] | np.ndarray) -> tuple[float, float]:
    """A 2-vector as a pair of plain floats."""
    return (float(v[0]), float(v[1]))


def _vector(x: float, y: float) -> tuple[float, float]:
    """A vector of plain floats (no -0.0)."""
    return (float(x) + 0.0, float(y) + 0.0)


@dataclass(frozen=True)
class Component:
    """One named vector: ``kind`` is "relative velocity", "sliding velocity",
    "centripetal", "tangential", "sliding" or "Coriolis"."""

    kind: str
    vector: tuple[float, float]

    @property
    def magnitude(self) -> float:
        """Its length."""
        return math.hypot(*self.vector)

    @property
    def direction(self) -> float | None:
        """Degrees CCW from +x in [0, 360) (None for a zero vector)."""
        return direction_deg(self.vector)

    def to_dict(self) -> dict[str, Any]:
        """The component in ``chaingraph polygons --json``."""
        return {"kind": self.kind, "vector": list(self.vector),
                "magnitude": self.magnitude, "direction": self.direction}


@dataclass(frozen=True)
class Relative:
    """The motion of image ``to`` relative to image ``start`` (from): two points of
    ``link`` (``joint`` None), or the block's point relative to the guide's at the P
    joint ``joint``. ``velocity`` and ``acceleration`` are lists of components."""

    start: str
    to: str
    link: str | None
    joint: str | None
    velocity: tuple[Component, ...]
    acceleration: tuple[Component, ...]

    @property
    def velocity_vector(self) -> tuple[float, float]:
        """The relative velocity: its components summed."""
        return _floats(np.sum([c.vector for c in self.velocity], axis=0))

    @property
    def acceleration_vector(self) -> tuple[float, float]:
        """The relative acceleration: its components summed."""
        return _floats(np.sum([c.vector for c in self.acceleration], axis=0))

    def to_dict(self, which: str) -> dict[str, Any]:
        """The vector in ``chaingraph polygons --json``: ``which`` is ``"velocity"`` or
        ``"acceleration"``."""
        components = self.velocity if which == "velocity" else self.acceleration
        total = self.velocity_vector if which == "velocity" else self.acceleration_vector
        out: dict[str, Any] = {"from": self.start, "to": self.to}
        out.update({"link": self.link} if self.joint is None else {"joint": self.joint})
        out.update(vector=list(total), magnitude=math.hypot(*total),
                   direction=direction_deg(total),
                   components=[c.to_dict() for c in components])
        return out


@dataclass(frozen=True)
class Image:
    """A point's image: ``name`` (a joint or point id; ``B'`` the guide's point under a
    block's point ``B``), the ``link`` it belongs to, its position ``at`` in the
    mechanism, and its ``velocity`` and ``acceleration`` (the images' positions in the
    two polygons, from the pole)."""

    name: str
    link: str
    at: tuple[float, float]
    velocity: tuple[float, float]
    acceleration: tuple[float, float]

    def to_dict(self) -> dict[str, Any]:
        """The image in ``chaingraph polygons --json``."""
        return {"name": self.name, "link": self.link, "at": list(self.at),
                "velocity": list(self.velocity), "acceleration": list(self.acceleration)}


@dataclass(frozen=True, eq=False)
class Polygons(AtOneValue):
    """The velocity and acceleration polygons of a mechanism at one input value.

    ``images`` (name -> Image) built from the pole along ``relatives``; ``loops`` one
    per vector that closes a loop: (the images around it, the sum of the relative
    velocities around it, the sum of the relative accelerations), both zero vectors up
    to rounding."""

    images: dict[str, Image]
    relatives: tuple[Relative, ...]
    loops: tuple[tuple[tuple[str, ...], tuple[float, float], tuple[float, float]], ...]
    state: PoseMotion

    def relative(self, start: str, to: str) -> Relative:
        """The relative vector from image ``start`` to image ``to`` (either way round:
        reversed, its components change sign)."""
        for r in self.relatives:
            if (r.start, r.to) == (start, to):
                return r
            if (r.start, r.to) == (to, start):
                def neg(cs: Sequence[Component]) -> tuple[Component, ...]:
                    return tuple(Component(c.kind, (-c.vector[0], -c.vector[1])) for c in cs)
                return Relative(start, to, r.link, r.joint, neg(r.velocity),
                                neg(r.acceleration))
        raise KeyError(f"no relative vector between {start!r} and {to!r}")

    @property
    def closure(self) -> dict[str, float]:
        """The largest loop sum of each polygon (0 when there is no loop)."""
        return {"velocity": max((math.hypot(*v) for _, v, _ in self.loops), default=0.0),
                "acceleration": max((math.hypot(*a) for _, _, a in self.loops), default=0.0)}

    def image_rows(self) -> list[list[str]]:
        """Each image as a text row: point, link, vx, vy, |v|, ax, ay, |a|."""
        def num(v: float) -> str:
            return f"{v:.6g}"
        return [[im.name, im.link, *map(num, im.velocity), num(math.hypot(*im.velocity)),
                 *map(num, im.acceleration), num(math.hypot(*im.acceleration))]
                for im in self.images.values()]

    def vector_rows(self) -> list[list[str]]:
        """Each component of each relative vector as a text row: vector, on (link or
        joint), component, magnitude, direction (degrees)."""
        out: list[list[str]] = []
        for r in self.relatives:
            on = str(r.link) if r.joint is None else f"joint {r.joint}"   # a link's own
            for c in (*r.velocity, *r.acceleration):
                out.append([f"{r.to} rel. {r.start}", on, c.kind, f"{c.magnitude:.6g}",
                            "-" if c.direction is None else f"{c.direction:.6g}"])
        return out

    def to_dict(self) -> dict[str, Any]:
        """The JSON of ``chaingraph polygons --json``."""
        s = self.state
        out: dict[str, Any] = {"name": s.name, "fixed": s.fixed, "input": s.input}
        if s.inputs:
            out["inputs"] = [{"joint": j, "value": v} for j, v in s.inputs.items()]
        out["omega"] = s.omega
        out["images"] = [im.to_dict() for im in self.images.values()]
        out["velocity"] = [r.to_dict("velocity") for r in self.relatives]
        out["acceleration"] = [r.to_dict("acceleration") for r in self.relatives]
        out["loops"] = [{"images": list(names), "velocity": list(v), "acceleration": list(a)}
                        for names, v, a in self.loops]
        out["closure"] = self.closure
        return out


def _images_of(state):
    """Every image (name -> (link, position)) and each link's images in order, and the
    P joints' (guide image, block image)."""
    chain, fixed = state.chain, state.fixed
    images: dict[str, Any] = {}
    on_link: dict[str, list[Any]] = {x: [] for x in chain.links}
    slides: dict[str, Any] = {}
    taken = {j.id for j in chain.joints} | {p.id for p in chain.points}

    def add(name, link, at):
        if name not in images:
            images[name] = (link, at)
        if name not in on_link[link]:
            on_link[link].append(name)
    for j in chain.joints:
        if j.kind == "R":                          # a pivot's image is the fixed link's
            for link in sorted(j.links, key=lambda x: x != fixed):
                add(j.id, link, state.positions[j.id])
    for p in chain.points:
        add(p.id, p.link, state.positions[p.id])
    for j in chain.joints:
        if j.kind != "P":
            continue
        # the two coincident points: at a pin of the block or the guide (one not on
        # the fixed link first, then the nearest), as the textbook takes B on the block
        # and B' on the lever; else at the block's reference point
        here = state.positions[j.id]
        pins = [r for r in chain.joints if r.kind == "R" and
                (j.guide in r.links) != (j.block in r.links)]
        pins.sort(key=lambda r: (fixed in r.links, math.dist(state.positions[r.id], here)))
        if pins:
            pin = pins[0]
            at = state.positions[pin.id]
            names = {x: pin.id if x in pin.links else pin.id + "'" for x in j.links}
        else:
            at = here
            names = {j.block: j.id, j.guide: j.id + "'"}
        for link in j.links:
            name = names[link]
            if name.endswith("'"):
                while name in taken or (name in images and images[name][0] != link):
                    name += "'"
                names[link] = name
            add(name, link, at)
        slides[j.id] = (names[j.guide], names[j.block], at)
    return images, on_link, slides


def polygons_of(state: PoseMotion) -> Polygons:
    """The polygons of a solved pose (see :func:`velocity_polygon`)."""
    fixed = state.fixed
    images, on_link, slides = _images_of(state)
    relatives = []
    for link, names in on_link.items():
        if link == fixed or len(names) < 2:
            continue
        m = state.links[link]
        w, al = m.omega, m.alpha
        first = names[0]
        p0 = images[first][1]
        for name in names[1:]:
            r = np.subtract(images[name][1], p0)
            relatives.append(Relative(
                first, name, link, None,
                (Component("relative velocity", _vector(-w * r[1], w * r[0])),),
                (Component("centripetal", _vector(-w * w * r[0], -w * w * r[1])),
                 Component("tangential", _vector(-al * r[1], al * r[0])))))
    for joint, (guide, block, _) in slides.items():
        s = state.slides[joint]
        u = np.array(s.axis)
        v_rel = s.speed * u
        w = state.links[s.guide].omega
        coriolis = 2.0 * w * np.array(perp(v_rel))
        relatives.append(Relative(
            guide, block, None, joint,
            (Component("sliding velocity", _vector(*v_rel)),),
            (Component("sliding", _vector(*(s.acceleration * u))),
             Component("Coriolis", _vector(*coriolis)))))
    # the images from the pole along a tree of the vectors; the others close loops
    known = {n: ((0.0, 0.0), (0.0, 0.0)) for n in on_link[fixed]}
    parent: dict[str, tuple[str, int] | None] = {n: None for n in known}
    tree, loops = set(), []
    pending = list(range(len(relatives)))
    while pending:
        rest = []
        for i in pending:
            r = relatives[i]
            dv, da = np.array(r.velocity_vector), np.array(r.acceleration_vector)
            if r.start in known and r.to not in known:
                v, a = known[r.start]
                known[r.to] = (tuple(np.add(v, dv)), tuple(np.add(a, da)))
                parent[r.to] = (r.start, i)
                tree.add(i)
            elif r.to in known and r.start not in known:
                v, a = known[r.to]
                known[r.start] = (tuple(np.subtract(v, dv)), tuple(np.subtract(a, da)))
                parent[r.start] = (r.to, i)
                tree.add(i)
            elif r.start not in known:
                rest.append(i)
        if len(rest) == len(pending):
            break                                  # a part not joined to the fixed link
        pending = rest
    for i, r in enumerate(relatives):
        if i in tree or r.start not in known or r.to not in known:
            continue
        path = _path(parent, r.start, r.to)
        dv = np.array(r.velocity_vector)
        da = np.array(r.acceleration_vector)
        (vs, as_), (vt, at) = known[r.start], known[r.to]
        # around the loop: from the pole to start, the vector, back from to to the pole
        loops.append((tuple(path), _floats(np.add(vs, dv) - np.array(vt)),
                      _floats(np.add(as_, da) - np.array(at))))
    out: dict[str, Image] = {}
    for name, (link, at) in images.items():
        v, a = known.get(name, ((math.nan, math.nan), (math.nan, math.nan)))
        out[name] = Image(name, link, _floats(at), _floats(v), _floats(a))
    return Polygons(images=out, relatives=tuple(relatives), loops=tuple(loops), state=state)


def _path(parent, start, end):
    """The images around the loop that the vector from ``start`` to ``end`` closes:
    the tree path from ``end`` to ``start``, then back to ``end`` by the vector."""
    def up(n):
        out = [n]
        while parent.get(n) is not None:
            n = parent[n][0]
            out.append(n)
        return out
    a, b = up(start), up(end)
    common = next((n for n in a if n in b), None)
    if common is None:                            # both reach the pole by different roots
        return b + ["pole"] + a[::-1] + [end]
    return b[:b.index(common) + 1] + a[:a.index(common)][::-1] + [end]


def velocity_polygon(chain: Chain, *, at: float | Sequence[float] | None = None,
                     fixed: str | None = None, driver: str | None = None,
                     inputs: Sequence[Any] | None = None, omega: float | None = None,
                     ) -> Polygons:
    """The velocity and acceleration polygons of a mechanism at one input value.

    Parameters are those of :func:`chaingraph.instant_centres`. With several inputs
    they move together at their sweeps' rates (one polygon for the combined motion;
    a polygon per input is not drawn yet).

    Returns
    -------
    Polygons
        ``images`` every joint's and point's velocity and acceleration image (a block's
        point and the guide's point under it both), ``relatives`` the relative vectors
        with their components (centripetal, tangential; sliding, Coriolis), ``loops``
        the loop sums (zero).

    Examples
    --------
    The crank and slotted lever, the crank at 90 degrees turning at 10 rad/s:

    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> shaper = chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism"))
    >>> p = chaingraph.velocity_polygon(shaper, at=90.0, omega=10.0)
    >>> [round(x, 6) for x in p.images["B"].velocity]           # the crank pin: 1200 mm/s
    [-1200.0, 0.0]
    >>> slide = p.relative("B", "B'")             # B' on the lever relative to B on the block
    >>> [(c.kind, round(c.magnitude, 6)) for c in slide.acceleration]   # 12000 - 420 (1200/420)^2
    [('sliding', 8571.428571), ('Coriolis', 0.0)]
    >>> p.closure["velocity"] < 1e-9
    True
    """
    return polygons_of(pose_motion(chain, at=at, fixed=fixed, driver=driver,
                                   inputs=inputs, omega=omega))
