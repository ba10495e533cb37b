"""The atlas: every kinematic chain of N links and F degrees of freedom.

The chains are planar, with simple (binary) revolute joints, non-degenerate (no proper
sub-chain with mobility <= 0), connected, and counted once up to isomorphism; non-planar
link graphs and fractionated chains are included. A chain is its link graph: a simple
graph on N links with J = (3 (N - 1) - F) / 2 joints as edges.

Method (structural synthesis by contracted graphs):

1. Number synthesis: the link assortments (how many links of each order) with N links
   and 2J joint ends, every link of order 2 or more.
2. For each assortment, the contracted graphs: connected multigraphs (self-loops
   allowed: a loop of binary links on one link makes a fractionated chain) on the links
   of order 3 or more, with those orders as degrees, up to isomorphism.
3. The binary links distributed on the contracted graph's edges in every way (a
   self-loop needs two at least; of parallel edges, at most one may have none), each
   expansion kept if it has no rigid proper sub-chain (the exhaustive test of
   :mod:`chaingraph.rigidity`), then counted once by its exact canonical form
   (:mod:`chaingraph.isomorphism`).

The work splits by (assortment, contracted graph), independent pieces that ``workers``
processes run side by side.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from .errors import AtlasSizeError
from .isomorphism import _orbits_of, _Partition, _search

__all__ = ["atlas", "atlas_graphs", "AtlasEntry", "joints_for", "assortments"]


def joints_for(links: int, dof: int) -> int:
    """J for a chain of ``links`` links and ``dof`` degrees of freedom, or AtlasSizeError."""
    for name, value in (("--links", links), ("--dof", dof)):
        if isinstance(value, bool) or not isinstance(value, int) or value < 1:
            raise AtlasSizeError(f"{name} must be a positive whole number, got {value!r}",
                                 links=links, dof=dof)
    twice = 3 * (links - 1) - dof
    if twice % 2:
        raise AtlasSizeError(
            f"no chain has {links} links and {dof} degree(s) of freedom: 3(N - 1) - F = "
            f"{twice} is odd, and simple revolute joints remove two freedoms each",
            links=links, dof=dof)
    joints = twice // 2
    if joints < links:
        raise AtlasSizeError(
            f"no closed chain has {links} links and {dof} degree(s) of freedom: it would "
            f"have {joints} joints, fewer than its {links} links (the fewest links is "
            f"{dof + 3}, a single loop)", links=links, dof=dof)
    return joints


def assortments(links: int, joints: int):
    """Link assortments: tuples (n2, n3, ...) with sum n = links, sum k n_k = 2 joints."""
    # each independent loop through a link adds at most two of its joints (a link shared
    # by the loops of a fractionated chain has order twice their number)
    loops = joints - links + 1
    top = min(links - 1, 2 * loops)
    out = []

    def rec(order, left_links, left_ends, acc):
        if order > top:
            if left_links == 0 and left_ends == 0:
                out.append(tuple(acc))
            return
        for count in range(left_links + 1):
            if count * order > left_ends:
                break
            rec(order + 1, left_links - count, left_ends - count * order, acc + [count])
    rec(2, links, 2 * joints, [])
    return out


# -- contracted graphs ---------------------------------------------------------------
def _contracted_graphs(degrees):
    """Connected multigraphs with self-loops on nodes of the given degrees, up to
    isomorphism, each as a sorted tuple of edges (i, j), i <= j."""
    k = len(degrees)
    found = {}
    remaining = list(degrees)
    edges = []

    def rec(i):
        if i == k:
            if _connected(k, edges):
                key = _multigraph_form(degrees, edges)
                found.setdefault(key, tuple(sorted(edges)))
            return
        if remaining[i] == 0:
            rec(i + 1)
            return
        # node i's stubs go to nodes j >= i, in non-decreasing order of j; of the nodes
        # not yet touched, those of one degree are interchangeable: only the first is
        # tried (the others would give the same graphs relabelled)
        last = edges[-1][1] if edges and edges[-1][0] == i else i
        tried_fresh = set()
        for j in range(last, k):
            if j > i and remaining[j] == degrees[j]:
                if degrees[j] in tried_fresh:
                    continue
                tried_fresh.add(degrees[j])
            if j == i:
                if remaining[i] >= 2:
                    remaining[i] -= 2
                    edges.append((i, i))
                    rec(i)
                    edges.pop()
                    remaining[i] += 2
            elif remaining[j] >= 1:
                remaining[i] -= 1
                remaining[j] -= 1
                edges.append((i, j))
                rec(i)
                edges.pop()
                remaining[i] += 1
                remaining[j] += 1
    rec(0)
    return list(found.values())


def _connected(k, edges):
    blocks = _Partition(k)
    for a, b in edges:
        blocks.join(a, b)
    return len({blocks.find(x) for x in range(k)}) == 1


def _weighted(degrees, edges):
    """A multigraph with loops as a coloured simple graph on its nodes: a node's colour
    is its degree and number of loops, an edge's colour its multiplicity."""
    k = len(degrees)
    loops = [0] * k
    mult = {}
    for a, b in edges:
        if a == b:
            loops[a] += 1
        else:
            mult[(a, b)] = mult.get((a, b), 0) + 1
    labels = [("node", d, loops[i]) for i, d in enumerate(degrees)]
    adj = [[] for _ in range(k)]
    for (a, b), m in mult.items():
        adj[a].append((b, m))
        adj[b].append((a, m))
    return labels, adj


