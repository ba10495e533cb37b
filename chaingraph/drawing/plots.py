"""Drawings of a solved motion (matplotlib, imported only here, with the Agg backend).

:func:`plot_motion` plots the output's displacement, velocity and acceleration against
the input angle with its extremes and the dead centres marked; :func:`draw_mechanism`
draws the mechanism in its drawn pose with the paths of its joints and points.
"""

from __future__ import annotations

import functools
import os
import sys
import textwrap
from collections.abc import Callable, Sequence
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any, ParamSpec, Protocol, TypeVar, overload

from chaingraph.drawing.scene import Scene, draw_shapes, frame_shapes, path_shapes
from chaingraph.kinematics import Motion, Summary, output_signal, solve
from chaingraph.model.chain import Chain

if TYPE_CHECKING:                       # matplotlib is imported only to draw with it
    from matplotlib.figure import Figure

__all__ = ["plot_motion", "draw_mechanism", "output_series"]

_P = ParamSpec("_P")
_R = TypeVar("_R")


class SummaryAt(Protocol):
    """What :func:`plot_variation` reads of one value of a length (a
    :class:`chaingraph.variation.VariationRow`, a module the drawings do not import)."""

    @property
    def value(self) -> float: ...
    @property
    def summary(self) -> Summary | None: ...


class SummariesOverLength(Protocol):
    """What :func:`plot_variation` reads of a :class:`chaingraph.variation.Variation`."""

    @property
    def name(self) -> str: ...
    @property
    def link(self) -> str: ...
    @property
    def units(self) -> str | None: ...
    @property
    def rows(self) -> Sequence[SummaryAt]: ...


def plain_text(draw: Callable[_P, _R]) -> Callable[_P, _R]:
    """Draw with mathtext off: names are text, so ``$\\frac{a}{b}$`` in a link's name is
    drawn as typed instead of being parsed (and failing) as mathematics."""

    @functools.wraps(draw)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        import matplotlib
        with matplotlib.rc_context({"text.parse_math": False}):
            return draw(*args, **kwargs)
    return wrapper


def pyplot_module() -> ModuleType:

    import matplotlib
    if "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")       # headless; a notebook that chose a backend keeps it
    import matplotlib.pyplot as plt
    return plt


def output_series(motion: Motion) -> tuple[str, Any, Any, Any, str]:
    """The output's (label, displacement, velocity, acceleration, unit) along the sweep."""
    output = motion.summary.output if motion.summary else None
    if output is None and motion.plan.chain.mechanism is not None:
        output = motion.plan.chain.mechanism.output
    if output is None:
        output = motion.driver or motion.plan.inputs[motion.plan.lead].b
    # (the motion reads its CSV's columns from its typed fields, without building them)
    signal = output_signal(motion.plan, output, motion)
    if signal is None:                 # (there is always an output here)
        raise ValueError(f"{motion.name!r} has no output to plot")
    u, v, a = signal.values(motion)
    return signal.label, u, v, a, signal.unit or "length"


@overload
def plot_motion(motion: Motion, path: None = None) -> Figure: ...
@overload
def plot_motion(motion: Motion, path: str | os.PathLike[str]) -> None: ...
@plain_text
def plot_motion(motion: Motion, path: str | os.PathLike[str] | None = None) -> Figure | None:
    """The output's displacement, velocity and acceleration against the input.

    Writes an SVG (or PNG, by the file's ending) to ``path``; without a path, returns
    the matplotlib Figure (a notebook shows it)."""
    plt = pyplot_module()
    label, u, v, a, unit = output_series(motion)
    theta = motion.theta
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(7.5, 7.5))
    rate = f"{unit}/s"
    for ax, y, name in zip(axes, (u, v, a), (f"displacement ({unit})", f"velocity ({rate})",
                                              f"acceleration ({unit}/s²)")):
        ax.plot(theta, y, color="#1f4e79", lw=1.6)
        ax.set_ylabel(name)
        ax.grid(True, color="#dddddd", lw=0.6)
    s = motion.summary
    for t in (s.dead_centres if s else None) or ():
        for ax in axes:
            for tt in _in_sweep(t, theta):
                ax.axvline(tt, color="#c00000", lw=1.0, ls="--")
    for e in (s.extreme_positions if s else None) or ():   # every extreme, as refined
        for tt in _in_sweep(e.input, theta):
            axes[0].plot([tt], [e.value], "o", color="#e07b00", ms=6)
    axes[-1].set_xlabel(_input_label(motion))
    title = f"{motion.name}: {label}"
    if s and s.time_ratio:
        title += f"\nstroke {s.stroke:.4g} {s.stroke_unit or ''}, " \
                 f"time ratio {s.time_ratio:.4f}"
    elif s and s.note:
        title += "\n" + textwrap.fill(s.note, 80)
    axes[0].set_title(title, fontsize=10)
    handles = [plt.Line2D([], [], color="#e07b00", marker="o", ls="", label="extreme"),
               plt.Line2D([], [], color="#c00000", ls="--", label="dead centre")]
    axes[0].legend(handles=handles, fontsize=8, loc="best")
    fig.tight_layout()
    return finish(plt, fig, path)


@overload
def finish(plt: ModuleType, fig: Figure, path: None) -> Figure: ...
@overload
def finish(plt: ModuleType, fig: Figure, path: str | os.PathLike[str]) -> None: ...
@overload
def finish(plt: ModuleType, fig: Figure, path: str | os.PathLike[str] | None
           ) -> Figure | None: ...
