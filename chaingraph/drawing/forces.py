"""Pictures of forces: the free-body diagrams at one pose (every moving link on its own,
with its forces as arrows to one scale, as the textbook draws them) and the
turning-moment diagram of a sweep (the effort against the input over a turn, its mean,
the energy swing shaded).

The free bodies are computed once as :class:`~chaingraph.drawing.scene.Shape` items
(:func:`free_body_shapes`) and emitted as SVG (:func:`free_body_svg`); the
turning-moment diagram is a matplotlib plot (:func:`plot_turning_moment`).
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING, overload

import numpy as np

from chaingraph.drawing.plots import finish, pyplot_module
from chaingraph.drawing.scene import (
    COLOURS,
    LABEL_DEPTH,
    LABEL_HEIGHT,
    Scene,
    Shape,
    View,
    label_box,
    segments_meet_boxes,
    svg_document,
    svg_elements,
)
from chaingraph.dynamics.reactions import PoseForces, SweepForces
from chaingraph.geometry import convex_hull, polygon_area, segment_distance

if TYPE_CHECKING:                   # matplotlib is imported only when a plot is drawn
    from matplotlib.figure import Figure

__all__ = ["plot_shaking", "cycle_of", "closed_cycle", "energy_lobes", "link_turns",
           "free_body_shapes", "free_body_svg", "force_polygon_shapes", "force_polygon_svg",
           "plot_turning_moment"]

#: arrow colours by what the force is
_Point = tuple[float, float]
#: a force on a link: (what, its colour's key in ARROWS, where it acts, the force)
Force = tuple[str, str, _Point, _Point]

ARROWS = {"reaction": "#b2182b", "load": "#2166ac", "weight": "#1b7837",
          "inertia force": "#777777", "effort": "#000000"}


def _newtons(f: _Point) -> str:
    m = math.hypot(*f)
    return f"{m / 1000:.3g} kN" if m >= 1000 else f"{m:.3g} N"


def forces_on(result: PoseForces, link: str) -> list[Force]:
    """(what, colour key, point, force) of every force on ``link``."""
    chain = result.chain
    out: list[Force] = []
    for r in result.reactions:
        fx, fy = r.force
        if fx is None or fy is None:
            continue
        j = chain.joint(r.joint)
        if r.on == link:
            out.append((f"{r.joint}", "reaction", result.points[r.joint], (fx, fy)))
        elif len(j.links) == 2 and link in j.links:
            out.append((f"{r.joint}", "reaction", result.points[r.joint], (-fx, -fy)))
    for a in result.applied:
        if a.link == link and None not in a.force:
            key = "effort" if a.what.startswith("effort") else a.what
            out.append((a.what, key, a.at, a.force))
    return out


#: the free bodies' panels across the picture
PANEL_COLUMNS = 2


def link_turns(result: PoseForces) -> dict[str, float]:
    """Each link's rotation from the drawn pose (radians) at the pose of ``result``:
    from two of its turning pairs' points, else that of the link it slides on (a block
    turns with its guide), else 0 (the frame)."""
    chain = result.chain
    turn: dict[str, float] = {result.fixed: 0.0}
    for link in chain.links:
        pins = [(j.id, j.at) for j in chain.joints
                if j.kind == "R" and link in j.links and j.at is not None]
        pairs = [(a, b) for i, a in enumerate(pins) for b in pins[i + 1:]
                 if math.dist(a[1], b[1]) > 0]
        if link in turn or not pairs:
            continue
        (ja, a), (jb, b) = max(pairs, key=lambda e: math.dist(e[0][1], e[1][1]))
        p, q = result.points[ja], result.points[jb]
        turn[link] = (math.atan2(q[1] - p[1], q[0] - p[0])
                      - math.atan2(b[1] - a[1], b[0] - a[0]))
    for _ in chain.links:
        for j in chain.joints:
            if j.kind == "P":
                known = [x for x in j.links if x in turn]
                for x in j.links:
                    if x not in turn and known:
                        turn[x] = turn[known[0]]
    return {link: turn.get(link, 0.0) for link in chain.links}


@dataclass(frozen=True)
class _Body:
    """A link's free body at the pose: its pins, the points its outline joins, its
    blocks (centre, direction), the slots it carries (centre, direction, style, a
    barrel's shut end) and its centre of mass."""

    pins: list[_Point]
    members: list[_Point]
    blocks: list[tuple[_Point, float]]
    slots: list[tuple[_Point, float, str, str | None]]   # centre, direction, style, cap
    centres: list[_Point]                                # its centre of mass, if known


def _bodies(result: PoseForces, links: list[str]) -> dict[str, _Body]:
    """Each link's body; a sliding pair's block and guide on the links the mechanism's
    drawing puts them on (:class:`~chaingraph.drawing.scene.Scene`: a slot in a lever,
    the barrel of an oscillating cylinder, the block on the other link)."""
    chain = result.chain
    turn = link_turns(result)
    pairs = Scene.of_chain(chain).pairs
    out = {}
    for link in links:
        pins = [result.points[j.id] for j in chain.joints if j.kind == "R" and link in j.links]
        members = list(pins)
        blocks: list[tuple[_Point, float]] = []
        slots: list[tuple[_Point, float, str, str | None]] = []
        for j in chain.joints:
            if j.kind != "P" or link not in j.links:
                continue
            q = result.points[j.id]
            angle = math.radians(j.axis or 0.0) + turn[j.links[0]]
            pair = pairs[j.id]
            if pair.block_link == link:
                blocks.append((q, angle))
            else:
                slots.append((q, angle, pair.style, pair.cap))
            members.append(q)
        # the body reaches its centre of mass (a crank's counterweight, a bent lever)
        centres = [a.at for a in result.applied if a.link == link
                   and a.what in ("weight", "inertia force")][:1]
        out[link] = _Body(pins, members + centres, blocks, slots, centres)
    return out


def free_body_shapes(result: PoseForces) -> tuple[list[Shape], View]:
    """The free bodies of a :class:`~chaingraph.dynamics.PoseForces` as shapes: each
    moving link in a panel of its own (two to a row, a row as high as its tallest),
    drawn with its real shape (a bar,
    a plate for a link of three or more joints, a block for a slider, the slots it
    carries) and its forces as arrows, lengths and forces each to one scale over every
    panel, each arrow labelled where it collides with no other label, and a force scale
    under the panels. Returns (shapes, view)."""
    links = [x for x in result.chain.links if x != result.fixed]
    bodies = _bodies(result, links)
    extent = 0.0
    for b in bodies.values():
        xs, ys = [p[0] for p in b.members], [p[1] for p in b.members]
        extent = max(extent, max(xs) - min(xs), max(ys) - min(ys))
    allpts = [p for b in bodies.values() for p in b.members]
    span = max(max(p[0] for p in allpts) - min(p[0] for p in allpts),
               max(p[1] for p in allpts) - min(p[1] for p in allpts), 1e-9)
    extent = max(extent, 0.25 * span)
    forces = {link: forces_on(result, link) for link in links}
    biggest = max([math.hypot(*f) for fs in forces.values() for _, _, _, f in fs] + [1e-300])
    arrow = 0.9 * extent                       # the largest force's length
    scale = arrow / biggest
    # each panel holds its body and its arrows, centred; the panels of a row as high as
    # its highest content, every column as wide as the widest
    arrows = {link: _arrows(bodies[link], forces[link], scale, 0.04 * extent)
              for link in links}
    boxes = {link: _content(bodies[link], arrows[link]) for link in links}
    wide = max(b[2] - b[0] for b in boxes.values())
    cols = min(PANEL_COLUMNS, len(links))
    rows = [links[k:k + cols] for k in range(0, len(links), cols)]
    highs = [max(boxes[x][3] - boxes[x][1] for x in row) for row in rows]
    margin = 0.18 * max(wide, min(highs), 0.3 * extent)
    width = wide + 2 * margin
    size = 0.011 * width                       # a pin's radius, the text's scale
    labels = _Labels(size)
    shapes: list[Shape] = []
    top = 0.0
    for row, high in zip(rows, highs):
        cell = (width, high + 2.3 * margin)
        top -= cell[1]
        for k, link in enumerate(row):
            shapes += _panel(result, link, bodies[link],
                             list(zip(forces[link], arrows[link])),
                             ((k * width, top), cell, boxes[link]), size, scale, labels,
                             colour=COLOURS[result.chain.links.index(link) % len(COLOURS)])
    strip = 12 * size
    shapes += _force_scale(biggest, scale, (3 * size, top - 0.6 * strip), size, labels)
    view = View((0.0, top - strip), (cols * width, 0.0), size)
    return shapes, view


def _content(body, arrows):
    """The box (x0, y0, x1, y1) of a link's body and its ``arrows`` (drawn pose)."""
    pts = list(body.members) + [p for tail, head in arrows for p in (tail, head)]
    return (min(p[0] for p in pts), min(p[1] for p in pts), max(p[0] for p in pts),
            max(p[1] for p in pts))


def _arrows(body, forces, scale, near):
    """(tail, head) of each of a link's ``forces`` in the drawn pose, in their order:
    placed the way :func:`arrow_ends` gives first, unless its shaft runs along the body or along
    an arrow placed before it (the larger forces first) more than the other way round
    does (the arrow then starts at its point where it would end there, or the other
    way): within ``near`` of them."""
    middle = _middle(body)
    pts = list(body.members)
    hull = convex_hull(pts) if len(pts) >= 3 else []
    if len(hull) >= 3:
        lines = list(zip(hull, hull[1:] + hull[:1]))
    else:
        lines = [max(((p, q) for p in pts for q in pts), key=lambda e: math.dist(*e))]
    out: dict[int, tuple[_Point, _Point]] = {}
    order = sorted(range(len(forces)), key=lambda i: -math.hypot(*forces[i][3]))
    for i in order:
        _, key, q, f = forces[i]
        best = min(arrow_ends(q, f, scale, middle, key),
                   key=lambda e: _crowding(e, q, lines, near))
        out[i] = best
        lines.append(best)
    return [out[i] for i in range(len(forces))]


def _crowding(ends, q, lines, near):
    """How much of the arrow ``ends`` (away from its point q) runs within ``near`` of
    the ``lines``: samples along its shaft."""
    far = ends[1] if ends[0] == q else ends[0]
    count = 0
    for t in (0.2, 0.4, 0.6, 0.8, 1.0):
        p = (q[0] + t * (far[0] - q[0]), q[1] + t * (far[1] - q[1]))
        count += any(segment_distance(p, a, b) < near for a, b in lines)
    return count


def _middle(body):
    """The middle of the box round a body's points."""
    xs, ys = [p[0] for p in body.members], [p[1] for p in body.members]
    return (0.5 * (max(xs) + min(xs)), 0.5 * (max(ys) + min(ys)))


def arrow_ends(q: _Point, f: _Point, scale: float, middle: _Point, key: str
               ) -> tuple[tuple[_Point, _Point], tuple[_Point, _Point]]:
    """The two ways to draw the arrow of the force ``f`` acting at ``q`` on a body whose
    middle is ``middle``, each (tail, head), the one a textbook draws first (off the
    body): a push ends at its point, coming from outside; a pull starts at its point,
    going out (so that a two-force member's arrows lie beyond its pins, not along it);
    a weight or an inertia force starts at the centre of mass."""
    head_at = ((q[0] - f[0] * scale, q[1] - f[1] * scale), q)
    tail_at = (q, (q[0] + f[0] * scale, q[1] + f[1] * scale))
    if key in ("weight", "inertia force"):
        return tail_at, head_at
    # the end away from the point: whichever lies farther from the body's middle
    if math.dist(tail_at[1], middle) > math.dist(head_at[0], middle) + 1e-9 * scale * \
            math.hypot(*f):
        return tail_at, head_at
    return head_at, tail_at


def _panel(result, link, body, forces, place, size, scale, labels, *, colour):
    """One link's panel: its frame, name, body, pins, forces and couples; ``place``
    the panel's lower left corner, size (width, height) and its content's box."""
    lo, (cw, ch), content = place
    box = (lo[0], lo[1], lo[0] + cw, lo[1] + ch)
    title_room = 6.0 * size
    cx, cy = 0.5 * (content[0] + content[2]), 0.5 * (content[1] + content[3])
    ox, oy = lo[0] + 0.5 * cw - cx, lo[1] + 0.5 * (ch - title_room) - cy
    bx, by = _middle(body)

    def at(p: _Point) -> _Point:
        return (p[0] + ox, p[1] + oy)
    tag = (("link", link),)
    shapes = [Shape("polygon", "panel", ((box[0], box[1]), (box[2], box[1]), (box[2], box[3]),
                                         (box[0], box[3])), tag, stroke="#cccccc",
                    width=0.3 * size)]
    title = (box[0] + 1.5 * size, box[3] - 1.5 * size - 3.0 * size * LABEL_HEIGHT)
    shapes.append(Shape("text", "label", (title,), tag, text=link, size=3.0 * size))
    labels.take(label_box(*title, link, 3.0 * size))
    drawn = _body_shapes(body, at, size, colour, tag)
    shapes += drawn
    for s in drawn:
        if s.kind == "circle":
            labels.avoid_circle(s.points[0], s.radius or 0.0)
        else:
            pts = list(s.points) + ([s.points[0]] if s.kind == "polygon" else [])
            for p, q in zip(pts, pts[1:]):
                labels.avoid_segment(p, q, 0.5 * (s.width or 0.0))
    arrows, small = [], []
    for (what, key, q, f), ends in forces:
        if math.hypot(*f) * scale < 1e-9 * cw:         # nothing (rounding)
            continue
        if math.hypot(*f) * scale < 0.5 * size:
            small.append(f"{what} {_newtons(f)}")
            continue
        tail, head = (at(p) for p in ends)
        arrows.append((tail, head, what, key, f))
        labels.avoid_segment(tail, head, 0.6 * size)
    if small:                                  # too short to draw to the scale (its
        # place taken first: the labels placed after it keep clear of it)
        text = "too small to draw: " + ", ".join(small)
        anchor = (box[0] + 1.5 * size, box[1] + 1.5 * size + LABEL_DEPTH * labels.font)
        labels.take(label_box(*anchor, text, labels.font))
        shapes.append(Shape("text", "small-forces", (anchor,), tag, text=text,
                            size=labels.font))
    for tail, head, what, key, f in arrows:
        # a head 1.6 pin radii wide, narrower on an arrow too short for it
        shapes += _arrow(tail, head, ARROWS[key], size, what, f,
                         dash=(2 * size, size) if key == "inertia force" else (),
                         head=min(1.6 * size, 0.2 * math.dist(tail, head)),
                         label=None, data=tag)
    for tail, head, what, key, f in sorted(arrows, key=lambda a: -math.hypot(*a[4])):
        text = f"{what} {_newtons(f)}"
        shapes.append(labels.along(text, tail, head, box, tag))
    centre = at((bx, by))
    for c in result.couples:
        if c.link == link and c.value is not None and abs(c.value) > 1e-12:
            turn = "\u21ba" if c.value > 0 else "\u21bb"
            text = f"{c.what} {abs(c.value):.3g} N m {turn}"
            shapes.append(labels.near(text, centre, box, tag, cls="couple"))
    return shapes


def _body_shapes(body, at, size, colour, tag):
    """A link's outline (a plate, a bar), its slots, blocks and pins."""
    shapes = []
    pts = [at(p) for p in body.members]
    distinct = {(round(p[0], 9), round(p[1], 9)) for p in pts}
    hull = convex_hull(pts) if len(distinct) >= 3 else []
    if len(hull) >= 3 and polygon_area(hull) > 1e-4 * max(
            math.dist(p, q) for p in hull for q in hull) ** 2:
        shapes.append(Shape("polygon", "plate", tuple(hull), tag, fill=colour,
                            fill_opacity=0.25, stroke=colour, width=size, join="round"))
    elif len(distinct) >= 2:
        ends = max(((p, q) for p in pts for q in pts), key=lambda e: math.dist(*e))
        shapes.append(Shape("polyline", "bar", ends, tag, stroke=colour, width=1.8 * size,
                            cap="round"))
    w = 3.2 * size
    for q, angle, style, cap in body.slots:
        u, n = (math.cos(angle), math.sin(angle)), (-math.sin(angle), math.cos(angle))
        c = at(q)

        def on(t, d):
            return (c[0] + t * w * u[0] + d * w * n[0], c[1] + t * w * u[1] + d * w * n[1])
        if style == "cylinder":                # a barrel, shut at one end
            shut, open_ = (-2.6, 2.6) if cap == "lo" else (2.6, -2.6)
            shapes.append(Shape("polyline", "barrel", (on(open_, -1.0), on(shut, -1.0),
                                                       on(shut, 1.0), on(open_, 1.0)), tag,
                                stroke="#333333", width=0.5 * size, join="round"))
        else:                                  # a slot: its two sides
            for side in (-0.75, 0.75):
                shapes.append(Shape("line", "slot", (on(-2.2, side), on(2.2, side)), tag,
                                    stroke="#444444", width=0.5 * size))
    for q, angle in body.blocks:
        u, n = (math.cos(angle), math.sin(angle)), (-math.sin(angle), math.cos(angle))
        c = at(q)
        corners = tuple((c[0] + du * 1.3 * w * u[0] + dn * 0.8 * w * n[0],
                         c[1] + du * 1.3 * w * u[1] + dn * 0.8 * w * n[1])
                        for du, dn in ((-1, -1), (1, -1), (1, 1), (-1, 1)))
        shapes.append(Shape("polygon", "block", corners, tag, fill=colour, fill_opacity=0.35,
                            stroke="#222222", width=0.4 * size))
    for p in body.pins:
        shapes.append(Shape("circle", "pin", (at(p),), tag, radius=size, fill="white",
                            stroke="#222222", width=0.4 * size))
    for p in body.centres:
        shapes.append(Shape("circle", "centre", (at(p),), tag, radius=0.55 * size,
                            fill="#222222"))
    return shapes


def _nice(v: float) -> float:
    """The largest of 1, 2, 5 times a power of ten not above ``v``."""
    e = 10.0 ** math.floor(math.log10(v))
    return max(m * e for m in (1.0, 2.0, 5.0) if m * e <= v * (1 + 1e-12))


def _force_scale(biggest, scale, where, size, labels):
    """A bar of a round force to the arrows' scale, with its value."""
    f = _nice(biggest)
    x, y = where
    length = f * scale
    out = [Shape("line", "scale", ((x, y), (x + length, y)), stroke="#222222", width=0.5 * size)]
    for e in (x, x + length):
        out.append(Shape("line", "scale", ((e, y - size), (e, y + size)), stroke="#222222",
                         width=0.5 * size))
    text = f"force scale: {_newtons((f, 0.0))}"
    anchor = (x + length + 2 * size, y - 0.8 * size)
    labels.take(label_box(*anchor, text, 2.2 * size))
    out.append(Shape("text", "scale-label", (anchor,), text=text, size=2.2 * size))
    return out


class _Labels:
    """The labels placed so far (their boxes: none may overlap another) and what a
    label had better not cover (arrows, pins)."""

    def __init__(self, size: float) -> None:
        self.size = size
        self.font = 2.2 * size
        self.boxes: list[tuple[float, float, float, float]] = []
        self.segments: list[tuple[_Point, _Point, float]] = []
        self.circles: list[tuple[_Point, float]] = []

    def take(self, box):
        self.boxes.append(box)

    def avoid_segment(self, p, q, half):
        self.segments.append((p, q, half))

    def avoid_circle(self, c, r):
        self.circles.append((c, r))

    def free(self, box, panel) -> bool:
        gap = 0.2 * self.size
        if box[0] < panel[0] + gap or box[1] < panel[1] + gap or box[2] > panel[2] - gap \
                or box[3] > panel[3] - gap:
            return False
        return not any(box[0] < b[2] + gap and b[0] < box[2] + gap and box[1] < b[3] + gap
                       and b[1] < box[3] + gap for b in self.boxes)

    def clutter(self, box) -> int:
        """How many arrows and pins the box meets."""
        hits = 0
        if self.segments:
            segs = np.array([(*p, *q, half) for p, q, half in self.segments], dtype=float)
            hits += int(segments_meet_boxes(segs, np.array([box], dtype=float)).sum())
        for c, r in self.circles:
            hits += (box[0] - r < c[0] < box[2] + r) and (box[1] - r < c[1] < box[3] + r)
        return hits

    def _place(self, text, tried, panel, data, cls):
        """The first free box of the ``tried`` (cost, centre) places, by cost; else
        the free place of a grid over the panel nearest the first tried."""
        x0, y0, x1, y1 = label_box(0.0, 0.0, text, self.font)
        hw, hh = 0.5 * (x1 - x0), 0.5 * (y1 - y0)
        best = None
        for cost, (cx, cy) in sorted(tried, key=lambda t: t[0]):
            box = (cx - hw, cy - hh, cx + hw, cy + hh)
            if best is not None and cost >= best[0]:
                break
            if self.free(box, panel):
                total = cost + 3.0 * self.clutter(box)
                if best is None or total < best[0]:
                    best = (total, box)
        if best is None:
            want = tried[0][1]
            step = 0.5 * (y1 - y0)
            grid = [(panel[0] + hw + i * step, panel[1] + hh + k * step)
                    for i in range(int((panel[2] - panel[0]) / step) + 1)
                    for k in range(int((panel[3] - panel[1]) / step) + 1)]
            grid.sort(key=lambda c: math.dist(c, want))
            for cx, cy in grid:
                box = (cx - hw, cy - hh, cx + hw, cy + hh)
                if self.free(box, panel):
                    best = (0.0, box)
                    break
        if best is None:                        # nowhere free: under the others
            box = (panel[0], panel[1] - 2 * hh * (len(self.boxes) + 1), panel[0] + 2 * hw,
                   panel[1] - 2 * hh * len(self.boxes))
            best = (0.0, box)
        box = best[1]
        self.take(box)
        anchor = (box[0], box[1] + LABEL_DEPTH * self.font)
        return Shape("text", cls, (anchor,), data, text=text, size=self.font,
                     halo=0.5 * self.size)

    def along(self, text, p, q, panel, data) -> Shape:
        """A label for the arrow p -> q: beside it, near its middle, moved along it and
        away from it where it would collide."""
        x0, y0, x1, y1 = label_box(0.0, 0.0, text, self.font)
        hw, hh = 0.5 * (x1 - x0), 0.5 * (y1 - y0)
        length = math.dist(p, q) or 1.0
        u = ((q[0] - p[0]) / length, (q[1] - p[1]) / length)
        n = (-u[1], u[0])
        reach = abs(n[0]) * hw + abs(n[1]) * hh
        tried = []
        for k, t in enumerate((0.5, 0.35, 0.65, 0.2, 0.8, 0.05)):
            for ring, d in enumerate((0.9, 2.5, 5.0, 8.0)):
                for side in (1, -1):
                    m = (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]))
                    off = (d * self.size + reach) * side
                    tried.append((0.4 * k + 1.0 * ring + 0.1 * (side < 0),
                                  (m[0] + off * n[0], m[1] + off * n[1])))
        # beyond the tail, on the arrow's line
        ahead = abs(u[0]) * hw + abs(u[1]) * hh + self.size
        tried.append((2.5, (p[0] - ahead * u[0], p[1] - ahead * u[1])))
        return self._place(text, tried, panel, (("force", text), *data), "force-label")

    def near(self, text, c, panel, data, *, cls) -> Shape:
        """A label near the point c (a couple's, by the link's middle): its box's near
        side (not its middle) at each distance tried, so that a long label beside a
        link is clear of it."""
        x0, y0, x1, y1 = label_box(0.0, 0.0, text, self.font)
        hw, hh = 0.5 * (x1 - x0), 0.5 * (y1 - y0)
        tried = []
        for ring, d in enumerate((1.5, 3.0, 6.0, 10.0, 15.0)):
            for k in range(8):
                a = math.pi / 2 + k * math.pi / 4
                u = (math.cos(a), math.sin(a))
                reach = d * self.size + abs(u[0]) * hw + abs(u[1]) * hh
                tried.append((ring + 0.1 * k, (c[0] + reach * u[0], c[1] + reach * u[1])))
        return self._place(text, tried, panel, data, cls)


