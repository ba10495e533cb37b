"""Drawings of a disc cam: the profile with its follower at one angle (SVG, through the
scene's shapes and emitter) and the follower's displacement, velocity, acceleration and
jerk diagrams (matplotlib)."""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING, overload

import numpy as np

from chaingraph.drawing.plots import finish, pyplot_module
from chaingraph.drawing.scene import COLOURS, Shape, View, svg_document, svg_elements
from chaingraph.geometry import rotate
from chaingraph.kinematics.cams import CamAnalysis, analyse_cam
from chaingraph.model.cams import Cam

if TYPE_CHECKING:                       # matplotlib is imported only to draw with it
    from matplotlib.figure import Figure

__all__ = ["cam_shapes", "cam_svg", "plot_cam"]


def _turned(points: np.ndarray, theta: float) -> list[tuple[float, float]]:
    """Points (n x 2) of the cam's frame in the world, the cam turned by ``theta``."""
    x, y = rotate(points.T, theta)
    return list(zip(x.tolist(), y.tolist()))


def cam_shapes(cam: Cam, result: CamAnalysis, *, at: float = 0.0) -> list[Shape]:
    """The cam turned by ``at`` (radians) and its follower there, as scene shapes in the
    cam's coordinates (its centre at the origin): the profile, the base circle and the
    pitch curve (dashed), the follower (a roller, a knife edge or a flat face on its stem,
    or an arm about its pivot), the pins and the labels."""
    size = cam.base + cam.stroke * (1 if cam.moves == "translating" else cam.arm or 1)
    pin, text = 0.035 * size, 0.09 * size
    here = analyse_cam(cam, np.array([at]))
    w = _turned(here.pitch, at)[0]                 # the follower's point in the world
    touch = _turned(here.profile, at)[0]
    out = [Shape("polygon", "plate", tuple(_turned(result.profile, at)),
                 data=(("link", cam.cam),), fill=COLOURS[0], fill_opacity=0.18,
                 stroke=COLOURS[0], width=0.012 * size, join="round"),
           Shape("circle", "base", ((0.0, 0.0),), radius=cam.base, stroke="#888888",
                 width=0.005 * size, dash=(0.03 * size, 0.02 * size))]
    if cam.contact != "flat":
        out.append(Shape("polygon", "pitch", tuple(_turned(result.pitch, at)),
                         stroke="#888888", width=0.005 * size, dash=(0.01 * size, 0.015 * size)))
    colour, stem = COLOURS[2], 0.015 * size
    if cam.moves == "translating":
        foot = (cam.offset if cam.contact != "flat" else 0.0, w[1])
        top = (foot[0], w[1] + 0.6 * size)
        out.append(Shape("line", "bar", (foot, top), data=(("link", cam.follower),),
                         stroke=colour, width=stem, cap="round"))
        for side in (-1, 1):           # the guide the follower slides in
            x = foot[0] + side * 1.5 * stem
            out.append(Shape("line", "guide", ((x, w[1] + 0.3 * size), (x, w[1] + 0.55 * size)),
                             stroke="#444444", width=0.006 * size))
    else:
        q = cam.pivot or (0.0, 0.0)
        out.append(Shape("line", "bar", (q, w), data=(("link", cam.follower),),
                         stroke=colour, width=stem, cap="round"))
        out.append(Shape("circle", "pin", (q,), radius=pin, fill="white", stroke="#222222",
                         width=0.006 * size))
    if cam.contact == "roller":
        out.append(Shape("circle", "roller", (w,), radius=cam.roller, fill="white",
                         fill_opacity=0.9, stroke=colour, width=0.01 * size))
    elif cam.contact == "flat":
        half = max(abs(float(x)) for x in result.ds) + 0.1 * size
        out.append(Shape("line", "face", ((-half, w[1]), (half, w[1])), stroke=colour,
                         width=stem, cap="round"))
    else:
        out.append(Shape("polygon", "knife", (touch, (touch[0] - pin, touch[1] + 3 * pin),
                                              (touch[0] + pin, touch[1] + 3 * pin)),
                         fill=colour, stroke=colour, width=0.004 * size))
    out += [Shape("circle", "point", (touch,), radius=0.5 * pin, fill="#d62728"),
            Shape("circle", "pin", ((0.0, 0.0),), radius=pin, fill="white", stroke="#222222",
                  width=0.006 * size),
            Shape("text", "label", ((0.1 * size, -0.15 * size),), text=cam.cam, size=text,
                  halo=0.02 * size),
            Shape("text", "label", ((w[0] + 0.08 * size, w[1] + 0.45 * size),),
                  text=cam.follower, size=text, halo=0.02 * size)]
    return out


