"""Gear trains drawn: the textbook's schematic of a train (SVG) and its graph.

:func:`train_shapes` draws a chain's gear pairs as the front view of the textbook: each
gear's pitch circle about its axis (an annulus as a ring), the radii in the proportion
of the teeth and summing (or, for an annulus, differing) to the distance between the
axes the file places, each carrier that moves as an arm through the axes it holds, the
fixed link's bearings hatched, the pins and the names. :func:`train_graph_shapes` draws
the train's graph (Buchsbaum and Freudenstein's): the links as numbered vertices, the
tree of turning pairs drawn down from its busiest link, thin, with each pair's axis
(level) letter, the gear pairs as thick arcs, each marked with its transfer vertex (the
carrier's number at the arc's middle). Both go through the scene's shapes and SVG emitter, in its colours.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace

import numpy as np

from chaingraph.drawing.scene import (
    COLOURS,
    Shape,
    View,
    label_box,
    segments_meet_boxes,
    svg_document,
    svg_elements,
)
from chaingraph.errors import MechanismError
from chaingraph.geometry import segment_distance
from chaingraph.model.chain import Chain, Joint
from chaingraph.structure.atlas.gears import chain_graph, train_levels

__all__ = ["train_shapes", "train_svg", "train_graph_shapes", "train_graph_svg",
           "gear_circles", "label_boxes", "tree_layout", "schematic_shapes",
           "schematic_svg"]

Point = tuple[float, float]


def _axis(chain: Chain, link: str, carrier: str) -> Point | None:
    """Where ``link`` turns on ``carrier``: the drawn R joint that joins them."""
    return next((j.at for j in chain.joints if j.kind == "R" and link in j.links
                 and carrier in j.links and j.at is not None), None)


def gear_circles(chain: Chain) -> list[tuple[str, str, Point, float, bool]]:
    """Every gear's pitch circle: ``(pair id, link, centre, radius, annulus)``, the
    radii from the teeth and the distance between the drawn axes (a pair whose axes
    are not drawn, or coincide, is left out)."""
    out = []
    for g in chain.gears:
        a, b = (_axis(chain, x, g.carrier) for x in g.links)
        if a is None or b is None:
            continue
        d = math.dist(a, b)
        za, zb = g.teeth
        if d <= 0 or (g.internal and za >= zb):
            continue
        ra, rb = ((d * za / (zb - za), d * zb / (zb - za)) if g.internal
                  else (d * za / (za + zb), d * zb / (za + zb)))
        out += [(g.id, g.links[0], a, ra, False), (g.id, g.links[1], b, rb, g.internal)]
    return out


def _ground(x: float, y: float, s: float) -> list[Shape]:
    """A bearing on the fixed link: a triangle under the pin on a hatched base."""
    base = y - 1.8 * s
    out = [Shape("polyline", "ground", ((x - s, base), (x, y), (x + s, base)),
                 stroke="#444444", width=0.25 * s, join="round"),
           Shape("line", "ground", ((x - 1.5 * s, base), (x + 1.5 * s, base)),
                 stroke="#444444", width=0.3 * s)]
    for k in range(5):
        x0 = x - 1.4 * s + 0.65 * s * k
        out.append(Shape("line", "hatch", ((x0, base), (x0 - 0.5 * s, base - 0.6 * s)),
                         stroke="#444444", width=0.18 * s))
    return out


def _free(box: tuple[float, float, float, float], placed: list[tuple[float, ...]],
          gap: float) -> bool:
    return all(box[2] + gap < p[0] or p[2] + gap < box[0] or box[3] + gap < p[1]
               or p[3] + gap < box[1] for p in placed)


_ANGLES = (90, 60, 120, 30, 150, 0, 180, 300, 240, 270, 45, 135, 210, 330)


def _place(text: str, centre: Point, reach: float, size: float,
           placed: list[tuple[float, ...]], *, below: bool = False,
           avoid: Sequence[tuple[Point, Point]] = ()) -> Shape:
    """A label round ``centre`` at ``reach``, at the first angle (top first, or bottom
    first when ``below``) whose box meets no label placed before, nor (where it can)
    the segments to ``avoid``; farther out when every angle is taken."""
    w = len(text) * 0.62 * size
    lines = np.array([(*p, *q, 0.0) for p, q in avoid], dtype=float).reshape(-1, 5)
    for strict in ((True, False) if avoid else (False,)):
        for ring in (1.0, 1.4, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0)[:4 if strict else 8]:
            for deg in ((270, *_ANGLES[:9], *_ANGLES[10:]) if below else _ANGLES):
                a = math.radians(deg)
                away = reach * ring + 0.3 * size + (ring - 1.0) * size
                cx = centre[0] + away * math.cos(a)
                cy = centre[1] + away * math.sin(a)
                x = cx if math.cos(a) > 0.3 else cx - w if math.cos(a) < -0.3 else cx - 0.5 * w
                y = cy if math.sin(a) > 0.3 else cy - 0.8 * size if math.sin(a) < -0.3 \
                    else cy - 0.3 * size
                box = label_box(x, y, text, size)
                if _free(box, placed, 0.15 * size) and not (
                        strict and segments_meet_boxes(lines, np.array([box])).any()):
                    placed.append(box)
                    return Shape("text", "label", ((x, y),), text=text, size=size,
                                 halo=0.25 * size)
    box = label_box(centre[0], centre[1], text, size)
    placed.append(box)
    return Shape("text", "label", (centre,), text=text, size=size, halo=0.25 * size)


def train_shapes(chain: Chain, *, fixed: str | None = None) -> list[Shape]:
    """The train's schematic (module text) as scene shapes in the file's coordinates;
    ``fixed`` the link drawn as the frame (default: the mechanism's, else none)."""
    if fixed is None and chain.mechanism is not None:
        fixed = chain.mechanism.fixed
    if not any(j.kind == "R" and j.at is not None for j in chain.joints):
        raise MechanismError("the train's axes are not placed (no turning pair has 'at'): "
                             "a drawing needs where each axis is", mechanism=chain.name,
                             parameter="at")
    circles = gear_circles(chain)
    pivots = [j.at for j in chain.joints if j.kind == "R" and j.at is not None]
    xs = [p[0] for p in pivots] + [c[0] - r for _, _, c, r, _ in circles] + \
        [c[0] + r for _, _, c, r, _ in circles]
    ys = [p[1] for p in pivots] + [c[1] - r for _, _, c, r, _ in circles] + \
        [c[1] + r for _, _, c, r, _ in circles]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9) if xs else 1.0
    colour = {x: COLOURS[i % len(COLOURS)] for i, x in enumerate(chain.links)}
    out: list[Shape] = []
    seen = set()
    for _, link, c, r, annulus in sorted(circles, key=lambda t: -t[3]):
        if (link, c, round(r, 9)) in seen:
            continue
        seen.add((link, c, round(r, 9)))
        if annulus:
            out.append(Shape("circle", "annulus", (c,), data=(("link", link),),
                             radius=r + 0.02 * span, stroke=colour[link], width=0.04 * span,
                             fill_opacity=0.0))
        out.append(Shape("circle", "gear", (c,), data=(("link", link),), radius=r,
                         fill=None if annulus else colour[link],
                         fill_opacity=None if annulus else 0.12, stroke=colour[link],
                         width=0.008 * span))
    for link in chain.links:
        if link == fixed:
            continue
        held = [j.at for j in chain.joints if j.kind == "R" and link in j.links
                and j.at is not None]
        if len(held) > 1 and any(g.carrier == link for g in chain.gears):
            out.append(Shape("polyline", "arm", tuple(held), data=(("link", link),),
                             stroke=colour[link], width=0.03 * span, join="round",
                             cap="round"))
    pin = 0.018 * span
    for j in chain.joints:
        if j.kind != "R" or j.at is None:
            continue
        if fixed is not None and fixed in j.links:
            out += _ground(j.at[0], j.at[1], pin * 1.6)
        out.append(Shape("circle", "pin", (j.at,), data=(("joint", j.id),), radius=pin,
                         fill="white", stroke="#222222", width=0.006 * span))
    out += _train_labels(chain, circles, fixed, span)
    return out


