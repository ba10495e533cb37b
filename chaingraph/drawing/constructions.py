"""Pictures of the graphical analysis (matplotlib): the mechanism with its
instantaneous centres and the circle diagram; the velocity and acceleration polygons.

Each function writes ``path`` (SVG, PNG or any format matplotlib writes) or, without
one, returns the matplotlib Figure.
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING, overload

import numpy as np

from chaingraph.drawing.plots import finish, plain_text, pyplot_module
from chaingraph.drawing.scene import COLOURS, Scene, draw_shapes, frame_shapes
from chaingraph.graphical.centres import InstantCentres
from chaingraph.graphical.polygons import Polygons

if TYPE_CHECKING:                       # matplotlib is imported only to draw with it
    from matplotlib.figure import Figure

__all__ = ["draw_centres", "draw_polygons"]


def _num(value, size):
    """A coordinate for a label: 4 digits, rounding off what is below 1e-9 of the size."""
    return f"{(0.0 if abs(value) < 1e-9 * size else value):.4g}"


def _unit_word(state, per):
    unit = state.units or "length units"
    return f"{unit}/{per}"


@overload
def draw_centres(centres: InstantCentres, path: None = None) -> Figure: ...
@overload
def draw_centres(centres: InstantCentres, path: str | os.PathLike[str]) -> None: ...
@plain_text
def draw_centres(centres: InstantCentres, path: str | os.PathLike[str] | None = None
                 ) -> Figure | None:
    """The mechanism with its instantaneous centres (left) and the circle diagram
    (right): primary centres from the joints as filled dots, those found by Kennedy's
    theorem as open ones with the two lines that met dashed; a centre at infinity as an
    arrow at the picture's edge in its direction; a centre too far to show within the
    picture as an arrow towards it, with its coordinates."""
    plt = pyplot_module()
    state = centres.state
    fig, (ax, circle) = plt.subplots(1, 2, figsize=(12, 6),
                                     gridspec_kw={"width_ratios": [3, 2]})
    scene = Scene.of_pose(state)
    centre_of_view, edge, shown = _centres_view(centres, scene)
    lo, hi = centre_of_view - edge, centre_of_view + edge
    for c in centres.centres:
        if isinstance(c.found, str):             # from a joint, or not by Kennedy
            continue
        for pair1, pair2 in c.found:
            a = centres.centre(*pair1).homogeneous
            b = centres.centre(*pair2).homogeneous
            _line_through(ax, state.plan, np.array(a), np.array(b), centre_of_view, edge,
                          color="#9a9a9a", lw=0.6, ls="--", zorder=0)
    _centre_marks(ax, centres, shown, centre_of_view, edge)
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    ax.grid(True, color="#eeeeee", lw=0.5)
    ax.set_title(f"{state.name}\ninstantaneous centres at {state.input_text('θ', '°')}", fontsize=10)
    _circle_diagram(circle, centres, centres.numbers)
    fig.tight_layout()
    # the mechanism under the construction, as every drawing of it looks
    draw_shapes(ax, scene, frame_shapes(scene, 0), view=(lo, hi), zorder=0.5)
    return finish(plt, fig, path)


def _centres_view(centres, scene):
    """The view of the centres' picture, a square (its centre, half its edge): the
    mechanism (its joints, and what the ``scene`` draws round them: a guide's travel, a
    cam's profile, a gear's pitch circle) and the centres within 2.5 times its reach;
    and those centres."""
    state = centres.state
    points = np.array([*state.positions.values(), scene.lo, scene.hi])
    middle = (points.min(axis=0) + points.max(axis=0)) / 2
    reach = max(float(np.ptp(points, axis=0).max()) / 2, 1e-9 * state.plan.size) * 1.6
    shown = [c for c in centres.centres if c.at is not None and
             np.abs(np.subtract(c.at, middle)).max() <= 2.5 * reach]
    every = np.array([*points, *(c.at for c in shown)])
    lo = every.min(axis=0) - 0.12 * reach
    hi = every.max(axis=0) + 0.12 * reach
    edge = max(hi[0] - lo[0], hi[1] - lo[1]) / 2
    return (lo + hi) / 2, edge, shown


def _line_through(ax, plan, a, b, centre_of_view, edge, **style):
    """The line through the homogeneous points a and b (about the plan's origin, in
    units of its size), drawn across the view."""
    h = np.cross(a, b)
    if np.linalg.norm(h[:2]) < 1e-12:
        return
    # the line h . (x, y, 1) = 0 clipped to the view, drawn across it
    n = h[:2] / np.linalg.norm(h[:2])
    d = np.array([-n[1], n[0]])
    size, (ox, oy) = plan.size, plan.origin
    c = -h[2] / np.linalg.norm(h[:2]) * size
    base = np.array([ox, oy]) + n * c
    t = np.dot(centre_of_view - base, d)
    p0, p1 = base + d * (t - 3 * edge), base + d * (t + 3 * edge)
    ax.plot([p0[0], p1[0]], [p0[1], p1[1]], **style)


def _centre_marks(ax, centres, shown, centre_of_view, edge):
    """Each centre: a dot where it is ``shown``, else (far off or at infinity) an arrow
    at the view's edge towards it with its coordinates or direction."""
    size = centres.state.plan.size
    far = 0
    for c in centres.centres:
        label = c.name
        colour = "#c0392b" if c.primary else "#1f4e9a"
        if c.at is not None and c in shown:
            ax.plot([c.at[0]], [c.at[1]], "o", ms=6 if c.primary else 7,
                    mfc=colour if c.primary else "white", mec=colour, mew=1.5, zorder=5)
            ax.annotate(label, c.at, fontsize=8, color=colour, xytext=(5, 5),
                        textcoords="offset points", zorder=6)
        elif c.at is not None or c.direction is not None:
            if c.at is not None:
                d = np.subtract(c.at, centre_of_view)
                d = d / np.linalg.norm(d)
                text = f"{label} at ({_num(c.at[0], size)}, {_num(c.at[1], size)})"
            else:
                a = math.radians(c.direction)
                d = np.array([math.cos(a), math.sin(a)])
                text = f"{label} at infinity, {c.direction:.4g}°"
                # either way along the line: point towards the nearer side of the view
            reach_d = 0.95 * edge / max(abs(d[0]), abs(d[1]))     # to the square's edge
            tip = centre_of_view + d * reach_d
            tail = centre_of_view + d * (reach_d - 0.15 * edge)
            ax.annotate("", tip, tail, arrowprops={"arrowstyle": "->", "color": colour})
            ax.annotate(text, tail, fontsize=7, color=colour, va="center",
                        ha="left" if d[0] < 0 else "right", xytext=(0, -9 * far),
                        textcoords="offset points")
            far += 1


