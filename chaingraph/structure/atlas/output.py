"""Writing an atlas: ``atlas.json``, one graph6 file, the HTML index and, on request,
one chain file per chain. Everything is written from a stream of chains (from memory
or from a run's shards), so that memory does not grow with the atlas."""

from __future__ import annotations

import html as _html
import json
import math
import os
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import IO, Any

from chaingraph._util.atomic import withdraw
from chaingraph._util.text import freedom
from chaingraph.geometry import segment_distance
from chaingraph.structure.atlas.entry import (
    AtlasEntry,
    chain_file_name,
    encode_chains,
    order_counts,
)
from chaingraph.structure.atlas.run import Atlas, AtlasCounts, ring_of

__all__ = ["atlas_dict", "write_atlas", "chains_of", "CHAIN_FILES_UP_TO",
           "FIGURES_UP_TO"]

#: chain files are written by default up to this many chains (more only on request)
CHAIN_FILES_UP_TO = 10_000
#: the HTML index draws at most this many chains (all are in atlas.json and graph6)
FIGURES_UP_TO = 1_000

_Point = tuple[float, float]


def chains_of(atlas: Atlas, *, no_fractionated: bool = False,
              ) -> Iterator[tuple[list[list[int]], int, bool]]:
    """The chains of an in-memory :class:`~chaingraph.structure.atlas.run.Atlas` in order, as
    ``(edges, inversion_classes, fractionated)``."""
    for e, o, x in zip(atlas.edges, atlas.inversion_classes, atlas.fractionated):
        if not (no_fractionated and x):
            yield e.tolist(), int(o), bool(x)


def _in_memory(atlas: Atlas | AtlasCounts) -> Atlas:
    """``atlas`` itself, when its chains are held (an :class:`Atlas`, not counts)."""
    if not isinstance(atlas, Atlas):
        raise TypeError("the chains of an atlas whose chains were not kept in memory "
                        "are read from its shards: give shard_dir")
    return atlas


def _records(atlas: Atlas | AtlasCounts, shard_dir: str | os.PathLike[str] | None,
             no_fractionated: bool, block: int = 4096,
             ) -> Iterator[tuple[str, bytes, dict[str, Any]]]:
    """Each chain in order as ``(json_line, graph6_line, record)``: encoded from memory,
    or read back from the shard files of a run (after the single loop, if any)."""
    def pairs() -> Iterator[tuple[str, bytes]]:
        if shard_dir is None:
            held = _in_memory(atlas)
            for s in range(0, len(held), block):
                g6, text = encode_chains(held.links, held.edges[s:s + block],
                                         held.inversion_classes[s:s + block],
                                         held.fractionated[s:s + block])
                yield from zip(text.splitlines(True), g6.splitlines(True))
            return
        if atlas.links == atlas.dof + 3:
            g6, text = encode_chains(atlas.links, *ring_of(atlas.links, atlas.labelling))
            yield text, g6
        for path in sorted(Path(shard_dir).glob("shard-*.jsonl")):
            with open(path, encoding="utf-8") as lines, \
                    open(path.with_suffix(".g6"), "rb") as graphs:
                yield from zip(lines, graphs)
    for line, g6 in pairs():
        record = json.loads(line)
        if not (no_fractionated and record["fractionated"]):
            yield line, g6, record


def _header(atlas: Atlas | AtlasCounts, no_fractionated: bool) -> dict[str, Any]:
    """The counts that open atlas.json (``distinct_inversions`` is added by the caller:
    streamed, it is known only at the end)."""
    count = atlas.count_non_fractionated if no_fractionated else atlas.count
    return {"links": atlas.links, "dof": atlas.dof, "count": count,
            "count_non_fractionated": atlas.count_non_fractionated}


