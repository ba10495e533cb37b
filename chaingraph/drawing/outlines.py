"""Outlines to cut: each link of a mechanism at one pose as a flat part, true size in the
file's units, written as DXF (for a laser cutter or a CAD program) or SVG.

A binary link is a bar with rounded ends, a link of three or more joints a plate (its
joints' convex hull grown by half the bar's width, the corners rounded), a sliding
pair a block on the block's link and a slot cut in the link that carries the guide,
long enough for the block's whole travel over the mechanism's cycle. Every turning
pair is a hole in each of its links. Which joints, points, guides and blocks belong to
which link is the scene's (:class:`~chaingraph.drawing.scene.Scene`), so a part is cut
as the mechanism is drawn.

A contour is kept as DXF keeps a polyline with arcs: vertices, each with the *bulge*
of the segment that leaves it (the tangent of a quarter of the arc's turn, 0 for a
straight segment), so the rounded ends are true arcs in both formats.

ezdxf (``pip install chaingraph[cad]``) is imported by :func:`outlines_dxf` alone.
"""

from __future__ import annotations

import html
import io
import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from chaingraph.drawing.scene import COLOURS, Scene, View
from chaingraph.errors import ChainGraphError, MechanismError
from chaingraph.geometry import Vec, convex_hull, cross, dot, perp, sub
from chaingraph.kinematics import pose_motion, solve
from chaingraph.model.chain import Chain

__all__ = ["Contour", "Hole", "LinkOutline", "Outlines", "link_outlines", "outlines_dxf",
           "outlines_svg", "layer_name", "DXF_UNITS"]

#: the file's units as DXF's $INSUNITS codes
DXF_UNITS = {"in": 1, "ft": 2, "mm": 4, "cm": 5, "m": 6}
#: characters a DXF layer name may not hold
_NOT_IN_LAYER = re.compile(r'[<>/\\":;?*|=`\x00-\x1f]')


@dataclass(frozen=True)
class Contour:
    """A closed outline: ``vertices`` in order (counter-clockwise for a part's
    boundary) and each one's ``bulge``, the tangent of a quarter of the turn of the arc
    to the next vertex (0: a straight segment; 1: a half circle to the left)."""

    vertices: tuple[tuple[float, float], ...]
    bulges: tuple[float, ...]

    def points(self, *, degrees: float = 5.0) -> list[tuple[float, float]]:
        """The contour as a polygon, each arc cut into chords of at most ``degrees``."""
        out = []
        n = len(self.vertices)
        for i, (p, b) in enumerate(zip(self.vertices, self.bulges)):
            out.append(p)
            if b:
                q = self.vertices[(i + 1) % n]
                centre, radius, start, turn = arc_of(p, q, b)
                pieces = max(1, int(math.ceil(abs(math.degrees(turn)) / degrees)))
                out += [(centre[0] + radius * math.cos(start + turn * k / pieces),
                         centre[1] + radius * math.sin(start + turn * k / pieces))
                        for k in range(1, pieces)]
        return out

    def contains(self, p: Vec) -> bool:
        """Whether the point is inside the contour (its polygon at half a degree)."""
        poly = self.points(degrees=0.5)
        inside = False
        for (x1, y1), (x2, y2) in zip(poly, poly[1:] + poly[:1]):
            if (y1 > p[1]) != (y2 > p[1]) and \
                    p[0] < x1 + (p[1] - y1) * (x2 - x1) / (y2 - y1):
                inside = not inside
        return inside


def arc_of(p: Vec, q: Vec, bulge: float) -> tuple[tuple[float, float], float, float, float]:
    """The arc from ``p`` to ``q`` of ``bulge``: ``(centre, radius, start angle, turn)``
    (radians; the turn counter-clockwise positive)."""
    turn = 4.0 * math.atan(bulge)
    chord = math.dist(p, q)
    radius = chord / (2.0 * abs(math.sin(turn / 2.0)))
    mid = (0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1]))
    # the centre lies off the chord's middle, to the left for a counter-clockwise arc
    lean = radius * math.cos(turn / 2.0) * (1.0 if turn > 0 else -1.0)
    d = ((q[0] - p[0]) / chord, (q[1] - p[1]) / chord)
    left = perp(d)
    centre = (mid[0] + lean * left[0], mid[1] + lean * left[1])
    return centre, radius, math.atan2(p[1] - centre[1], p[0] - centre[0]), turn


@dataclass(frozen=True)
class Hole:
    """A hole for the pin of the turning pair ``joint``: its centre and diameter."""

    joint: str
    centre: tuple[float, float]
    diameter: float