def _train_labels(chain: Chain, circles: list[tuple[str, str, Point, float, bool]],
                  fixed: str | None, span: float) -> list[Shape]:
    """Each link's name (and its wheels' teeth) by its largest circle, a carrier's by
    its arm, the fixed link's by its first bearing, no two overlapping."""
    size = 0.045 * span
    placed: list[tuple[float, ...]] = []
    teeth: dict[str, list[int]] = {}
    for g in chain.gears:
        for x, z in zip(g.links, g.teeth):
            if z not in teeth.setdefault(x, []):
                teeth[x].append(z)
    out = []
    biggest: dict[str, tuple[Point, float]] = {}
    for _, link, c, r, annulus in circles:
        reach = r + (0.04 * span if annulus else 0.0)
        if link not in biggest or reach > biggest[link][1]:
            biggest[link] = (c, reach)
    for link in sorted(biggest, key=lambda x: biggest[x][1]):
        c, reach = biggest[link]
        text = f"{link} ({', '.join(map(str, teeth[link]))})"
        out.append(_place(text, c, reach, size, placed))
    for link in chain.links:
        if link in biggest:
            continue
        held: list[Point] = [j.at for j in chain.joints if j.kind == "R"
                             and link in j.links and j.at is not None]
        if not held:
            continue
        if link == fixed:
            out.append(_place(link, held[0], 0.075 * span, size, placed, below=True))
        else:
            mid = (float(np.mean([p[0] for p in held])), float(np.mean([p[1] for p in held])))
            out.append(_place(link, mid, 0.04 * span, size, placed))
    return out