def force_polygon_shapes(result: PoseForces) -> tuple[list[Shape], View] | None:
    """The force polygon of each dyad of the solver's plan, as the graphical method
    draws it: the forces on the dyad's first link head to tail, then those on its
    second, closing where they began (the dyad is in equilibrium); the reaction at the
    joint between the two links, dashed, closes the first link's polygon. Panels side
    by side, each to its own scale. Returns (shapes, view), or None without dyads."""
    chain = result.chain
    panels: list[tuple[str, str, str, list[Force], list[Force]]] = []
    for a, b in result.dyads:
        middle = [j.id for j in chain.joints if a in j.links and b in j.links]
        on_a = [x for x in forces_on(result, a) if x[0] not in middle]
        on_b = [x for x in forces_on(result, b) if x[0] not in middle]
        if middle and on_a and on_b:
            panels.append((a, b, middle[0], on_a, on_b))
    if not panels:
        return None
    shapes: list[Shape] = []
    cell = 1.0
    size = 0.012 * cell
    for i, (a, b, mid, on_a, on_b) in enumerate(panels):
        tips = [(0.0, 0.0)]
        for _, _, _, f in on_a + on_b:
            tips.append((tips[-1][0] + f[0], tips[-1][1] + f[1]))
        xs, ys = [p[0] for p in tips], [p[1] for p in tips]
        span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-300)
        scale = 0.7 * cell / span
        ox = i * cell + 0.5 * cell - 0.5 * (max(xs) + min(xs)) * scale
        oy = -0.5 * cell - 0.5 * (max(ys) + min(ys)) * scale

        def at(p: _Point) -> _Point:
            return (ox + p[0] * scale, oy + p[1] * scale)
        shapes.append(Shape("text", "label", ((i * cell + 0.03 * cell, -0.05 * cell),),
                            text=f"dyad {a}, {b}", size=3.2 * size))
        for k, (what, key, _, f) in enumerate(on_a + on_b):
            p, q = at(tips[k]), at(tips[k + 1])
            shapes += _arrow(p, q, ARROWS[key], size, what, f,
                             head=min(1.6 * size, 0.2 * math.dist(p, q)),
                             dash=(2 * size, size) if key == "inertia force" else ())
        # the middle joint's reaction on the first link closes its polygon
        p, q = at(tips[len(on_a)]), at(tips[0])
        f = (tips[0][0] - tips[len(on_a)][0], tips[0][1] - tips[len(on_a)][1])
        shapes += _arrow(p, q, "#b2182b", size, f"{mid} on {a}", f, dash=(size, size),
                         head=min(1.6 * size, 0.2 * math.dist(p, q)))
    view = View((0.0, -cell), (len(panels) * cell, 0.0), 0.02 * cell)
    return shapes, view