def _multigraph_form(degrees, edges):
    """Canonical form of a multigraph with loops."""
    labels, adj = _weighted(degrees, edges)
    cert, order, _, _ = _search(labels, adj)
    return (tuple(labels[v] for v in order), cert)


def _edge_group(degrees, edges):
    """Every automorphism of the multigraph, as a permutation of its edges: a node
    automorphism, with any order within each bundle of parallel edges (and of loops)."""
    labels, adj = _weighted(degrees, edges)
    _, _, gens, _ = _search(labels, adj)
    k = len(degrees)
    identity = tuple(range(k))
    nodes, frontier = {identity}, [identity]
    while frontier:
        nxt = []
        for p in frontier:
            for g in gens:
                q = tuple(g[p[v]] for v in range(k))
                if q not in nodes:
                    nodes.add(q)
                    nxt.append(q)
        frontier = nxt
    bundles = {}
    for e, (a, b) in enumerate(edges):
        bundles.setdefault((a, b), []).append(e)
    shuffles = [list(itertools.permutations(b)) for b in bundles.values()]
    group = set()
    for p in nodes:
        base = {}
        for (a, b), members in bundles.items():
            target = bundles[tuple(sorted((p[a], p[b])))]
            for e, f in zip(members, target):
                base[e] = f
        for choice in itertools.product(*shuffles):
            within = {}
            for members, order in zip(bundles.values(), choice):
                for e, f in zip(members, order):
                    within[e] = f
            group.add(tuple(within[base[e]] for e in range(len(edges))))
    group.discard(tuple(range(len(edges))))
    return list(group)


# -- expansion and filtering ---------------------------------------------------------
def _distributions(edges, binaries):
    """Ways to put ``binaries`` binary links on the edges: loops get 2 or more, and of
    parallel edges between the same two links at most one gets none."""
    n = len(edges)
    minimum = [2 if a == b else 0 for a, b in edges]
    spare = binaries - sum(minimum)
    if spare < 0:
        return
    groups = {}
    for e, (a, b) in enumerate(edges):
        if a != b:
            groups.setdefault((a, b), []).append(e)
    parallel = [g for g in groups.values() if len(g) > 1]
    for cut in itertools.combinations(range(spare + n - 1), n - 1):
        counts, prev = [], -1
        for c in cut + (spare + n - 1,):
            counts.append(c - prev - 1)
            prev = c
        counts = [c + m for c, m in zip(counts, minimum)]
        if any(sum(1 for e in g if counts[e] == 0) > 1 for g in parallel):
            continue
        yield counts


def _expand(k, edges, counts):
    """The link graph: contracted nodes 0..k-1, then binary links, as an edge list."""
    out = []
    nxt = k
    for (a, b), c in zip(edges, counts):
        prev = a
        for _ in range(c):
            out.append((prev, nxt))
            prev = nxt
            nxt += 1
        out.append((prev, b))
    return nxt, out


def _rigid_free(n, edges):
    """True when no proper sub-chain of at least two links is rigid (mobility <= 0)."""
    masks = np.array([(1 << a) | (1 << b) for a, b in edges], dtype=np.int64)
    subsets = np.arange(1 << n, dtype=np.int64)
    size = np.bitwise_count(subsets).astype(np.int64)
    inside = (np.bitwise_count(subsets[:, None] & masks[None, :]) == 2).sum(axis=1)
    mobility = 3 * (size - 1) - 2 * inside
    proper = (size >= 2) & (subsets != (1 << n) - 1)
    return not np.any(proper & (mobility <= 0))


def _graph_form(n, edges):
    """Canonical form and automorphism orbit count of a simple link graph."""
    labels = [("link",)] * n
    adj = [[] for _ in range(n)]
    for a, b in edges:
        adj[a].append((b, 0))
        adj[b].append((a, 0))
    cert, order, gens, size = _search(labels, adj)
    position = {v: i for i, v in enumerate(order)}
    canon = tuple(sorted((min(position[a], position[b]), max(position[a], position[b]))
                         for a, b in edges))
    orbits = _orbit_count(n, gens)
    return canon, orbits


def _orbit_count(n, gens):
    return len(set(_orbits_of(gens, n)))


