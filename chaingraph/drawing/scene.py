"""A mechanism's picture, computed once as a scene and emitted twice: as SVG elements
(the report, ``solve --draw FILE.svg``, the notebook) and through matplotlib (PNG, the
constructions of the graphical method), so that a mechanism has one look in every
format.

A :class:`Scene` holds what the picture needs over a motion (or at one pose): every
joint's and point's position, each sliding line's direction and slide, and how each
sliding pair is drawn (a hatched way on the fixed link, a slot in a moving link, the
barrel of a cylinder). :func:`frame_shapes` turns one pose of it into :class:`Shape`
items in the mechanism's own coordinates: plates and bars, guides and blocks, ground
and pins, points and labels; :func:`svg_elements` and :func:`draw_shapes` emit them.
"""

from __future__ import annotations

import html
import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from chaingraph.geometry import Vec, convex_hull, polygon_area, rotate, segment_distance
from chaingraph.kinematics import Motion, PoseMotion
from chaingraph.kinematics.cams import analyse_cam, turn_angles
from chaingraph.kinematics.higher import HIGHER_KINDS, cam_contact, cam_frame
from chaingraph.model.chain import Chain, Joint

if TYPE_CHECKING:                       # matplotlib is imported only to draw with it
    from matplotlib.axes import Axes

#: a coordinate, or its values over a motion's steps
Coordinate = float | np.ndarray

__all__ = ["View", "Scene", "Shape", "segments_meet_boxes", "svg_document", "frame_shapes", "path_shapes", "svg_elements", "draw_shapes",
           "COLOURS"]

#: the links' colours, in the order of the chain's links
COLOURS = ["#1f77b4", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf",
           "#bcbd22", "#ff7f0e"]


@dataclass(frozen=True)
class Shape:
    """One item of a picture, in the mechanism's coordinates (lengths in its units).

    ``kind`` is "polygon", "polyline", "line", "circle" or "text"; ``points`` its
    vertices (a circle's centre, a text's anchor); ``cls`` what it draws (plate, bar,
    guide, slot, barrel, hatch, block, ground, pin, point, label, path); ``data`` the
    joint, link or point it belongs to, as ``(("joint", id), ...)``; the style:
    ``fill`` (None: none), ``fill_opacity``, ``stroke`` and its ``width``, ``dash``
    lengths, line ``join`` and ``cap``; a circle's ``radius``; a text's ``text``,
    font ``size`` and white ``halo`` width.
    """

    kind: str
    cls: str
    points: tuple[Vec, ...]
    data: tuple[tuple[str, str], ...] = ()
    fill: str | None = None
    fill_opacity: float | None = None
    stroke: str | None = None
    width: float | None = None
    dash: tuple[float, ...] = ()
    join: str | None = None
    cap: str | None = None
    radius: float | None = None
    text: str | None = None
    size: float | None = None
    halo: float | None = None


class _Pair:
    """How one sliding pair is drawn: the link that carries the guide and the guide's
    style (a hatched ``way`` on the fixed link, a ``slot`` in a moving link, the barrel
    of a ``cylinder``), the guide's extent in line coordinates on that link (slides from
    the joint's reference point in the drawn pose), and where the block sits on the
    other link: on a pin (``pin``), else at line coordinate ``at``."""

    def __init__(self, carrier, block_link, style, extent, *, pin=None, at=0.0, cap=None):
        self.carrier, self.block_link, self.style = carrier, block_link, style
        self.lo, self.hi = extent
        self.pin, self.at = pin, at
        self.cap = cap                     # a barrel's closed end: "lo" or "hi"


class View:
    """A picture's window on the mechanism's plane: the box ``lo``-``hi`` (its units)
    with ``pad`` around it, mapped to picture coordinates (y down) for SVG."""

    def __init__(self, lo: Sequence[float], hi: Sequence[float], pad: float) -> None:
        self.lo, self.hi, self.pad = lo, hi, pad

    @property
    def decimals(self) -> int:
        """Decimals enough that a length keeps its value to 1e-5 of the picture's size,
        whatever the size (a link's length must not wobble from frame to frame)."""
        return max(0, 5 - math.floor(math.log10(max(max(self.size), 1e-300))))

    def num(self, v: float) -> str:
        """A picture coordinate as text, to the view's decimals."""
        if getattr(self, "_format", None) is None:
            self._format = f"{{:.{self.decimals}f}}"
        text = self._format.format(v)
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        return "0" if text in ("-0", "") else text

    # model -> picture coordinates (y up -> y down)
    def X(self, x: float) -> float:
        return x - self.lo[0] + self.pad

    def Y(self, y: float) -> float:
        return self.hi[1] - y + self.pad

    def pt(self, x: float, y: float) -> str:
        return f"{self.num(self.X(x))},{self.num(self.Y(y))}"

    @property
    def size(self) -> tuple[float, float]:
        return (self.hi[0] - self.lo[0] + 2 * self.pad, self.hi[1] - self.lo[1] + 2 * self.pad)