@dataclass(frozen=True)
class LinkOutline:
    """One link as a part: its ``boundary``, the ``holes`` of its pins and the
    ``slots`` cut in it (the guides of the sliding pairs it carries)."""

    link: str
    boundary: Contour
    holes: tuple[Hole, ...]
    slots: tuple[Contour, ...] = ()


@dataclass(frozen=True)
class Outlines:
    """A mechanism's parts at one pose, in the file's ``units``: each link's outline,
    the bars' ``width`` and the holes' diameter ``hole``."""

    name: str
    units: str | None
    width: float
    hole: float
    links: tuple[LinkOutline, ...]

    def link(self, name: str) -> LinkOutline:
        """The outline of link ``name``."""
        return next(o for o in self.links if o.link == name)


def rounded_hull(points: Iterable[Vec], radius: float) -> Contour:
    """The convex hull of ``points`` grown by ``radius``, its corners arcs of that
    radius (a circle round one point, a bar with half-round ends round two).

    >>> c = rounded_hull([(0.0, 0.0), (10.0, 0.0)], 2.0)
    >>> [tuple(round(v, 9) + 0.0 for v in p) for p in c.vertices]
    [(0.0, 2.0), (0.0, -2.0), (10.0, -2.0), (10.0, 2.0)]
    >>> [round(b, 12) for b in c.bulges]
    [1.0, 0.0, 1.0, 0.0]
    """
    hull = convex_hull((float(x), float(y)) for x, y in points)
    if len(hull) == 1:
        (x, y), = hull
        return Contour(((x + radius, y), (x - radius, y)), (1.0, 1.0))
    n = len(hull)
    normals = []
    for i in range(n):
        e = sub(hull[(i + 1) % n], hull[i])
        length = math.hypot(e[0], e[1])
        normals.append((e[1] / length, -e[0] / length))      # outward: the edge turned right
    vertices, bulges = [], []
    for i in range(n):
        before, after = normals[i - 1], normals[i]
        turn = math.atan2(cross(before, after), dot(before, after)) % (2 * math.pi)
        v = hull[i]
        vertices += [(v[0] + radius * before[0], v[1] + radius * before[1]),
                     (v[0] + radius * after[0], v[1] + radius * after[1])]
        bulges += [math.tan(turn / 4.0), 0.0]
    # each arc's end is followed by the straight edge to the next arc's start
    return Contour(tuple(vertices), tuple(bulges))


def _around(p, reach, sides=24):
    """A polygon of ``sides`` round ``p`` that holds the disc of radius ``reach`` (``p``
    alone for none)."""
    if reach <= 0:
        return [p]
    r = reach / math.cos(math.pi / sides)
    return [(p[0] + r * math.cos(2 * math.pi * k / sides),
             p[1] + r * math.sin(2 * math.pi * k / sides)) for k in range(sides)]


def _sized(chain: Chain, width: float | None, hole: float | None, span: float
           ) -> tuple[float, float]:
    """The bar's width and the holes' diameter: given, or from the mechanism's size (a
    twentieth of it, to two figures; the holes half the width)."""
    if width is None:
        raw = span / 20.0
        width = float(f"{raw:.2g}")
    if hole is None:
        hole = width / 2.0
    for value, what in ((width, "width"), (hole, "hole")):
        if not (math.isfinite(value) and value > 0):
            raise MechanismError(f"the {what} must be a finite number above 0, got {value}",
                                 mechanism=chain.source or chain.name, parameter=what)
    if hole >= width:
        raise MechanismError(f"the hole's diameter {hole:g} must be smaller than the bars' "
                             f"width {width:g} (a hole that wide cuts the bar through)",
                             mechanism=chain.source or chain.name, parameter="hole")
    return width, hole


def _pose_scene(chain: Chain, at: float | Sequence[float] | None) -> Scene:
    """The scene at the pose: the drawn pose, or the mechanism solved at ``at``."""
    if at is None:
        return Scene.of_chain(chain)
    return Scene.of_pose(pose_motion(chain, at=at))


def _travel_pairs(chain: Chain, scene: Scene) -> dict:
    """Each sliding pair's guide over the mechanism's whole cycle (so that a slot lets
    its block travel all the way), else as the pose's scene has it."""
    if not scene.pairs or chain.mechanism is None:
        return scene.pairs
    try:
        return Scene.of_motion(solve(chain, steps=180, summary=False)).pairs
    except ChainGraphError:
        return scene.pairs