def _piece(job):
    """One independent piece of the work: every chain from one contracted graph.

    Two distributions of the binary links give isomorphic chains exactly when an
    automorphism of the contracted graph maps one onto the other (an isomorphism of
    chains maps binary links to binary links, so it is one of the contracted graphs),
    and chains from different contracted graphs are never isomorphic. So one
    distribution per orbit (the largest under the group) gives each chain once.
    """
    k, edges, binaries, links, degrees = job
    group = _edge_group(degrees, edges)
    found = {}
    for counts in _distributions(list(edges), binaries):
        counts = tuple(counts)
        if any(tuple(counts[p[e]] for e in range(len(counts))) > counts for p in group):
            continue
        n, expanded = _expand(k, edges, counts)
        if not _rigid_free(n, expanded):
            continue
        canon, orbits = _graph_form(n, expanded)
        found[canon] = orbits
    return found


@dataclass(frozen=True)
class AtlasEntry:
    """One chain of the atlas: its link graph in canonical labels."""

    id: int
    edges: tuple
    links: int
    inversion_classes: int

    @property
    def link_orders(self) -> dict:
        from .classify import order_name
        degree = [0] * self.links
        for a, b in self.edges:
            degree[a] += 1
            degree[b] += 1
        counts = {}
        for d in sorted(degree):
            counts[order_name(d)] = counts.get(order_name(d), 0) + 1
        return counts

    def chain(self, dof=None):
        """The chain as a :class:`~chaingraph.chain.Chain` (links L1..LN, joints J1..)."""
        from .chain import Chain, Joint
        joints = tuple(Joint(f"J{i + 1}", "R", (f"L{a + 1}", f"L{b + 1}"))
                       for i, (a, b) in enumerate(self.edges))
        name = f"chain {self.id} of {self.links} links" + (f", {dof} dof" if dof else "")
        return Chain(name, joints, family="atlas")


def _jobs(links, dof):
    joints = joints_for(links, dof)
    jobs = []
    for assortment in assortments(links, joints):
        binaries = assortment[0]
        degrees = [order for order, count in enumerate(assortment[1:], start=3)
                   for _ in range(count)]
        degrees.sort(reverse=True)
        if not degrees:
            continue                                   # the single loop: atlas_graphs
        for edges in _contracted_graphs(degrees):
            jobs.append((len(degrees), edges, binaries, links, tuple(degrees)))
    return jobs