class Scene(View):
    """What a picture of a mechanism needs over a motion's steps, in its coordinates.

    ``xy`` maps every joint and point to its (x, y) arrays over the steps; ``angle``
    every P joint to its sliding line's direction (radians) and ``slide`` to its slide
    from the drawn pose; ``turns`` each link to its rotation from the drawn pose
    (radians; none given: the drawn pose), which turns a cam's profile, its follower's
    roller and a gear's pitch circle with their links. Build one with
    :meth:`of_motion` or :meth:`of_pose`.
    """

    def __init__(self, chain, fixed, xy, angle, slide, turns=None):
        self.chain, self.fixed = chain, fixed
        self.xy = {name: (np.asarray(x, dtype=float), np.asarray(y, dtype=float))
                   for name, (x, y) in xy.items()}
        self.n = next(iter(self.xy.values()))[0].size if self.xy else 0
        self.turns = {link: np.broadcast_to(np.asarray(v, dtype=float), (self.n,))
                      for link, v in (turns or {}).items()}
        self.higher = _higher_parts(chain)
        self.slides = [j for j in chain.joints if j.kind == "P"]
        self.angle, self.slide, self.pairs, self.ends, self.blocks = {}, {}, {}, {}, {}
        for j in self.slides:
            a = np.asarray(angle[j.id], dtype=float)
            self.angle[j.id] = np.where(np.isfinite(a), a, math.radians(j.axis or 0.0))
            s = np.asarray(slide[j.id], dtype=float)
            self.slide[j.id] = np.where(np.isfinite(s), s, 0.0)
            pair = self.pairs[j.id] = self._pair(j, s[np.isfinite(s)])
            side = j.links.index(pair.carrier)
            self.ends[j.id] = (self.on_line(j, side, pair.lo), self.on_line(j, side, pair.hi))
            self.blocks[j.id] = (self.xy[pair.pin] if pair.pin else
                                 self.on_line(j, j.links.index(pair.block_link), pair.at))
        xs = [v[0] for v in self.xy.values()] + [e[0] for p in self.ends.values() for e in p]
        ys = [v[1] for v in self.xy.values()] + [e[1] for p in self.ends.values() for e in p]
        for part in self.higher:            # a cam's or gear's circle about its centre
            cx, cy = self.xy[part.centre]
            xs += [cx - part.reach, cx + part.reach]
            ys += [cy - part.reach, cy + part.reach]
        every_x, every_y = np.concatenate(xs), np.concatenate(ys)
        every_x, every_y = every_x[np.isfinite(every_x)], every_y[np.isfinite(every_y)]
        lo = [float(every_x.min()), float(every_y.min())]
        hi = [float(every_x.max()), float(every_y.max())]
        self.span = max(hi[0] - lo[0], hi[1] - lo[1], 1e-9)
        for axis in (0, 1):       # no sliver of a picture: each side at least half the other
            grow = 0.25 * self.span - 0.5 * (hi[axis] - lo[axis])
            if grow > 0:
                lo[axis], hi[axis] = lo[axis] - grow, hi[axis] + grow
        self.lo, self.hi = tuple(lo), tuple(hi)
        self.pad = 0.12 * self.span
        self.w = 0.035 * self.span           # a block's half length, a slot's width

    @classmethod
    def of_motion(cls, motion: Motion, *, also: Motion | None = None,
                  rows: Sequence[int] | None = None) -> Scene:
        """The scene over a solved :class:`~chaingraph.kinematics.Motion`; ``also``, a
        motion of the same mechanism whose steps are added after the first's (a pose
        to draw that is not one of the sweep's steps); ``rows``, the steps to keep (the
        scene's steps are then those, in that order: the picture is fitted to them)."""
        chain = motion.plan.chain
        names = [j.id for j in chain.joints] + [p.id for p in chain.points]
        motions = [motion] if also is None else [motion, also]
        keep = slice(None) if rows is None else np.asarray(rows, dtype=int)

        def series(values):
            return np.concatenate([np.asarray(v, dtype=float).reshape(-1)
                                   for v in values])[keep]
        xy = {name: (series(m.point(name).x for m in motions),
                     series(m.point(name).y for m in motions)) for name in names}
        turns = {link: series(m.link(link).angle for m in motions)
                 - math.radians(chain.reference_direction(link)) for link in chain.links}
        angle, slide = {}, {}
        for j in chain.joints:
            if j.kind == "P":
                # the sliding line turns with its guide from the drawn pose
                angle[j.id] = math.radians(j.axis or 0.0) + turns[j.links[0]]
                slide[j.id] = series(m.slide(j.id).s for m in motions)
        return cls(chain, motion.fixed, xy, angle, slide, turns)

    @classmethod
    def of_chain(cls, chain: Chain) -> Scene:
        """The scene of a chain in its drawn pose (one step): a mechanism's fixed link
        is the ground; a chain without a mechanism has none."""
        xy = {name: ([x], [y]) for name, (x, y) in chain.positions().items()}
        angle = {j.id: [math.radians(j.axis or 0.0)] for j in chain.joints if j.kind == "P"}
        slide = {j.id: [0.0] for j in chain.joints if j.kind == "P"}
        return cls(chain, chain.mechanism.fixed if chain.mechanism else None, xy, angle,
                   slide)

    @classmethod
    def of_pose(cls, state: PoseMotion) -> Scene:
        """The scene of one pose: a mechanism solved at one input value (the result
        of :func:`chaingraph.kinematics.pose.pose_motion`)."""
        xy = {name: ([p[0]], [p[1]]) for name, p in state.positions.items()}
        angle = {j: [math.atan2(s.axis[1], s.axis[0])] for j, s in state.slides.items()}
        slide = {j: [s.slide] for j, s in state.slides.items()}
        turns = {link: [state.links[link].angle] for link in state.chain.links}
        return cls(state.chain, state.fixed, xy, angle, slide, turns)

    def on_line(self, joint: Joint, side: int, along: Coordinate
                ) -> tuple[np.ndarray, np.ndarray]:
        """Over the motion, the point at line coordinate ``along`` on the pair's link
        ``joint.links[side]`` (the joint's reference point moves with the second link;
        the first sees it slide by ``s``)."""
        x, y = self.xy[joint.id]
        a = self.angle[joint.id]
        c = along - self.slide[joint.id] if side == 0 else along
        return x + c * np.cos(a), y + c * np.sin(a)

    def _pair(self, joint, s):
        """Which link carries the guide, in what style, over what extent.

        A way on the fixed link. Between moving links: a slot in the link that reaches
        past a block on a pin (the textbook numbers the crank and slotted lever so that
        the small block carries the pair's guide; the slot still goes on the lever); but
        a block on a pin to the frame is a trunnion, drawn as an oscillating cylinder
        with the other link's rod and piston in it; a pair whose two links both reach
        away from it, the second from one side only, is a cylinder and its rod."""
        chain, fixed = self.chain, self.fixed
        s = s if s.size else np.zeros(1)
        pts = list(chain.positions().values())
        extent = max(max(p[0] for p in pts) - min(p[0] for p in pts),
                     max(p[1] for p in pts) - min(p[1] for p in pts), 1e-9)
        tol = 0.035 * extent
        u = (math.cos(math.radians(joint.axis)), math.sin(math.radians(joint.axis)))

        def coord(p):
            return (p[0] - joint.at[0]) * u[0] + (p[1] - joint.at[1]) * u[1]

        def pins(link):
            return [x for x in chain.joints_of(link) if x.kind == "R"]

        def on_pin(link):
            p = pins(link)
            if link != fixed and p and all(math.dist(x.at, joint.at) <= tol for x in p):
                return p[0]
            return None

        def across(c, side):
            """Line coordinate ``c`` on link ``side``, seen from the other link."""
            return c + s if side == 1 else c - s

        def padded(values, extra):
            values = np.concatenate([np.atleast_1d(np.asarray(v, dtype=float)) for v in values])
            lo, hi = float(values.min()), float(values.max())
            margin = 0.06 * (hi - lo) + extra
            return lo - margin, hi + margin

        links = joint.links
        if fixed in links:
            side = 1 - links.index(fixed)
            pin = on_pin(links[side])
            at = coord(pin.at) if pin else 0.0
            return _Pair(fixed, links[side], "way", padded([across(at, side)], 0.1 * extent),
                         pin=pin.id if pin else None, at=at)
        held = [side for side in (0, 1) if on_pin(links[side])]
        if len(held) == 1:
            side = held[0]
            pin, other = on_pin(links[side]), 1 - side
            at = coord(pin.at)
            if fixed in pin.links and pins(links[other]):
                # a trunnion: the block's link is the cylinder, the other link its rod,
                # with the piston at the rod's end beyond the trunnion's whole travel
                travel = across(at, side)
                rod = [coord(x.at) for x in pins(links[other])]
                gap = 0.1 * float(np.ptp(travel)) + 2 * tol
                ahead = np.mean(rod) <= 0.5 * (travel.min() + travel.max())
                end = float(travel.max() + gap if ahead else travel.min() - gap)
                piston = across(end, other)
                entry = np.mean([across(c, other).mean() for c in rod])
                return _Pair(links[side], links[other], "cylinder",
                             padded([piston, at], 1.2 * tol), at=end,
                             cap="hi" if entry < piston.mean() else "lo")
            return _Pair(links[other], links[side], "slot",
                         padded([across(at, side)] + [coord(x.at) for x in pins(links[other])],
                                0.04 * extent), pin=pin.id, at=at)
        travel = across(0.0, 1)                      # the second link's reference point
        rod = [coord(x.at) for x in pins(links[1])]
        reach = [coord(x.at) for x in pins(links[0])]
        if rod and (all(c > tol for c in rod) or all(c < -tol for c in rod)):
            return _Pair(links[0], links[1], "cylinder", padded([travel] + reach, 1.2 * tol),
                         cap="lo" if rod[0] > 0 else "hi")
        return _Pair(links[0], links[1], "slot", padded([travel] + reach, 0.04 * extent))


