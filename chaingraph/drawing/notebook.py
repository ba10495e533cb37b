"""Displays in a notebook: short plain reprs and rich HTML and SVG for chains,
classifications, inversions and solved motions, and an inline animation.

:func:`register` hands these functions to IPython's display formatters (``import
chaingraph`` in a notebook does it), so Jupyter shows a chain as its kinematic skeleton,
a classification and inversions as tables, a motion as its summary and plot, and
instant centres and polygons as tables and pictures. The results themselves know
nothing of notebooks (the displays are drawn here, above them). Nothing here needs
IPython; :meth:`Motion.to_frame` needs pandas (``pip install chaingraph[notebook]``).
"""

from __future__ import annotations

import html
import io
import os
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any, Protocol

from chaingraph.drawing.constructions import draw_centres, draw_polygons
from chaingraph.drawing.forces import free_body_svg, plot_turning_moment
from chaingraph.drawing.mechanism import mechanism_svg, skeleton_svg
from chaingraph.drawing.plots import plot_motion
from chaingraph.drawing.synthesis import DrawnSolution, draw_solution
from chaingraph.dynamics.reactions import PoseForces, SweepForces
from chaingraph.graphical.centres import InstantCentres
from chaingraph.graphical.polygons import Polygons
from chaingraph.kinematics import Motion, summary_rows
from chaingraph.model.chain import Chain
from chaingraph.structure.classification import Classification

if TYPE_CHECKING:                   # matplotlib is imported only when a plot is drawn
    from matplotlib.figure import Figure

__all__ = ["Animation", "animate", "figure_svg", "register", "DISPLAYS",
           "DISPLAYS_BY_NAME"]


class InversionTable(Protocol):
    """What the inversions' display reads of
    :class:`~chaingraph.naming.inversion_classes.Inversions` (naming is beside drawing,
    not below it)."""

    name: str
    links: int
    classes: int

    def rows(self) -> list[tuple]: ...


class SolutionError(Protocol):
    """A synthesis solution's error (``max``, ``rms``, a pose's ``angle``)."""

    @property
    def max(self) -> float: ...

    @property
    def rms(self) -> float: ...

    @property
    def angle(self) -> float | None: ...


class SolutionRow(DrawnSolution, Protocol):
    """What the synthesis display reads of each ``Solution`` (synthesis is above
    drawing: read through this protocol)."""

    @property
    def rank(self) -> int: ...

    @property
    def error(self) -> SolutionError: ...

    @property
    def transmission_angle(self) -> tuple[float, float] | None: ...

    @property
    def input(self) -> str: ...

    @property
    def grashof(self) -> str | None: ...

    @property
    def names(self) -> tuple[str, ...]: ...

    @property
    def dimensions(self) -> dict[str, float]: ...


class SearchedSpace(Protocol):
    """A synthesis's searched space."""

    @property
    def chains(self) -> int: ...

    @property
    def inversions(self) -> int: ...

    @property
    def candidates(self) -> int: ...


class SynthesisResult(Protocol):
    """What the synthesis display reads of :class:`chaingraph.synthesis.Synthesis`."""

    @property
    def task(self) -> Any: ...

    @property
    def solutions(self) -> Sequence[SolutionRow]: ...

    @property
    def rejected(self) -> dict[str, int]: ...

    @property
    def searched(self) -> SearchedSpace: ...


def figure_svg(fig: Figure) -> str:
    """A matplotlib Figure as SVG text."""
    buf = io.StringIO()
    fig.savefig(buf, format="svg")
    return buf.getvalue()


def _table(rows: Iterable[Sequence[object]], header: Sequence[object] | None = None) -> str:
    out = ["<table>"]
    if header:
        out.append("<tr>" + "".join(f"<th>{html.escape(str(h))}</th>" for h in header) + "</tr>")
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>")
    out.append("</table>")
    return "".join(out)


def chain_svg(chain: Chain) -> str:
    """The chain's kinematic skeleton."""
    return skeleton_svg(chain)