def label_boxes(shapes: Sequence[Shape]) -> list[tuple[float, float, float, float]]:
    """The boxes of the labels among ``shapes`` (for the tests: none may overlap)."""
    return [label_box(s.points[0][0], s.points[0][1], s.text or "", s.size or 0.0)
            for s in shapes if s.kind == "text"]


def _view(shapes: Sequence[Shape], pad: float) -> View:
    xs, ys = [], []
    for s in shapes:
        for x, y in s.points:
            r = (s.radius or 0.0) + (0.5 * (s.width or 0.0) if s.kind == "circle" else 0.0)
            xs += [x - r, x + r]
            ys += [y - r, y + r]
        if s.kind == "text":
            x0, y0, x1, y1 = label_box(s.points[0][0], s.points[0][1], s.text or "",
                                       s.size or 0.0)
            xs += [x0, x1]
            ys += [y0, y1]
    return View((min(xs), min(ys)), (max(xs), max(ys)), pad)


def _moved(shape: Shape, scale: float, dx: float, dy: float) -> Shape:
    """A shape scaled about the origin, then moved by (dx, dy)."""
    def k(v: float | None) -> float | None:
        return None if v is None else v * scale
    return replace(shape, points=tuple((x * scale + dx, y * scale + dy) for x, y in shape.points),
                   width=k(shape.width), radius=k(shape.radius), size=k(shape.size),
                   halo=k(shape.halo), dash=tuple(d * scale for d in shape.dash))


def train_svg(chain: Chain, *, fixed: str | None = None, graph: bool = True,
              width: int = 900) -> str:
    """The train's schematic (:func:`train_shapes`) as a standalone SVG, with its graph
    (:func:`train_graph_shapes`, the links by name) on the right when ``graph``."""
    shapes = train_shapes(chain, fixed=fixed)
    if graph:
        box = _view(shapes, 0.0)
        links, turning, gears = chain_graph(chain)
        drawn = train_graph_shapes(links, turning, gears)
        other = _view(drawn, 0.0)
        scale = 0.8 * box.size[1] / max(other.size[1], 2.0)
        dx = box.hi[0] + 0.12 * box.size[0] - other.lo[0] * scale
        dy = 0.5 * (box.lo[1] + box.hi[1]) - 0.5 * (other.lo[1] + other.hi[1]) * scale
        shapes = shapes + [_moved(s, scale, dx, dy) for s in drawn]
    view = _view(shapes, 0.0)
    view = View(view.lo, view.hi, 0.05 * max(view.size))
    title = f"{chain.name}: gear train" + (f", {fixed} fixed" if fixed else "")
    return svg_document(view, svg_elements(view, shapes), width=width, title=title)


