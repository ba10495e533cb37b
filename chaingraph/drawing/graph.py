"""Drawing the link-joint graph (matplotlib, imported only here).

Links are circles, joints squares labelled with their kind; a P joint's edge to the link
that carries its guide has an arrow; higher pairs are dashed; the fixed link (of a
mechanism) is dark. Nodes start from the drawn pose (a link at the centre of its joints)
and a few spring-layout iterations pull apart those that coincide; a chain without a
pose gets a spring layout. The layout is seeded, so drawings are reproducible.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

import networkx as nx
import numpy as np

from chaingraph.drawing.plots import finish, plain_text, pyplot_module
from chaingraph.model.chain import Chain

if TYPE_CHECKING:                   # matplotlib is imported only when a graph is drawn
    from matplotlib.figure import Figure

__all__ = ["draw_link_joint_graph", "layout"]


def layout(chain: Chain) -> dict[tuple[str, str], np.ndarray]:
    """Positions of the link-joint graph's nodes for drawing."""
    g = chain.graph
    if chain.has_pose:
        init: dict[tuple[str, str], np.ndarray] = {}
        for j in chain.joints:
            init[("joint", j.id)] = np.array(j.at, dtype=float)
        for link in chain.links:
            pts = [np.array(j.at) for j in chain.joints_of(link)]
            init[("link", link)] = np.mean(pts, axis=0)
        span = max(np.ptp([p[0] for p in init.values()]), np.ptp([p[1] for p in init.values()]),
                   1e-9)
        init = {k: v / span for k, v in init.items()}
        return nx.spring_layout(g, pos=init, iterations=25, seed=7, k=0.25)
    return nx.spring_layout(g, seed=7)


@plain_text
def draw_link_joint_graph(chain: Chain, path: str | os.PathLike[str] | None = None,
                          ) -> Figure | None:
    """The link-joint graph of ``chain``: written as SVG (or PNG, by the file's ending)
    to ``path``, or returned as a matplotlib Figure without one."""
    plt = pyplot_module()
    g = chain.graph
    pos = layout(chain)
    fixed = chain.mechanism.fixed if chain.mechanism else None
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    links = [n for n in g if n[0] == "link"]
    joints = [n for n in g if n[0] == "joint"]
    lower = [(u, v) for u, v in g.edges if g.nodes[u if u[0] == "joint" else v]["kind"] in
             ("R", "P", "screw", "cylindrical", "spherical", "planar")]
    higher = [e for e in g.edges if e not in lower]
    nx.draw_networkx_edges(g, pos, edgelist=lower, ax=ax, width=1.6, edge_color="#444444")
    nx.draw_networkx_edges(g, pos, edgelist=higher, ax=ax, width=1.6, edge_color="#b05000",
                           style="dashed")
    guides = [(("joint", j.id), ("link", j.guide)) for j in chain.joints if j.kind == "P"]
    if guides:
        nx.draw_networkx_edges(g, pos, edgelist=guides, ax=ax, arrows=True, arrowstyle="-|>",
                               arrowsize=16, width=1.6, edge_color="#1f4e79",
                               node_shape="s", min_target_margin=14)
    colours = ["#1b1b1b" if n[1] == fixed else "#cfe3f5" for n in links]
    nx.draw_networkx_nodes(g, pos, nodelist=links, node_shape="o", node_size=900,
                           node_color=colours, edgecolors="#1f4e79", linewidths=1.5, ax=ax)
    kinds = [g.nodes[n]["kind"] for n in joints]
    jcol = ["#fff2cc" if k == "R" else "#d9ead3" if k == "P" else "#f4cccc" for k in kinds]
    nx.draw_networkx_nodes(g, pos, nodelist=joints, node_shape="s", node_size=420,
                           node_color=jcol, edgecolors="#7f6000", linewidths=1.2, ax=ax)
    nx.draw_networkx_labels(g, pos, labels={n: n[1] for n in links}, font_size=8, ax=ax,
                            font_color="#1b1b1b")
    if fixed is not None:
        nx.draw_networkx_labels(g, pos, labels={("link", fixed): fixed}, font_size=8, ax=ax,
                                font_color="white")
    nx.draw_networkx_labels(g, pos, labels={n: f"{n[1]}\n{g.nodes[n]['kind']}"
                                            for n in joints}, font_size=6, ax=ax)
    ax.set_title(f"{chain.name}: {len(links)} links, {len(joints)} joints"
                 + (f" ({fixed} fixed)" if fixed else ""), fontsize=9)
    ax.set_axis_off()
    ax.margins(0.12)
    fig.tight_layout()
    return finish(plt, fig, path)
