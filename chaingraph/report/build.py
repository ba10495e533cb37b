"""The catalog report: a browsable HTML catalog with drawings, tables and motion.

:func:`build_report` writes ``index.html`` (a table of every entry) and one page per
entry: its link-joint graph, classification with both textbook checks, inversions, and
for a mechanism its drawn pose with the paths of its points, the output's motion, the
summary and an animation of one cycle (an animated SVG). Pages and images are plain
files that open from disk with no network. A file that cannot be read or analysed is
listed on the index as a failure and the rest go on.
"""

from __future__ import annotations

import html
import json
import math
import os
import re
import sys
import warnings
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path

import numpy as np

from chaingraph._util.atomic import staged, write_atomic
from chaingraph._util.parallel import process_runner
from chaingraph._util.progress import ProgressBar
from chaingraph.drawing.constructions import draw_centres, draw_polygons
from chaingraph.drawing.forces import force_polygon_svg, free_body_svg, plot_turning_moment
from chaingraph.drawing.graph import draw_link_joint_graph
from chaingraph.drawing.limits import limits_svg
from chaingraph.drawing.mechanism import frame_steps, mechanism_svg, skeleton_svg
from chaingraph.drawing.plots import output_series, plot_motion
from chaingraph.dynamics import forces
from chaingraph.errors import ChainGraphError
from chaingraph.files import load
from chaingraph.graphical.centres import centres_of
from chaingraph.graphical.polygons import polygons_of
from chaingraph.kinematics import solve, summary_rows
from chaingraph.kinematics.pose import pose_motion
from chaingraph.model.chain import Input
from chaingraph.naming.inversions import inversions
from chaingraph.structure.classify import classify

__all__ = ["Report", "build_report", "chain_paths"]


def _asset(name):
    """A file of the report's own (its style sheet, its scripts), as text."""
    return resources.files("chaingraph.report").joinpath(name).read_text(encoding="utf-8")


_STYLE = _asset("report.css")
_SCRIPT = "\n<script>\n" + _asset("images.js") + "</script>\n"
_PLAYER_SCRIPT = _asset("player.js")




@dataclass
class Entry:
    """One page of the report."""

    source: str
    slug: str
    chain: object = None
    classification: object = None
    inversions: object = None
    motion: object = None
    error: str | None = None
    warnings: list = field(default_factory=list)
    frames: int = 48
    grid: object = None           # two moving inputs: the poses over both, row by row
    centres: object = None        # instantaneous centres at the drawn pose
    polygons: object = None       # velocity and acceleration polygons at the drawn pose
    limits: bool = False          # a time ratio: its limit positions drawn
    forces: object = None         # with masses or loads: the forces over the sweep
    pose_forces: object = None    # and at the sweep's first pose (the free bodies)


@dataclass
class Report:
    """What :func:`build_report` wrote."""

    index: Path
    entries: list        # one Row per chain file, in file order
    failures: list       # (path, problem)

    @property
    def complete(self) -> bool:
        """True when every chain file made its entry."""
        return not self.failures


def chain_paths(paths):
    """The chain files named by ``paths`` (files, or folders of ``*.toml``), and the
    paths that are neither, as (files, problems)."""
    files, problems = [], []
    for p in paths:
        p = Path(p)
        if p.is_dir():
            found = sorted(p.glob("*.toml"))
            if not found:
                problems.append((str(p), "is a folder with no chain files (*.toml)"))
            files += found
        elif p.is_file():
            files.append(p)
        else:
            problems.append((str(p), "no such file or folder"))
    return files, problems


#: names the report itself uses: no entry may take them (a chain file called Index.toml
#: would otherwise overwrite the index, one called img.toml sit beside the image folder)
RESERVED = frozenset({"index", "img"})


def _slug(text, taken):
    base = re.sub(r"[^a-z0-9]+", "-", text.lower()).strip("-") or "entry"
    slug, k = base, 2
    while slug in taken:
        slug, k = f"{base}-{k}", k + 1
    taken.add(slug)
    return slug