def link_outlines(chain: Chain, *, at: float | Sequence[float] | None = None,
                  width: float | None = None, hole: float | None = None) -> Outlines:
    """Each link of a chain as a part to cut, at one pose.

    Parameters
    ----------
    chain : Chain
        A chain with a drawn pose (a mechanism for ``at``).
    at : float or sequence of float, optional
        The input value (as :func:`chaingraph.kinematics.pose_motion` takes it); by
        default the drawn pose.
    width : float, optional
        The bars' width, in the file's units (default a twentieth of the mechanism's
        size, to two figures). A slot is as wide as a bar, its link twice as wide round
        it; a block a bar's width across and twice along.
    hole : float, optional
        The pins' holes' diameter (default half the width); below the width.

    Returns
    -------
    Outlines

    Raises
    ------
    MechanismError
        No drawn pose, or a width or hole that is not a positive number, or a hole as
        wide as the bars (``parameter`` names which).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> parts = link_outlines(chaingraph.load(catalog_path("four-bar-chain")), width=10)
    >>> [(o.link, len(o.holes)) for o in parts.links]
    [('frame', 2), ('crank', 2), ('coupler', 2), ('rocker', 2)]
    """
    if not chain.has_pose:
        raise MechanismError("outlines need a drawn pose ('at' of every joint)",
                             mechanism=chain.source or chain.name)
    scene = _pose_scene(chain, at)
    width, hole = _sized(chain, width, hole, scene.span)
    pairs = _travel_pairs(chain, scene)
    spot = {name: (float(v[0][0]), float(v[1][0])) for name, v in scene.xy.items()}
    cores: dict[str, list] = {link: [] for link in chain.links}
    corner = {link: 0.5 * width for link in chain.links}
    slots: dict[str, list[Contour]] = {link: [] for link in chain.links}
    blocks: dict[str, list[tuple[float, float]]] = {link: [] for link in chain.links}
    for j in scene.slides:
        _sliding_pair(scene, j, pairs[j.id], width, cores, corner, slots, blocks)
    parts = []
    for link in chain.links:
        members = [spot[j.id] for j in chain.joints_of(link) if j.kind != "P"]
        members += [spot[p.id] for p in chain.points if p.link == link]
        # a pin in the middle of its block is inside it already
        members = [m for m in members
                   if not any(math.dist(m, b) <= 1e-9 * scene.span for b in blocks[link])]
        reach = 0.5 * width - corner[link]
        core = cores[link] + [q for m in members for q in _around(m, reach)]
        if not core:
            continue
        holes = tuple(Hole(j.id, spot[j.id], hole) for j in chain.joints_of(link)
                      if j.kind == "R")
        parts.append(LinkOutline(link, rounded_hull(core, corner[link]), holes,
                                 tuple(slots[link])))
    return Outlines(chain.name, chain.units, width, hole, tuple(parts))


def _sliding_pair(scene, joint, pair, width, cores, corner, slots, blocks):
    """A sliding pair's parts: a slot a bar's width wide over the guide's travel in the
    carrier (its link half a width round it), a block a width across and two along
    (corners rounded an eighth of a width) on the block's link."""
    side = joint.links.index(pair.carrier)
    ends = [scene.on_line(joint, side, c) for c in (pair.lo, pair.hi)]
    p1, p2 = ((float(np.ravel(x)[0]), float(np.ravel(y)[0])) for x, y in ends)
    slots[pair.carrier].append(rounded_hull([p1, p2], 0.5 * width))
    cores[pair.carrier] += _around(p1, width - corner[pair.carrier]) + \
        _around(p2, width - corner[pair.carrier])
    if pair.pin is not None:
        x, y = scene.xy[pair.pin]
    else:
        x, y = scene.on_line(joint, joint.links.index(pair.block_link), pair.at)
    centre = (float(np.ravel(x)[0]), float(np.ravel(y)[0]))
    blocks[pair.block_link].append(centre)
    a = float(np.ravel(scene.angle[joint.id])[0])
    u, n = (math.cos(a), math.sin(a)), (-math.sin(a), math.cos(a))
    rho = width / 8.0
    corner[pair.block_link] = min(corner[pair.block_link], rho)
    along, across = width - rho, 0.5 * width - rho
    cores[pair.block_link] += [(centre[0] + du * along * u[0] + dn * across * n[0],
                                centre[1] + du * along * u[1] + dn * across * n[1])
                               for du, dn in ((-1, -1), (1, -1), (1, 1), (-1, 1))]


def layer_name(link: str) -> str:
    """A link's name as a DXF layer's: the characters a layer may not hold as ``_``."""
    return _NOT_IN_LAYER.sub("_", link) or "_"