class _Part:
    """A higher pair's drawn part on one link: a cam's profile (``points``, drawn, about
    the joint ``centre``), a follower's roller (``points`` its drawn centre, ``radius``),
    a gear's pitch circle (``radius``, its spoke towards ``points[0]``); ``link`` carries
    it, turning about ``centre`` (a joint of it); ``reach`` its size about the centre."""

    def __init__(self, kind, link, centre, points, radius=0.0, reach=0.0):
        self.kind, self.link, self.centre = kind, link, centre
        self.points = np.asarray(points, dtype=float)
        self.radius, self.reach = radius, reach


def _higher_parts(chain):
    """Every cam's profile and follower, every gear pair's two pitch circles."""
    out = []
    for cam in chain.cams:
        frame = cam_frame(chain, cam)
        centre = next(j for j in chain.joints if j.kind == "R" and set(j.links) ==
                      {cam.cam, frame.on})
        profile = frame.on_cam(analyse_cam(cam, turn_angles(cam, 180)).profile)
        reach = float(np.max(np.hypot(*(profile - centre.at).T)))
        out.append(_Part("cam", cam.cam, centre.id, profile, reach=reach))
        if cam.contact == "roller":
            held = next(j for j in chain.joints if cam.follower in j.links and
                        (j.kind == "R" or (j.kind == "P" and j.links[1] == cam.follower)))
            roller = cam_contact(chain, cam, np.zeros(1))[2]
            out.append(_Part("roller", cam.follower, held.id, roller, radius=cam.roller))
    for g in chain.gears:
        pitch = chain.joint(g.id).at
        for link in g.links:
            axis = next(j for j in chain.joints if j.kind == "R" and link in j.links
                        and g.carrier in j.links)
            r = math.dist(axis.at, pitch) if pitch is not None else 0.0
            out.append(_Part("gear", link, axis.id, [pitch], radius=r, reach=r))
    return out