def build_report(paths, out_dir, *, progress=sys.stderr, steps=180, frames=48,
                 workers=None) -> Report:
    """Write the HTML catalog of the chain files ``paths`` into ``out_dir``.

    Parameters
    ----------
    paths : sequence of path
        Chain files or folders of them.
    out_dir : path
        Where ``index.html`` and the entry pages and images go (made if missing).
    progress : file, optional
        Where a progress bar goes (stderr by default; None for none).
    steps, frames : int
        Sweep steps of the motion plots, and frames of the animation.
    workers : int, optional
        Processes that analyse and draw entries side by side (default: one per CPU;
        1 works in this process).

    Returns
    -------
    Report
        ``failures`` lists (path, message) of what could not be done; ``complete`` is
        True when there are none.
    """
    if str(out_dir) == "":
        raise ValueError("out_dir is an empty path: give the folder to write the report into")
    cpus = os.cpu_count() or 1
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise ValueError(f"workers must be a whole number of 1 or more, got {workers!r}")
    out = Path(out_dir)
    files, problems = chain_paths(paths)
    failures = list(problems)
    taken = set(RESERVED)
    # built where nobody looks, then moved into place, the index last: an interrupted
    # report leaves the folder as it was (staged)
    with staged(out) as stage:
        (stage / "img").mkdir()
        jobs = [(str(path), _slug(path.stem, taken), str(stage), steps, frames)
                for path in files]
        workers = min(workers or cpus, cpus, max(len(jobs), 1))
        bar = ProgressBar(len(jobs), progress)
        bar.show(0, "")
        results = {}

        def finished(k, row):
            results[jobs[k][1]] = row
            done.append(k)
            bar.show(len(done), Path(jobs[k][0]).name)
        done = []
        try:
            process_runner(workers)(_entry_job, jobs, finished)
        finally:
            bar.close()
        entries = [results[job[1]] for job in jobs]
        failures += [(e.source, e.error) for e in entries if e.error]
        write_atomic(stage / "index.html", _index_page(entries, failures))
    return Report(index=out / "index.html", entries=entries, failures=failures)


@dataclass
class Row:
    """What the index needs of an entry (small, so that processes can send it back)."""

    source: str
    slug: str
    name: str = ""
    family: str = ""
    links: int = 0
    joint_equivalents: int = 0
    mobility: int = 0
    verdict: str = ""
    classes: int | None = None
    time_ratio: float | None = None
    error: str | None = None


def _entry_job(job):
    """Analyse one chain file and write its page and images; returns its index row."""
    source, slug, out, steps, frames = job
    entry = Entry(source=source, slug=slug)
    row = Row(source=source, slug=slug)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            _analyse(entry, steps)
            _write_images(entry, Path(out), frames)
            entry.frames = frames
        write_atomic(Path(out) / f"{slug}.html", _entry_page(entry))
    except ChainGraphError as e:
        row.error = str(e)
        return row
    c = entry.classification
    row.name, row.family = entry.chain.name, entry.chain.family or ""
    row.links, row.joint_equivalents = c.links, c.joint_equivalents
    row.mobility, row.verdict = c.mobility, c.verdict
    row.classes = entry.inversions.classes if entry.inversions is not None else None
    if entry.motion is not None:
        row.time_ratio = entry.motion.summary.time_ratio
    return row


def _analyse(entry, steps):
    chain = load(entry.source)
    entry.chain = chain
    entry.classification = classify(chain)
    if len(chain.pieces) == 1:
        entry.inversions = inversions(chain)
    m = chain.mechanism
    if m is not None and (m.driver is not None or m.inputs) and chain.has_pose:
        try:
            entry.motion = solve(chain, steps=steps)
        except ChainGraphError as e:
            entry.warnings.append(f"motion not solved: {e}")
        else:
            entry.grid = input_grid(chain, entry.motion)
            try:
                state = pose_motion(chain)
            except ChainGraphError as e:
                entry.warnings.append(f"centres and polygons not found: {e}")
            else:
                entry.centres, entry.polygons = centres_of(state), polygons_of(state)
            if chain.masses or chain.loads or chain.gravity:
                try:
                    entry.forces = forces(chain, steps=steps)
                    entry.pose_forces = forces(chain, at=entry.motion.input_values(0))
                except ChainGraphError as e:
                    entry.warnings.append(f"forces not found: {e}")


def input_grid(chain, motion, *, size=13):
    """For a mechanism whose two inputs move, its poses over every pair of input
    values (``size`` values of each over its sweep), as one motion whose rows run
    through the first input for each value of the second: what lets the player's two
    sliders move independently. None when the inputs are not two moving ones, or when
    some pair of values cannot be assembled."""
    if len(motion.inputs) != 2 or motion.plan.moving_inputs != 2:
        return None
    first, second = (np.asarray(motion.values[i.joint]) for i in motion.inputs)
    rows = []
    for value in np.linspace(second[0], second[-1], size):
        try:
            rows.append(solve(chain, inputs=[Input(motion.inputs[0].joint, float(first[0]),
                                                   float(first[-1])),
                                             Input(motion.inputs[1].joint, float(value),
                                                   float(value))],
                              steps=size - 1, summary=False))
        except ChainGraphError:
            return None
    return replace(rows[0].joined(*rows[1:]), name=motion.name, fixed=motion.fixed,
                   driver=None, omega=motion.omega, summary=None, units=motion.units,
                   inputs=motion.inputs)