def _arrow(p: _Point, q: _Point, colour: str, size: float, what: str, f: _Point, *,
           dash: tuple[float, ...] = (), head: float | None = None,
           label: str | None = "mid", data: tuple[tuple[str, str], ...] = ()
           ) -> list[Shape]:
    """An arrow from p to q for the force ``f``: a shaft, and a head ``head`` wide (1.6
    pin radii ``size`` unless given), labelled with ``what`` and its size at the arrow's
    middle (``label`` "mid"), by its tail ("tail"), or not (None: placed by the
    caller)."""
    length = math.dist(p, q)
    if length < 1e-12:
        return []
    ux, uy = (q[0] - p[0]) / length, (q[1] - p[1]) / length
    w = 1.6 * size if head is None else head
    tip = [q, (q[0] - 2.5 * w * ux - w * uy, q[1] - 2.5 * w * uy + w * ux),
           (q[0] - 2.5 * w * ux + w * uy, q[1] - 2.5 * w * uy - w * ux)]
    at = ((p[0] + 0.6 * size, p[1] + 0.6 * size) if label == "tail" else
          (0.5 * (p[0] + q[0]) + 0.8 * size, 0.5 * (p[1] + q[1]) + 0.8 * size))
    out = [Shape("line", "force", (p, (q[0] - 2 * w * ux, q[1] - 2 * w * uy)),
                 (("force", what), *data), stroke=colour, width=0.6 * size, dash=dash),
           Shape("polygon", "arrowhead", tuple(tip), data, fill=colour, stroke=colour,
                 width=0.1 * size)]
    if label is not None:
        out.append(Shape("text", "force-label", (at,), text=f"{what} {_newtons(f)}",
                         size=2.2 * size, halo=0.6 * size))
    return out


