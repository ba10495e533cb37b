"""The illustrated atlas's index page: a row per chain with a thumbnail of its
skeleton, its base chain (the chain with every sliding pair made a turning pair, a
multiple joint kept as it is: Watt's, Stephenson's, or the catalog's name where it has
one), where its sliding pairs and multiple joints are, the catalog's names of its
inversions, and a filter by those, run by a small script in the page (no other asset:
the page is opened from disk).

The thumbnails are SVG files beside the pages (``thumbs/chain-N.svg``), loaded by the
browser as they scroll into view, so that the index of a large atlas (3,107 chains of 8
links) stays light.
"""

from __future__ import annotations

import html
import os
from collections.abc import Iterable, Sequence
from importlib import resources
from pathlib import Path
from typing import Any

from chaingraph._util.atomic import write_atomic
from chaingraph._util.text import counted
from chaingraph.drawing.mechanism import skeleton_svg
from chaingraph.model.chain import Chain, Joint
from chaingraph.naming.atlas import atlas_names
from chaingraph.structure.atlas.sliding import SlidingAtlas, SlidingEntry
from chaingraph.structure.classification import order_name

__all__ = ["THUMBNAIL_WIDTH", "thumbnail_svg", "base_chain", "base_labels", "where_text",
           "index_page", "write_index"]

#: the width of a thumbnail, in pixels
THUMBNAIL_WIDTH = 200

#: one chain of the index: its entry, its catalog names (as
#: :func:`~chaingraph.naming.atlas.atlas_names` gives them) and its thumbnail's SVG
Card = tuple[SlidingEntry, dict[str, Any], str]