def atlas_dict(atlas: Atlas | AtlasCounts, *, no_fractionated: bool = False,
               chains: bool = True) -> dict[str, Any]:
    """The JSON object of ``chaingraph atlas --json`` (``chains=False``: ``--summary``).

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas_graphs
    >>> d = atlas_dict(atlas_graphs(7, 2), chains=False)
    >>> d["count"], d["count_non_fractionated"], d["distinct_inversions"]
    (4, 3, 14)
    """
    out = _header(atlas, no_fractionated)
    out["distinct_inversions"] = (atlas.distinct_inversions_non_fractionated
                                  if no_fractionated else atlas.distinct_inversions)
    if chains:
        out["chains"] = [_chain_record(i + 1, edges, orbits, fractionated, atlas.links)
                         for i, (edges, orbits, fractionated) in enumerate(
                             chains_of(_in_memory(atlas), no_fractionated=no_fractionated))]
    return out


def _chain_record(id_: int, edges: list[list[int]], orbits: int, fractionated: bool,
                  links: int) -> dict[str, Any]:
    return {"id": id_, "edges": [list(e) for e in edges], "link_orders": order_counts(edges, links),
            "inversion_classes": orbits, "fractionated": fractionated}


def _open_for_writing(path: Path, mode: str = "w") -> tuple[Path, IO[Any]]:
    """A temporary file beside ``path``, renamed onto it by :func:`_finish`."""
    tmp = path.with_name(path.name + ".tmp")
    return tmp, open(tmp, mode, encoding=None if "b" in mode else "utf-8")


