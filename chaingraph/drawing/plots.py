"""Drawings of a solved motion (matplotlib, imported only here, with the Agg backend).

:func:`plot_motion` plots the output's displacement, velocity and acceleration against
the input angle with its extremes and the dead centres marked; :func:`draw_mechanism`
draws the mechanism in its drawn pose with the paths of its joints and points.
"""

from __future__ import annotations

import functools
import math
import sys
import textwrap
from pathlib import Path

import numpy as np

from chaingraph.kinematics import Motion, output_signal, solve
from chaingraph.model.chain import Chain

__all__ = ["plot_motion", "draw_mechanism", "output_series"]


def plain_text(draw):
    """Draw with mathtext off: names are text, so ``$\\frac{a}{b}$`` in a link's name is
    drawn as typed instead of being parsed (and failing) as mathematics."""

    @functools.wraps(draw)
    def wrapper(*args, **kwargs):
        import matplotlib
        with matplotlib.rc_context({"text.parse_math": False}):
            return draw(*args, **kwargs)
    return wrapper


def pyplot_module():

    import matplotlib
    if "matplotlib.pyplot" not in sys.modules:
        matplotlib.use("Agg")       # headless; a notebook that chose a backend keeps it
    import matplotlib.pyplot as plt
    return plt


def output_series(motion):
    """The output's (label, displacement, velocity, acceleration, unit) along the sweep."""
    output = motion.summary.get("output") if motion.summary else None
    if output is None and motion.plan.chain.mechanism is not None:
        output = motion.plan.chain.mechanism.output
    if output is None:
        output = motion.driver or motion.plan.inputs[motion.plan.lead].b
    signal = output_signal(motion.plan, output, motion.columns)
    u, v, a = signal.values(motion.columns)
    return signal.label, u, v, a, signal.unit or "length"


@plain_text
def plot_motion(motion, path=None):
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
    s = motion.summary or {}
    for t in s.get("dead_centres") or []:
        for ax in axes:
            for tt in _in_sweep(t, theta):
                ax.axvline(tt, color="#c00000", lw=1.0, ls="--")
    for e in s.get("extreme_positions") or []:     # every extreme, where it was refined
        for tt in _in_sweep(e["input"], theta):
            axes[0].plot([tt], [e["value"]], "o", color="#e07b00", ms=6)
    axes[-1].set_xlabel(_input_label(motion))
    title = f"{motion.name}: {label}"
    if s.get("time_ratio"):
        title += f"\nstroke {s['stroke']:.4g} {s.get('stroke_unit') or ''}, " \
                 f"time ratio {s['time_ratio']:.4f}"
    elif s.get("note"):
        title += "\n" + textwrap.fill(s["note"], 80)
    axes[0].set_title(title, fontsize=10)
    handles = [plt.Line2D([], [], color="#e07b00", marker="o", ls="", label="extreme"),
               plt.Line2D([], [], color="#c00000", ls="--", label="dead centre")]
    axes[0].legend(handles=handles, fontsize=8, loc="best")
    fig.tight_layout()
    return finish(plt, fig, path)


def finish(plt, fig, path):
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


@plain_text
def draw_mechanism(motion, path=None, *, pose_index=0):
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
    motion, drawn = _motion_and_pose(motion, pose_index)
    chain = motion.plan.chain
    fig, ax = plt.subplots(figsize=(7, 6))
    _draw_pose(ax, *drawn)
    names = [j.id for j in chain.joints] + [p.id for p in chain.points]
    for name in names:
        x, y = motion[f"x:{name}"], motion[f"y:{name}"]
        if np.ptp(x) + np.ptp(y) > 1e-9:
            ax.plot(x, y, lw=0.8, color="#7f7f7f", alpha=0.8)
    ax.set_aspect("equal")
    driving = (f"{motion.driver} driving" if not motion.inputs else
               "input" + ("s " if len(motion.inputs) > 1 else " ")
               + ", ".join(i.joint for i in motion.inputs))
    ax.set_title(f"{motion.name}\n({motion.fixed} fixed, {driving}; paths over "
                 f"{_input_symbol(motion)} = {motion.theta[0]:.4g}..{motion.theta[-1]:.4g}"
                 f"{_input_unit(motion)})", fontsize=10)
    ax.grid(True, color="#eeeeee", lw=0.5)
    fig.tight_layout()
    return finish(plt, fig, path)


COLOURS = ["#1f77b4", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#17becf",
            "#bcbd22", "#ff7f0e"]


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


def _draw_pose(ax, motion, k):
    """The mechanism in the sweep's pose ``k`` (see :func:`draw_positions`)."""
    chain = motion.plan.chain
    pos = {}
    for j in chain.joints:
        pos[j.id] = (motion[f"x:{j.id}"][k], motion[f"y:{j.id}"][k])
    for p in chain.points:
        pos[p.id] = (motion[f"x:{p.id}"][k], motion[f"y:{p.id}"][k])
    axes = {j.id: j.axis + motion[f"angle:{j.guide}"][k] - motion[f"angle:{j.guide}"][0]
            for j in chain.joints if j.kind == "P"}
    draw_positions(ax, chain, motion.fixed, pos, axes, motion.plan.size)


def draw_positions(ax, chain, fixed, pos, axes, size):
    """Links as bars or polygons through their joints, R joints as circles, P joints as
    squares on their sliding line (``axes``: each P joint's direction now, degrees), the
    fixed link as hatched ground marks; ``pos`` every joint's and point's position."""
    for j in chain.joints_of(fixed):          # ground marks at the fixed link's joints
        x, y = pos[j.id]
        w = 0.035 * size
        ax.fill([x, x - w, x + w], [y, y - 1.6 * w, y - 1.6 * w], facecolor="#dddddd",
                edgecolor="#555555", hatch="///", lw=0.8, zorder=1)
    for i, link in enumerate(chain.links):
        if link == fixed:
            continue
        pts = [pos[j.id] for j in chain.joints_of(link)]
        pts += [pos[p.id] for p in chain.points if p.link == link]
        if len(pts) < 2:
            continue
        colour = COLOURS[i % len(COLOURS)]
        xs, ys = zip(*pts)
        if len(pts) >= 3:
            cx, cy = np.mean(xs), np.mean(ys)
            order = np.argsort([math.atan2(y - cy, x - cx) for x, y in pts])
            poly = [pts[o] for o in order]
            ax.fill(*zip(*poly), color=colour, alpha=0.18)
            ax.plot(*zip(*(poly + poly[:1])), color=colour, lw=2.2)
        else:
            ax.plot(xs, ys, color=colour, lw=3)
        ax.annotate(link, (np.mean(xs), np.mean(ys)), fontsize=8, color=colour,
                    xytext=(4, 4), textcoords="offset points")
    for j in chain.joints:
        x, y = pos[j.id]
        if j.kind == "P":
            angle = math.radians(axes[j.id])
            span = 0.15 * size
            ax.plot([x - span * math.cos(angle), x + span * math.cos(angle)],
                    [y - span * math.sin(angle), y + span * math.sin(angle)],
                    color="#333333", lw=1.0, ls=":")
            ax.plot([x], [y], "s", ms=9, mfc="white", mec="#333333")
        else:
            ax.plot([x], [y], "o", ms=7, mfc="white", mec="#000000", mew=1.5)
        ax.annotate(j.id, (x, y), fontsize=8, xytext=(-10, -12), textcoords="offset points")
    for p in chain.points:
        x, y = pos[p.id]
        ax.plot([x], [y], "*", ms=9, color="#e07b00")
        ax.annotate(p.id, (x, y), fontsize=8, xytext=(4, -10), textcoords="offset points")