def tree_layout(n: int, turning: Sequence[tuple[int, int]]) -> list[Point]:
    """Places for the vertices of a train's graph: the tree of turning pairs drawn
    down from the link that holds most, each link centred over those that turn on it,
    leaves one unit apart."""
    adjacent: list[list[int]] = [[] for _ in range(n)]
    for a, b in turning:
        adjacent[a].append(b)
        adjacent[b].append(a)
    root = max(range(n), key=lambda v: (len(adjacent[v]), -v))
    at: list[Point] = [(0.0, 0.0)] * n
    seen, column = {root}, [0.0]

    def place(v: int, depth: int) -> float:
        children = [u for u in sorted(adjacent[v]) if u not in seen]
        seen.update(children)
        if not children:
            x = column[0]
            column[0] += 1.0
        else:
            xs = [place(u, depth + 1) for u in children]
            x = 0.5 * (xs[0] + xs[-1])
        at[v] = (x, -1.1 * depth)
        return x
    place(root, 0)
    return at


def _arc(p: Point, q: Point, bend: float, steps: int = 16) -> list[Point]:
    """A quadratic curve from ``p`` to ``q`` bulging ``bend`` times their distance to
    the left of p -> q."""
    mx, my = 0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])
    cx, cy = mx - bend * (q[1] - p[1]), my + bend * (q[0] - p[0])
    return [((1 - t) ** 2 * p[0] + 2 * t * (1 - t) * cx + t * t * q[0],
             (1 - t) ** 2 * p[1] + 2 * t * (1 - t) * cy + t * t * q[1])
            for t in (k / steps for k in range(steps + 1))]


def _near(p: Point, lines: Sequence[Sequence[Point]]) -> float:
    """The distance from ``p`` to the nearest of the polylines ``lines``."""
    return min([segment_distance(p, q, r) for line in lines for q, r in zip(line, line[1:])]
               + [math.inf])


def _on_line(text: str, line: Sequence[Point], size: float, placed: list[tuple[float, ...]],
             others: Sequence[Sequence[Point]], *, shift: Point = (0.0, 0.0)) -> Shape:
    """A label centred on ``line`` (moved by ``shift``), at the first place from its
    middle outward whose box meets no label placed before and whose centre is clear of
    the ``others`` (the other edges: not on a crossing); else the clearest place."""
    w, h = 0.62 * size * len(text), 0.8 * size
    best: tuple[float, Shape, tuple[float, ...]] | None = None
    n = len(line) - 1
    for k in sorted(range(1, n), key=lambda k: abs(k - n / 2)):
        x, y = line[k][0] + shift[0], line[k][1] + shift[1]
        box = label_box(x - w / 2, y - 0.3 * size, text, size)
        clear = _near((x, y), others) if _free(box, placed, 0.05 * size) else -1.0
        shape = Shape("text", "label", ((x - w / 2, y - 0.3 * size),), text=text,
                      size=size, halo=0.3 * size)
        if clear >= 0.9 * h:
            placed.append(box)
            return shape
        if best is None or clear > best[0]:
            best = (clear, shape, box)
    assert best is not None
    placed.append(best[2])
    return best[1]


def _segment(p: Point, q: Point, steps: int = 12) -> list[Point]:
    return [(p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t)
            for t in (k / steps for k in range(steps + 1))]


def _gear_arc(p: Point, q: Point, at: Sequence[Point]) -> list[Point]:
    """The arc of a gear pair from ``p`` to ``q``: the least bend that keeps it off
    every other vertex (else the one that keeps farthest)."""
    flat = abs(p[1] - q[1]) < 1e-9
    best: tuple[float, list[Point]] | None = None
    for bend in ((-0.35, 0.35, -0.55, 0.55, -0.2) if flat else (-0.2, 0.2, -0.4, 0.4, -0.6)):
        curve = _arc(p, q, bend)
        clear = min([math.dist(v, c) for v in at if v not in (p, q) for c in curve]
                    + [math.inf])
        if clear >= 0.3:
            return curve
        if best is None or clear > best[0]:
            best = (clear, curve)
    assert best is not None
    return best[1]


