"""The illustrated atlas: a browsable index of the chains with sliding pairs or
multiple joints, and a page per chain with its skeleton in a generic pose, its
link-joint graph, its classification, its inversions with the catalog's names and,
for each inversion with a natural input, its motion over the range it can be
assembled in, animated, and a chain file that ``chaingraph solve`` runs as is.
"""

from __future__ import annotations

import html
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeAlias

from chaingraph._util.atomic import withdraw
from chaingraph._util.parallel import process_runner
from chaingraph.drawing.mechanism import skeleton_svg
from chaingraph.errors import ChainGraphError
from chaingraph.files import dumps
from chaingraph.naming.atlas import atlas_names, named_mechanisms
from chaingraph.report.animation import animate_inversion
from chaingraph.report.atlas_index import thumbnail_svg, write_index
from chaingraph.structure.atlas.estimate import LOCAL_HOURS
from chaingraph.structure.atlas.sliding import SlidingAtlas
from chaingraph.structure.atlas.illustrate import (
    generic_pose,
    inversion_mechanism,
    link_layout,
    natural_input,
)
from chaingraph.structure.classification import classify
from chaingraph.structure.isomorphism import automorphism_orbits

__all__ = ["write_illustrated", "IllustratedPage", "animated_by_default",
           "animation_seconds", "SECONDS_PER_INVERSION"]

_STYLE = ("body{font-family:sans-serif;margin:1.5em;max-width:70em}"
          "table{border-collapse:collapse;margin:.6em 0}"
          "td,th{border:1px solid #ccc;padding:.2em .5em;text-align:left;vertical-align:top}"
          "figure{display:inline-block;margin:.4em;text-align:center}"
          "figcaption{font-size:.85em}svg{max-width:100%;height:auto}")


@dataclass(frozen=True)
class IllustratedPage:
    """What was written for one chain: its page, its chain files (one per inversion with
    a natural input) and how many of those inversions were animated."""

    chain_id: int
    page: Path
    chain_files: tuple
    animated: int
    failed: tuple                # (fixed link, message) of inversions that did not solve


def _esc(x):
    return html.escape(str(x))


def _graph_svg(chain, size=260):
    """The link-joint graph: links as circles, joints as squares (sliding pairs filled),
    at the generic layout's places."""
    places = link_layout(chain)
    pts = {("link", x): p for x, p in places.items()}
    for j in chain.joints:
        xs = [places[x] for x in j.links]
        pts[("joint", j.id)] = (sum(p[0] for p in xs) / len(xs), sum(p[1] for p in xs) / len(xs))
    lo_x = min(p[0] for p in pts.values()) - 12
    lo_y = min(p[1] for p in pts.values()) - 12
    span = max(max(p[0] for p in pts.values()) - lo_x, max(p[1] for p in pts.values()) - lo_y) + 12

    def xy(p):
        return (p[0] - lo_x) * size / span, (p[1] - lo_y) * size / span
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" '
           f'class="link-joint-graph">']
    for j in chain.joints:
        a = xy(pts[("joint", j.id)])
        for x in j.links:
            b = xy(pts[("link", x)])
            out.append(f'<line x1="{a[0]:.1f}" y1="{a[1]:.1f}" x2="{b[0]:.1f}" y2="{b[1]:.1f}" '
                       'stroke="#888"/>')
    for x in chain.links:
        a = xy(pts[("link", x)])
        out.append(f'<circle cx="{a[0]:.1f}" cy="{a[1]:.1f}" r="9" fill="#dbe8f6" '
                   f'stroke="#1f4e79"/><text x="{a[0]:.1f}" y="{a[1] + 3:.1f}" font-size="8" '
                   f'text-anchor="middle">{_esc(x)}</text>')
    for j in chain.joints:
        a = xy(pts[("joint", j.id)])
        fill = "#444" if j.kind == "P" else "white"
        out.append(f'<rect class="joint" x="{a[0] - 4:.1f}" y="{a[1] - 4:.1f}" width="8" '
                   f'height="8" fill="{fill}" stroke="#222"/>')
    out.append("</svg>")
    return "".join(out)


@dataclass(frozen=True)
class _Figure:
    """One animated (or drawn) inversion on a chain's page: its heading (a catalog name,
    or None), its chain file's name and text, its picture (None when not animated or
    not solved), what the page says under it, and why it failed to solve."""

    title: str | None
    file: str
    text: str
    svg: str | None
    notes: tuple
    failed: str | None = None


