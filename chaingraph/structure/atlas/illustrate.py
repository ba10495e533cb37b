"""A generic drawn pose for an atlas chain, with readable proportions, and its
inversions as mechanisms with a natural input.

The pose comes from a layout of the link graph (planar where the graph is planar, so
that no two bars cross, evened out by a spring layout where that keeps it planar; else
a spring layout): each joint sits at the middle of the links
it joins, moved a little off by a fixed pseudo-random amount so that no three joints
line up by accident and no pose is a dead centre by construction; a sliding pair's line
runs from its guide's link towards its block's. The size is about 100 units.

An inversion's natural input is a link turning about the fixed link (a turning pair of
two links on it), else a slide on it (a sliding pair on it).
"""

from __future__ import annotations

import math
import random
from collections.abc import Iterable, Mapping

import networkx as nx
import numpy as np

from chaingraph.model.chain import Chain, Input, Joint, Mechanism

_Point = tuple[float, float]

__all__ = ["generic_pose", "natural_input", "inversion_mechanism", "link_layout"]


def link_layout(chain: Chain) -> dict[str, _Point]:
    """Positions of the chain's links (a dict), about 100 units across."""
    # the links as their numbers: networkx's planar embedding iterates over sets of
    # nodes, whose order for names would change with Python's hash seed from run to run
    number = {x: k for k, x in enumerate(chain.links)}
    g = nx.Graph()
    g.add_nodes_from(range(len(chain.links)))
    for j in chain.joints:
        for i, a in enumerate(j.links):
            for b in j.links[i + 1:]:
                g.add_edge(number[a], number[b])
    planar, _ = nx.check_planarity(g)
    if planar:
        # a planar drawing, evened out by a spring layout from it when that keeps it
        # planar (no two bars cross)
        pos = nx.planar_layout(g)
        spread = nx.spring_layout(g, pos=pos, iterations=60, seed=1)
        if not _crossings(g, spread):
            pos = spread
    else:
        pos = nx.spring_layout(g, seed=1, iterations=200)
    xy = np.array([pos[number[x]] for x in chain.links], dtype=float)
    span = max(float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1])), 1e-9)
    xy = (xy - xy.mean(axis=0)) * (100.0 / span)
    return {x: (float(p[0]), float(p[1])) for x, p in zip(chain.links, xy)}


def _crossings(g: nx.Graph, pos: Mapping[str, _Point]) -> int:
    """How many pairs of the graph's edges cross in the layout ``pos``."""
    edges = list(g.edges)
    count = 0
    for i, (a, b) in enumerate(edges):
        for c, d in edges[i + 1:]:
            if len({a, b, c, d}) == 4 and _segments_cross(pos[a], pos[b], pos[c], pos[d]):
                count += 1
    return count


def _segments_cross(p: _Point, q: _Point, r: _Point, s: _Point) -> bool:
    def side(a: _Point, b: _Point, c: _Point) -> float:
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return side(p, q, r) * side(p, q, s) < 0 and side(r, s, p) * side(r, s, q) < 0


def generic_pose(chain: Chain, *, seed: int = 0) -> Chain:
    """The chain with a drawn pose: every joint at the middle of its links' places in
    :func:`link_layout`, moved off by up to 6 units (a fixed pseudo-random amount, one
    per ``seed``), P joints along the line from the guide's link to the block's; no
    turning pair within :data:`CLEARANCE` of the size of a sliding line of its links
    (it would read back as a joint drawn on the line and rounded).

    Examples
    --------
    >>> from chaingraph.structure.atlas import atlas
    >>> posed = generic_pose(next(atlas(links=4, prismatic=1)))
    >>> all(j.at is not None for j in posed.joints), posed.has_pose
    (True, True)
    """
    places = link_layout(chain)
    rnd = random.Random(f"{seed}:{[j.links for j in chain.joints]}")
    joints = []
    for j in chain.joints:
        pts = np.array([places[x] for x in j.links])
        at = pts.mean(axis=0) + np.array([rnd.uniform(-6, 6), rnd.uniform(-6, 6)])
        axis = None
        if j.kind == "P":
            d = np.subtract(places[j.links[1]], places[j.links[0]])
            axis = round(math.degrees(math.atan2(d[1], d[0])) + rnd.uniform(-25, 25), 6)
        joints.append(Joint(j.id, j.kind, j.links, at=(round(float(at[0]), 6),
                                                       round(float(at[1]), 6)), axis=axis))
    return Chain(chain.name, tuple(_clear_of_lines(joints)), family=chain.family,
                 units="mm", notes=chain.notes)


#: the least distance of a turning pair from a sliding line of its links, as a share of
#: the pose's size: far beyond what a file reader takes for rounding (1e-3), so that a
#: file of the pose reads back exactly as written
CLEARANCE = 0.02


def _clear_of_lines(joints: Iterable[Joint]) -> list[Joint]:
    """The joints with every turning pair that lies near a sliding line of its links
    (within :data:`CLEARANCE` of the size) moved off it, across the line, to that
    distance (a few passes: a move may bring it near another line)."""
    joints = list(joints)
    at = [j.at for j in joints if j.at is not None]
    size = max(max(p[0] for p in at) - min(p[0] for p in at),
               max(p[1] for p in at) - min(p[1] for p in at))
    clear = CLEARANCE * size
    for _ in range(4):
        moved = False
        for p in [j for j in joints if j.kind == "P"]:
            if p.axis is None or p.at is None:          # every joint is posed here
                continue
            n = (-math.sin(math.radians(p.axis)), math.cos(math.radians(p.axis)))
            for i, j in enumerate(joints):
                if j.kind != "R" or j.at is None or not set(j.links) & set(p.links):
                    continue
                d = n[0] * (j.at[0] - p.at[0]) + n[1] * (j.at[1] - p.at[1])
                if abs(d) < clear:
                    step = math.copysign(clear * 1.01, d if d else 1.0) - d
                    joints[i] = Joint(j.id, j.kind, j.links, at=(
                        round(j.at[0] + step * n[0], 6), round(j.at[1] + step * n[1], 6)))
                    moved = True
        if not moved:
            break
    return joints


def natural_input(chain: Chain, fixed: str) -> Joint | None:
    """The joint a mechanism with ``fixed`` fixed is naturally driven by: a turning pair
    of two links on the fixed link, else a sliding pair on it; None when it has neither.
    """
    on = [j for j in chain.joints if fixed in j.links and len(j.links) == 2]
    turning = [j for j in on if j.kind == "R"]
    natural = turning or [j for j in on if j.kind == "P"]
    return natural[0] if natural else None


def inversion_mechanism(chain: Chain, fixed: str, *, name: str | None = None,
                        slide: float | None = None) -> Chain | None:
    """The posed chain as a mechanism with ``fixed`` fixed, driven by its natural input
    (None when it has none). ``slide``: a sliding input's sweep, from ``-slide`` to
    ``slide`` about the drawn pose (for a slide without limits, whose whole range
    cannot be swept); by default the input's whole range."""
    joint = natural_input(chain, fixed)
    if joint is None:
        return None
    item = Input(joint.id) if slide is None or joint.kind != "P" else \
        Input(joint.id, -float(slide), float(slide))
    return Chain(name or f"{chain.name}, {fixed} fixed", chain.joints, family=chain.family,
                 units=chain.units, notes=chain.notes,
                 mechanism=Mechanism(fixed, inputs=(item,)))
