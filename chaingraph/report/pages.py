"""The report's pages: the index of the entries and each entry's page (HTML text from
what the job found and drew)."""

from __future__ import annotations

import html
import math
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

from chaingraph.drawing.forces import force_polygon_svg
from chaingraph.kinematics import summary_rows
from chaingraph.report.gears import gears_section
from chaingraph.report.player import player_html

if TYPE_CHECKING:                       # the runner's records; it imports this module
    from chaingraph.report.build import Entry, Row

__all__ = ["index_page", "entry_page"]


def _asset(name):
    """A file of the report's own (its style sheet, its scripts), as text."""
    return resources.files("chaingraph.report").joinpath(name).read_text(encoding="utf-8")


_STYLE = _asset("report.css")
_SCRIPT = "\n<script>\n" + _asset("images.js") + "</script>\n"


def _esc(x):
    return html.escape(str(x))


def _page(title, body):
    return (f"<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>{_esc(title)}</title><style>{_STYLE}</style></head>\n<body>\n{body}\n"
            f"{_SCRIPT}</body></html>\n")


def _fmt(value, digits=6):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    if isinstance(value, float):
        return f"{value:.{digits}g}"
    return _esc(value)


def index_page(rows: list[Row], failures: list[tuple[str, str]]) -> str:
    """The index: a row per entry made (``rows``), and the ``failures`` (path, problem)."""
    lines = []
    for r in rows:
        if r.error:
            continue
        lines.append(
            f"<tr><td><a href=\"{r.slug}.html\"><img class=\"thumb\" src=\"{_esc(r.picture)}\" "
            f"alt=\"\" height=\"56\"></a></td>"
            f"<td><a href=\"{r.slug}.html\">{_esc(r.name)}</a></td>"
            f"<td>{_esc(r.family)}</td><td class=\"num\">{r.links}</td>"
            f"<td class=\"num\">{r.joint_equivalents}</td><td class=\"num\">{r.mobility}</td>"
            f"<td>{_esc(r.verdict)}</td><td class=\"num\">{_fmt(r.classes)}</td>"
            f"<td class=\"num\">{_fmt(r.time_ratio, 5)}</td></tr>")
    body = ["<h1>Catalog of kinematic chains and mechanisms</h1>",
            f"<p>{len(lines)} entries, each pictured by its skeleton (a gear train by its "
            "drawing). Each entry's page has its link-joint graph, its classification "
            "with the textbook's checks, its inversions and, for a mechanism, its motion; "
            "for a gear train, its speeds.</p>",
            "<table id=\"entries\"><thead><tr><th>picture</th><th>name</th><th>family</th><th>L</th>"
            "<th>J</th><th>mobility</th><th>verdict</th><th>inversion classes</th>"
            "<th>time ratio</th></tr></thead><tbody>", *lines, "</tbody></table>"]
    if failures:
        body.append("<h2 class=\"fail\">Not included</h2><table id=\"failures\"><tr><th>file"
                    "</th><th>problem</th></tr>")
        body += [f"<tr><td>{_esc(p)}</td><td class=\"fail\">{_esc(m)}</td></tr>"
                 for p, m in failures]
        body.append("</table>")
    body.append("<p><small>Made by chaingraph.</small></p>")
    return _page("Catalog of kinematic chains and mechanisms", "\n".join(body))