def _circle_diagram(ax, centres, numbers):
    """Links as numbered points on a circle; a line for every centre: solid for those
    the joints give, dashed for those Kennedy's theorem found, dotted for the others."""
    count = len(numbers)
    spots = {}
    for link, n in numbers.items():
        a = math.pi / 2 - 2 * math.pi * (n - 1) / count
        spots[link] = (math.cos(a), math.sin(a))
    for c in centres.centres:
        (x0, y0), (x1, y1) = spots[c.links[0]], spots[c.links[1]]
        style = ({"ls": "-", "color": "#c0392b"} if c.primary else
                 {"ls": "--", "color": "#1f4e9a"} if not isinstance(c.found, str) else
                 {"ls": ":", "color": "#7f7f7f"})
        ax.plot([x0, x1], [y0, y1], lw=1.2, **style)
        ax.annotate(c.name, ((x0 + x1) / 2, (y0 + y1) / 2), fontsize=7, ha="center",
                    color=style["color"],
                    bbox={"boxstyle": "round,pad=0.1", "fc": "white", "ec": "none"})
    for link, (x, y) in spots.items():
        ax.plot([x], [y], "o", ms=18, mfc="white", mec="#000000")
        ax.annotate(str(numbers[link]), (x, y), ha="center", va="center", fontsize=9)
        ax.annotate(link, (x * 1.14, y * 1.14), fontsize=8, va="center",
                    ha="left" if x > 0.3 else "right" if x < -0.3 else "center")
    ax.set_xlim(-1.9, 1.9)
    ax.set_ylim(-1.35, 1.35)
    ax.set_aspect("equal")
    ax.axis("off")
    ax.set_title("circle diagram (solid: joints; dashed: Kennedy's theorem)", fontsize=9)