def outlines_dxf(parts: Outlines) -> str:
    """The parts as DXF text (R2010): a layer per link named after it, its boundary and
    slots as closed polylines with true arcs, its holes as circles; ``$INSUNITS`` from
    the units.

    Raises
    ------
    ImportError
        Without ezdxf: "DXF needs the cad extra: pip install chaingraph[cad]".
    """
    try:
        import ezdxf
    except ImportError:
        raise ImportError("DXF needs the cad extra: pip install chaingraph[cad]") from None
    doc = ezdxf.new("R2010", units=DXF_UNITS.get(parts.units or "", 0))
    doc.header["$MEASUREMENT"] = 0 if parts.units in ("in", "ft") else 1
    msp = doc.modelspace()
    taken: dict[str, str] = {}
    for k, part in enumerate(parts.links):
        name = layer_name(part.link)
        if name.upper() in taken:
            name = f"{name}_{k + 1}"
        taken[name.upper()] = part.link
        doc.layers.add(name, color=1 + k % 6)
        attribs = {"layer": name}
        for contour in (part.boundary, *part.slots):
            msp.add_lwpolyline([(x, y, 0.0, 0.0, b) for (x, y), b in
                                zip(contour.vertices, contour.bulges)],
                               format="xyseb", close=True, dxfattribs=attribs)
        for h in part.holes:
            msp.add_circle(h.centre, h.diameter / 2.0, dxfattribs=attribs)
    out = io.StringIO()
    doc.write(out)
    return out.getvalue()


def _svg_path(view: View, contour: Contour) -> str:
    """A contour as an SVG path's data in the view's picture coordinates (y down: a
    counter-clockwise arc is drawn with sweep flag 0)."""
    n = len(contour.vertices)
    x0, y0 = contour.vertices[0]
    parts = [f"M{view.pt(x0, y0)}"]
    for i, (p, b) in enumerate(zip(contour.vertices, contour.bulges)):
        q = contour.vertices[(i + 1) % n]
        if b:
            _, radius, _, turn = arc_of(p, q, b)
            r = view.num(radius)
            parts.append(f"A{r},{r} 0 {int(abs(turn) > math.pi)},{int(turn < 0)} "
                         f"{view.pt(*q)}")
        elif i < n - 1:
            parts.append(f"L{view.pt(*q)}")
    return " ".join(parts) + " Z"


_SVG_UNITS = {"mm": ("mm", 1.0), "cm": ("cm", 1.0), "in": ("in", 1.0), "m": ("mm", 1000.0)}


def outlines_svg(parts: Outlines) -> str:
    """The parts as SVG, true size where the units are SVG's (mm, cm, in; m as mm): a
    group per link (``<g class="link" data-link=...>``) with its boundary and slots as
    paths (``class="outline"``, ``class="slot"``) and its holes as circles
    (``class="hole" data-joint=...``), drawn as cutting lines (no fill)."""
    every = [p for part in parts.links for c in (part.boundary, *part.slots)
             for p in c.points()]
    xs, ys = [p[0] for p in every], [p[1] for p in every]
    pad = 0.02 * max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    view = View((min(xs), min(ys)), (max(xs), max(ys)), pad)
    w, h = view.size
    unit, scale = _SVG_UNITS.get(parts.units or "", ("", 1.0))
    stroke = view.num(parts.width / 40.0)
    lines = ['<?xml version="1.0"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{w * scale:.6g}{unit}" '
             f'height="{h * scale:.6g}{unit}" viewBox="0 0 {view.num(w)} {view.num(h)}">',
             f"<title>{html.escape(parts.name)}: outlines to cut"
             f"{' (' + parts.units + ')' if parts.units else ''}</title>"]
    for k, part in enumerate(parts.links):
        colour = COLOURS[k % len(COLOURS)]
        lines.append(f'<g class="link" data-link="{html.escape(part.link, quote=True)}" '
                     f'fill="none" stroke="{colour}" stroke-width="{stroke}">')
        lines.append(f'<path class="outline" d="{_svg_path(view, part.boundary)}"/>')
        lines += [f'<path class="slot" d="{_svg_path(view, s)}"/>' for s in part.slots]
        lines += [f'<circle class="hole" data-joint="{html.escape(h.joint, quote=True)}" '
                  f'cx="{view.num(view.X(h.centre[0]))}" cy="{view.num(view.Y(h.centre[1]))}" '
                  f'r="{view.num(h.diameter / 2)}"/>' for h in part.holes]
        lines.append("</g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"