def entry_page(e: Entry) -> str:
    """An entry's page: its chain, graph, classification, inversions and, for a
    mechanism, its motion, limit positions, centres and polygons, and forces."""
    chain, c = e.chain, e.classification
    body = ["<nav><a href=\"index.html\">&larr; index</a></nav>",
            f"<h1>{_esc(chain.name)}</h1>",
            f"<p><b>Family:</b> {_esc(chain.family or '–')} &nbsp; <b>File:</b> "
            f"<code>{_esc(Path(e.source).name)}</code></p>"]
    if chain.notes:
        body.append(f"<p class=\"notes\">{_esc(chain.notes)}</p>")
    if e.train is not None:
        body += gears_section(chain, e.slug, e.train, e.ways)
    body.append("<h2>The chain and its link-joint graph</h2><div class=\"figures\">")
    if e.train is None:
        body.append(f"<figure><img src=\"img/{e.slug}-skeleton.svg\" alt=\"kinematic "
                    f"skeleton of {_esc(chain.name)}\" width=\"360\"><figcaption>The "
                    "kinematic skeleton: links as bars and plates, R joints as pins, P "
                    "joints as blocks"
                    + (", from the drawn pose" if chain.has_pose else ", in a computed "
                       "layout (the file gives no pose)") + ".</figcaption></figure>")
    body.append(f"<figure><img src=\"img/{e.slug}-graph.svg\" alt=\"link-joint graph of "
                f"{_esc(chain.name)}\" width=\"560\"><figcaption>Links as circles, joints as "
                "squares labelled with their kind (R turning, P sliding: the arrow points to "
                "the link carrying the guide; higher pairs dashed); the fixed link is drawn "
                "dark.</figcaption></figure></div>")
    body.append("<h2>Classification</h2><table id=\"classification\">")
    facts = [row for row in c.rows() if row[0] not in {ch.rule for ch in c.checks}]
    body += [f"<tr><th>{_esc(a)}</th><td class=\"num\">{_esc(b)}</td><td>{_esc(d)}</td></tr>"
             for a, b, d in facts]
    body.append("</table><table id=\"checks\"><tr><th>check</th><th>LHS</th><th>RHS</th>"
                "<th>verdict</th><th>note</th></tr>")
    for ch in c.checks:
        body.append(f"<tr><td>{_esc(ch.rule)}</td><td class=\"num\">{_fmt(ch.lhs)}</td>"
                    f"<td class=\"num\">{_fmt(ch.rhs)}</td>"
                    f"<td>{_esc(ch.verdict) if ch.applicable else 'not applicable'}</td>"
                    f"<td>{_esc(ch.note)}</td></tr>")
    body.append("</table>")
    for o in c.oddities:
        body.append(f"<p>{_esc(o)}</p>")
    if e.inversions is not None:
        inv = e.inversions
        body.append(f"<h2>Inversions</h2><p>{len(inv.inversions)} inversions in "
                    f"{inv.classes} {'class' if inv.classes == 1 else 'classes'} by "
                    "structure.</p><table id=\"inversions\"><tr><th>fixed link</th>"
                    "<th>class</th><th>behaviour</th><th>names</th></tr>")
        for i, (fixed, class_, how, names) in zip(inv.inversions, inv.rows()[1:]):
            body.append(f"<tr><td>{_esc(fixed)}</td><td class=\"num\">{class_}</td>"
                        f"<td>{_esc(how)}</td><td>{_esc(names)}"
                        + (f"<br><small>{_esc(i.note)}</small>" if i.note else "")
                        + "</td></tr>")
        body.append("</table>")
    if e.motion is not None:
        body += _motion_section(e)
    if chain.task:
        body += _task_section(e)
    for w in e.warnings:
        body.append(f"<p class=\"fail\">{_esc(w)}</p>")
    body.append("<p><a href=\"index.html\">&larr; back to the index</a></p>")
    return _page(chain.name, "\n".join(body))


def _motion_section(e):
    rows = summary_rows(e.motion)
    out = ["<h2>Motion</h2><table id=\"summary\">"]
    out += [f"<tr><th>{_esc(a)}</th><td>{_esc(b)}</td></tr>" for a, b in rows]
    out.append("</table>")
    out += player_html(e)
    out.append("<div class=\"figures\">")
    out.append(f"<figure><img src=\"img/{e.slug}-pose.svg\" alt=\"drawn pose\" width=\"480\">"
               "<figcaption>The drawn pose with the paths of its joints and points."
               "</figcaption></figure>")
    out.append(f"<figure><img src=\"img/{e.slug}-motion.svg\" alt=\"output motion\" "
               "width=\"560\"><figcaption>The output's displacement, velocity and "
               "acceleration against the input angle.</figcaption></figure></div>")
    if e.limits:
        s = e.motion.summary
        out.append(f"<h2>Limit positions</h2><div class=\"figures\"><figure><img "
                   f"src=\"img/{e.slug}-limits.svg\" alt=\"limit positions\" width=\"560\">"
                   f"<figcaption>The output at the two ends of its stroke ({_esc(_fmt(s.stroke))}"
                   f" {_esc(s.stroke_unit or '')}): the two poses overlaid, the second dashed; "
                   f"the input's arcs between them, forward {_esc(_fmt(s.forward_deg))}° and "
                   f"return {_esc(_fmt(s.return_deg))}°, so the time ratio "
                   f"{_esc(_fmt(s.time_ratio))}.</figcaption></figure></div>")
    if e.centres is not None:
        out += _graphical_section(e)
    if e.pose_forces is not None:
        out += _forces_section(e)
    return out


def _forces_section(e):
    """The forces: the summary over the sweep, the free bodies at its first pose and
    the turning-moment diagram."""
    f, pose = e.forces, e.pose_forces
    kind = "static" if f.static else f"kinetostatic, {_pose_speed(e)}"
    out = [f"<h2>Forces</h2><p>From the file's masses, gravity and loads ({_esc(kind)}); "
           "<code>chaingraph forces</code> gives them at any pose and speed.</p>"
           "<table id=\"forces\">"]
    out += [f"<tr><th>{_esc(a)}</th><td>{_esc(b)}</td></tr>" for a, b in f.rows()]
    out.append("</table>")
    out += [f"<p>{_esc(n)}</p>" for n in f.notes]
    out.append("<div class=\"figures\">")
    at = ", ".join(f"{j} = {v:.6g}" for j, v in zip(pose.inputs, pose.at))
    out.append(f"<figure><img src=\"img/{e.slug}-free-bodies.svg\" alt=\"free bodies\" "
               f"width=\"720\"><figcaption>The free bodies at {_esc(at)}: every moving link "
               "with the forces on it, to one scale (red the joints' reactions, blue the "
               "loads, green the weights, grey dashed the inertia forces, black an "
               "input's effort).</figcaption></figure>")
    if force_polygon_svg(pose) is not None:
        out.append(f"<figure><img src=\"img/{e.slug}-force-polygons.svg\" alt=\"force "
                   "polygons\" width=\"420\"><figcaption>The force polygon of each dyad, "
                   "as the graphical method draws it: the forces on its links head to "
                   "tail, closing; dashed, the reaction between its two links."
                   "</figcaption></figure>")
    if len(f.inputs) == 1:
        out.append(f"<figure><img src=\"img/{e.slug}-turning-moment.svg\" alt=\""
                   "turning-moment diagram\" width=\"640\"><figcaption>The turning-moment "
                   "diagram over the cycle: the moment an engine delivers to its shaft (or "
                   "the effort a driven machine needs), its mean and the energy of each loop "
                   "about it.</figcaption></figure>")
    if f.shaking is not None:
        out.append(f"<figure><img src=\"img/{e.slug}-shaking.svg\" alt=\"polar diagram of "
                   "the shaking force\" width=\"420\"><figcaption>The shaking force: the "
                   "force the moving links put on the frame over the cycle (weights, loads "
                   "and inertia), its tip traced about the origin.</figcaption></figure>")
    out.append("</div>")
    return out


