"""The illustrated atlas: a browsable index of the chains with sliding pairs or
multiple joints, and a page per chain with its skeleton in a generic pose, its
link-joint graph, its classification, its inversions with the catalog's names and,
for each inversion with a natural input, its motion over the range it can be
assembled in, animated, and a chain file that ``chaingraph solve`` runs as is.
"""

from __future__ import annotations

import html
from dataclasses import dataclass
from pathlib import Path

from chaingraph._util.atomic import withdraw
from chaingraph._util.parallel import process_runner
from chaingraph.drawing.mechanism import mechanism_svg, skeleton_svg
from chaingraph.errors import ChainGraphError, UnboundedRangeError
from chaingraph.files import dumps
from chaingraph.kinematics import solve
from chaingraph.model.snap import size_of
from chaingraph.naming.atlas import atlas_names
from chaingraph.report.atlas_index import thumbnail_svg, write_index
from chaingraph.structure.atlas.estimate import LOCAL_HOURS
from chaingraph.structure.atlas.illustrate import (
    generic_pose,
    inversion_mechanism,
    link_layout,
)
from chaingraph.structure.classify import classify
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


def _page_job(task):
    """Everything of one chain's page, computed in a worker: (html, chain files, how many
    inversions were animated, those that failed, its catalog names, its thumbnail)."""
    entry, dof, oriented, animate, frames = task
    chain = generic_pose(entry.chain(dof))
    names = atlas_names(chain, oriented=oriented)
    named = {link: c["names"] for c in names["inversions"] for link in c["links"]}
    rows = classify(chain).rows()
    classes = automorphism_orbits(chain, oriented=oriented)
    files, figures, failed, animated = [], [], [], 0
    for i, links in enumerate(classes, start=1):
        fixed = links[0]
        label = ", ".join(named.get(fixed, [])) or f"inversion {i}"
        mechanism = inversion_mechanism(chain, fixed, name=f"{chain.name}: {label}")
        if mechanism is None:
            figures.append((i, links, label, None, "no turning or sliding pair on the fixed "
                                                   "link to drive it by"))
            continue
        svg, why = None, None
        if animate:
            try:
                try:
                    motion = solve(mechanism, steps=2 * frames, summary=False)
                except UnboundedRangeError:
                    # a slide that runs on without a limit: shown over half its size each way
                    half = size_of({j.id: j.at for j in chain.joints}) / 2
                    sliding = inversion_mechanism(chain, fixed, name=mechanism.name, slide=half)
                    if sliding.mechanism == mechanism.mechanism:
                        raise
                    motion = solve(sliding, steps=2 * frames, summary=False)
                    mechanism = sliding
                    why = "its input slides without a limit: shown over half its size each way"
                svg = mechanism_svg(motion, frames=frames, width=300).split("?>", 1)[-1]
                animated += 1
            except ChainGraphError as e:
                failed.append((fixed, str(e)))
                svg = None
        files.append((f"chain-{entry.id}-inversion-{i}.toml", dumps(mechanism)))
        figures.append((i, links, label, svg, why))
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
    for i, links, label, svg, why in figures:
        body.append(f"<h3>{i}. {_esc(label)} <small>(fixed: {_esc(', '.join(links))})</small>"
                    "</h3>")
        if why and svg is None:
            body.append(f"<p>{_esc(why)}</p>")
            continue
        body.append(f"<p><a href=\"chains/chain-{entry.id}-inversion-{i}.toml\">chain file</a>"
                    f" (driven by its natural input; <code>chaingraph solve</code> runs it)</p>")
        if svg:
            body.append(svg)
            if why:
                body.append(f"<p>{_esc(why)}</p>")
        elif animate:
            message = next(m for f, m in failed if f == links[0])
            body.append(f"<p>not solved: {_esc(message)}</p>")
    page = (f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>"
            f"{_esc(chain.name)}</title><style>{_STYLE}</style></head><body>"
            + "\n".join(body) + "</body></html>\n")
    return page, files, animated, tuple(failed), names, thumbnail_svg(chain)


#: seconds of one core to solve and animate an inversion, by links: 6 and 8 measured
#: with ``chaingraph atlas --links N --prismatic ... --out DIR --workers 2`` (234
#: inversions of 6 links in 33 s, the 575 of 8 links with one sliding pair in 3 min 0 s),
#: the others between and below them (4 and 5 links take seconds in all)
SECONDS_PER_INVERSION = {4: 0.1, 5: 0.2, 6: 0.3, 7: 0.45, 8: 0.65}


def animation_seconds(result, *, workers=1) -> float:
    """About how long animating every inversion of ``result`` takes on ``workers``
    processes (seconds of the wall clock)."""
    per = SECONDS_PER_INVERSION.get(result.links, SECONDS_PER_INVERSION[8])
    return result.distinct_inversions * per / max(1, workers)


def animated_by_default(result, *, workers=1) -> bool:
    """Whether :func:`write_illustrated` animates ``result``'s inversions unless told:
    chains of up to 8 links, when that is estimated to take at most the hour an atlas
    run takes here without a cluster (:data:`~chaingraph.structure.atlas.estimate.
    LOCAL_HOURS`)."""
    return result.links <= 8 and \
        animation_seconds(result, workers=workers) <= LOCAL_HOURS * 3600


def write_illustrated(result, out_dir, *, animate=None, frames=24, workers=1) -> list:
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
    done = {}
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