def _higher_shapes(scene, k, at):
    """At step ``k``: each cam's profile turned with it, each roller on its follower,
    each gear's pitch circle (dash-dot) with a spoke that turns with the gear."""
    out = []
    stroke = 0.012 * scene.span
    colours = {link: COLOURS[c % len(COLOURS)] for c, link in enumerate(scene.chain.links)}
    for part in scene.higher:
        pts = _moved(scene, part, k, at)
        if pts is None:
            continue
        tag = (("link", part.link),)
        colour = colours[part.link]
        if part.kind == "cam":
            out.append(Shape("polygon", "cam", pts, data=tag, fill=colour, fill_opacity=0.3,
                             stroke=colour, width=stroke, join="round"))
        elif part.kind == "roller":
            out.append(Shape("circle", "roller", pts, data=tag, radius=part.radius,
                             fill="white", stroke=colour, width=stroke))
        else:
            centre = at[part.centre]
            out.append(Shape("circle", "pitch", (centre,), data=tag, radius=part.radius,
                             stroke=colour, width=0.6 * stroke,
                             dash=(3 * stroke, stroke, 0.6 * stroke, stroke)))
            out.append(_line("spoke", centre, pts[0], colour, 0.6 * stroke, tag))
    return out


def _moved(scene, part, k, at):
    """A part's drawn points where its link has carried them at step ``k`` (None
    where the pose is not known)."""
    turn = float(scene.turns[part.link][k]) if part.link in scene.turns else 0.0
    c0, ck = scene.chain.joint(part.centre).at, at[part.centre]
    if not (math.isfinite(turn) and _finite(ck)):
        return None
    p = part.points
    d = rotate((p[:, 0] - c0[0], p[:, 1] - c0[1]), turn)
    return tuple((float(x), float(y)) for x, y in zip(ck[0] + d[0], ck[1] + d[1]))


def _finite(*points):
    return all(math.isfinite(v) for p in points for v in p)


def _line(cls, p, q, colour, width, data=(), dash=()):
    return Shape("line", cls, (p, q), data=data, stroke=colour, width=width, dash=dash)


def frame_shapes(scene: Scene, k: int) -> list[Shape]:
    """The shapes of the pose at step ``k``: links (plates and bars, each whole: with
    its blocks and the slots it carries), sliding pairs (guides and blocks), joints
    (fixed pivots on hatched ground, pins, higher pairs), points, and labels placed
    clear of each other and, where they can be, of the links."""
    at = {name: (v[0][k], v[1][k]) for name, v in scene.xy.items()}
    ends = {j: ((e1[0][k], e1[1][k]), (e2[0][k], e2[1][k])) for j, (e1, e2) in scene.ends.items()}
    blocks = {j: (b[0][k], b[1][k]) for j, b in scene.blocks.items()}
    rollers = {part.link: _moved(scene, part, k, at) or () for part in scene.higher
               if part.kind == "roller"}
    out = _higher_shapes(scene, k, at) + _bodies(scene, at, ends, blocks, rollers)
    for j in scene.slides:
        out += _slide_shapes(scene, j, k, ends[j.id], blocks[j.id])
    out += _joint_shapes(scene, at)
    out += _labels(scene, at, out)
    return out


def _members(scene, link, at, ends, blocks, rollers=None):
    """The points a link's body joins at one pose: its turning pairs and points, the
    blocks it carries (a block not on one of its pins, a piston at its rod's end), the
    middles of the slots cut in it, and a cylinder's barrel where the body does not
    reach it."""
    chain = scene.chain
    drawn = {c.id for c in chain.cams} | {g.id for g in chain.gears}   # as parts
    members = [at[j.id] for j in chain.joints_of(link)
               if j.kind != "P" and not (j.kind in HIGHER_KINDS and j.id in drawn)]
    members += list((rollers or {}).get(link, ()))       # a follower reaches its roller
    members += [at[p.id] for p in chain.points if p.link == link]
    barrels = []
    for jid, pair in scene.pairs.items():
        if pair.block_link == link and pair.pin is None:
            members.append(blocks[jid])
        if pair.carrier == link and pair.style == "slot":
            (x1, y1), (x2, y2) = ends[jid]
            members.append((0.5 * (x1 + x2), 0.5 * (y1 + y2)))
        elif pair.carrier == link and pair.style == "cylinder":
            barrels.append(ends[jid])
    for p1, p2 in barrels:
        if not any(segment_distance(m, p1, p2) <= 0.9 * scene.w for m in members):
            members.append(min((p1, p2), key=lambda e: min(
                (math.dist(e, m) for m in members), default=0.0)))
    return [p for p in members if _finite(p)]