def _pose_speed(e):
    """The input speed the inertia forces are worked out at, in words."""
    lead = e.motion.plan.inputs[e.motion.plan.lead]
    unit = "rad/s" if lead.kind == "R" else f"{e.chain.units}/s"
    return f"input at {e.motion.omega:g} {unit}"


def _graphical_section(e):
    """The instantaneous centres and the polygons at the drawn pose."""
    centres, polygons = e.centres, e.polygons
    state = centres.state
    out = [f"<h2>Instantaneous centres and polygons</h2><p>At the drawn pose "
           f"({_esc(state.input_text('θ', '°'))}, "
           f"{_esc(state.speed_text)}). Links numbered "
           + ", ".join(f"{n} {_esc(link)}" for link, n in centres.numbers.items())
           + ".</p><table id=\"centres\"><tr><th>centre</th><th>links</th><th>x</th>"
           "<th>y</th><th>found from</th></tr>"]
    out += ["<tr>" + "".join(f"<td>{_esc(c)}</td>" for c in row) + "</tr>"
            for row in centres.rows()]
    out.append("</table>")
    closure = polygons.closure
    out.append("<div class=\"figures\">")
    out.append(f"<figure><img src=\"img/{e.slug}-centres.svg\" alt=\"instantaneous "
               "centres\" width=\"720\"><figcaption>The centres: filled from the joints, "
               "open by Kennedy's theorem (the two lines that met dashed); the circle "
               "diagram.</figcaption></figure>")
    out.append(f"<figure><img src=\"img/{e.slug}-polygons.svg\" alt=\"velocity and "
               "acceleration polygons\" width=\"720\"><figcaption>The velocity and "
               "acceleration polygons (loops close to "
               f"{closure['velocity']:.2g} and {closure['acceleration']:.2g}).</figcaption>"
               "</figure></div>")
    return out


#: the [task] keys shown, in this order, with their labels (the rest follow as written)
_TASK_KEYS = {"kind": "kind", "function": "y =", "x": "x from, to",
              "swing": "input, output swing", "start": "input, output at x = A",
              "points": "precision points", "spacing": "spacing",
              "precision_x": "precision points' x", "targets": "targets (x, y)",
              "timing": "input at each target", "closed": "closed curve",
              "poses": "poses (x, y, degrees)", "mechanism": "mechanism",
              "min_transmission": "least transmission angle"}


def _task_value(value):
    if isinstance(value, list):
        return "; ".join(_task_value(v) if isinstance(v, list) else _fmt(v) for v in value)
    return _fmt(value)


def _task_section(e):
    """A synthesised mechanism's task: its [task] table (what it was designed to do)
    and, drawn as the synthesis draws it, the mechanism at its first target with the
    targets (points, poses as small frames) and, for a function generator, its
    structural error over the range with the precision points marked."""
    task = e.chain.task
    keys = [k for k in _TASK_KEYS if k in task] + sorted(set(task) - set(_TASK_KEYS))
    out = ["<h2>Synthesis task</h2><p>What this mechanism was designed to do (its "
           "<code>[task]</code> table, written by <code>chaingraph design</code>, which "
           "<code>solve</code> ignores); it was certified by chaingraph's solver from "
           "its file.</p><table id=\"task\">"]
    out += [f"<tr><th>{_esc(_TASK_KEYS.get(k, k))}</th><td>{_esc(_task_value(task[k]))}"
            "</td></tr>" for k in keys]
    out.append("</table>")
    if e.task is not None:
        what = ("its structural error over the range (the output's departure from the "
                "task, from the solver's motion), the precision points marked"
                if e.task["curve"] is not None else
                "the targets marked" if e.task["targets"] else
                "the poses as small numbered frames")
        out.append(f"<div class=\"figures\"><figure><img src=\"img/{e.slug}-task.svg\" "
                   "alt=\"the synthesis task\" width=\"760\"><figcaption>The mechanism at "
                   f"its first target with its joints' paths, and {what}.</figcaption>"
                   "</figure></div>")
    return out