def force_polygon_svg(result: PoseForces, *, width: int | None = None) -> str | None:
    """The dyads' force polygons (:func:`force_polygon_shapes`) as SVG (``width``:
    420 pixels a dyad by default); None when the mechanism has no dyad with forces on
    both links."""
    made = force_polygon_shapes(result)
    if made is None:
        return None
    shapes, view = made
    width = width or int(420 * view.hi[0])
    return svg_document(view, svg_elements(view, shapes), width=width,
                        title=f"{result.name}: force polygons of the dyads")


def free_body_svg(result: PoseForces, *, width: int = 1000) -> str:
    """The free-body diagrams of a :class:`~chaingraph.dynamics.PoseForces` as SVG.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> f = chaingraph.forces(chaingraph.load(catalog_path("reciprocating-engine")), at=60.0)
    >>> svg = free_body_svg(f)
    >>> svg.count('class="force"') >= 7, 'data-force="load"' in svg
    (True, True)
    """
    shapes, view = free_body_shapes(result)
    kind = "static" if result.static else "kinetostatic"
    at = ", ".join(f"{j} = {v:.6g}" for j, v in zip(result.inputs, result.at))
    return svg_document(view, svg_elements(view, shapes), width=width,
                        title=f"{result.name}: free bodies ({kind}) at {at}")