def _bodies(scene, at, ends, blocks, rollers=None):
    """The moving links as plates (three or more points not in one line) and bars."""
    stroke = 0.012 * scene.span
    out = []
    for c, link in enumerate(scene.chain.links):
        if link == scene.fixed:
            continue
        pts = _members(scene, link, at, ends, blocks, rollers)
        colour = COLOURS[c % len(COLOURS)]
        hull = convex_hull([(round(x, 12), round(y, 12)) for x, y in pts])
        if len(hull) >= 3 and polygon_area(hull) <= 1e-6 * scene.span ** 2:
            # points in one line (a rod through its pin and point to its piston): a bar
            hull = list(max(((p, q) for p in hull for q in hull), key=lambda e: math.dist(*e)))
        if len(hull) >= 3:
            out.append(Shape("polygon", "plate", tuple(hull), data=(("link", link),),
                             fill=colour, fill_opacity=0.25, stroke=colour, width=stroke,
                             join="round"))
        elif len(hull) == 2:
            out.append(Shape("polyline", "bar", tuple(hull), data=(("link", link),),
                             stroke=colour, width=2 * stroke, cap="round"))
    return out


def _slide_shapes(scene, j, k, guide, centre):
    """One sliding pair at step ``k``: its guide on the link that carries it (a hatched
    way, a slot, a barrel) and its block on the other link."""
    pair, w = scene.pairs[j.id], scene.w
    stroke = 0.012 * scene.span
    p1, p2 = guide
    if not _finite(p1, p2, centre):
        return []
    a = float(scene.angle[j.id][k])
    u, nrm = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
    tag = (("joint", j.id), ("link", pair.carrier))
    out = []

    def off(p, d):
        return (p[0] + d * nrm[0], p[1] + d * nrm[1])

    if pair.style == "way":
        # a way on the fixed link: hatched on one side
        out.append(_line("guide", p1, p2, "#444444", stroke, tag))
        count = max(2, min(40, int(round(math.dist(p1, p2) / (0.8 * w)))))
        for i in range(count + 1):
            t = i / count
            b = off((p1[0] + t * (p2[0] - p1[0]), p1[1] + t * (p2[1] - p1[1])), -0.9 * w)
            e = (b[0] - 0.5 * w * (u[0] + nrm[0]), b[1] - 0.5 * w * (u[1] + nrm[1]))
            out.append(_line("hatch", b, e, "#777777", 0.5 * stroke))
    elif pair.style == "slot":
        # a slot in a moving link: two sides about its centre line
        out.append(_line("guide", p1, p2, "#444444", 0.5 * stroke, tag))
        for side in (-1, 1):
            out.append(_line("slot", off(p1, side * 0.8 * w), off(p2, side * 0.8 * w),
                             "#444444", stroke, (("joint", j.id),)))
    else:
        # a cylinder: the barrel, closed at one end, about a dash-dot centre line
        out.append(_line("guide", p1, p2, "#888888", 0.4 * stroke, tag,
                         dash=(2 * stroke, stroke, 0.5 * stroke, stroke)))
        shut, open_ = (p1, p2) if pair.cap == "lo" else (p2, p1)
        wall = (off(open_, -0.9 * w), off(shut, -0.9 * w), off(shut, 0.9 * w),
                off(open_, 0.9 * w))
        out.append(Shape("polyline", "barrel", wall, data=tag, stroke="#333333",
                         width=stroke, join="round"))
    half = (0.6 * w, 0.85 * w) if pair.style == "cylinder" else (w, 0.7 * w)
    corners = tuple((centre[0] + du * half[0] * u[0] + dn * half[1] * nrm[0],
                     centre[1] + du * half[0] * u[1] + dn * half[1] * nrm[1])
                    for du, dn in ((-1, -1), (1, -1), (1, 1), (-1, 1)))
    out.append(Shape("polygon", "block", corners,
                     data=(("joint", j.id), ("link", pair.block_link)),
                     fill="#f2f2f2", stroke="#222222", width=stroke))
    return out


def _joint_shapes(scene, at):
    """Fixed pivots on hatched ground, pins as circles, higher pairs as dashed rings,
    tracer points as dots."""
    w, stroke = scene.w, 0.012 * scene.span
    out = []
    for j in scene.chain.joints:
        if j.kind == "P" or not all(math.isfinite(v) for v in at[j.id]):
            continue
        x, y = at[j.id]
        if j.kind != "R":
            out.append(Shape("circle", "higher", ((x, y),), data=(("joint", j.id),),
                             radius=0.6 * w, stroke="#b05000", width=stroke * 0.8,
                             dash=(stroke, stroke)))
            continue
        if scene.fixed in j.links:
            tri = ((x, y), (x - 1.1 * w, y - 1.6 * w), (x + 1.1 * w, y - 1.6 * w))
            out.append(Shape("polygon", "ground", tri, fill="#dddddd", stroke="#222222",
                             width=stroke * 0.7))
            for i in range(5):
                bx = x - 1.5 * w + i * 0.75 * w
                out.append(_line("hatch", (bx, y - 1.6 * w), (bx - 0.5 * w, y - 2.1 * w),
                                 "#777777", stroke * 0.5))
        out.append(Shape("circle", "pin", ((x, y),), data=(("joint", j.id),),
                         radius=0.45 * w, fill="#555555" if scene.fixed in j.links else "white",
                         stroke="#111111", width=stroke * 0.8))
    for p in scene.chain.points:
        x, y = at[p.id]
        if math.isfinite(x) and math.isfinite(y):
            out.append(Shape("circle", "point", ((x, y),), data=(("point", p.id),),
                             radius=0.3 * w, fill="#c00000"))
    return out