def atlas_graphs(links: int, dof: int = 1, *, workers: int = 1, progress=None):
    """Every chain of the atlas as an :class:`AtlasEntry`, in canonical order.

    Parameters
    ----------
    links, dof : int
    workers : int
        Processes that run the pieces side by side.
    progress : callable, optional
        Called as ``progress(done, total)`` after each piece.

    Examples
    --------
    >>> [len(atlas_graphs(n, 1)) for n in (4, 6, 8)]
    [1, 2, 16]
    >>> sum(e.inversion_classes for e in atlas_graphs(6, 1))
    5
    """
    jobs = _jobs(links, dof)
    found = {}
    if links == dof + 3:                          # the single loop of N binary links
        ring = tuple((i, (i + 1) % links) for i in range(links))
        canon, orbits = _graph_form(links, ring)
        found[canon] = orbits
    total = len(jobs)
    if workers > 1 and total > 1:
        from concurrent.futures import ProcessPoolExecutor
        with ProcessPoolExecutor(max_workers=workers) as pool:
            for done, piece in enumerate(pool.map(_piece, jobs, chunksize=max(1, total // (8 * workers)))):
                found.update(piece)
                if progress:
                    progress(done + 1, total)
    else:
        for done, job in enumerate(jobs):
            found.update(_piece(job))
            if progress:
                progress(done + 1, total)
    return [AtlasEntry(id=i + 1, edges=canon, links=links, inversion_classes=orbits)
            for i, (canon, orbits) in enumerate(sorted(found.items()))]


def atlas(*, links: int, dof: int = 1, workers: int = 1):
    """Yield every chain of ``links`` links and ``dof`` degrees of freedom as a Chain.

    Examples
    --------
    >>> [c.name for c in atlas(links=6, dof=1)]
    ['chain 1 of 6 links, 1 dof', 'chain 2 of 6 links, 1 dof']
    """
    for entry in atlas_graphs(links, dof, workers=workers):
        yield entry.chain(dof)


# -- writing an atlas ------------------------------------------------------------------
def atlas_dict(entries, links, dof) -> dict:
    """The JSON object of ``chaingraph atlas --json``."""
    return {"links": links, "dof": dof, "count": len(entries),
            "distinct_inversions": sum(e.inversion_classes for e in entries),
            "chains": [{"id": e.id, "edges": [list(x) for x in e.edges],
                        "link_orders": e.link_orders,
                        "inversion_classes": e.inversion_classes} for e in entries]}


def write_atlas(entries, links, dof, out_dir) -> dict:
    """Write atlas.json, the graph6 file, one TOML chain file per chain and index.html
    into ``out_dir``; returns the paths written, by kind."""
    import json
    from pathlib import Path

    import networkx as nx

    from .chainfile import dumps
    out = Path(out_dir)
    (out / "chains").mkdir(parents=True, exist_ok=True)
    paths = {"json": out / "atlas.json", "graph6": out / f"atlas-{links}-links-{dof}-dof.g6",
             "html": out / "index.html", "chains": []}
    paths["json"].write_text(json.dumps(atlas_dict(entries, links, dof), indent=1))
    with open(paths["graph6"], "wb") as f:
        for e in entries:
            g = nx.Graph()
            g.add_nodes_from(range(e.links))
            g.add_edges_from(e.edges)
            f.write(nx.to_graph6_bytes(g, header=False))
    width = len(str(len(entries)))
    for e in entries:
        path = out / "chains" / f"chain-{e.id:0{width}d}.toml"
        path.write_text(dumps(e.chain(dof)))
        paths["chains"].append(path)
    paths["html"].write_text(_atlas_page(entries, links, dof), encoding="utf-8")
    return paths


def _atlas_svg(entry, size=170):
    """A small SVG of one chain's link-joint graph: links as circles on a ring (ordered to
    follow the chain), joints as squares on the bars between them."""
    n = entry.links
    order = _ring_order(n, entry.edges)
    place = {}
    for i, v in enumerate(order):
        a = 2 * math.pi * i / n - math.pi / 2
        place[v] = (size / 2 + 0.38 * size * math.cos(a), size / 2 + 0.38 * size * math.sin(a))
    degree = [0] * n
    for a, b in entry.edges:
        degree[a] += 1
        degree[b] += 1
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{size}" height="{size}" '
             f'viewBox="0 0 {size} {size}">']
    for a, b in entry.edges:
        (x1, y1), (x2, y2) = place[a], place[b]
        parts.append(f'<line x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" '
                     'stroke="#444" stroke-width="1.3"/>')
        mx, my = (x1 + x2) / 2, (y1 + y2) / 2
        parts.append(f'<rect x="{mx - 3:.1f}" y="{my - 3:.1f}" width="6" height="6" '
                     'fill="#fff2cc" stroke="#7f6000" stroke-width="0.8"/>')
    colour = {2: "#cfe3f5", 3: "#9fc5e8", 4: "#6fa8dc", 5: "#3d85c6"}
    for v, (x, y) in place.items():
        parts.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="7" fill="{colour.get(degree[v], "#1f4e79")}" '
                     'stroke="#1f4e79" stroke-width="1.2"/>')
    parts.append("</svg>")
    return "".join(parts)


def _ring_order(n, edges):
    """Links in an order that follows the chain (a depth-first walk), for drawing."""
    adj = {v: [] for v in range(n)}
    for a, b in edges:
        adj[a].append(b)
        adj[b].append(a)
    seen, order, stack = set(), [], [max(range(n), key=lambda v: len(adj[v]))]
    while stack:
        v = stack.pop()
        if v in seen:
            continue
        seen.add(v)
        order.append(v)
        stack.extend(sorted(adj[v], key=lambda w: -len(adj[w])))
    return order + [v for v in range(n) if v not in seen]


def _atlas_page(entries, links, dof):
    import html as _html
    cells = []
    for e in entries:
        orders = ", ".join(f"{v} {k}" for k, v in e.link_orders.items())
        cells.append(f'<figure id="chain-{e.id}">{_atlas_svg(e)}<figcaption><b>{e.id}</b>: '
                     f'{_html.escape(orders)}; {e.inversion_classes} distinct inversion'
                     f'{"s" if e.inversion_classes != 1 else ""}</figcaption></figure>')
    total = sum(e.inversion_classes for e in entries)
    return ("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<title>Atlas: {links} links, {dof} degree(s) of freedom</title><style>"
            "body{font-family:Georgia,serif;margin:2em;color:#1b1b1b}"
            "h1{font-family:Arial,sans-serif;color:#1f4e79}"
            ".grid{display:flex;flex-wrap:wrap;gap:10px}"
            "figure{margin:0;width:170px;border:1px solid #ddd;padding:4px}"
            "figcaption{font-size:11px}</style></head><body>"
            f"<h1>Kinematic chains of {links} links, {dof} degree(s) of freedom</h1>"
            f"<p>{len(entries)} chains (non-isomorphic, non-degenerate, simple revolute "
            f"joints), {total} distinct inversions. Links are circles (darker for more "
            "joints), joints squares.</p>"
            f"<div class=\"grid\">{''.join(cells)}</div></body></html>\n")