# -- images ----------------------------------------------------------------------------
def _write_images(entry, out, frames):
    img = out / "img"
    draw_link_joint_graph(entry.chain, img / f"{entry.slug}-graph.svg")
    (img / f"{entry.slug}-skeleton.svg").write_text(skeleton_svg(entry.chain), encoding="utf-8")
    if entry.motion is not None:
        (img / f"{entry.slug}-pose.svg").write_text(mechanism_svg(entry.motion),
                                                     encoding="utf-8")
        plot_motion(entry.motion, img / f"{entry.slug}-motion.svg")
        (img / f"{entry.slug}-cycle.svg").write_text(
            mechanism_svg(entry.motion, frames=frames), encoding="utf-8")
    if entry.motion is not None and entry.motion.summary.time_ratio is not None:
        try:
            (img / f"{entry.slug}-limits.svg").write_text(limits_svg(entry.motion),
                                                          encoding="utf-8")
            entry.limits = True
        except ChainGraphError as e:
            entry.warnings.append(f"limit positions not drawn: {e}")
    if entry.pose_forces is not None:
        (img / f"{entry.slug}-free-bodies.svg").write_text(free_body_svg(entry.pose_forces),
                                                            encoding="utf-8")
        polygons = force_polygon_svg(entry.pose_forces)
        if polygons is not None:
            (img / f"{entry.slug}-force-polygons.svg").write_text(polygons, encoding="utf-8")
        if len(entry.forces.inputs) == 1:
            plot_turning_moment(entry.forces, img / f"{entry.slug}-turning-moment.svg")
    if entry.centres is not None:
        draw_centres(entry.centres, img / f"{entry.slug}-centres.svg")
        draw_polygons(entry.polygons, img / f"{entry.slug}-polygons.svg")


# -- pages ------------------------------------------------------------------------------
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


def _index_page(rows, failures):
    lines = []
    for r in rows:
        if r.error:
            continue
        lines.append(
            f"<tr><td><a href=\"{r.slug}.html\">{_esc(r.name)}</a></td>"
            f"<td>{_esc(r.family)}</td><td class=\"num\">{r.links}</td>"
            f"<td class=\"num\">{r.joint_equivalents}</td><td class=\"num\">{r.mobility}</td>"
            f"<td>{_esc(r.verdict)}</td><td class=\"num\">{_fmt(r.classes)}</td>"
            f"<td class=\"num\">{_fmt(r.time_ratio, 5)}</td></tr>")
    body = ["<h1>Catalog of kinematic chains and mechanisms</h1>",
            f"<p>{len(lines)} entries. Each entry's page has its link-joint graph, its "
            "classification with the textbook's checks, its inversions and, for a "
            "mechanism, its motion.</p>",
            "<table id=\"entries\"><thead><tr><th>name</th><th>family</th><th>L</th>"
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


def _entry_page(e):
    chain, c = e.chain, e.classification
    body = ["<nav><a href=\"index.html\">&larr; index</a></nav>",
            f"<h1>{_esc(chain.name)}</h1>",
            f"<p><b>Family:</b> {_esc(chain.family or '–')} &nbsp; <b>File:</b> "
            f"<code>{_esc(Path(e.source).name)}</code></p>"]
    if chain.notes:
        body.append(f"<p class=\"notes\">{_esc(chain.notes)}</p>")
    body.append("<h2>The chain and its link-joint graph</h2><div class=\"figures\">")
    body.append(f"<figure><img src=\"img/{e.slug}-skeleton.svg\" alt=\"kinematic skeleton of "
                f"{_esc(chain.name)}\" width=\"360\"><figcaption>The kinematic skeleton: "
                "links as bars and plates, R joints as pins, P joints as blocks"
                + (", from the drawn pose" if chain.has_pose else ", in a computed layout "
                   "(the file gives no pose)") + ".</figcaption></figure>")
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
    for w in e.warnings:
        body.append(f"<p class=\"fail\">{_esc(w)}</p>")
    body.append("<p><a href=\"index.html\">&larr; back to the index</a></p>")
    return _page(chain.name, "\n".join(body))


def _motion_section(e):
    rows = summary_rows(e.motion)
    out = ["<h2>Motion</h2><table id=\"summary\">"]
    out += [f"<tr><th>{_esc(a)}</th><td>{_esc(b)}</td></tr>" for a, b in rows]
    out.append("</table>")
    out += _player(e)
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
                   "turning-moment diagram\" width=\"640\"><figcaption>The effort the input "
                   "needs over the sweep, its mean and the swing of energy about it."
                   "</figcaption></figure>")
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