#: a label's box, in font sizes: the width of a character (an over-estimate for the
#: sans-serif capitals and digits of joint names), the depth below the baseline and the
#: height above it
LABEL_CHAR, LABEL_DEPTH, LABEL_HEIGHT = 0.62, 0.25, 0.8


def label_box(x: float, y: float, text: str, size: float
              ) -> tuple[float, float, float, float]:
    """The box ``(x0, y0, x1, y1)`` a label of ``size`` at baseline point ``(x, y)``
    takes (in the mechanism's coordinates, y up)."""
    return (x, y - LABEL_DEPTH * size, x + LABEL_CHAR * size * len(text),
            y + LABEL_HEIGHT * size)


def _labels(scene, at, shapes):
    """Every joint's and point's name, placed where it overlaps no other name and, as
    far as it can, no link, pin or guide: tried round the joint, away from the links it
    joins first, nearer first."""
    font = 0.045 * scene.span
    clutter = _Clutter(shapes, (scene.lo[0] - scene.pad, scene.lo[1] - scene.pad,
                                scene.hi[0] + scene.pad, scene.hi[1] + scene.pad))
    near: dict[str, list[tuple[float, float]]] = {}
    for link in scene.chain.links:
        names = [j.id for j in scene.chain.joints_of(link)]
        names += [p.id for p in scene.chain.points if p.link == link]
        for name in names:
            near.setdefault(name, []).extend(at[n] for n in names if n != name)
    wanted = []
    for name, (x, y) in at.items():
        if not (math.isfinite(x) and math.isfinite(y)):
            continue
        others = [p for p in near.get(name, []) if _finite(p)]
        dx, dy = (x - sum(p[0] for p in others) / len(others),
                  y - sum(p[1] for p in others) / len(others)) if others else (1.0, 1.0)
        base = math.atan2(dy, dx) if math.hypot(dx, dy) > 1e-9 * scene.span else math.pi / 4
        wanted.append((name, *_candidates(x, y, name, font, scene.w, base)))
    if not wanted:
        return []
    every = np.concatenate([boxes for _, _, boxes in wanted])
    costs = np.split(clutter.of(every), len(wanted))
    placed, out, gap = np.zeros((0, 4)), [], 0.1 * font
    for (name, cost, boxes), more in zip(wanted, costs):
        taken = ((boxes[:, None, 0] < placed[None, :, 2] + gap)
                 & (placed[None, :, 0] < boxes[:, None, 2] + gap)
                 & (boxes[:, None, 1] < placed[None, :, 3] + gap)
                 & (placed[None, :, 1] < boxes[:, None, 3] + gap)).any(axis=1)
        box = boxes[int(np.argmin(cost + more + np.where(taken, np.inf, 0.0)))]
        placed = np.vstack([placed, box])
        out.append(Shape("text", "label", ((float(box[0]), float(box[1]) + LABEL_DEPTH * font),),
                         text=name, size=font, halo=0.25 * font))
    return out


def _candidates(x, y, text, size, w, base):
    """(preference cost, boxes) of the places tried for a label of the point (x, y):
    eight directions from ``base`` (the nearer to it, the better), at four distances
    (the nearer, the better); boxes as rows (x0, y0, x1, y1)."""
    x0, y0, x1, y1 = label_box(0.0, 0.0, text, size)
    hw, hh = 0.5 * (x1 - x0), 0.5 * (y1 - y0)
    turn = np.tile(np.arange(-3, 5), 4)
    ring = np.repeat(np.arange(4), 8)
    a = base + turn * math.pi / 4
    dx, dy = np.cos(a), np.sin(a)
    reach = np.array([0.75, 1.6, 2.8, 4.5])[ring] * w + np.abs(dx) * hw + np.abs(dy) * hh
    cx, cy = x + dx * reach, y + dy * reach
    return 0.3 * np.abs(turn) + 0.9 * ring, np.stack([cx - hw, cy - hh, cx + hw, cy + hh],
                                                     axis=1)