def classification_html(result: Classification) -> str:
    """The classification as a table."""
    return f"<b>{html.escape(result.name)}</b>" + _table(result.rows())


def inversions_html(result: InversionTable) -> str:
    """The inversions as a table."""
    header, *rows = result.rows()
    return (f"<b>{html.escape(result.name)}</b>: {result.links} links, {result.classes} "
            "distinct inversions" + _table(rows, header))


def motion_html(motion: Motion) -> str:
    """The motion's summary as a table, and its plot."""
    rows = [("mechanism", motion.name), *summary_rows(motion)]
    return _table(rows) + figure_svg(plot_motion(motion))


def centres_html(centres: InstantCentres) -> str:
    """The centres as a table and the picture of the construction."""
    return (f"<b>{html.escape(centres.name)}</b>: instantaneous centres at input "
            f"{centres.input:.6g}" + _table(centres.rows(), ["centre", "links", "x", "y",
                                                              "found from"])
            + figure_svg(draw_centres(centres)))


def polygons_html(polygons: Polygons) -> str:
    """The images as a table and the two polygons."""
    return (f"<b>{html.escape(polygons.name)}</b>: velocity and acceleration polygons at "
            f"input {polygons.input:.6g}"
            + _table(polygons.image_rows(), ["point", "link", "vx", "vy", "|v|", "ax",
                                             "ay", "|a|"])
            + figure_svg(draw_polygons(polygons)))


def pose_forces_html(result: PoseForces) -> str:
    """The reactions and efforts as tables and the free bodies."""
    efforts = [(e.joint, "-" if e.value is None else f"{e.value:.6g} {e.unit}")
               for e in result.efforts]
    return (f"<b>{html.escape(result.name)}</b>: forces at "
            + ", ".join(f"{j} = {v:.6g}" for j, v in zip(result.inputs, result.at))
            + _table(result.rows(), ["joint", "on", "by", "Fx N", "Fy N", "|F| N",
                                     "normal N", "couple N m"])
            + _table(efforts, ["input", "effort"])
            + "".join(f"<p>{html.escape(n)}</p>" for n in result.notes)
            + free_body_svg(result).split("?>", 1)[-1])


def sweep_forces_html(result: SweepForces) -> str:
    """The summary and the turning-moment diagram."""
    out = (f"<b>{html.escape(result.name)}</b>: forces over {result.steps} steps"
           + _table(result.rows()) + "".join(f"<p>{html.escape(n)}</p>" for n in result.notes))
    if len(result.inputs) == 1:
        out += figure_svg(plot_turning_moment(result))
    return out


def synthesis_html(result: SynthesisResult) -> str:
    """A synthesis: its task, the certified solutions as a table (best first) and the
    best one's drawing (the mechanism at its first target, the targets, and a
    function's structural error), then what was rejected and searched."""
    task = result.task.to_dict()
    what = ", ".join(f"{k} {v}" for k, v in task.items()
                     if k not in ("kind", "units", "min_transmission") and v is not None)
    out = [f"<b>{html.escape(str(task['kind']).capitalize())} synthesis</b>: "
           f"{html.escape(what)}"]
    angles = any(s.error.angle is not None for s in result.solutions)
    header = ["rank", "error max", "error rms"] + (["angle error"] if angles else []) + [
        "transmission", "input", "Grashof", "names", "dimensions"]
    rows = [[s.rank, f"{s.error.max:.6g}", f"{s.error.rms:.6g}"]
            + ([f"{s.error.angle or 0.0:.6g}"] if angles else [])
            + ["-" if s.transmission_angle is None else
               f"{s.transmission_angle[0]:.1f}..{s.transmission_angle[1]:.1f}",
               s.input, s.grashof or "-", "; ".join(s.names),
               ", ".join(f"{k.replace('_', ' ')} {v:.6g}" for k, v in s.dimensions.items())]
            for s in result.solutions]
    out.append(_table(rows, header))
    if result.solutions:
        fig = draw_solution(result.solutions[0])
        assert fig is not None                      # without a path, the figure
        out.append(figure_svg(fig).split("?>", 1)[-1])
    else:
        out.append("<p>No certified solution.</p>")
    rejected = ", ".join(f"{k} {v}" for k, v in result.rejected.items()) or "none"
    s = result.searched
    out.append(f"<p>Rejected: {html.escape(rejected)}; searched {s.chains} chains, "
               f"{s.inversions} inversions, {s.candidates} candidates.</p>")
    return "".join(out)


