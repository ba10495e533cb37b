"""Displays in a notebook: short plain reprs and rich HTML and SVG for chains,
classifications, inversions and solved motions, and an inline animation.

The classes call these functions from their ``_repr_*_`` methods, so Jupyter shows a
chain as its kinematic skeleton, a classification and inversions as tables, and a motion
as its summary and plot. Nothing here needs IPython; :meth:`Motion.to_frame` needs
pandas (``pip install chaingraph[notebook]``).
"""

from __future__ import annotations

import html
import io

__all__ = ["Animation", "animate", "figure_svg", "short_list"]


def short_list(items, keep=6) -> str:
    """``[a, b, c, ... (N)]``: a list cut to ``keep`` items for a repr.

    Examples
    --------
    >>> short_list(["theta", "x:A", "y:A"], keep=2)
    "['theta', 'x:A', ... (3)]"
    """
    items = list(items)
    if len(items) <= keep:
        return repr(items)
    return "[" + ", ".join(repr(x) for x in items[:keep]) + f", ... ({len(items)})]"


def figure_svg(fig) -> str:
    """A matplotlib Figure as SVG text."""
    buf = io.StringIO()
    fig.savefig(buf, format="svg")
    return buf.getvalue()


def _table(rows, header=None) -> str:
    out = ["<table>"]
    if header:
        out.append("<tr>" + "".join(f"<th>{html.escape(str(h))}</th>" for h in header) + "</tr>")
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>")
    out.append("</table>")
    return "".join(out)


def chain_svg(chain) -> str:
    from .drawing import skeleton_svg
    return skeleton_svg(chain)


def classification_html(result) -> str:
    rows = [("links L", result.links), ("pairs P", result.pairs),
            ("joint equivalents J", result.joint_equivalents),
            ("higher pairs H", result.higher_pairs), ("loops", result.loops),
            ("mobility F", result.mobility)]
    rows += [(c.rule, f"{c.lhs} vs {c.rhs}: {c.verdict}" if c.applicable
              else f"not applicable: {c.note}") for c in result.checks]
    rows += [("verdict", result.verdict), ("degenerate", "yes" if result.degenerate else "no")]
    return f"<b>{html.escape(result.name)}</b>" + _table(rows)


def inversions_html(result) -> str:
    rows = [(i.fixed, i.class_, "; ".join(i.names) or "-", i.behaviour or "-")
            for i in result.inversions]
    return (f"<b>{html.escape(result.name)}</b>: {result.links} links, {result.classes} "
            "distinct inversions" + _table(rows, ["fixed", "class", "names", "behaviour"]))


def motion_html(motion) -> str:
    from .kinematics import summary_rows
    from .plots import plot_motion
    rows = [("mechanism", motion.name), *summary_rows(motion)]
    return _table(rows) + figure_svg(plot_motion(motion))


def centres_html(centres) -> str:
    """The centres as a table and the picture of the construction."""
    from .graphical.draw import draw_centres
    return (f"<b>{html.escape(centres.name)}</b>: instantaneous centres at input "
            f"{centres.input:.6g}" + _table(centres.rows(), ["centre", "links", "x", "y",
                                                              "found from"])
            + figure_svg(draw_centres(centres)))


def polygons_html(polygons) -> str:
    """The images as a table and the two polygons."""
    from .graphical.draw import draw_polygons
    return (f"<b>{html.escape(polygons.name)}</b>: velocity and acceleration polygons at "
            f"input {polygons.input:.6g}"
            + _table(polygons.image_rows(), ["point", "link", "vx", "vy", "|v|", "ax",
                                             "ay", "|a|"])
            + figure_svg(draw_polygons(polygons)))


class Animation:
    """One cycle of a solved motion as an animated SVG (SMIL: no script, no network).
    A notebook shows it inline; :meth:`save` writes it."""

    def __init__(self, svg: str):
        self.svg = svg

    def __repr__(self):
        return f"Animation(svg={len(self.svg)} characters)"

    def _repr_svg_(self):
        return self.svg

    def save(self, path) -> None:
        with open(path, "w", encoding="utf-8") as f:
            f.write(self.svg)


def animate(motion, *, frames=48, seconds=4.0) -> Animation:
    """The motion animated, for a notebook (``chaingraph.animate(motion)``).

    Examples
    --------
    >>> import chaingraph
    >>> from chaingraph.catalog import catalog_path
    >>> m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=36)
    >>> a = animate(m, frames=12)
    >>> "<svg" in a.svg and a.svg.count('class="frame"') == 12
    True
    """
    from .drawing import mechanism_svg
    return Animation(mechanism_svg(motion, frames=frames, seconds=seconds))