class _Clutter:
    """What a label should not cover, from a frame's shapes: pins, lines (with their
    half widths), the inside of plates and blocks, the outside of the ``view``."""

    def __init__(self, shapes, view):
        segs, circles, self.areas = [], [], []
        for s in shapes:
            if s.cls in ("hatch", "path", "label"):
                continue
            half = 0.5 * (s.width or 0.0)
            pts = list(s.points)
            if s.kind in ("line", "polyline"):
                segs += [(*p, *q, half) for p, q in zip(pts, pts[1:])]
            elif s.kind == "polygon":
                segs += [(*p, *q, half) for p, q in zip(pts, pts[1:] + pts[:1])]
                if s.cls in ("plate", "block", "ground"):
                    self.areas.append(pts)
            elif s.kind == "circle":
                circles.append((*s.points[0], s.radius + half))
        self.segs = np.array(segs, dtype=float).reshape(-1, 5)
        self.circles = np.array(circles, dtype=float).reshape(-1, 3)
        self.view = view

    def of(self, boxes):
        """The clutter cost of each box (rows x0, y0, x1, y1)."""
        c = self.circles
        cost = 4.0 * ((boxes[:, None, 0] - c[None, :, 2] < c[None, :, 0])
                      & (c[None, :, 0] < boxes[:, None, 2] + c[None, :, 2])
                      & (boxes[:, None, 1] - c[None, :, 2] < c[None, :, 1])
                      & (c[None, :, 1] < boxes[:, None, 3] + c[None, :, 2])).sum(axis=1)
        cost = cost + 1.5 * segments_meet_boxes(self.segs, boxes).sum(axis=1)
        middle = np.stack([0.5 * (boxes[:, 0] + boxes[:, 2]),
                           0.5 * (boxes[:, 1] + boxes[:, 3])], axis=1)
        for pts in self.areas:
            xs, ys = [p[0] for p in pts], [p[1] for p in pts]
            near = ((middle[:, 0] > min(xs)) & (middle[:, 0] < max(xs))
                    & (middle[:, 1] > min(ys)) & (middle[:, 1] < max(ys)))
            if near.any():
                cost = cost + 0.8 * (near & _inside_many(middle, pts))
        v = self.view
        return cost + 2.0 * ((boxes[:, 0] < v[0]) | (boxes[:, 1] < v[1])
                             | (boxes[:, 2] > v[2]) | (boxes[:, 3] > v[3]))


def segments_meet_boxes(segs: np.ndarray, boxes: np.ndarray) -> np.ndarray:
    """(boxes, segments) booleans: whether each segment (rows x1, y1, x2, y2, half
    width) meets each box grown by its half width (Liang-Barsky clipping)."""
    px, py, qx, qy, half = (segs[None, :, i] for i in range(5))
    lo_x, lo_y = boxes[:, None, 0] - half, boxes[:, None, 1] - half
    hi_x, hi_y = boxes[:, None, 2] + half, boxes[:, None, 3] + half
    t0 = np.zeros(lo_x.shape)
    t1 = np.ones(lo_x.shape)
    ok = np.ones(lo_x.shape, dtype=bool)
    for p, d, lo, hi in ((px, qx - px, lo_x, hi_x), (py, qy - py, lo_y, hi_y)):
        flat = np.abs(d) < 1e-300
        ok &= ~(flat & ((p < lo) | (p > hi)))
        safe = np.where(flat, 1.0, d)
        a, b = (lo - p) / safe, (hi - p) / safe
        a, b = np.where(flat, -np.inf, np.minimum(a, b)), np.where(flat, np.inf, np.maximum(a, b))
        t0, t1 = np.maximum(t0, a), np.minimum(t1, b)
    return ok & (t0 <= t1)


def _inside_many(points, polygon):
    """Whether each of the points (rows x, y) is inside the polygon (even-odd)."""
    inside = np.zeros(len(points), dtype=bool)
    x, y = points[:, 0], points[:, 1]
    for (x1, y1), (x2, y2) in zip(polygon, polygon[1:] + polygon[:1]):
        if y1 == y2:
            continue
        cross = ((y1 > y) != (y2 > y)) & (x < x1 + (y - y1) * (x2 - x1) / (y2 - y1))
        inside ^= cross
    return inside


def path_shapes(scene: Scene, *, steps: int | None = None) -> list[Shape]:
    """The paths of the joints and points that move over the scene's steps (the first
    ``steps`` of them), faint (points orange, pins grey), to be drawn under everything."""
    out = []
    for name, (xs, ys) in scene.xy.items():
        xs, ys = xs[:steps], ys[:steps]
        ok = np.isfinite(xs) & np.isfinite(ys)
        if ok.sum() > 1 and np.ptp(xs[ok]) + np.ptp(ys[ok]) > 1e-9 * scene.span:
            is_point = any(p.id == name for p in scene.chain.points)
            out.append(Shape("polyline", "path", tuple(zip(xs[ok], ys[ok])),
                             stroke="#e07b00" if is_point else "#bbbbbb",
                             width=0.004 * scene.span))
    return out


# -- the SVG emitter -------------------------------------------------------------------
def svg_document(view: View, elements: Iterable[str], *, width: int, title: str) -> str:
    """A standalone SVG picture of ``view`` (a :class:`View`) at ``width`` pixels: a
    white ground, the ``elements`` (SVG text) and the ``title``."""
    w, h = view.size
    height = int(round(width * h / w))
    return "\n".join(
        ['<?xml version="1.0"?>',
         f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
         f'viewBox="0 0 {w:.6g} {h:.6g}">', f"<title>{html.escape(title)}</title>",
         '<rect class="background" width="100%" height="100%" fill="white"/>',
         *elements, "</svg>"]) + "\n"



def svg_elements(scene: View, shapes: Iterable[Shape]) -> list[str]:
    """The shapes as SVG elements, in the scene's picture coordinates (y down)."""
    return [_svg(scene, s) for s in shapes]


