"""A synthesised mechanism's picture: the mechanism at its first target, drawn by the
shared scene (:mod:`chaingraph.drawing.scene`) with its paths over the task's sweep,
the targets marked, and beside it the plot of its error (a function generator's
structural error over the range, the precision points marked). matplotlib, so the one
picture is written as SVG or PNG, or returned as a figure for a notebook.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol

import numpy as np

from chaingraph.drawing.plots import finish, plain_text, pyplot_module
from chaingraph.drawing.scene import Scene, draw_shapes, frame_shapes, path_shapes
from chaingraph.kinematics import solve
from chaingraph.model.chain import Chain

if TYPE_CHECKING:                   # matplotlib is imported only when a picture is drawn
    from matplotlib.figure import Figure

__all__ = ["draw_synthesis", "draw_solution", "ErrorCurve", "DrawnSolution"]


class ErrorCurve(Protocol):
    """What is plotted beside a synthesised mechanism (synthesis's ``Curve``, read
    here through this protocol: synthesis sits above drawing): ``x`` and ``y`` arrays,
    their axes' labels, and the x values ``marks`` marked (the precision points)."""

    @property
    def x(self) -> np.ndarray: ...

    @property
    def y(self) -> np.ndarray: ...

    @property
    def x_label(self) -> str: ...

    @property
    def y_label(self) -> str: ...

    @property
    def marks(self) -> tuple[float, ...]: ...


@plain_text
def draw_synthesis(mechanism: Chain, *, at: float, sweep: tuple[float, float] | None = None,
                   curve: ErrorCurve | None = None,
                   targets: Sequence[tuple[float, float]] = (),
                   poses: Sequence[tuple[float, float, float]] = (),
                   title: str | None = None,
                   path: str | os.PathLike[str] | None = None) -> Figure | None:
    """Draw a synthesised mechanism and its error.

    Parameters
    ----------
    mechanism : Chain
        The solution's mechanism, drawn at its first target.
    at : float
        The input's value at the first target (the pose drawn).
    sweep : (float, float), optional
        The input's values over which the paths are drawn (default: its whole cycle).
    curve : ErrorCurve, optional
        What to plot beside it: ``x``, ``y`` (arrays), ``x_label``, ``y_label`` and
        ``marks`` (x values marked, the precision points), such as a
        :class:`chaingraph.synthesis.Curve`; None for the mechanism alone.
    targets : sequence of (x, y)
        Points marked on the mechanism's picture (a path's targets).
    poses : sequence of (x, y, degrees)
        Poses marked on it as small frames, numbered (a motion's targets): an arrow
        along the pose's angle from its point, and a shorter tick square to it.
    title : str, optional
    path : str or os.PathLike, optional
        Write SVG (or PNG, by the ending); without it, return the matplotlib Figure.
    """
    plt = pyplot_module()
    if sweep is None:
        motion = solve(mechanism, steps=360, summary=False)
    else:
        motion = solve(mechanism, start=sweep[0], stop=sweep[1], steps=240, summary=False)
    pose = solve(mechanism, start=at, stop=at, steps=1, summary=False)
    scene = Scene.of_motion(motion, also=pose)
    # targets small beside the mechanism get a panel of their own, enlarged, with the
    # curve traced through them (else the fit is a cluster of crosses at the point)
    zoom = curve is None and len(targets) > 1 and _extent(targets) < ZOOM_BELOW * scene.span
    columns = 2 if curve is not None or zoom else 1
    fig, axes = plt.subplots(1, columns, figsize=(6.0 * columns, 5.0),
                             gridspec_kw={"width_ratios": [1.0, 1.0][:columns]})
    axes = np.atleast_1d(axes)
    ax = axes[0]
    ax.set_axis_off()
    ax.set_title(title or mechanism.name, fontsize=10)
    fig.tight_layout()
    draw_shapes(ax, scene, path_shapes(scene, steps=motion.theta.size)
                + frame_shapes(scene, motion.theta.size))
    if len(targets):
        xs, ys = zip(*targets)
        ax.plot(xs, ys, "x", color="#b2182b", markersize=8, zorder=5, label="targets")
    _pose_frames(ax, poses, scene.span)
    if zoom:
        _traced_near(axes[1], scene, targets)
        fig.tight_layout()
    if curve is not None:
        _error_plot(axes[1], curve)
        fig.tight_layout()
    return finish(plt, fig, path)


#: targets spanning less than this share of the mechanism's size are shown enlarged too
ZOOM_BELOW = 0.3


def _extent(points: Sequence[tuple[float, float]]) -> float:
    xs, ys = zip(*points)
    return float(np.hypot(np.ptp(xs), np.ptp(ys)))


