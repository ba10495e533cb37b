"""Drawings of a mechanism in the textbook's style, as SVG (no matplotlib, no script).

One drawing for the report, ``solve --draw`` and the notebook: fixed pivots on hatched
ground; each sliding pair as a block on its guide, the guide drawn on the link that
carries it (a hatched way on the fixed link, a slot on a moving link that reaches past
the block over the whole motion); binary links as bars, links of three or more joints as
plates; tracer points marked with their paths; every joint labelled; a scale bar in the
file's units. :func:`mechanism_svg` draws one pose, or, with ``frames``, a cycle in which
every frame is drawn the same way (SMIL, with the first frame shown without it).

The drawing is plain SVG that tests (and users) can read: each frame is a
``<g class="frame">``; a block is ``<polygon class="block" data-joint=...>``, its guide
``<line class="guide" data-joint=...>`` (the guide's centre line), a link
``<polyline class="bar">`` or ``<polygon class="plate">`` with ``data-link``.
"""

from __future__ import annotations

import html
import math

import networkx as nx
import numpy as np

from chaingraph.drawing.scene import (
    COLOURS,
    Scene,
    frame_shapes,
    path_shapes,
    svg_elements,
)
from chaingraph.geometry import convex_hull

__all__ = ["mechanism_svg", "frame_steps", "skeleton_svg"]

def frame_steps(motion, frames):
    """The steps of the motion that an animation of ``frames`` frames shows: evenly
    over the sweep, and back again for a rocker."""
    n = motion.theta.size
    picks = [int(k) for k in np.linspace(0, n - 1, min(frames, n)).round()]
    if motion.summary and not motion.summary.full_turn:
        picks = picks + picks[::-1][1:-1]
    return picks


def mechanism_svg(motion, *, frames=None, seconds=4.0, width=640, paths=True):
    """The mechanism drawn in the textbook's style, as SVG text.

    Parameters
    ----------
    motion : Motion
        A solved motion (its drawn pose, or its cycle).
    frames : int, optional
        Without it, the first pose of the motion with every point's path; with it, one
        cycle in that many frames, animated with SMIL (a rocker goes there and back).
    seconds : float
        The cycle's duration.
    width : int
        The picture's width in pixels (it scales; the coordinates are the file's).
    paths : bool
        Draw the paths of the moving joints and points (not for a motion whose rows
        are not one path, such as a grid over two inputs).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")), steps=36)
    >>> svg = mechanism_svg(m)
    >>> svg.count('class="block"'), svg.count('class="guide"'), svg.count('class="frame"')
    (1, 1, 1)
    """
    scene = Scene.of_motion(motion)
    picks = frame_steps(motion, frames) if frames else [0]
    width_m, height_m = scene.size
    height = int(round(width * height_m / width_m))
    units = motion.units or "units"
    parts = ['<?xml version="1.0"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
             f'viewBox="0 0 {width_m:.6g} {height_m:.6g}">',
             f'<title>{html.escape(motion.name)}</title>',
             '<rect class="background" width="100%" height="100%" fill="white"/>']
    # the paths of the points (and pins) that move, faint, under everything
    if paths:
        parts += svg_elements(scene, path_shapes(scene))
    count = len(picks)
    for i, k in enumerate(picks):
        shown = "visible" if i == 0 else "hidden"
        anim = ""
        if count > 1:
            if i == 0:
                values, times = "visible;hidden", f"0;{1 / count:.6f}"
            else:
                values, times = "hidden;visible;hidden", f"0;{i / count:.6f};{(i + 1) / count:.6f}"
            anim = (f'<animate attributeName="visibility" values="{values}" keyTimes="{times}" '
                    f'calcMode="discrete" dur="{seconds:g}s" repeatCount="indefinite"/>')
        parts.append(f'<g class="frame" data-step="{k}" visibility="{shown}">{anim}')
        parts += svg_elements(scene, frame_shapes(scene, k))
        parts.append("</g>")
    # a scale bar in the file's units
    bar = 10 ** math.floor(math.log10(scene.span / 3))
    for step in (5, 2):
        if bar * step <= scene.span / 3:
            bar *= step
            break
    x0, y0 = 0.4 * scene.pad, height_m - 0.4 * scene.pad
    parts.append(f'<g class="scale"><line x1="{x0:.4g}" y1="{y0:.4g}" x2="{x0 + bar:.4g}" '
                 f'y2="{y0:.4g}" stroke="black" stroke-width="{0.006 * scene.span:.3g}"/>'
                 f'<text x="{x0:.4g}" y="{y0 - 0.02 * scene.span:.4g}" '
                 f'font-size="{0.035 * scene.span:.3g}" font-family="sans-serif">'
                 f'{bar:g} {html.escape(units)}</text></g>')
    parts.append("</svg>")
    return "\n".join(parts)