_SHORT = {"centripetal": "c", "tangential": "t", "sliding": "s", "Coriolis": "cor"}


def _label(name):
    return name.lower()


@overload
def draw_polygons(polygons: Polygons, path: None = None) -> Figure: ...
@overload
def draw_polygons(polygons: Polygons, path: str | os.PathLike[str]) -> None: ...
@plain_text
def draw_polygons(polygons: Polygons, path: str | os.PathLike[str] | None = None
                  ) -> Figure | None:
    """The velocity polygon (left) and the acceleration polygon (right), to scale:
    the pole o, each point's image labelled with its name in lower case (b' the
    guide's point under the block's b), the relative vectors as arrows coloured by link;
    in the acceleration polygon each relative vector drawn as its components head to
    tail: centripetal then tangential, sliding then Coriolis."""
    plt = pyplot_module()
    state = polygons.state
    fig, axes = plt.subplots(1, 2, figsize=(12, 6))
    colours = {link: COLOURS[i % len(COLOURS)] for i, link in enumerate(state.chain.links)}
    styles = {"centripetal": "-", "tangential": "--", "sliding": "-", "Coriolis": "-."}
    for ax, which in zip(axes, ("velocity", "acceleration")):
        spots = {name: getattr(im, which) for name, im in polygons.images.items()}
        finite = [p for p in spots.values() if all(map(math.isfinite, p))]
        span = max((math.hypot(*p) for p in finite), default=1.0) or 1.0
        ax.plot([0], [0], "o", color="#000000", ms=5)
        ax.annotate("o", (0, 0), fontsize=10, xytext=(-10, -12), textcoords="offset points")
        for name, p in spots.items():
            if not all(map(math.isfinite, p)) or math.hypot(*p) <= 1e-12 * span:
                continue
            ax.plot([0, p[0]], [0, p[1]], color="#c8c8c8", lw=0.8, zorder=0)
            ax.plot([p[0]], [p[1]], "o", color="#333333", ms=4)
            ax.annotate(_label(name), p, fontsize=9, xytext=(5, 4), textcoords="offset points")
        kinds = set()
        reached = [(0.0, 0.0), *finite]
        for r in polygons.relatives:
            start = np.array(spots[r.start])
            colour = colours[r.link] if r.link else "#555555"
            parts = r.velocity if which == "velocity" else r.acceleration
            for c in parts:
                end = start + np.array(c.vector)
                if c.magnitude > 1e-12 * span:
                    ax.annotate("", end, start, arrowprops={
                        "arrowstyle": "-|>", "color": colour, "lw": 1.4,
                        "linestyle": styles.get(c.kind, "-"), "shrinkA": 0, "shrinkB": 0})
                    if which == "acceleration" and c.magnitude > 0.04 * span:
                        middle = (start + end) / 2
                        ax.annotate(_SHORT[c.kind], middle, fontsize=7, color=colour,
                                    xytext=(3, 3), textcoords="offset points")
                    kinds.add(c.kind)
                start = end
                reached.append(tuple(end))
        box = np.array([p for p in reached if all(map(math.isfinite, p))])
        lo, hi = box.min(axis=0), box.max(axis=0)
        pad = 0.12 * max(float((hi - lo).max()), 1e-12)
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
        ax.grid(True, color="#eeeeee", lw=0.5)
        unit = _unit_word(state, "s" if which == "velocity" else "s²")
        ax.set_xlabel(unit)
        ax.set_ylabel(unit)
        legend = ("relative vectors coloured by link" if which == "velocity" else
                  ", ".join(f"{_SHORT[k]} {k}" for k in sorted(kinds, key=list(_SHORT).index)))
        ax.set_title(f"{which} polygon at {state.input_text('θ', '°')}, {state.speed_text}\n"
                     f"{legend}", fontsize=9)
    fig.suptitle(state.name, fontsize=10)
    fig.tight_layout()
    return finish(plt, fig, path)