def _traced_near(ax, scene, targets):
    """The targets and the path of the point that passes nearest them, enlarged."""
    tx, ty = (np.asarray(v, dtype=float) for v in zip(*targets))
    names = [p.id for p in scene.chain.points] or list(scene.xy)

    def miss(name):
        xs, ys = scene.xy[name]
        d = np.hypot(xs[None, :] - tx[:, None], ys[None, :] - ty[:, None])
        return float(np.nanmin(d, axis=1).max()) if np.isfinite(d).any() else np.inf
    best = min(names, key=miss)
    xs, ys = scene.xy[best]
    ax.plot(xs, ys, color="#e07b00", linewidth=1.4, label=f"path of {best}")
    ax.plot(tx, ty, "x", color="#b2182b", markersize=8, label="targets")
    for k, (x, y) in enumerate(zip(tx, ty), 1):
        ax.annotate(str(k), (x, y), xytext=(4, 4), textcoords="offset points", fontsize=7,
                    color="#b2182b")
    pad = 0.15 * _extent(targets)
    ax.set_xlim(tx.min() - pad, tx.max() + pad)
    ax.set_ylim(ty.min() - pad, ty.max() + pad)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, linewidth=0.3)
    ax.set_title(f"the targets and the path of {best}, enlarged", fontsize=10)
    ax.legend(fontsize=8, loc="best")


def _pose_frames(ax, poses, span):
    """Each pose as a small frame: an arrow along its angle, a tick square to it, its
    number beside."""
    size = 0.07 * span
    for k, (x, y, deg) in enumerate(poses, 1):
        a = np.radians(deg)
        u, v = np.array([np.cos(a), np.sin(a)]), np.array([-np.sin(a), np.cos(a)])
        ax.annotate("", xy=(x + size * u[0], y + size * u[1]), xytext=(x, y), zorder=6,
                    arrowprops={"arrowstyle": "-|>", "color": "#b2182b", "lw": 1.4,
                                "shrinkA": 0, "shrinkB": 0, "mutation_scale": 10})
        ax.plot([x, x + 0.5 * size * v[0]], [y, y + 0.5 * size * v[1]], color="#b2182b",
                linewidth=1.4, zorder=6)
        ax.plot([x], [y], "o", color="#b2182b", markersize=3.5, zorder=6)
        ax.annotate(str(k), (x, y), xytext=(-6 * (u[0] + v[0]), -6 * (u[1] + v[1])),
                    textcoords="offset points", ha="center", va="center", fontsize=8,
                    color="#b2182b", zorder=6)


def _error_plot(ax, curve: ErrorCurve) -> None:
    ax.plot(curve.x, curve.y, color="#2166ac", linewidth=1.5)
    ax.axhline(0.0, color="#888888", linewidth=0.8)
    marks = np.asarray(curve.marks, dtype=float)
    if marks.size:
        ax.plot(marks, np.interp(marks, curve.x, curve.y) if curve.x[0] < curve.x[-1]
                else np.interp(marks, curve.x[::-1], curve.y[::-1]), "o", color="#b2182b",
                label="precision points")
        ax.legend(loc="best", fontsize=8)
    ax.set_xlabel(curve.x_label)
    ax.set_ylabel(curve.y_label)
    ax.grid(True, color="#dddddd", linewidth=0.6)
    worst = float(np.max(np.abs(curve.y))) if len(curve.y) else 0.0
    ax.set_title(f"structural error: largest {worst:.4g}", fontsize=10)


class DrawnSolution(Protocol):
    """What :func:`draw_solution` reads of a synthesis's ``Solution``: its mechanism
    (with its ``[task]``), the input at each target and its error curve."""

    @property
    def mechanism(self) -> Chain: ...

    @property
    def reached_at(self) -> tuple[float, ...]: ...

    @property
    def curve(self) -> ErrorCurve | None: ...


def draw_solution(solution: DrawnSolution, *,
                  path: str | os.PathLike[str] | None = None) -> Figure | None:
    """A synthesis's solution drawn as ``design ... --draw`` draws it: the mechanism at
    its first target, its paths over the task's sweep (a function's input swing, else
    the whole cycle), its targets (points, or poses as frames) and, for a function, its
    structural error beside it."""
    task = solution.mechanism.task or {}
    sweep = None
    if "swing" in task and "start" in task:
        sweep = (float(task["start"][0]), float(task["start"][0]) + float(task["swing"][0]))
    poses = [tuple(p) for p in task.get("poses", ())]
    return draw_synthesis(solution.mechanism, at=solution.reached_at[0], sweep=sweep,
                          curve=None if poses else solution.curve,
                          targets=[tuple(p) for p in task.get("targets", ())],
                          poses=poses, path=path)