class Animation:
    """One cycle of a solved motion as an animated SVG (SMIL: no script, no network).
    A notebook shows it inline; :meth:`save` writes it."""

    def __init__(self, svg: str) -> None:
        self.svg = svg

    def __repr__(self) -> str:
        return f"Animation(svg={len(self.svg)} characters)"

    def _repr_svg_(self) -> str:
        return self.svg

    def save(self, path: str | os.PathLike[str]) -> None:
        """Write the SVG to ``path``."""
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.svg)


def animate(motion: Motion, *, frames: int = 48, seconds: float = 4.0) -> Animation:
    """The motion animated, for a notebook (``chaingraph.animate(motion)``).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.naming.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=36)
    >>> a = animate(m, frames=12)
    >>> "<svg" in a.svg and a.svg.count('class="frame"') == 12
    True
    """
    return Animation(mechanism_svg(motion, frames=frames, seconds=seconds))


#: the rich display of each result, by the result's class name: (MIME type, function)
DISPLAYS: dict[str, tuple[str, Callable[[Any], str]]] = {"Chain": ("image/svg+xml", chain_svg),
            "Classification": ("text/html", classification_html),
            "Inversions": ("text/html", inversions_html),
            "Motion": ("text/html", motion_html),
            "InstantCentres": ("text/html", centres_html),
            "Polygons": ("text/html", polygons_html),
            "PoseForces": ("text/html", pose_forces_html),
            "SweepForces": ("text/html", sweep_forces_html)}

#: the rich displays of results whose modules ``import chaingraph`` does not load (a
#: synthesis: its module loads scipy's optimisers), by (module, class name): the shell
#: shows them once the module is loaded, without loading it for them
DISPLAYS_BY_NAME: dict[tuple[str, str], tuple[str, Callable[[Any], str]]] = {
    ("chaingraph.synthesis.result", "Synthesis"): ("text/html", synthesis_html)}


def register(classes: Iterable[type], shell: Any = None) -> bool:
    """Register the rich displays of ``classes`` (the results named in :data:`DISPLAYS`;
    ``chaingraph`` passes its own), and those of :data:`DISPLAYS_BY_NAME` by their
    module and class name, with an IPython shell's display formatters (the running one
    by default); returns whether there was a shell to register with.

    Examples
    --------
    >>> class Formatter:
    ...     def __init__(self): self.types = {}
    ...     def for_type(self, cls, fn): self.types[cls.__name__] = fn
    ...     def for_type_by_name(self, module, name, fn): self.types[name] = fn
    >>> class Shell:
    ...     class display_formatter:
    ...         formatters = {"text/html": Formatter(), "image/svg+xml": Formatter()}
    >>> import chaingraph
    >>> register(chaingraph.RESULTS, Shell())
    True
    >>> sorted(Shell.display_formatter.formatters["text/html"].types)
    ['Classification', 'InstantCentres', 'Inversions', 'Motion', 'Polygons', 'PoseForces', 'SweepForces', 'Synthesis']
    """
    if shell is None:
        try:
            from IPython import get_ipython
        except ImportError:
            return False
        shell = get_ipython()
        if shell is None:
            return False
    formatters = shell.display_formatter.formatters
    for cls in classes:
        mime, fn = DISPLAYS[cls.__name__]
        formatters[mime].for_type(cls, fn)
    for (module, name), (mime, fn) in DISPLAYS_BY_NAME.items():
        formatters[mime].for_type_by_name(module, name, fn)
    return True