def write_atlas(atlas: Atlas | AtlasCounts, out_dir: str | os.PathLike[str], *,
                shard_dir: str | os.PathLike[str] | None = None,
                no_fractionated: bool = False, chain_files: bool | None = None,
                ) -> dict[str, Any]:
    """Write ``atlas.json``, ``atlas-N-links-F-dof.g6``, ``index.html`` and, when
    ``chain_files`` is true (by default up to :data:`CHAIN_FILES_UP_TO` chains), one
    TOML file per chain under ``chains/``, into ``out_dir``; returns the paths by kind.

    The chains are streamed (from ``shard_dir`` when given), each file written under a
    temporary name and renamed when complete; the old index is removed first and the
    new one written last, so an interrupted write is never presented as complete."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    withdraw(out)             # no old index beside new files until the new one is written
    count = atlas.count_non_fractionated if no_fractionated else atlas.count
    if chain_files is None:
        chain_files = count <= CHAIN_FILES_UP_TO
    paths: dict[str, Any] = {"json": out / "atlas.json",
             "graph6": out / f"atlas-{atlas.links}-links-{atlas.dof}-dof.g6",
             "html": out / "index.html", "chains": [], "chain_dir": None}
    if chain_files:
        paths["chain_dir"] = out / "chains"
        paths["chain_dir"].mkdir(exist_ok=True)
    header = _header(atlas, no_fractionated)
    json_tmp, json_file = _open_for_writing(paths["json"])
    g6_tmp, g6_file = _open_for_writing(paths["graph6"], "wb")
    by_assortment: dict[str, list[int]] = {}
    figures: list[AtlasEntry] = []
    total = 0
    with json_file, g6_file:
        json_file.write("{" + json.dumps(header)[1:-1] + ', "chains": [\n')
        for i, (line, g6, record) in enumerate(_records(atlas, shard_dir, no_fractionated)):
            json_file.write(("" if i == 0 else ",\n") + f'{{"id": {i + 1}, ' + line[1:-1])
            g6_file.write(g6)
            orbits, fractionated = record["inversion_classes"], record["fractionated"]
            total += orbits
            key = ", ".join(f"{v} {k}" for k, v in record["link_orders"].items())
            row = by_assortment.setdefault(key, [0, 0, 0])
            row[0] += 1
            row[1] += orbits
            row[2] += not fractionated
            if len(figures) < FIGURES_UP_TO or chain_files:
                entry = AtlasEntry(id=i + 1, edges=tuple(map(tuple, record["edges"])),
                                   links=atlas.links, inversion_classes=orbits,
                                   fractionated=fractionated)
                if len(figures) < FIGURES_UP_TO:
                    figures.append(entry)
            if chain_files:
                path = paths["chain_dir"] / chain_file_name(i + 1, count)
                path.write_text(chain_text(entry, atlas.dof), encoding="utf-8")
                paths["chains"].append(path)
        json_file.write(f'\n], "distinct_inversions": {total}}}\n')
    os.replace(json_tmp, paths["json"])
    os.replace(g6_tmp, paths["graph6"])
    page = _atlas_page(atlas, figures, by_assortment, count, total, no_fractionated)
    html_tmp, html_file = _open_for_writing(paths["html"])
    with html_file:
        html_file.write(page)
    os.replace(html_tmp, paths["html"])
    return paths


def chain_text(entry: AtlasEntry, dof: int | None = None) -> str:
    """The chain file of an atlas entry, as :func:`chaingraph.dumps` writes it (made
    directly: an atlas writes thousands).

    Examples
    --------
    >>> from chaingraph import dumps
    >>> from chaingraph.structure.atlas import AtlasEntry
    >>> e = AtlasEntry(id=1, edges=((0, 1), (1, 2), (2, 3), (0, 3)), links=4,
    ...                inversion_classes=1)
    >>> chain_text(e, 1) == dumps(e.chain(1))
    True
    """
    name = f"chain {entry.id} of {entry.links} links" + (f", {dof} dof" if dof else "")
    parts = [f'name = "{name}"\nfamily = "atlas"\n']
    for i, (a, b) in enumerate(entry.edges):
        parts.append(f'\n[[joints]]\nid = "J{i + 1}"\nkind = "R"\n'
                     f'links = ["L{a + 1}", "L{b + 1}"]\n')
    return "".join(parts)


def atlas_svg(entry: AtlasEntry, size: int = 170) -> str:
    """A small SVG of one chain's link-joint graph: links as numbered circles on a ring
    (ordered to follow the chain; L1 is link 1 of the chain file, edge 0 of atlas.json's
    ``edges``), joints as squares on the bars between them, each placed where no other
    bar crosses (a square at a crossing would read as a multiple joint)."""
    n = entry.links
    order = _ring_order(n, entry.edges)
    place: dict[int, _Point] = {}
    for i, v in enumerate(order):
        a = 2 * math.pi * i / n - math.pi / 2
        place[v] = (size / 2 + 0.38 * size * math.cos(a), size / 2 + 0.38 * size * math.sin(a))
    degree = [0] * n
    for a, b in entry.edges:
        degree[a] += 1
        degree[b] += 1
    bars = [(place[a], place[b]) for a, b in entry.edges]
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" '
             f'viewBox="0 0 {size} {size}">']
    for (x1, y1), (x2, y2) in bars:
        parts.append(f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" '
                     'stroke="#444" stroke-width="1.3"/>')
    squares: list[_Point] = []
    for k, bar in enumerate(bars):
        mx, my = _joint_place(bar, [b for i, b in enumerate(bars) if i != k], squares)
        squares.append((mx, my))
        parts.append(f'<rect class="joint" x="{mx - 3:.1f}" y="{my - 3:.1f}" width="6" '
                     'height="6" fill="#fff2cc" stroke="#7f6000" stroke-width="0.8"/>')
    colour = {2: "#cfe3f5", 3: "#9fc5e8", 4: "#6fa8dc", 5: "#3d85c6"}
    for v, (x, y) in place.items():
        dark = degree[v] >= 4
        parts.append(f'<circle class="link" cx="{x:.1f}" cy="{y:.1f}" r="7" '
                     f'fill="{colour.get(degree[v], "#1f4e79")}" stroke="#1f4e79" '
                     f'stroke-width="1.2"/><text x="{x:.1f}" y="{y + 3:.1f}" font-size="8" '
                     f'text-anchor="middle" font-family="sans-serif" '
                     f'fill="{"#fff" if dark else "#000"}">{v + 1}</text>')
    parts.append("</svg>")
    return "".join(parts)


def _joint_place(bar: tuple[_Point, _Point], others: Sequence[tuple[_Point, _Point]],
                 squares: Sequence[_Point], clear: float = 5.0) -> _Point:
    """Where on ``bar`` to draw its joint: the point nearest its middle that is at least
    ``clear`` from every other bar and square (else the clearest point tried)."""
    (x1, y1), (x2, y2) = bar
    best, best_gap = (x1, y1), -1.0         # the first point tried replaces it
    for t in (0.5, 0.4, 0.6, 0.32, 0.68, 0.26, 0.74, 0.45, 0.55, 0.36, 0.64, 0.3, 0.7):
        p = (x1 + t * (x2 - x1), y1 + t * (y2 - y1))
        gap = min([segment_distance(p, a, b) for a, b in others]
                  + [math.dist(p, q) for q in squares] + [math.inf])
        if gap >= clear:
            return p
        if gap > best_gap:
            best, best_gap = p, gap
    return best


def _ring_order(n: int, edges: Sequence[tuple[int, int]]) -> list[int]:
    """Links in an order that follows the chain (a depth-first walk), for drawing."""
    adj: dict[int, list[int]] = {v: [] for v in range(n)}
    for a, b in edges:
        adj[a].append(b)
        adj[b].append(a)
    seen: set[int] = set()
    order: list[int] = []
    stack = [max(range(n), key=lambda v: len(adj[v]))]
    while stack:
        v = stack.pop()
        if v in seen:
            continue
        seen.add(v)
        order.append(v)
        stack.extend(sorted(adj[v], key=lambda w: -len(adj[w])))
    return order + [v for v in range(n) if v not in seen]


def _atlas_page(atlas: Atlas | AtlasCounts, figures: Sequence[AtlasEntry],
                by_assortment: dict[str, list[int]], count: int, total: int,
                no_fractionated: bool) -> str:
    links, dof = atlas.links, atlas.dof
    cells: list[str] = []
    for e in figures:
        orders = ", ".join(f"{v} {k}" for k, v in e.link_orders.items())
        cells.append(f'<figure id="chain-{e.id}">{atlas_svg(e)}<figcaption><b>{e.id}</b>: '
                     f'{_html.escape(orders)}; {e.inversion_classes} distinct inversion'
                     f'{"s" if e.inversion_classes != 1 else ""}'
                     f'{"; fractionated" if e.fractionated else ""}</figcaption></figure>')
    rows = "".join(f"<tr><td>{_html.escape(k)}</td><td>{c:,}</td><td>{n:,}</td>"
                   f"<td>{o:,}</td></tr>" for k, (c, o, n) in by_assortment.items())
    shown = ("" if len(figures) == count else
             f"<p>The first {len(figures):,} chains are drawn below; every chain is in "
             "atlas.json and the graph6 file.</p>")
    which = ("non-fractionated chains only" if no_fractionated else
             f"{atlas.count_non_fractionated:,} of them non-fractionated")
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>Atlas: {links} links, {freedom(dof)}</title><style>"
            "body{font-family:Georgia,serif;margin:2em;color:#1b1b1b}"
            "h1{font-family:Arial,sans-serif;color:#1f4e79}"
            "table{border-collapse:collapse;margin:1em 0}"
            "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}"
            "td:first-child{text-align:left}"
            ".grid{display:flex;flex-wrap:wrap;gap:10px}"
            "figure{margin:0;width:170px;border:1px solid #ddd;padding:4px}"
            "figcaption{font-size:11px}</style></head><body>"
            f"<h1>Kinematic chains of {links} links, {freedom(dof)}</h1>"
            f"<p>{count:,} chains (non-isomorphic, non-degenerate, simple revolute "
            f"joints; {which}), {total:,} distinct inversions. Links are circles (darker "
            "for more joints) numbered as in the chain files (L1, L2, ...; atlas.json's "
            "<code>edges</code> count them from 0), joints squares on the bars.</p>"
            "<table><tr><th>link assortment</th><th>chains</th><th>non-fractionated</th>"
            f"<th>distinct inversions</th></tr>{rows}</table>{shown}"
            f"<div class=\"grid\">{''.join(cells)}</div></body></html>\n")
