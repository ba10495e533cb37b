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
from typing import TYPE_CHECKING, overload

import numpy as np

from chaingraph.drawing.plots import finish, pyplot_module
from chaingraph.drawing.scene import COLOURS, Shape, View, svg_document, svg_elements
from chaingraph.dynamics.reactions import PoseForces, SweepForces
from chaingraph.geometry import convex_hull

if TYPE_CHECKING:                   # matplotlib is imported only when a plot is drawn
    from matplotlib.figure import Figure

__all__ = ["free_body_shapes", "free_body_svg", "force_polygon_shapes", "force_polygon_svg",
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


def free_body_shapes(result: PoseForces) -> tuple[list[Shape], View]:
    """The free bodies of a :class:`~chaingraph.dynamics.PoseForces` as shapes: each
    moving link in a panel of its own (the panels in rows of three), its joints and
    forces drawn to one scale. Returns (shapes, view)."""
    chain = result.chain
    links = [x for x in chain.links if x != result.fixed]
    colour = {link: COLOURS[i % len(COLOURS)] for i, link in enumerate(chain.links)}
    bodies: dict[str, list[_Point]] = {}
    for link in links:
        pts = [result.points[j.id] for j in chain.joints if link in j.links]
        bodies[link] = pts
    allpts = [p for pts in bodies.values() for p in pts] + \
        [a.at for a in result.applied]
    xs, ys = [p[0] for p in allpts], [p[1] for p in allpts]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    extent = max(max(max(p[0] for p in pts) - min(p[0] for p in pts),
                     max(p[1] for p in pts) - min(p[1] for p in pts)) for pts in bodies.values())
    extent = max(extent, 0.2 * span)
    forces = {link: forces_on(result, link) for link in links}
    biggest = max([math.hypot(*f) for fs in forces.values() for _, _, _, f in fs] + [1e-300])
    arrow = 0.45 * extent                      # the largest force's length
    scale = arrow / biggest
    cell = extent + 2.4 * arrow
    size = 0.012 * cell                        # a pin's radius, the text's scale
    shapes: list[Shape] = []
    cols = min(3, len(links))
    for i, link in enumerate(links):
        pts = bodies[link]
        cx = 0.5 * (max(p[0] for p in pts) + min(p[0] for p in pts))
        cy = 0.5 * (max(p[1] for p in pts) + min(p[1] for p in pts))
        ox = (i % cols) * cell + 0.5 * cell - cx
        oy = -(i // cols) * cell - 0.5 * cell - cy

        def at(p: _Point) -> _Point:
            return (p[0] + ox, p[1] + oy)
        shapes.append(Shape("text", "label", (at((cx - 0.45 * cell, cy + 0.42 * cell)),),
                            text=link, size=3.2 * size))
        body = [at(p) for p in pts]
        if len(body) >= 3 and len({(round(p[0], 9), round(p[1], 9)) for p in body}) >= 3:
            hull = convex_hull(body)
            shapes.append(Shape("polygon", "plate", tuple(hull), (("link", link),),
                                fill=colour[link], fill_opacity=0.25, stroke=colour[link],
                                width=size, join="round"))
        elif len(body) >= 2:
            shapes.append(Shape("polyline", "bar", tuple(body), (("link", link),),
                                stroke=colour[link], width=1.6 * size, cap="round"))
        for p in body:
            shapes.append(Shape("circle", "pin", (p,), radius=size, fill="white",
                                stroke="#222222", width=0.4 * size))
        for what, key, q, f in forces[link]:
            if math.hypot(*f) * scale < 0.5 * size:
                continue
            head = at(q)
            tail = (head[0] - f[0] * scale, head[1] - f[1] * scale)
            shapes += _arrow(tail, head, ARROWS[key], size, what, f, label="tail",
                             dash=(2 * size, size) if key == "inertia force" else ())
        line = 0
        for c in result.couples:
            if c.link == link and c.value is not None and abs(c.value) > 1e-12:
                turn = "\u21ba" if c.value > 0 else "\u21bb"
                shapes.append(Shape("text", "couple", (at((cx - 0.45 * cell,
                                                           cy - 0.42 * cell + line * 3 * size)),),
                                    text=f"{c.what} {abs(c.value):.3g} N m {turn}",
                                    size=2.4 * size, halo=0.6 * size))
                line += 1
    rows = math.ceil(len(links) / cols)
    view = View((0.0, -rows * cell), (cols * cell, 0.0), 0.02 * cell)
    return shapes, view


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
           label: str = "mid") -> list[Shape]:
    """An arrow from p to q for the force ``f``, labelled with ``what`` and its size
    (at the arrow's middle, or by its ``tail``): a shaft, and a head ``head`` wide (1.6
    pin radii ``size`` unless given)."""
    length = math.dist(p, q)
    if length < 1e-12:
        return []
    ux, uy = (q[0] - p[0]) / length, (q[1] - p[1]) / length
    w = 1.6 * size if head is None else head
    tip = [q, (q[0] - 2.5 * w * ux - w * uy, q[1] - 2.5 * w * uy + w * ux),
           (q[0] - 2.5 * w * ux + w * uy, q[1] - 2.5 * w * uy - w * ux)]
    at = ((p[0] + 0.6 * size, p[1] + 0.6 * size) if label == "tail" else
          (0.5 * (p[0] + q[0]) + 0.8 * size, 0.5 * (p[1] + q[1]) + 0.8 * size))
    return [Shape("line", "force", (p, (q[0] - 2 * w * ux, q[1] - 2 * w * uy)),
                  (("force", what),), stroke=colour, width=0.6 * size, dash=dash),
            Shape("polygon", "arrowhead", tuple(tip), fill=colour, stroke=colour,
                  width=0.1 * size),
            Shape("text", "force-label", (at,), text=f"{what} {_newtons(f)}",
                  size=2.2 * size, halo=0.6 * size)]


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


def free_body_svg(result: PoseForces, *, width: int = 900) -> str:
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


@overload
def plot_turning_moment(result: SweepForces, path: None = None) -> Figure: ...


@overload
def plot_turning_moment(result: SweepForces, path: str | os.PathLike[str]) -> None: ...


def plot_turning_moment(result: SweepForces, path: str | os.PathLike[str] | None = None,
                        ) -> Figure | None:
    """The turning-moment diagram of a :class:`~chaingraph.dynamics.SweepForces` (one
    input): the effort against the input, its mean, and the largest swing of the
    energy about the mean shaded between its two extremes. Written to ``path`` (SVG,
    PNG...) or returned as a matplotlib figure."""
    plt = pyplot_module()
    joint = result.inputs[0]
    x = np.asarray(result["theta"], dtype=float)
    e = np.asarray(result[f"effort:{joint}"], dtype=float)
    kind = result.motion.plan.inputs[0].kind if result.motion is not None else "R"
    unit = "N m" if kind == "R" else "N"
    fig, ax = plt.subplots(figsize=(7.5, 3.8))
    ax.plot(x, e, color="#b2182b", linewidth=1.4, label=f"effort at {joint}")
    mean = result.summary.efforts[joint].mean
    if mean is not None:
        ax.axhline(mean, color="#444444", linewidth=0.9, linestyle="--",
                   label=f"mean {mean:.4g} {unit}")
        ax.fill_between(x, e, mean, where=np.isfinite(e) & (e >= mean), color="#b2182b",
                        alpha=0.15, linewidth=0)
        ax.fill_between(x, e, mean, where=np.isfinite(e) & (e < mean), color="#2166ac",
                        alpha=0.15, linewidth=0)
    swing = result.summary.energy_fluctuation
    title = f"{result.name}: turning-moment diagram"
    if swing is not None:
        title += f" (energy fluctuation {swing:.4g} J)"
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("theta, degrees" if kind == "R" else f"{joint} slide")
    ax.set_ylabel(f"effort, {unit}")
    ax.grid(True, linewidth=0.3)
    ax.legend(fontsize=8, loc="best")
    return finish(plt, fig, path)
