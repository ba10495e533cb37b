"""The limit positions of a mechanism, drawn as the lecture draws them: its two extreme
poses overlaid (the output at each end of its stroke), the input's arcs between them
with their angles (for a quick-return drive: the forward and the return stroke, the
crank at each extreme, the lever on the tangents from its pivot to the crank circle),
and the stroke marked.

:func:`limit_motion` solves the two poses; :func:`limit_shapes` computes the picture as
:class:`~chaingraph.drawing.scene.Shape` items on a :class:`~chaingraph.drawing.scene.Scene`
of those two poses; :func:`limits_svg` writes it.
"""

from __future__ import annotations

import html
import math
from dataclasses import replace

import numpy as np

from chaingraph.drawing.scene import Scene, Shape, frame_shapes, svg_document, svg_elements
from chaingraph.errors import MechanismError
from chaingraph.kinematics import Motion, solve
from chaingraph.kinematics.summary import output_signal

__all__ = ["limit_motion", "limit_shapes", "limits_svg"]


def limit_motion(motion: Motion) -> Motion | None:
    """The mechanism at the input values of its output's two extremes (a motion of two
    rows, the summary's ``extremes`` in order); None when the summary has none."""
    s = motion.summary
    if s is None or not s.extremes or len(s.extremes) != 2:
        return None
    chain = motion.plan.chain
    lead = motion.plan.inputs[motion.plan.lead]
    e1, e2 = s.extremes
    if motion.inputs:
        inputs = [(lead.joint, e1, e2)] + [i.joint for i in motion.inputs if i.joint != lead.joint]
        if len(motion.inputs) > 1:
            return None
        return solve(chain, fixed=motion.fixed, inputs=inputs, steps=1, summary=False)
    return solve(chain, fixed=motion.fixed, driver=motion.driver, start=e1, stop=e2,
                 steps=1, summary=False)


def _arc(centre, radius, a0, sweep, n=64):
    t = np.radians(a0 + sweep * np.linspace(0.0, 1.0, n))
    return tuple((centre[0] + radius * math.cos(x), centre[1] + radius * math.sin(x)) for x in t)


def limit_shapes(motion: Motion) -> tuple[Scene, list[Shape]]:
    """The limit-position picture of a solved motion with an output: (scene, shapes).
    The extreme poses carry ``data-extreme`` 1 and 2 and their input values as
    ``data-input``; the input's arcs their angles as ``data-angle``."""
    two = limit_motion(motion)
    if two is None:
        raise MechanismError("the mechanism has no output with two extreme positions to "
                             "draw (name an output)", mechanism=motion.name,
                             parameter="output")
    s = motion.summary
    scene = Scene.of_motion(two)
    shapes = _extreme_poses(scene, s)
    shapes += _input_arcs(two, s, scene)
    shapes += _stroke_marks(two, s, scene)
    _fit_view(scene, shapes)
    return scene, shapes


def _extreme_poses(scene, s):
    """The two extreme poses, the second faint and dashed, the labels once."""
    shapes = []
    for k in (0, 1):
        for shape in frame_shapes(scene, k):
            data = shape.data + (("extreme", str(k + 1)), ("input", repr(float(s.extremes[k]))))
            if k == 1 and shape.kind == "text":     # the labels once
                continue
            if k == 1:                              # the second pose: faint and dashed
                shape = replace(shape, fill_opacity=None if shape.fill_opacity is None else
                                0.08, dash=(0.015 * scene.span, 0.01 * scene.span)
                                if shape.kind in ("line", "polyline", "polygon") else ())
            shapes.append(replace(shape, data=data))
    return shapes