_STYLE = ("body{font-family:sans-serif;margin:1.5em;max-width:75em}"
          "table{border-collapse:collapse;margin:.6em 0;width:100%;table-layout:fixed}"
          "th:nth-child(1){width:" + str(THUMBNAIL_WIDTH + 6) + "px}th:nth-child(2){width:13%}"
          "th:nth-child(3){width:14%}th:nth-child(4){width:25%}"
          "td,th{border:1px solid #ccc;padding:.2em .5em;text-align:left;vertical-align:top}"
          "td.thumb{width:" + str(THUMBNAIL_WIDTH) + "px;padding:2px}"
          "img.thumb{width:" + str(THUMBNAIL_WIDTH) + "px;height:" + str(THUMBNAIL_WIDTH * 3 // 4)
          + "px;object-fit:contain;display:block}"
          "ul{margin:0;padding-left:1.1em}small{color:#555}"
          "#filter{position:sticky;top:0;background:#f4f6f9;border:1px solid #ccd;"
          "padding:.5em .7em;display:flex;flex-wrap:wrap;gap:.4em 1.2em;align-items:center}"
          "#filter output{margin-left:auto;font-weight:bold}")


def thumbnail_svg(chain: Chain) -> str:
    """The skeleton of a posed atlas chain, small: the SVG document of its thumbnail."""
    return skeleton_svg(chain, width=THUMBNAIL_WIDTH, labels=False)


def base_chain(entry: SlidingEntry) -> Chain:
    """The chain of turning pairs that an atlas entry (a
    :class:`~chaingraph.structure.atlas.sliding.SlidingEntry`) comes from: every sliding
    pair made a turning pair, a multiple joint kept as it is.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> from chaingraph.structure.atlas.sliding import sliding_atlas
    >>> entry = sliding_atlas(atlas_graphs(4, 1), prismatic=1).entries[0]
    >>> [j.kind for j in base_chain(entry).joints], entry.base
    (['R', 'R', 'R', 'R'], 1)
    """
    joints = tuple(Joint(f"J{i + 1}", "R", tuple(f"L{x + 1}" for x in links))
                   for i, links in enumerate(entry.edges))
    return Chain(f"base chain {entry.base}", joints, family="atlas")


def base_labels(result: Iterable[SlidingEntry]) -> dict[int, str]:
    """``{base id: label}`` of the base chains of ``result``'s entries: the catalog's
    names of the base chain (``"Watt six-bar chain"``), else ``"turning-pair chain N"``,
    N its number in the atlas of turning pairs (with multiple joints: in that atlas)."""
    out: dict[int, str] = {}
    for e in result:
        if e.base not in out:
            names = atlas_names(base_chain(e))["chain"]
            out[e.base] = " / ".join(names) or f"turning-pair chain {e.base}"
    return out


def where_text(entry: SlidingEntry, *, oriented: bool = False) -> list[str]:
    """Where an entry's sliding pairs and multiple joints are, in words, one item each:
    ``"sliding pair J3 between binary L1 and ternary L4"`` (``oriented``: ``"sliding
    pair J3: ternary L4 on a guide on binary L1"``), ``"multiple joint J2 joining L2,
    L3 and L6"``.

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> from chaingraph.structure.atlas.sliding import sliding_atlas
    >>> where_text(sliding_atlas(atlas_graphs(4, 1), prismatic=1).entries[0])
    ['sliding pair J1 between binary L1 and binary L2']
    """
    order = [order_name(sum(x in j for j in entry.edges)) for x in range(entry.links)]
    out: list[str] = []
    for i, (links, kind) in enumerate(zip(entry.edges, entry.kinds)):
        names = [f"{order[x]} L{x + 1}" for x in links]
        if kind == "P":
            out.append(f"sliding pair J{i + 1}: {names[1]} on a guide on {names[0]}"
                       if oriented else f"sliding pair J{i + 1} between {names[0]} and "
                       f"{names[1]}")
        elif len(links) > 2:
            out.append(f"multiple joint J{i + 1} joining "
                       f"{', '.join(f'L{x + 1}' for x in links[:-1])} and L{links[-1] + 1}")
    return out


def _alternatives(items: Sequence[str]) -> str:
    """``"L1, L2 or L3"``."""
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " or " + items[-1]


def _esc(x: object) -> str:
    return html.escape(str(x), quote=True)


def _script() -> str:
    return resources.files("chaingraph.report").joinpath("atlas-index.js").read_text(
        encoding="utf-8")


def _row(entry: SlidingEntry, names: dict[str, Any], base: str, base_page: str | None, *,
         oriented: bool) -> str:
    """One chain's row of the index, with its filter's data attributes."""
    multiple = sum(len(j) > 2 for j in entry.edges)
    named = [(n, c["links"]) for c in names["inversions"] for n in c["names"]]
    where = where_text(entry, oriented=oriented)
    orders = ", ".join(f"{v} {o}" for o, v in entry.link_orders.items())
    title = "".join(f"<br><b>{_esc(n)}</b>" for n in names["chain"])
    base_cell = (f'<a href="{base_page}">{_esc(base)}</a>' if base_page else _esc(base))
    where_cell = ("<ul>" + "".join(f"<li>{_esc(w)}</li>" for w in where) + "</ul>"
                  if where else "turning pairs only")
    inversions = counted(entry.inversion_classes, "inversion")
    if named:
        inversions += "<ul>" + "".join(
            f"<li>{_esc(n)} <small>(fixed {_esc(_alternatives(links))})</small></li>"
            for n, links in named) + "</ul>"
    return (f'<tr class="chain" id="chain-{entry.id}" data-base="{_esc(base)}" '
            f'data-sliding="{entry.prismatic}" data-multiple="{multiple}" '
            f'data-named="{1 if named else 0}">'
            f'<td class="thumb"><a href="chain-{entry.id}.html"><img class="thumb" '
            f'src="thumbs/chain-{entry.id}.svg" loading="lazy" '
            f'alt="chain {entry.id}"></a></td>'
            f'<td><a href="chain-{entry.id}.html">chain {entry.id}</a>{title}'
            f'<br><small>{_esc(orders)} links</small></td><td>{base_cell}</td>'
            f'<td>{where_cell}</td><td>{inversions}</td></tr>')


def _filter(rows: Sequence[Card], labels: dict[int, str]) -> str:
    """The filter's form: base chain, sliding pairs, multiple joints, named, text."""
    def select(id_: str, title: str, values: Iterable[tuple[object, object]]) -> str:
        options = "".join(f'<option value="{_esc(v)}">{_esc(text)}</option>'
                          for v, text in values)
        return (f'<label>{title} <select id="{id_}"><option value="">any</option>'
                f"{options}</select></label>")
    bases: dict[int, int] = {}
    for e, *_ in rows:
        bases[e.base] = bases.get(e.base, 0) + 1
    sliding = sorted({e.prismatic for e, *_ in rows})
    multiple = sorted({sum(len(j) > 2 for j in e.edges) for e, *_ in rows})
    parts = [select("f-base", "base chain",
                    [(labels[b], f"{labels[b]} ({n})") for b, n in sorted(bases.items())]),
             select("f-sliding", "sliding pairs", [(k, k) for k in sliding])]
    if multiple != [0]:
        parts.append(select("f-multiple", "multiple joints", [(k, k) for k in multiple]))
    parts.append('<label><input type="checkbox" id="f-named"> with named inversions'
                 '</label><label>text <input type="search" id="f-text" '
                 'placeholder="Watt, engine, L4, chain 12"></label>'
                 f'<output id="f-shown">{len(rows)} chains</output>')
    return '<form id="filter" hidden onsubmit="return false">' + "".join(parts) + "</form>"


def index_page(result: SlidingAtlas, cards: Sequence[Card]) -> str:
    """The index of an illustrated atlas: ``cards``, one per entry of ``result`` in
    order, are ``(entry, names, thumbnail)`` with the entry's catalog names as
    :func:`~chaingraph.naming.atlas.atlas_names` gives them (its thumbnail is not used
    here: :func:`write_index` writes it beside). Chains are grouped by their numbers
    of sliding pairs and multiple joints."""
    labels = base_labels(result)
    pages = {e.base: f"chain-{e.id}.html" for e, *_ in cards if e.prismatic == 0}
    listing = f"chaingraph atlas --links {result.links}" + (
        " --multiple" if any(getattr(e, "multiple", False) for e in result) else "")
    heading = (f"Chains of {result.links} links, "
               f"{counted(result.dof, 'degree of freedom', 'degrees of freedom')}"
               f"{' (oriented)' if result.oriented else ''}")
    body = [f"<h1>{_esc(heading)}</h1>",
            f"<p>{counted(len(cards), 'chain')}, "
            f"{counted(sum(e.inversion_classes for e, *_ in cards), 'distinct inversion')}. "
            "A chain's <b>base chain</b> is the chain with its sliding pairs made turning "
            "pairs (a multiple joint kept): named from the catalog where it has it, else "
            f"numbered as in <code>{_esc(listing)}</code>. Links "
            "are L1, L2...; joints J1, J2... as on the chain's page; the thumbnails show "
            "each skeleton in a generic pose (sliding pairs as blocks on guides).</p>",
            _filter(cards, labels)]
    headers = ("<tr><th>skeleton</th><th>chain</th><th>base chain</th>"
               "<th>sliding pairs and multiple joints</th><th>inversions</th></tr>")
    groups: dict[tuple[int, int], list[Card]] = {}
    for card in cards:
        e = card[0]
        groups.setdefault((e.prismatic, sum(len(j) > 2 for j in e.edges)), []).append(card)
    for (k, multiple), group in sorted(groups.items()):
        title = counted(k, "sliding pair") + (
            f", {counted(multiple, 'multiple joint')}" if multiple else "")
        body.append(f'<section class="group"><h2>{_esc(title)} (<span class="shown">'
                    f'{len(group)}</span>)</h2>'
                    f"<table>{headers}")
        for e, names, *_ in group:
            body.append(_row(e, names, labels[e.base], pages.get(e.base),
                             oriented=result.oriented))
        body.append("</table></section>")
    return (f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>atlas: "
            f"{_esc(heading)}</title><style>{_STYLE}</style></head><body>"
            + "\n".join(body) + f"\n<script>\n{_script()}</script></body></html>\n")


def write_index(result: SlidingAtlas, out_dir: str | os.PathLike[str],
                cards: Sequence[Card]) -> Path:
    """Write ``DIR/index.html`` (:func:`index_page`) and each chain's thumbnail,
    ``DIR/thumbs/chain-N.svg``; returns the index's path."""
    out = Path(out_dir)
    (out / "thumbs").mkdir(parents=True, exist_ok=True)
    for e, _, thumbnail in cards:
        (out / "thumbs" / f"chain-{e.id}.svg").write_text(thumbnail, encoding="utf-8")
    # last, after every page and thumbnail (the caller withdrew the old one first)
    return write_atomic(out / "index.html", index_page(result, cards))