#: one chain's page as a worker computes it: (html, chain files (name, text), how many
#: inversions were animated, those that failed (link, why), its catalog names, its thumbnail)
PageJob: TypeAlias = tuple[str, list[tuple[str, str]], int, tuple[tuple[str, str], ...],
                           dict[str, list[Any]], str]


def _page_job(task: tuple[Any, ...]) -> PageJob:
    """Everything of one chain's page, computed in a worker: (html, chain files, how many
    inversions were animated, those that failed, its catalog names, its thumbnail)."""
    entry, dof, oriented, animate, frames = task
    chain = generic_pose(entry.chain(dof))
    names = atlas_names(chain, oriented=oriented)
    named = {link: c["names"] for c in names["inversions"] for link in c["links"]}
    proportioned = named_mechanisms(chain, oriented=oriented)
    rows = classify(chain).rows()
    classes = automorphism_orbits(chain, oriented=oriented)
    sections, files, failed, animated = [], [], [], 0
    for i, links in enumerate(classes, start=1):
        label = ", ".join(named.get(links[0], [])) or f"inversion {i}"
        stem = f"chain-{entry.id}-inversion-{i}"
        mine = [m for m in proportioned if m.links == links]
        if mine:
            figures = [_named_figure(m, stem if n == 0 else f"{stem}-{m.source}", animate,
                                     frames) for n, m in enumerate(mine)]
        elif natural_input(chain, links[0]) is None:
            figures = []
        else:
            figures = [_generic_figure(entry, dof, chain, links[0], f"{chain.name}: {label}",
                                       stem, animate, frames)]
        for f in figures:
            files.append((f.file, f.text))
            animated += f.svg is not None
            if f.failed:
                failed.append((links[0], f.failed))
        sections.append((i, links, label, figures))
    page = _page_html(entry, chain, names, rows, sections, animate)
    return page, files, animated, tuple(failed), names, thumbnail_svg(chain)


def _named_figure(named, stem, animate, frames):
    """A catalog mechanism of the chain's structure, animated with its own proportions
    (scaled), so that it moves as its name says."""
    scale = "" if named.scale == 1 else f", scaled by {named.scale:g}"
    notes = (f"Shown with the proportions of the catalog's {named.name} "
             f"(catalog/{named.source}.toml{scale}).",)
    return _animated(named.mechanism, named.name, stem, notes, animate, frames)[0]


def _generic_figure(entry, dof, chain, fixed, name, stem, animate, frames):
    """An inversion in the chain's generic pose; one that its generic pose makes hard
    to read (the links fill the picture over less than :data:`_READABLE` of its range)
    in the first other generic pose that does better."""
    mechanism = inversion_mechanism(chain, fixed, name=name)
    best = _animated(mechanism, None, stem, ("Shown in the chain's generic pose.",),
                     animate, frames)
    for seed in range(1, _SEEDS + 1):
        if not animate or best[1] >= _READABLE or best[0].svg is None:
            break
        other = inversion_mechanism(generic_pose(entry.chain(dof), seed=seed), fixed,
                                    name=name)
        why = (f"Re-proportioned: in the chain's generic pose the links fill the picture "
               f"over only {best[1]:.0%} of this inversion's range; shown in another "
               f"generic pose (number {seed}).",)
        tried = _animated(other, None, stem, why, animate, frames)
        if tried[0].svg is not None and tried[1] > best[1] + 0.05:
            best = tried
    return best[0]


#: an inversion is re-proportioned when its links fill the picture over less than this
#: share of its input's range, trying up to :data:`_SEEDS` other generic poses
_READABLE, _SEEDS = 0.3, 3


def _animated(mechanism, title, stem, notes, animate, frames):
    """(the figure, the share of the range shown) of ``mechanism``."""
    if not animate:
        return _Figure(title, f"{stem}.toml", dumps(mechanism), None, notes), 1.0
    try:
        a = animate_inversion(mechanism, frames=frames, width=300)
    except ChainGraphError as e:
        return _Figure(title, f"{stem}.toml", dumps(mechanism), None, notes, str(e)), 0.0
    return _Figure(title, f"{stem}.toml", dumps(a.mechanism), a.svg, notes + a.notes), \
        a.shown