def train_graph_shapes(names: Sequence[str], turning: Sequence[tuple[int, int]],
                       gears: Sequence[tuple[int, int, int]]) -> list[Shape]:
    """The train's graph (module text), the turning pairs' tree drawn down from its
    busiest link (:func:`tree_layout`), the gear pairs as arcs bent off the other
    vertices: ``names`` the links (listed beside the graph by number unless they are
    the numbers), ``turning`` and ``gears`` (``(a, b, carrier)``) by index into them.
    The carriers' numbers and the axes' letters are moved along their edges off the
    crossings and off each other."""
    n = len(names)
    at = tree_layout(n, turning)
    try:
        levels: Sequence[int] | None = train_levels(n, turning, gears)
    except (ValueError, KeyError):
        levels = None
    edges = [_segment(at[a], at[b]) for a, b in turning]
    arcs = []
    for a, b, c in gears:
        p, q = (at[a], at[b]) if at[a][0] <= at[b][0] else (at[b], at[a])
        arcs.append(_gear_arc(p, q, at))
    placed: list[tuple[float, ...]] = [(x - 0.16, y - 0.16, x + 0.16, y + 0.16) for x, y in at]
    out: list[Shape] = [Shape("line", "turning", (at[a], at[b]), stroke="#333333",
                              width=0.025) for a, b in turning]
    out += [Shape("polyline", "gear", tuple(curve), stroke=COLOURS[2], width=0.08,
                  cap="round", join="round") for curve in arcs]
    labels = []
    for (a, b, c), curve in zip(gears, arcs):
        others = edges + [x for x in arcs if x is not curve]
        labels.append(replace(_on_line(str(c + 1), curve, 0.22, placed, others),
                              cls="carrier"))
    if levels is not None:
        for k, line in enumerate(edges):
            others = arcs + [x for x in edges if x is not line]
            labels.append(replace(_on_line("abcdefghij"[levels[k]], line, 0.2, placed,
                                           others, shift=(0.1, 0.0)), cls="level",
                                  halo=0.05))
    for i, (x, y) in enumerate(at):
        out.append(Shape("circle", "vertex", ((x, y),), radius=0.16, fill="white",
                         stroke="#222222", width=0.025))
        out.append(Shape("text", "vertex-label", ((x - 0.062 * len(str(i + 1)), y - 0.075),),
                         text=str(i + 1), size=0.22))
    out += labels
    if any(name != str(i + 1) for i, name in enumerate(names)):      # a key, not labels
        right = max(x for x, _ in at) + 0.6
        top = max(y for _, y in at) + 0.05
        step = max(0.3, (top - min(y for _, y in at) + 0.3) / n)
        for i, name in enumerate(names):
            out.append(Shape("text", "label", ((right, top - step * i - 0.07),),
                             text=f"{i + 1} {name}", size=0.2))
    return out


def train_graph_svg(names: Sequence[str], turning: Sequence[tuple[int, int]],
                    gears: Sequence[tuple[int, int, int]], *, title: str = "gear train graph",
                    width: int = 320, scale: float | None = None) -> str:
    """The train's graph (:func:`train_graph_shapes`) as a standalone SVG, ``width``
    pixels wide or ``scale`` pixels per unit (the distance between two leaves: one
    scale for several graphs)."""
    shapes = train_graph_shapes(names, turning, gears)
    view = _view(shapes, 0.15)
    if scale is not None:
        width = max(1, int(round(view.size[0] * scale)))
    return svg_document(view, svg_elements(view, shapes), width=width, title=title)



def _heights(joints: Sequence[Joint]) -> dict[Point, float]:
    """Each axis's height in the functional schematic, by its place in the front view:
    along the line of the axes (the coordinate in which they spread most; the axes of a
    textbook train lie on one line)."""
    places = [j.at for j in joints if j.at is not None]
    spread = [max(p[k] for p in places) - min(p[k] for p in places) for k in (0, 1)]
    k = 1 if spread[1] >= spread[0] else 0
    return {p: round(float(p[k]), 9) for p in places}


def _bearings(joints: Sequence[Joint], height: dict[Point, float],
              own: dict[tuple[str, float], list[float]], fixed: str | None,
              ) -> list[tuple[tuple[str, float], float]]:
    """Where each link turns on the first link of its joint: the column of its own
    (a gear, an arm) nearest to one of the first link's, or the frame's bearing (column
    0) when that link is the fixed one; both shafts drawn to it. Returns ``((link, axis
    height), column)`` for each pin."""
    pins = []
    for j in joints:
        h = height[j.at]                                       # type: ignore[index]
        hub = own.setdefault((j.links[0], h), [])
        for x in j.links[1:]:
            mine = own.setdefault((x, h), [])
            if not mine and not hub:
                continue
            if j.links[0] == fixed:
                at = 0.0
            elif not hub or not mine:
                at = (mine or hub)[0]
            else:
                at = min(mine, key=lambda c: min(abs(c - d) for d in hub))
            for cols in (hub, mine):
                if at not in cols:
                    cols.append(at)
            pins.append(((x, h), at))
    return pins