def cam_svg(cam: Cam, result: CamAnalysis, *, at: float = 0.0, name: str = "",
            width: int = 640) -> str:
    """The cam turned by ``at`` (radians) with its follower there, as a standalone SVG."""
    shapes = cam_shapes(cam, result, at=at)
    xs = [p[0] for s in shapes for p in s.points] + [-cam.base - cam.stroke, cam.base]
    ys = [p[1] for s in shapes for p in s.points] + [-cam.base - cam.stroke]
    view = View((min(xs), min(ys)), (max(xs), max(ys)), 0.15 * (max(ys) - min(ys)))
    title = f"{name or cam.id}: cam {cam.cam} at {math.degrees(at):g} degrees"
    return svg_document(view, svg_elements(view, shapes), width=width, title=title)


@overload
def plot_cam(cam: Cam, result: CamAnalysis, path: None = None, *, name: str = "",
             omega: float | None = None, units: str | None = None) -> Figure: ...


@overload
def plot_cam(cam: Cam, result: CamAnalysis, path: str | os.PathLike[str], *,
             name: str = "", omega: float | None = None, units: str | None = None) -> None: ...


def plot_cam(cam: Cam, result: CamAnalysis, path: str | os.PathLike[str] | None = None, *,
             name: str = "", omega: float | None = None, units: str | None = None
             ) -> Figure | None:
    """The follower's displacement, velocity, acceleration and jerk over a turn, stacked
    (derivatives with respect to the cam's angle; at the cam's speed ``omega`` in rad/s
    when given; a translating follower's in ``units``, the chain file's). Written to ``path`` (SVG, PNG...) or returned as a matplotlib figure."""
    plt = pyplot_module()
    x = np.degrees(result.theta)
    unit = "deg" if cam.moves == "oscillating" else (units or "units")
    scale = math.degrees(1.0) if cam.moves == "oscillating" else 1.0
    w = 1.0 if omega is None else omega
    per = "rad" if omega is None else "s"
    rows = [("displacement", result.s, unit), ("velocity", result.ds * w, f"{unit}/{per}"),
            ("acceleration", result.dds * w ** 2, f"{unit}/{per}²"),
            ("jerk", result.ddds * w ** 3, f"{unit}/{per}³")]
    fig, axes = plt.subplots(4, 1, figsize=(8, 8.5), sharex=True)
    starts = np.cumsum([0.0] + [math.degrees(s.over) for s in cam.motion])
    for ax, (label, y, u), colour in zip(axes, rows, COLOURS):
        ax.plot(x, y * scale, color=colour, linewidth=1.3)
        for b in starts[1:-1]:
            ax.axvline(b, color="#999999", linewidth=0.6, linestyle=":")
        ax.axhline(0.0, color="#444444", linewidth=0.5)
        ax.set_ylabel(f"{label}\n{u}", fontsize=9)
        ax.grid(True, linewidth=0.3)
    axes[-1].set_xlim(0, 360)
    axes[-1].set_xticks(np.arange(0, 361, 60))
    axes[-1].set_xlabel("cam angle, degrees")
    laws = ", ".join(f"{s.kind} {s.law}" for s in cam.motion if s.law)
    axes[0].set_title(f"{name or cam.id}: the motion of {cam.follower!r} ({laws})", fontsize=10)
    fig.tight_layout()
    return finish(plt, fig, path)
