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
from collections.abc import Sequence
from dataclasses import replace

import networkx as nx
import numpy as np

from chaingraph.drawing.scene import (
    Scene,
    frame_shapes,
    path_shapes,
    svg_document,
    svg_elements,
)
from chaingraph.kinematics import Motion
from chaingraph.model.chain import Chain

__all__ = ["mechanism_svg", "frame_steps", "skeleton_svg"]

def frame_steps(motion: Motion, frames: int, *, there_and_back: bool | None = None
                ) -> list[int]:
    """The steps of the motion that an animation of ``frames`` frames shows: evenly
    over the sweep, and back again for a rocker (``there_and_back``; by default when
    the motion's summary says its input does not turn fully)."""
    if there_and_back is None:
        there_and_back = bool(motion.summary and not motion.summary.full_turn)
    return _picks(motion.theta.size, frames, there_and_back)


def _picks(n, frames, there_and_back):
    """``frames`` of ``n`` steps, evenly, first and last included (and back again)."""
    picks = [int(k) for k in np.linspace(0, n - 1, min(frames, n)).round()]
    return picks + picks[::-1][1:-1] if there_and_back else picks


def mechanism_svg(motion: Motion, *, frames: int | None = None, seconds: float = 4.0,
                  width: int = 640, paths: bool = True, rows: Sequence[int] | None = None,
                  there_and_back: bool | None = None, compact: bool = False) -> str:
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
    rows : sequence of int, optional
        The steps of the motion to draw (by default all): the picture is fitted to
        them, at one scale for every frame, and the frames are chosen among them.
    there_and_back : bool, optional
        Animate the frames there and back (a rocker, a part of a range); by default
        when the motion's summary says its input does not turn fully.
    compact : bool
        Draw each pose once, shown at each of its times (a rocker's way back shows the
        frames of its way there again), for a picture that only SMIL plays: half the
        size; by default one ``<g class="frame">`` per time, for a player that steps
        through them.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("reciprocating-engine")), steps=36)
    >>> svg = mechanism_svg(m)
    >>> svg.count('class="block"'), svg.count('class="guide"'), svg.count('class="frame"')
    (1, 1, 1)
    """
    scene = Scene.of_motion(motion, rows=rows)
    steps = list(range(motion.theta.size)) if rows is None else [int(k) for k in rows]
    if there_and_back is None:
        there_and_back = bool(motion.summary and not motion.summary.full_turn)
    picks = _picks(len(steps), frames, there_and_back) if frames else [0]
    width_m, height_m = scene.size
    height = int(round(width * height_m / width_m))
    units = motion.units or "units"
    parts = ['<?xml version="1.0"?>',
             f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
             f'viewBox="0 0 {scene.num(width_m)} {scene.num(height_m)}">',
             f'<title>{html.escape(motion.name)}</title>',
             '<rect class="background" width="100%" height="100%" fill="white"/>']
    # the paths of the points (and pins) that move, faint, under everything
    if paths:
        parts += svg_elements(scene, path_shapes(scene))
    count = len(picks)
    # each frame drawn (its step, and its pick unless compact), and the times it is shown at
    when: dict[tuple[int, int], list[int]] = {}
    for i, k in enumerate(picks):
        when.setdefault((k, -1) if compact else (k, i), []).append(i)
    for (k, _), times in when.items():
        anim = ""
        if count > 1:
            edges = sorted({0, *times, *(i + 1 for i in times if i + 1 < count)})
            values = ";".join("visible" if b in times else "hidden" for b in edges)
            keys = ";".join(f"{b / count:.6f}".rstrip("0").rstrip(".") for b in edges)
            anim = (f'<animate attributeName="visibility" values="{values}" keyTimes="{keys}" '
                    f'calcMode="discrete" dur="{seconds:g}s" repeatCount="indefinite"/>')
        shown = "visible" if 0 in times else "hidden"
        parts.append(f'<g class="frame" data-step="{steps[k]}" visibility="{shown}">{anim}')
        parts += svg_elements(scene, frame_shapes(scene, k))
        parts.append("</g>")
    parts.append(_scale_bar(scene, height_m, units))
    parts.append("</svg>")
    return "\n".join(parts)


def _scale_bar(scene, height_m, units):
    """A scale bar in the file's units, at the picture's lower left."""
    bar = 10 ** math.floor(math.log10(scene.span / 3))
    for step in (5, 2):
        if bar * step <= scene.span / 3:
            bar *= step
            break
    x0, y0 = 0.4 * scene.pad, height_m - 0.4 * scene.pad
    num = scene.num
    return (f'<g class="scale"><line x1="{num(x0)}" y1="{num(y0)}" x2="{num(x0 + bar)}" '
            f'y2="{num(y0)}" stroke="black" stroke-width="{0.006 * scene.span:.3g}"/>'
            f'<text x="{num(x0)}" y="{num(y0 - 0.02 * scene.span)}" '
            f'font-size="{0.035 * scene.span:.3g}" font-family="sans-serif">'
            f'{bar:g} {html.escape(units)}</text></g>')


def skeleton_svg(chain: Chain, *, width: int = 420, labels: bool = True) -> str:
    """The kinematic skeleton of any chain, mechanism or not, drawn as its animation is
    (one scene): its links as bars (binary) and plates (three or more joints) between
    its joints, each whole with the blocks and slots it carries, R joints as pins, P
    joints as blocks on their guides, higher pairs as dashed rings; the fixed link (if
    any) is the ground: hatched pivots and ways, not a body. Pins are drawn over blocks,
    and the joints' names beside them unless ``labels`` is false (a thumbnail).
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
    if not drawn:
        g = nx.Graph()
        g.add_nodes_from(j.id for j in chain.joints)
        for link in chain.links:
            ids = [j.id for j in chain.joints_of(link)]
            g.add_edges_from((a, b) for i, a in enumerate(ids) for b in ids[i + 1:])
        layout = nx.spring_layout(g, seed=7, iterations=200)
        chain = replace(chain, points=(), joints=tuple(
            replace(j, at=(float(layout[j.id][0]) * 100, float(layout[j.id][1]) * 100),
                    axis=0.0 if j.kind == "P" else j.axis) for j in chain.joints))
    scene = Scene.of_chain(chain)
    shapes = [s for s in frame_shapes(scene, 0) if labels or s.cls != "label"]
    return svg_document(scene, svg_elements(scene, shapes), width=width,
                        title=f"{chain.name}: kinematic skeleton"
                              f"{'' if drawn else ' (computed layout)'}").rstrip("\n")