def cycle_of(result: SweepForces) -> tuple[np.ndarray, np.ndarray, float | None]:
    """The sweep's input values and indices ordered over its cycle: for a sweep of whole
    turns (360 or 720 degrees of an R input), (theta from 0 to the cycle, the steps in
    that order, the cycle); else the sweep as it is and None."""
    x = np.asarray(result["theta"], dtype=float)
    kind = result.motion.plan.inputs[0].kind
    span = abs(float(x[-1] - x[0]))
    turns = round(span / 360.0)
    if kind != "R" or turns < 1 or abs(span - 360.0 * turns) > 1e-6:
        return x, np.arange(x.size), None
    cycle = 360.0 * turns
    k = np.arange(x.size - 1)                   # the last step is the first, a cycle on
    wrapped = np.mod(x[:-1], cycle)
    order = k[np.argsort(wrapped, kind="stable")]
    xs = np.mod(x[order], cycle)
    return np.append(xs, xs[0] + cycle), np.append(order, order[0]), cycle


def closed_cycle(x: np.ndarray, values: np.ndarray, cycle: float | None
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The values over the cycle from exactly 0 to exactly ``cycle`` (degrees), the
    ends interpolated linearly between the sweep's last step before the cycle's end and
    its first after 0 (``x``, ``values`` as :func:`cycle_of` orders them); unchanged
    without a cycle."""
    if cycle is None or x.size < 3:
        return x, values
    before, after = x[-2] - cycle, x[0]
    f = 0.0 if after == before else (0.0 - before) / (after - before)
    start = values[-2] + f * (values[0] - values[-2])
    return (np.concatenate([[0.0], x[:-1], [cycle]]),
            np.concatenate([[start], values[:-1], [start]]))


def energy_lobes(x: np.ndarray, t: np.ndarray, mean: float) -> list[tuple[float, float, float]]:
    """The loops of the turning moment ``t`` about its ``mean`` against ``x`` (degrees):
    (start, end, energy J) of each stretch between two crossings of the mean, the
    energy the area between the curve and the mean (trapezoids; the crossings found
    by linear interpolation)."""
    d = t - mean
    edges = [float(x[0])]
    for i in range(d.size - 1):
        if d[i] == 0.0 or d[i] * d[i + 1] < 0:
            f = 0.0 if d[i] == 0.0 else d[i] / (d[i] - d[i + 1])
            edges.append(float(x[i] + f * (x[i + 1] - x[i])))
    edges.append(float(x[-1]))
    lobes = []
    for a, b in zip(edges, edges[1:]):
        if b - a <= 1e-9:
            continue
        inside = (x > a) & (x < b)
        xs = np.concatenate([[a], x[inside], [b]])
        ds = np.interp(xs, x, d)
        lobes.append((a, b, float(np.sum(0.5 * (ds[1:] + ds[:-1]) * np.diff(np.radians(xs))))))
    return lobes


@overload
def plot_turning_moment(result: SweepForces, path: None = None) -> Figure: ...


@overload
def plot_turning_moment(result: SweepForces, path: str | os.PathLike[str]) -> None: ...


def plot_turning_moment(result: SweepForces, path: str | os.PathLike[str] | None = None,
                        ) -> Figure | None:
    """The turning-moment diagram of a :class:`~chaingraph.dynamics.SweepForces` (one
    input), as the textbook draws it: over the cycle (0 to 360 degrees, or 720 for a
    sweep of two turns), the turning moment the machine delivers to its input shaft
    (minus the effort, and minus the steady load torque that balances it, if any) when
    that is positive on the mean (an engine), else the effort that drives it; the mean line; each loop between the curve and the mean shaded and
    marked with its energy (J), and the crank angles of the greatest and least energy
    with the fluctuation between them. Written to ``path`` (SVG, PNG...) or returned as
    a matplotlib figure."""
    plt = pyplot_module()
    joint = result.inputs[0]
    kind = result.motion.plan.inputs[0].kind
    unit = "N m" if kind == "R" else "N"
    x, order, cycle = cycle_of(result)
    x, e = closed_cycle(x, np.asarray(result[f"effort:{joint}"], dtype=float)[order], cycle)
    stats = result.summary.efforts[joint]
    # a steady load torque (torque = "mean") takes the engine's mean turning moment:
    # the engine alone delivers minus (the effort and that torque), about its mean
    steady = result.load_torque or 0.0
    mean_alone = None if stats.mean is None else stats.mean + steady
    engine = mean_alone is not None and mean_alone < 0
    t = -(e + steady) if engine else e
    what = (f"turning moment delivered at {joint}" if engine
            else f"effort at {joint} (to drive it)")
    fig, ax = plt.subplots(figsize=(8.5, 4.2))
    ax.plot(x, t, color="#b2182b", linewidth=1.4, label=what)
    mean = None if mean_alone is None else (-mean_alone if engine else stats.mean)
    swing = result.summary.energy_fluctuation
    if mean is not None and np.isfinite(t).all():
        ax.axhline(mean, color="#444444", linewidth=0.9, linestyle="--",
                   label=f"mean {mean:.4g} {unit}")
        ax.fill_between(x, t, mean, where=t >= mean, color="#b2182b", alpha=0.15,
                        linewidth=0, interpolate=True)
        ax.fill_between(x, t, mean, where=t < mean, color="#2166ac", alpha=0.15,
                        linewidth=0, interpolate=True)
        _mark_lobes(ax, x, t, mean, kind)
    title = f"{result.name}: turning-moment diagram"
    if swing is not None:
        title += f" (fluctuation of energy {swing:.4g} J)"
    ax.set_title(title, fontsize=10)
    if cycle is not None:
        ax.set_xlim(0.0, cycle)
        ax.set_xticks(np.arange(0.0, cycle + 1.0, 90.0 if cycle <= 360 else 180.0))
    ax.set_xlabel("crank angle, degrees" if kind == "R" else f"{joint} slide")
    ax.set_ylabel(f"{'turning moment' if engine else 'effort'}, {unit}")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize=8, loc="best")
    return finish(plt, fig, path)


def _mark_lobes(ax, x, t, mean, kind):
    """Each loop's energy (J) at its middle, and the angles of greatest and least
    energy (the work of the turning moment about its mean, from the start)."""
    lobes = energy_lobes(x, t, mean)
    top, bottom = float(np.nanmax(t)), float(np.nanmin(t))
    height = max(top - bottom, 1e-300)
    big = [lb for lb in lobes if abs(lb[2]) > 0.02 * max(abs(v[2]) for v in lobes)]
    for a, b, energy in big:
        mid = 0.5 * (a + b)
        ax.annotate(f"{energy:+.3g} J", (mid, mean + (0.06 if energy > 0 else -0.1) * height),
                    ha="center", fontsize=7, color="#222222")
    if kind != "R" or len(lobes) < 2:
        return
    work = np.cumsum([0.0] + [lb[2] for lb in lobes])
    where = [lobes[0][0]] + [lb[1] for lb in lobes]
    hi, lo = int(np.argmax(work)), int(np.argmin(work))
    for k, label in ((hi, "greatest energy"), (lo, "least energy")):
        ax.axvline(where[k], color="#555555", linewidth=0.7, linestyle=":")
        ax.annotate(label, (where[k], bottom + 0.02 * height), rotation=90, fontsize=7,
                    ha="left", va="bottom", color="#555555", xytext=(2, 0),
                    textcoords="offset points")


@overload
def plot_shaking(result: SweepForces, path: None = None, *,
                 balanced: SweepForces | None = None) -> Figure: ...


@overload
def plot_shaking(result: SweepForces, path: str | os.PathLike[str], *,
                 balanced: SweepForces | None = None) -> None: ...


def plot_shaking(result: SweepForces, path: str | os.PathLike[str] | None = None, *,
                 balanced: SweepForces | None = None) -> Figure | None:
    """The polar diagram of the shaking force of a :class:`~chaingraph.dynamics.SweepForces`:
    the path of the tip of the force the moving links put on the frame, drawn from the
    origin, with the input's value marked along it and its largest value; with
    ``balanced`` (the same sweep of the balanced mechanism,
    :attr:`chaingraph.dynamics.balance.Balance.result`) its path too. Written to
    ``path`` (SVG, PNG...) or returned as a matplotlib figure."""
    if result.shaking is None:
        raise ValueError("the sweep has no shaking force")
    plt = pyplot_module()
    x, order, cycle = cycle_of(result)
    _, fx = closed_cycle(x, result.shaking.fx[order], cycle)
    x, fy = closed_cycle(x, result.shaking.fy[order], cycle)
    ok = np.isfinite(fx) & np.isfinite(fy)
    fig, ax = plt.subplots(figsize=(6.2, 6.2))
    ax.plot(fx[ok], fy[ok], color="#b2182b", linewidth=1.4, label="tip of the shaking force")
    if balanced is not None and balanced.shaking is not None:
        _, border, _ = cycle_of(balanced)
        # (a ring on each step: a balanced force that stands still is still seen)
        ax.plot(balanced.shaking.fx[border], balanced.shaking.fy[border], color="#1b7837",
                linewidth=1.6, marker="o", markersize=9, markerfacecolor="none", zorder=5,
                label="balanced")
    ax.plot([0.0], [0.0], marker="o", color="#222222", markersize=4)
    ax.axhline(0.0, color="#999999", linewidth=0.6)
    ax.axvline(0.0, color="#999999", linewidth=0.6)
    mags = np.hypot(fx, fy)
    if ok.any():
        k = int(np.nanargmax(np.where(ok, mags, -np.inf)))
        ax.annotate("", (fx[k], fy[k]), (0.0, 0.0),
                    arrowprops={"arrowstyle": "->", "color": "#2166ac", "linewidth": 1.2})
        ax.plot([], [], color="#2166ac", linewidth=1.2,
                label=f"largest, {_newtons((fx[k], fy[k]))} at {x[k]:.4g}\u00b0")
    step = 30.0 if cycle is None or cycle <= 360 else 60.0
    marks = np.arange(0.0, (cycle or 0.0) + 1e-9, step) if cycle else x[::max(1, x.size // 12)]
    # each mark's label outward from the curve's middle; a mark nearer than a
    # twentieth of the curve's size to one labelled already is left out (they collided)
    cx, cy = float(np.mean(fx[ok])), float(np.mean(fy[ok]))
    size = max(float(np.ptp(fx[ok])), float(np.ptp(fy[ok])), 1e-300)
    labelled: list[tuple[float, float]] = []
    for m in marks[:-1] if cycle else marks:
        k = int(np.argmin(np.abs(x - m)))
        if not ok[k] or any(math.hypot(fx[k] - a, fy[k] - b) < size / 20 for a, b in labelled):
            continue
        labelled.append((float(fx[k]), float(fy[k])))
        out = math.atan2(fy[k] - cy, fx[k] - cx)
        ax.plot([fx[k]], [fy[k]], marker=".", color="#222222", markersize=5)
        ax.annotate(f"{x[k]:.0f}\u00b0", (fx[k], fy[k]), fontsize=7,
                    xytext=(9 * math.cos(out), 9 * math.sin(out)), textcoords="offset points",
                    ha="center", va="center", color="#444444")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("shaking force Fx, N")
    ax.set_ylabel("shaking force Fy, N")
    ax.set_title(f"{result.name}: polar diagram of the shaking force", fontsize=10)
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize=8, loc="lower right")
    return finish(plt, fig, path)