def _centre_lines(heights: Sequence[float], lo: float, hi: float, u: float) -> list[Shape]:
    """The axes as thin dash-dotted centre lines."""
    return [Shape("line", "axis", ((lo, h), (hi, h)), stroke="#9a9a9a", width=0.5 * u,
                  dash=(8 * u, 2 * u, 1.5 * u, 2 * u)) for h in heights]


def _gear_bar(x: float, h: float, r: float, annulus: bool, column: float, u: float,
              link: str, colour: str) -> list[Shape]:
    """A gear in the schematic: a bar of its pitch diameter across its axis at column
    ``x``; an annulus a web a little to the left with lips reaching the pitch circle at
    ``x`` (a bracket opening inward)."""
    data = (("link", link),)
    if not annulus:
        return [Shape("line", "gear", ((x, h - r), (x, h + r)), data=data, stroke=colour,
                      width=3.0 * u, cap="butt")]
    web = x - 0.3 * column
    return [Shape("polyline", "annulus", ((x + 0.15 * column, h + r), (web, h + r),
                                          (web, h - r), (x + 0.15 * column, h - r)),
                  data=data, stroke=colour, width=3.0 * u, join="miter")]


def schematic_shapes(chain: Chain, *, fixed: str | None = None,
                     unit: float | None = None) -> list[Shape]:
    """The train's functional schematic as the textbook prints it (docs/gears.md): axes
    as centre lines at their heights, shafts along them (coaxial links a little apart),
    each gear a bar of its pitch diameter in its pair's column (bars in mesh touch), an
    annulus a bracket opening inward, a moving carrier an arm in a column of its own,
    the fixed link's bearings hatched, pins, the names and teeth, no two labels
    overlapping. ``unit``: the line widths' and gaps' length (file units; by default
    the train's size over 150: give one to draw several trains at one scale)."""
    if fixed is None and chain.mechanism is not None:
        fixed = chain.mechanism.fixed
    joints = [j for j in chain.joints if j.kind == "R" and j.at is not None]
    if not joints:
        raise MechanismError("the train's axes are not placed (no turning pair has 'at'): "
                             "a drawing needs where each axis is", mechanism=chain.name,
                             parameter="at")
    height = _heights(joints)
    axes: dict[float, list[str]] = {}
    for j in joints:
        line = axes.setdefault(height[j.at], [])               # type: ignore[index]
        line += [x for x in j.links if x not in line]
    circles = [(p, x, height[c], r, a) for p, x, c, r, a in gear_circles(chain)]
    span = max([max(axes) - min(axes)] + [2 * r for *_, r, _ in circles] + [1e-9])
    u = unit if unit is not None else span / 150
    gap, column = 3.5 * u, 28.0 * u
    where = {g.id: column * (i + 1) for i, g in enumerate(chain.gears)}
    on = {x: [h for h, links in axes.items() if x in links] for x in chain.links}
    carriers = [x for x in chain.links if x != fixed and len(on[x]) > 1]
    arm = {x: column * (len(where) + 1 + i) for i, x in enumerate(carriers)}

    def level(link: str, h: float) -> float:
        i = axes[h].index(link)
        return h + gap * ((i + 1) // 2) * (1 if i % 2 else -1)
    own: dict[tuple[str, float], list[float]] = {}
    for pair, link, h, r, annulus in circles:
        own.setdefault((link, h), []).append(where[pair] - (0.3 * column if annulus else 0))
    for x in carriers:
        for h in on[x]:
            own.setdefault((x, h), []).append(arm[x])
    for h in on.get(fixed or "", []):
        own.setdefault((fixed or "", h), []).append(0.0)
    pins = _bearings(joints, height, own, fixed)
    colour = {x: COLOURS[i % len(COLOURS)] for i, x in enumerate(chain.links)}
    if fixed:
        colour[fixed] = "#555555"
    right = column * (len(where) + len(carriers) + 0.6)
    out = _centre_lines(list(axes), -0.6 * column, right, u)
    for (link, h), cols in own.items():
        if cols and (link != fixed or max(cols) > 0):
            y = level(link, h)
            lo = min(cols) - (0.3 * column if min(cols) == max(cols) else 0.0)
            out.append(Shape("line", "shaft", ((lo, y), (max(cols), y)),
                             data=(("link", link),), stroke=colour[link], width=1.6 * u,
                             cap="round"))
    for x in carriers:
        ys = [level(x, h) for h in on[x]]
        out.append(Shape("line", "arm", ((arm[x], min(ys)), (arm[x], max(ys))),
                         data=(("link", x),), stroke=colour[x], width=2.4 * u, cap="round"))
    for pair, link, h, r, annulus in circles:
        out += _gear_bar(where[pair], h, r, annulus, column, u, link, colour[link])
    for h in on.get(fixed or "", []):
        out += _ground(0.0, min(level(x, h) for x in axes[h]) - 1.2 * u, 2.2 * u)
    for (x, h), at in pins:
        out.append(Shape("circle", "pin", ((at, level(x, h)),), data=(("link", x),),
                         radius=1.5 * u, fill="white", stroke="#222222", width=0.6 * u))
    spots = {}
    for link in chain.links:
        spans = [(max(cols) - min(cols), h, cols) for (x, h), cols in own.items()
                 if x == link and cols]
        if link == fixed or not spans:
            h = max(on.get(link, [0.0]))
            spots[link] = (0.0, min(level(x, h) for x in axes[h]) - 6 * u) if h in axes \
                else (0.0, 0.0)
        elif link in arm:
            spots[link] = (arm[link], 0.5 * sum(level(link, h) for h in on[link][:2]))
        else:
            _, h, cols = max(spans)
            spots[link] = (0.5 * (min(cols) + max(cols)), level(link, h))
    return out + _schematic_labels(chain, out, [(p, where[p], x, h, r) for p, x, h, r, _
                                                in circles], spots, fixed, u)


def _schematic_labels(chain: Chain, shapes: Sequence[Shape],
                      bars: Sequence[tuple[str, float, str, float, float]],
                      spots: dict[str, Point], fixed: str | None, u: float) -> list[Shape]:
    """The schematic's labels: each gear's teeth over its bar (``(pair, column, link,
    axis height, radius)``), each link's name by its spot (the
    fixed link's below), none overlapping another, the names kept off the drawn
    ``shapes`` where they can."""
    teeth = {(g.id, x): z for g in chain.gears for x, z in zip(g.links, g.teeth)}
    placed: list[tuple[float, ...]] = []
    size = 8.0 * u
    avoid: list[tuple[Point, Point]] = [
        ((float(q[0]), float(q[1])), (float(r[0]), float(r[1]))) for shape in shapes
        if shape.cls in ("shaft", "arm", "gear", "annulus")
        for q, r in zip(shape.points, shape.points[1:])]
    labels = [_place(str(teeth[(pair, link)]), (x, h + r), 1.2 * u, size, placed)
              for pair, x, link, h, r in bars]
    for link in chain.links:
        label = _place(link, spots[link], 1.5 * u, size, placed, below=link == fixed,
                       avoid=avoid)
        labels.append(replace(label, cls="name", data=(("link", link),)))
    return labels


def schematic_svg(chain: Chain, *, fixed: str | None = None, unit: float | None = None,
                  scale: float | None = None, width: int = 600) -> str:
    """The functional schematic (:func:`schematic_shapes`) as a standalone SVG:
    ``width`` pixels wide, or ``scale`` pixels per file unit (one scale for several)."""
    shapes = schematic_shapes(chain, fixed=fixed, unit=unit)
    view = _view(shapes, 0.0)
    view = View(view.lo, view.hi, 0.04 * max(view.size))
    title = f"{chain.name}: functional schematic" + (f", {fixed} fixed" if fixed else "")
    if scale is not None:
        width = max(1, int(round(view.size[0] * scale)))
    return svg_document(view, svg_elements(view, shapes), width=width, title=title)