def skeleton_svg(chain, *, width=420, labels=True):
    """The kinematic skeleton of any chain, mechanism or not: its links as bars (binary)
    and plates (three or more joints) between its joints, R joints as pins, P joints as
    blocks on their guides, higher pairs as dashed rings; the fixed link (if any) is the
    ground: hatched pivots and ways, not a body. Pins are drawn over blocks, and the
    joints' names beside them unless ``labels`` is false (a thumbnail).
    From the drawn pose when every joint has one, else from a computed layout.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> svg = skeleton_svg(chaingraph.load(catalog_path("stephenson-six-bar-chain")))
    >>> svg.count('class="plate"'), svg.count('class="bar"'), svg.count('class="pin"')
    (2, 4, 7)
    """

    drawn = all(j.at is not None for j in chain.joints)
    if drawn:
        pos = {j.id: j.at for j in chain.joints}
    else:
        g = nx.Graph()
        g.add_nodes_from(j.id for j in chain.joints)
        for link in chain.links:
            ids = [j.id for j in chain.joints_of(link)]
            g.add_edges_from((a, b) for i, a in enumerate(ids) for b in ids[i + 1:])
        layout = nx.spring_layout(g, seed=7, iterations=200)
        pos = {k: (float(v[0]) * 100, float(v[1]) * 100) for k, v in layout.items()}
    xs, ys = [p[0] for p in pos.values()], [p[1] for p in pos.values()]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    pad = 0.15 * span
    w_m, h_m = max(xs) - min(xs) + 2 * pad, max(ys) - min(ys) + 2 * pad

    def pt(p):
        return f"{p[0] - min(xs) + pad:.4g},{max(ys) - p[1] + pad:.4g}"

    fixed = chain.mechanism.fixed if chain.mechanism else None
    r, stroke = 0.025 * span, 0.01 * span
    parts = ['<?xml version="1.0"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" '
             f'height="{int(round(width * h_m / w_m))}" viewBox="0 0 {w_m:.6g} {h_m:.6g}">',
             f'<title>{html.escape(chain.name)}: kinematic skeleton'
             f'{"" if drawn else " (computed layout)"}</title>',
             '<rect width="100%" height="100%" fill="white"/>']
    colours = {link: COLOURS[c % len(COLOURS)] for c, link in enumerate(chain.links)}
    # the moving links as plates and bars; the fixed link is the ground, drawn at its
    # joints (hatched pivots, ways for its slots), never as a moving body
    for link in chain.links:
        if link == fixed:
            continue
        ends = [pos[j.id] for j in chain.joints_of(link)]
        colour, name = colours[link], html.escape(link, quote=True)
        if len(ends) >= 3:
            hull = convex_hull([(round(x, 12), round(y, 12)) for x, y in ends])
            parts.append(f'<polygon class="plate" data-link="{name}" points="'
                         + " ".join(pt(p) for p in hull) + f'" fill="{colour}" '
                         f'fill-opacity="0.2" stroke="{colour}" stroke-width="{stroke:.3g}"/>')
        elif len(ends) == 2:
            parts.append(f'<polyline class="bar" data-link="{name}" points="'
                         + " ".join(pt(p) for p in ends) + f'" stroke="{colour}" '
                         f'stroke-width="{2 * stroke:.3g}" stroke-linecap="round"/>')
    where = {j.id: tuple(float(v) for v in pt(pos[j.id]).split(",")) for j in chain.joints}
    # sliding pairs: the guide along the axis on the link that carries it (a hatched
    # way on the ground), the block across it; under the pins, which stay in sight
    for j in chain.joints:
        if j.kind != "P":
            continue
        x, y = where[j.id]
        turn = -(j.axis if drawn and j.axis is not None else 0.0)   # SVG's y points down
        jid = html.escape(j.id, quote=True)
        on_ground = j.guide == fixed
        colour = "#222222" if on_ground else colours[j.guide]
        parts.append(f'<g class="guide" data-joint="{jid}" '
                     f'transform="translate({x:.4g},{y:.4g}) rotate({turn:.4g})">'
                     f'<line x1="{-4 * r:.4g}" y1="{r:.4g}" x2="{4 * r:.4g}" y2="{r:.4g}" '
                     f'stroke="{colour}" stroke-width="{0.8 * stroke:.3g}"/>'
                     + ("".join(f'<line x1="{t * r:.4g}" y1="{r:.4g}" x2="{(t - 0.6) * r:.4g}" '
                                f'y2="{1.7 * r:.4g}" stroke="#222222" '
                                f'stroke-width="{0.5 * stroke:.3g}"/>'
                                for t in range(-4, 5, 2)) if on_ground else
                        f'<line x1="{-4 * r:.4g}" y1="{-r:.4g}" x2="{4 * r:.4g}" '
                        f'y2="{-r:.4g}" stroke="{colour}" stroke-width="{0.8 * stroke:.3g}"/>')
                     + f'<rect class="block" x="{-1.5 * r:.4g}" y="{-r:.4g}" '
                     f'width="{3 * r:.3g}" height="{2 * r:.3g}" fill="#f2f2f2" '
                     f'stroke="#222222" stroke-width="{0.8 * stroke:.3g}"/></g>')
    for j in chain.joints:
        x, y = where[j.id]
        jid = html.escape(j.id, quote=True)
        if j.kind == "R" and fixed in j.links:
            parts.append(f'<polygon class="ground" points="{x:.4g},{y:.4g} {x - 1.4 * r:.4g},'
                         f'{y + 2 * r:.4g} {x + 1.4 * r:.4g},{y + 2 * r:.4g}" fill="#dddddd" '
                         f'stroke="#222222" stroke-width="{0.6 * stroke:.3g}"/>')
        if j.kind == "R":
            parts.append(f'<circle class="pin" data-joint="{jid}" cx="{x:.4g}" cy="{y:.4g}" '
                         f'r="{r:.3g}" fill="white" stroke="#111111" '
                         f'stroke-width="{0.8 * stroke:.3g}"/>')
        elif j.kind != "P":
            parts.append(f'<circle class="higher" data-joint="{jid}" cx="{x:.4g}" '
                         f'cy="{y:.4g}" r="{1.3 * r:.3g}" fill="none" stroke="#b05000" '
                         f'stroke-dasharray="{stroke:.3g}" stroke-width="{0.8 * stroke:.3g}"/>')
        if not labels:
            continue
        parts.append(f'<text x="{x + 1.2 * r:.4g}" y="{y - 1.2 * r:.4g}" '
                     f'font-size="{0.06 * span:.3g}" font-family="sans-serif" '
                     f'paint-order="stroke" stroke="white" stroke-width="{0.015 * span:.3g}">'
                     f'{html.escape(j.id)}</text>')
    parts.append("</svg>")
    return "\n".join(parts)