def _svg(scene, s):
    attrs = [f'class="{s.cls}"']
    attrs += [f'data-{key}="{html.escape(value, quote=True)}"' for key, value in s.data]
    if s.dash:
        attrs.append('stroke-dasharray="' + " ".join(f"{d:.3g}" for d in s.dash) + '"')
    if s.kind == "line":
        (x1, y1), (x2, y2) = s.points
        attrs.append(f'x1="{scene.num(scene.X(x1))}" y1="{scene.num(scene.Y(y1))}" '
                     f'x2="{scene.num(scene.X(x2))}" y2="{scene.num(scene.Y(y2))}"')
    elif s.kind in ("polygon", "polyline"):
        attrs.append('points="' + " ".join(scene.pt(*p) for p in s.points) + '"')
        attrs.append(f'fill="{s.fill or "none"}"')
    elif s.kind == "circle":
        (x, y), = s.points
        attrs.append(f'cx="{scene.num(scene.X(x))}" cy="{scene.num(scene.Y(y))}" '
                     f'r="{s.radius:.3g}"')
        attrs.append(f'fill="{s.fill or "none"}"')
    elif s.kind == "text":
        (x, y), = s.points
        attrs.append(f'x="{scene.num(scene.X(x))}" y="{scene.num(scene.Y(y))}" '
                     f'font-size="{s.size:.3g}" font-family="sans-serif"')
        if s.halo:
            attrs.append(f'paint-order="stroke" stroke="white" stroke-width="{s.halo:.3g}"')
        return f"<text {' '.join(attrs)}>{html.escape(s.text)}</text>"
    if s.fill_opacity is not None:
        attrs.append(f'fill-opacity="{s.fill_opacity:g}"')
    if s.stroke is not None:
        attrs.append(f'stroke="{s.stroke}" stroke-width="{s.width:.3g}"')
    if s.join:
        attrs.append(f'stroke-linejoin="{s.join}"')
    if s.cap:
        attrs.append(f'stroke-linecap="{s.cap}"')
    tag = {"polygon": "polygon", "polyline": "polyline", "line": "line",
           "circle": "circle"}[s.kind]
    return f"<{tag} {' '.join(attrs)}/>"


# -- the matplotlib emitter ------------------------------------------------------------
def draw_shapes(ax: Axes, scene: View, shapes: Sequence[Shape], *,
                view: tuple[tuple[float, float], tuple[float, float]] | None = None,
                zorder: float = 1.0) -> None:
    """Draw the shapes on matplotlib axes in the mechanism's coordinates, with the same
    look as the SVG. The view is ``view`` ((xmin, ymin), (xmax, ymax)), else the
    scene's with its padding, at equal scale; line widths and fonts, given in the
    mechanism's units, are converted to points for the axes as they are laid out now
    (lay the figure out first). The shapes go at ``zorder`` and just above, in order."""
    from matplotlib import patches, patheffects

    if view is None:
        view = ((scene.lo[0] - scene.pad, scene.lo[1] - scene.pad),
                (scene.hi[0] + scene.pad, scene.hi[1] + scene.pad))
    (x0, y0), (x1, y1) = view
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.apply_aspect()
    a, b = ax.transData.transform([(0.0, 0.0), (1.0, 0.0)])
    points = (b[0] - a[0]) * 72.0 / ax.figure.dpi            # points per unit length

    def lw(width):
        return (width or 0.0) * points

    for z, s in enumerate(shapes):
        order = zorder + 0.9 * z / max(len(shapes), 1)
        if s.kind in ("polygon", "polyline") and (s.kind == "polygon" or s.fill):
            face = "none" if not s.fill else s.fill
            alpha_face = s.fill_opacity if s.fill_opacity is not None else 1.0
            patch = patches.Polygon(np.asarray(s.points, dtype=float), closed=True,
                                    facecolor=face if face == "none" else
                                    _rgba(face, alpha_face),
                                    edgecolor=s.stroke or "none", linewidth=lw(s.width),
                                    joinstyle=s.join or "miter", zorder=order)
            ax.add_patch(patch)
        elif s.kind in ("polyline", "line"):
            xs, ys = zip(*s.points)
            line, = ax.plot(xs, ys, color=s.stroke, linewidth=lw(s.width),
                            solid_capstyle=s.cap or "butt",
                            solid_joinstyle=s.join or "miter", zorder=order)
            if s.dash:
                line.set_dashes([d * points / max(lw(s.width), 1e-9) for d in s.dash])
        elif s.kind == "circle":
            (x, y), = s.points
            ax.add_patch(patches.Circle((x, y), s.radius or 0.0,
                                        facecolor=s.fill or "none",
                                        edgecolor=s.stroke or "none",
                                        linewidth=lw(s.width), zorder=order))
        elif s.kind == "text":
            effects = ([patheffects.withStroke(linewidth=lw(s.halo), foreground="white")]
                       if s.halo else None)
            ax.text(s.points[0][0], s.points[0][1], s.text or "",
                    fontsize=(s.size or 0.0) * points,
                    family="sans-serif", va="baseline", ha="left", path_effects=effects,
                    zorder=order)


def _rgba(colour, alpha):
    from matplotlib.colors import to_rgba

    return to_rgba(colour, alpha)