def _player(e):
    """The interactive cycle: the animated drawing inline, play/pause, a slider per
    input and the output's plot with the current point marked. A small inline script
    drives it; without script the drawing plays by SMIL. With two moving inputs the
    sliders are independent (the drawing holds a pose for every pair of values);
    otherwise they follow the one sweep together."""


    m = e.grid if e.grid is not None else e.motion
    grid = e.grid is not None
    picks = list(range(m.theta.size)) if grid else frame_steps(m, e.frames)
    drawing = mechanism_svg(m, frames=len(picks), width=480, paths=not grid).split("?>", 1)[-1]
    if m.inputs:
        inputs = [(i.joint, m.values[i.joint]) for i in m.inputs]
    else:
        inputs = [("\u03b8 (degrees)", m.theta)]
    label, u, *_ = output_series(m)
    if grid:
        size = int(round(math.sqrt(m.theta.size)))
        data = {"grid": size, "inputs": [[float(v) for v in inputs[0][1][:size]],
                                         [float(v) for v in inputs[1][1][::size]]]}
    else:
        size = None
        data = {"inputs": [[float(v[k]) for k in picks] for _, v in inputs]}
    out = ["<h3>" + ("Drag each input" if grid else "One cycle: play it, or drag the input")
           + "</h3>",
           f"<div class=\"player\" id=\"player\" data-frame=\"0\" data-frames=\"{len(picks)}\">",
           "<div class=\"controls\"><button type=\"button\" id=\"play\">pause</button>"]
    for n, (name, values) in enumerate(inputs):
        top = (size if grid else len(picks)) - 1
        out.append(f"<label>{_esc(name)} <input type=\"range\" class=\"input-slider\" "
                   f"data-index=\"{n}\" min=\"0\" max=\"{top}\" step=\"1\" "
                   f"value=\"0\"> <output>{values[picks[0]]:.4g}</output></label>")
    out.append("</div>")
    out.append(f"<div class=\"stage\" id=\"stage\">{drawing}</div>")
    x = np.asarray(inputs[0][1] if grid else m.theta, dtype=float)
    y = np.asarray(u, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y)
    w, h, pad = 480.0, 200.0, 24.0
    x0, x1 = float(x[ok].min()), float(x[ok].max())
    y0, y1 = float(y[ok].min()), float(y[ok].max())

    def px(v):
        return pad + (v - x0) / max(x1 - x0, 1e-12) * (w - 2 * pad)

    def py(v):
        return h - pad - (v - y0) / max(y1 - y0, 1e-12) * (h - 2 * pad)

    runs = [range(r, r + size) for r in range(0, x.size, size)] if grid else [range(x.size)]
    lines = "".join(
        "<polyline points=\"" + " ".join(f"{px(x[k]):.2f},{py(y[k]):.2f}" for k in run if ok[k])
        + "\" fill=\"none\" stroke=\"#1f4e79\" stroke-width=\"" + ("0.8" if grid else "1.5")
        + "\"/>" for run in runs)
    data["px"] = [px(float(x[k])) if ok[k] else None for k in picks]
    data["py"] = [py(float(y[k])) if ok[k] else None for k in picks]
    against = f"{inputs[0][0]}, one line per value of {inputs[1][0]}" if grid else "the input"
    out.append(f"<div class=\"stage\"><svg id=\"output-plot\" xmlns=\"http://www.w3.org/2000/svg\" "
               f"width=\"{w:g}\" height=\"{h:g}\" viewBox=\"0 0 {w:g} {h:g}\">"
               f"<rect width=\"100%\" height=\"100%\" fill=\"white\"/>{lines}"
               f"<circle id=\"marker\" cx=\"{data['px'][0] or 0:.2f}\" cy=\"{data['py'][0] or 0:.2f}\" "
               f"r=\"5\" fill=\"#e07b00\"/>"
               f"<text x=\"{pad:g}\" y=\"14\" font-size=\"11\" font-family=\"sans-serif\">"
               f"{_esc(label)} against {_esc(against)}</text></svg></div>")
    out.append(f"<p><a href=\"img/{e.slug}-cycle.svg\">the animation alone</a> (SVG, plays "
               "without script)</p></div>")
    out.append("<script>\nvar PLAYER = " + json.dumps(data) + ";\n" + _PLAYER_SCRIPT + "</script>")
    return out