def finish(plt: ModuleType, fig: Figure, path: str | os.PathLike[str] | None
           ) -> Figure | None:
    """Save and close the figure, or, without a path, hand it back (closed to pyplot, so
    that it is shown once, where it is returned)."""
    if path is None:
        plt.close(fig)
        return fig
    try:
        # before closing; PNG without an ending, written to the very path asked for
        # (matplotlib would otherwise append ".png" to it)
        fig.savefig(path, format=None if Path(str(path)).suffix else "png")
    finally:
        plt.close(fig)
    return None


def _input_symbol(motion):
    plan = motion.plan
    return "θ" if not motion.inputs else plan.inputs[plan.lead].joint


def _input_unit(motion):
    plan = motion.plan
    return "°" if plan.inputs[plan.lead].kind == "R" else " " + plan.lead_unit


def _input_label(motion):
    """The x axis of the motion plot: the (lead) input, in its units."""
    plan = motion.plan
    lead = plan.inputs[plan.lead]
    if not motion.inputs:
        return "input angle θ (degrees)"
    what = "angle" if lead.kind == "R" else "slide"
    return f"input {lead.joint}: {what} ({plan.lead_unit})"


def _in_sweep(t, theta):
    lo, hi = min(theta[0], theta[-1]), max(theta[0], theta[-1])
    return [t + 360 * k for k in range(-3, 4) if lo - 1e-9 <= t + 360 * k <= hi + 1e-9]


@overload
def draw_mechanism(motion: Motion, path: None = None, *, pose_index: int = 0) -> Figure: ...
@overload
def draw_mechanism(motion: Motion, path: str | os.PathLike[str], *,
                   pose_index: int = 0) -> None: ...
@plain_text
def draw_mechanism(motion: Motion, path: str | os.PathLike[str] | None = None, *,
                   pose_index: int = 0) -> Figure | None:
    """The mechanism in a pose with every joint's and point's path: written as SVG (or
    PNG) to ``path``, or returned as a matplotlib Figure without one.

    ``motion`` is a solved :class:`~chaingraph.kinematics.Motion` (drawn in its pose
    ``pose_index``), or a chain with a mechanism and a drawn pose: drawn in that pose,
    with the paths over its default sweep.

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> fig = draw_mechanism(chaingraph.load(catalog_path("beam-engine")))
    >>> fig.axes[0].get_title().splitlines()[0]
    'Beam engine (crank and lever mechanism)'
    """
    plt = pyplot_module()
    motion, (pose, k) = _motion_and_pose(motion, pose_index)
    fig, ax = plt.subplots(figsize=(7, 6))
    if pose is motion:
        scene, k = Scene.of_motion(motion), k
    else:                                # the drawn pose, after the sweep's steps
        scene, k = Scene.of_motion(motion, also=pose), motion.theta.size + k
    driving = (f"{motion.driver} driving" if not motion.inputs else
               "input" + ("s " if len(motion.inputs) > 1 else " ")
               + ", ".join(i.joint for i in motion.inputs))
    ax.set_title(f"{motion.name}\n({motion.fixed} fixed, {driving}; paths over "
                 f"{_input_symbol(motion)} = {motion.theta[0]:.4g}..{motion.theta[-1]:.4g}"
                 f"{_input_unit(motion)})", fontsize=10)
    ax.set_axis_off()
    fig.tight_layout()
    draw_shapes(ax, scene, path_shapes(scene, steps=motion.theta.size)
                + frame_shapes(scene, k))
    return finish(plt, fig, path)


def _motion_and_pose(given, k):
    """(the motion whose paths are drawn, (motion, step) of the pose drawn) for a Motion
    or a chain with a mechanism (its drawn pose, where its sweep passes through it)."""
    if isinstance(given, Motion):
        return given, (given, k)
    if not isinstance(given, Chain):
        raise TypeError("draw_mechanism takes a solved motion (chaingraph.solve) or a chain "
                        f"with a mechanism and a drawn pose, not {type(given).__name__}")
    motion = solve(given, summary=False)
    plan = motion.plan
    if plan.theta0 is None:
        return motion, (motion, 0)
    value = float(plan.value(plan.theta0))
    return motion, (solve(given, start=value, stop=value, steps=1, summary=False), 0)


@overload
def plot_variation(variation: SummariesOverLength, path: None = None) -> Figure: ...
@overload
def plot_variation(variation: SummariesOverLength, path: str | os.PathLike[str]) -> None: ...
@plain_text
def plot_variation(variation: SummariesOverLength,
                   path: str | os.PathLike[str] | None = None) -> Figure | None:
    """A :class:`~chaingraph.variation.Variation` plotted: the time ratio and the stroke
    against the length (the values with no motion left out). Written to ``path`` or
    returned as a figure."""
    plt = pyplot_module()
    good = [(r.value, r.summary) for r in variation.rows if r.summary is not None]
    x = [value for value, _ in good]
    fig, ax = plt.subplots(figsize=(7.0, 3.8))
    ratio = [s.time_ratio for _, s in good]
    if any(v is not None for v in ratio):
        ax.plot(x, [float("nan") if v is None else v for v in ratio], "o-", color="#b2182b",
                label="time ratio")
        ax.set_ylabel("time ratio")
    stroke = [s.stroke for _, s in good]
    if any(v is not None for v in stroke):
        other = ax.twinx()
        unit = next((s.stroke_unit for _, s in good if s.stroke_unit), "")
        other.plot(x, [float("nan") if v is None else v for v in stroke], "s--",
                   color="#2166ac", label="stroke")
        other.set_ylabel(f"stroke, {unit}")
        fig.legend(loc="upper right", fontsize=8)
    units = variation.units or "length units"
    ax.set_xlabel(f"{variation.link}, {units}")
    ax.set_title(f"{variation.name}: over the length of {variation.link}", fontsize=10)
    ax.grid(True, linewidth=0.3)
    return finish(plt, fig, path)