def _page_html(entry, chain, names, rows, sections, animate):
    """The chain's page: skeleton, link-joint graph, classification, inversions."""
    body = [f"<p><a href=\"index.html\">atlas</a></p><h1>{_esc(chain.name)}</h1>"]
    if names["chain"]:
        body.append(f"<p>The catalog's <b>{_esc(', '.join(names['chain']))}</b>.</p>")
    body.append("<figure>" + skeleton_svg(chain, width=320).split("?>", 1)[-1]
                + "<figcaption>skeleton, in a generic pose</figcaption></figure>")
    body.append("<figure>" + _graph_svg(chain) + "<figcaption>link-joint graph (squares: "
                "joints, filled: sliding pairs)</figcaption></figure>")
    body.append("<h2>Classification</h2><table>" + "".join(
        "<tr>" + "".join(f"<td>{_esc(c)}</td>" for c in r) + "</tr>" for r in rows) + "</table>")
    body.append("<h2>Inversions</h2>")
    for i, links, label, figures in sections:
        body.append(f"<h3>{i}. {_esc(label)} <small>(fixed: {_esc(', '.join(links))})</small>"
                    "</h3>")
        if not figures:
            body.append("<p>no turning or sliding pair on the fixed link to drive it by</p>")
        for f in figures:
            if f.title and len(figures) > 1:
                body.append(f"<h4>{_esc(f.title)}</h4>")
            body.append(f"<p><a href=\"chains/{f.file}\">chain file</a> (driven by its "
                        "natural input; <code>chaingraph solve</code> runs it as shown)</p>")
            if f.svg:
                body.append(f"<figure class=\"inversion\">{f.svg}</figure>")
            elif f.failed:
                body.append(f"<p>not solved: {_esc(f.failed)}</p>")
            body.append("".join(f"<p class=\"note\">{_esc(n)}</p>" for n in f.notes))
    return (f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
            f"{_esc(chain.name)}</title><style>{_STYLE}</style></head><body>"
            + "\n".join(body) + "</body></html>\n")


#: seconds of one core to solve and animate an inversion, by links: 6 and 8 measured
#: (``chaingraph atlas --links 6 --prismatic all --out DIR --workers 2``: the 234
#: inversions in 31 s of CPU; ``python benchmarks/atlas_pages.py --links 8 --stride
#: 397``: 0.22 s of CPU per inversion), the others between and below them
SECONDS_PER_INVERSION = {4: 0.06, 5: 0.09, 6: 0.13, 7: 0.17, 8: 0.22}


def animation_seconds(result: SlidingAtlas, *, workers: int = 1) -> float:
    """About how long animating every inversion of ``result`` takes on ``workers``
    processes (seconds of the wall clock)."""
    per = SECONDS_PER_INVERSION.get(result.links, SECONDS_PER_INVERSION[8])
    return result.distinct_inversions * per / max(1, workers)


def animated_by_default(result: SlidingAtlas, *, workers: int = 1) -> bool:
    """Whether :func:`write_illustrated` animates ``result``'s inversions unless told:
    chains of up to 8 links, when that is estimated to take at most the hour an atlas
    run takes here without a cluster (:data:`~chaingraph.structure.atlas.estimate.
    LOCAL_HOURS`)."""
    return result.links <= 8 and \
        animation_seconds(result, workers=workers) <= LOCAL_HOURS * 3600


def write_illustrated(result: SlidingAtlas, out_dir: str | os.PathLike[str], *,
                      animate: bool | None = None, frames: int = 24,
                      workers: int = 1) -> list[IllustratedPage]:
    """Write ``DIR/index.html`` (the chains by links, sliding pairs and multiple joints,
    with their names) and ``DIR/chain-N.html`` per chain, with a chain file per
    inversion under ``DIR/chains/``; inversions are animated when ``animate`` is true
    (None: :func:`animated_by_default` on ``workers``). Returns the
    :class:`IllustratedPage` of each chain."""
    out = Path(out_dir)
    (out / "chains").mkdir(parents=True, exist_ok=True)
    withdraw(out)          # the old index goes before any page is rewritten
    animate = (animated_by_default(result, workers=workers) if animate is None
               else bool(animate))
    tasks = [(e, result.dof, result.oriented, animate, frames) for e in result]
    done: dict[int, PageJob] = {}
    process_runner(workers)(_page_job, tasks, done.__setitem__)
    pages, cards = [], []
    for i, e in enumerate(result):
        page, files, animated, failed, names, thumbnail = done[i]
        path = out / f"chain-{e.id}.html"
        path.write_text(page, encoding="utf-8")
        written = []
        for name, text in files:
            (out / "chains" / name).write_text(text, encoding="utf-8")
            written.append(out / "chains" / name)
        pages.append(IllustratedPage(e.id, path, tuple(written), animated, failed))
        cards.append((e, names, thumbnail))
    write_index(result, out, cards)
    return pages