def _input_arcs(two, s, scene):
    """The input's arcs: a driver turning about its pivot, with the angle between the
    extremes, forward and return."""
    plan = two.plan
    lead = plan.inputs[plan.lead]
    if lead.kind != "R" or plan.fixed not in (lead.a, lead.b):
        return []
    pivot = next(j for j in plan.chain.joints if j.id == lead.joint)
    moving = lead.b if lead.a == plan.fixed else lead.a
    other = next((j for j in plan.chain.joints_of(moving) if j.id != pivot.id), None)
    if other is None:
        return []
    width, text = 0.006 * scene.span, 0.032 * scene.span
    c = (float(two[f"x:{pivot.id}"][0]), float(two[f"y:{pivot.id}"][0]))
    p1 = (float(two[f"x:{other.id}"][0]), float(two[f"y:{other.id}"][0]))
    p2 = (float(two[f"x:{other.id}"][1]), float(two[f"y:{other.id}"][1]))
    radius = math.dist(c, p1)
    a1 = math.degrees(math.atan2(p1[1] - c[1], p1[0] - c[0]))
    a2 = math.degrees(math.atan2(p2[1] - c[1], p2[0] - c[0]))
    first = (a2 - a1) % 360.0
    arcs = [(a1, first, "#b2182b"), (a2, 360.0 - first, "#2166ac")] if s.full_turn \
        else [(a1, math.remainder(a2 - a1, 360.0), "#b2182b")]
    shapes = []
    for start, sweep, colour in arcs:
        if abs(sweep) < 1e-9:
            continue
        r = radius * (1.15 if colour == "#b2182b" else 1.3)
        pts = _arc(c, r, start, sweep)
        shapes.append(Shape("polyline", "input-arc", pts,
                            (("angle", repr(abs(sweep))),), stroke=colour, width=width))
        mid = pts[len(pts) // 2]
        label = "forward" if abs(sweep) >= 180.0 or not s.full_turn else "return"
        if s.full_turn and s.forward_deg is not None:
            label = ("forward" if abs(abs(sweep) - s.forward_deg) < 1e-6 else "return")
        shapes.append(Shape("text", "input-angle", (mid,), (("angle", repr(abs(sweep))),),
                            text=f"{label} {abs(sweep):.4g}\u00b0", size=text,
                            halo=0.4 * text))
    return shapes


def _stroke_marks(two, s, scene):
    """The stroke marked: a dimension line beside a slide's or a point's two extremes,
    or an arc between an angle's."""
    signal = output_signal(two.plan, s.output, two.columns)
    if signal is not None and signal.kind in ("slide", "point"):
        return _linear_stroke(two, s, scene, signal.name)
    if signal is not None and signal.kind == "angle":
        return _angular_stroke(two, s, scene, signal.name)
    return []


def _linear_stroke(two, s, scene, name):
    """The dimension line of a stroke along a line, offset from the two positions."""
    width, text = 0.006 * scene.span, 0.032 * scene.span
    q1 = (float(two[f"x:{name}"][0]), float(two[f"y:{name}"][0]))
    q2 = (float(two[f"x:{name}"][1]), float(two[f"y:{name}"][1]))
    off = 0.08 * scene.span
    d = (q2[0] - q1[0], q2[1] - q1[1])
    n = math.hypot(*d) or 1.0
    u = (-d[1] / n * off, d[0] / n * off)
    a, b = (q1[0] + u[0], q1[1] + u[1]), (q2[0] + u[0], q2[1] + u[1])
    shapes = [Shape("line", "stroke", (a, b), (("stroke", repr(s.stroke)),),
                    stroke="#000000", width=width)]
    for q, e in ((q1, a), (q2, b)):
        shapes.append(Shape("line", "stroke-end", (q, e), stroke="#000000",
                            width=0.5 * width))
    unit = f" {s.stroke_unit}" if s.stroke_unit else ""
    shapes.append(Shape("text", "stroke-label", (((a[0] + b[0]) / 2 + 0.3 * u[0],
                                                  (a[1] + b[1]) / 2 + 0.3 * u[1]),),
                        text=f"stroke {s.stroke:.4g}{unit}", size=text, halo=0.4 * text))
    return shapes


def _angular_stroke(two, s, scene, link):
    """A link's angular stroke: its two extreme lines from its pivot and the arc
    between them (nothing when the link has no R joint with the fixed link)."""
    plan = two.plan
    pivot = next((j for j in plan.chain.joints_of(link)
                  if plan.fixed in j.links and j.kind == "R"), None)
    if pivot is None:
        return []
    width, text = 0.006 * scene.span, 0.032 * scene.span
    c = (float(two[f"x:{pivot.id}"][0]), float(two[f"y:{pivot.id}"][0]))
    a1, a2 = (float(two[f"angle:{link}"][k]) for k in (0, 1))
    radius = 0.25 * scene.span
    sweep = math.remainder(a2 - a1, 360.0)
    shapes = []
    for a in (a1, a2):
        end = (c[0] + 1.4 * radius * math.cos(math.radians(a)),
               c[1] + 1.4 * radius * math.sin(math.radians(a)))
        shapes.append(Shape("line", "extreme-line", (c, end), stroke="#444444",
                            width=0.5 * width, dash=(0.01 * scene.span,)))
    pts = _arc(c, radius, a1, sweep)
    shapes.append(Shape("polyline", "stroke", pts, (("stroke", repr(s.stroke)),),
                        stroke="#000000", width=width))
    shapes.append(Shape("text", "stroke-label", (pts[len(pts) // 2],),
                        text=f"stroke {s.stroke:.4g}\u00b0", size=text,
                        halo=0.4 * text))
    return shapes


def _fit_view(scene, shapes):
    """The view: everything drawn, the arcs and marks included, and room for a title."""
    pts = [p for shape in shapes for p in shape.points if shape.kind != "text"]
    xs = [p[0] for p in pts if math.isfinite(p[0])]
    ys = [p[1] for p in pts if math.isfinite(p[1])]
    scene.lo = (min(xs + [scene.lo[0]]), min(ys + [scene.lo[1]]))
    scene.hi = (max(xs + [scene.hi[0]]), max(ys + [scene.hi[1]]) + 0.08 * scene.span)


def limits_svg(motion: Motion, *, width: int = 640) -> str:
    """The limit positions of a solved motion as SVG text (see the module).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("crank-and-slotted-lever-mechanism")))
    >>> svg = limits_svg(m)
    >>> svg.count('class="input-arc"'), 'forward 227.2' in svg, 'return 132.8' in svg
    (2, True, True)
    """
    scene, shapes = limit_shapes(motion)
    s = motion.summary
    title = f"{motion.name}: limit positions"
    if s is not None and s.time_ratio is not None:      # (limit_shapes needs a summary)
        title += f" (time ratio {s.time_ratio:.4g})"
    heading = (f'<text x="{0.03 * scene.size[0]:.4g}" y="{0.05 * scene.span:.4g}" '
               f'font-size="{0.03 * scene.span:.3g}" font-family="sans-serif">'
               f'{html.escape(title)}</text>')
    return svg_document(scene, [*svg_elements(scene, shapes), heading], width=width,
                        title=title)
