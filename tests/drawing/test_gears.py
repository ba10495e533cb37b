"""Gear trains drawn (issue 39): every gear's pitch circle about its axis with the radii
the teeth and the drawn axes give, the carriers' arms, the frame's bearings, labels that
do not overlap, and the graph: a vertex per link, an arc per gear pair marked with its
carrier, a line per turning pair with its axis letter."""

import itertools
import math

import pytest

from chaingraph.drawing.gears import (
    gear_circles,
    schematic_shapes,
    label_boxes,
    train_graph_shapes,
    train_shapes,
    train_svg,
    tree_layout,
)
from chaingraph.files import load
from chaingraph.naming.catalog import catalog_dir, catalog_path
from chaingraph.structure.atlas.gears import chain_graph, gear_atlas

#: the textbook's trains, in the catalog
TRAINS = sorted(catalog_dir().glob("*-gear-train.toml"))


def _overlap(a, b):
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


@pytest.mark.parametrize("path", TRAINS, ids=lambda p: p.stem)
def test_every_gear_is_drawn_about_its_axis(path):
    chain = load(path)
    circles = gear_circles(chain)
    assert {(g.id, x) for g in chain.gears for x in g.links} == {(i, x) for i, x, *_ in circles}
    for g in chain.gears:
        (_, _, ca, ra, _), (_, _, cb, rb, annulus) = [c for c in circles if c[0] == g.id]
        d = math.dist(ca, cb)
        assert annulus == g.internal
        # in mesh: the pitch circles touch (outside, or inside an annulus), radii as teeth
        assert math.isclose(rb - ra if g.internal else ra + rb, d, rel_tol=1e-12)
        assert math.isclose(ra / rb, g.teeth[0] / g.teeth[1], rel_tol=1e-12)
    shapes = train_shapes(chain, fixed="frame")
    drawn = {(dict(s.data)["link"], s.points[0], round(s.radius, 9)) for s in shapes
             if s.cls == "gear"}
    assert drawn == {(x, c, round(r, 9)) for _, x, c, r, _ in circles}
    assert sum(s.cls == "pin" for s in shapes) == sum(j.kind == "R" for j in chain.joints)
    bearings = [j for j in chain.joints if j.kind == "R" and "frame" in j.links]
    assert sum(s.cls == "ground" for s in shapes) == 2 * len(bearings)


@pytest.mark.parametrize("path", TRAINS, ids=lambda p: p.stem)
def test_labels_name_every_link_and_do_not_overlap(path):
    chain = load(path)
    shapes = train_shapes(chain, fixed="frame")
    texts = [s.text for s in shapes if s.kind == "text"]
    assert sorted(t.split(" (")[0] for t in texts) == sorted(chain.links)
    for a, b in itertools.combinations(label_boxes(shapes), 2):
        assert not _overlap(a, b)


def test_carriers_that_move_are_arms():
    chain = load(catalog_path("epicyclic-gear-train"))
    arms = [s for s in train_shapes(chain, fixed="frame") if s.cls == "arm"]
    assert [dict(s.data)["link"] for s in arms] == ["arm"]
    assert set(arms[0].points) == {(0.0, 0.0), (50.0, 0.0)}     # the axes it holds
    # held still, the frame's own axes are bearings, not an arm
    simple = load(catalog_path("simple-gear-train"))
    assert not any(s.cls == "arm" for s in train_shapes(simple, fixed="frame"))


def test_the_graph_has_every_link_pair_and_carrier():
    for e in gear_atlas(6, 1):
        names = [str(i + 1) for i in range(6)]
        shapes = train_graph_shapes(names, e.turning, e.gears)
        assert sum(s.cls == "vertex" for s in shapes) == 6
        assert sum(s.cls == "turning" for s in shapes) == 5
        assert sum(s.cls == "gear" for s in shapes) == len(e.gears) == 4
        carriers = sorted(s.text for s in shapes if s.cls == "carrier")
        assert carriers == sorted(str(c + 1) for _, _, c in e.gears)
        levels = [s.text for s in shapes if s.cls == "level"]
        assert len(levels) == 5 and len(set(levels)) == len(set(e.levels))


def test_the_tree_hangs_from_its_busiest_link():
    turning = [(0, 1), (0, 2), (0, 3), (3, 4)]
    at = tree_layout(5, turning)
    assert at[0][1] == 0 and {at[x][1] for x in (1, 2, 3)} == {-1.1} and at[4][1] == -2.2
    assert len({p for p in at}) == 5                  # no two vertices in one place
    assert at[0][0] == 0.5 * (at[1][0] + at[3][0])    # a parent over its children


def test_the_document_has_the_schematic_and_the_graph():
    chain = load(catalog_path("differential-gear-train"))
    svg = train_svg(chain, fixed="frame")
    links, turning, gears = chain_graph(chain)
    assert svg.count('class="vertex"') == len(links) == 7
    assert svg.count('class="turning"') == len(turning) == 6
    assert "<title>Differential gear train: gear train, frame fixed</title>" in svg
    assert 'class="gear"' in train_svg(chain, graph=False)
    assert 'class="vertex"' not in train_svg(chain, graph=False)


def _atlas_chains():
    """The chain files of the atlas's trains: 4 and 5 links, every third of 6."""
    from chaingraph.structure.atlas.gear_chains import gear_chain
    return ([gear_chain(e) for n in (4, 5) for e in gear_atlas(n, 1)]
            + [gear_chain(e) for e in gear_atlas(6, 1)[::3]])


ATLAS = _atlas_chains()


@pytest.mark.parametrize("chain", ATLAS + [load(p) for p in TRAINS],
                         ids=lambda c: c.name.replace(" ", "-"))
def test_schematic_names_every_link_once_and_labels_do_not_overlap(chain):
    fixed = chain.mechanism.fixed if chain.mechanism else "frame"
    shapes = schematic_shapes(chain, fixed=fixed)
    names = [s.text for s in shapes if s.cls == "name"]
    assert sorted(names) == sorted(chain.links)
    teeth = [s.text for s in shapes if s.kind == "text" and s.cls != "name"]
    assert sorted(teeth) == sorted(str(z) for g in chain.gears for z in g.teeth)
    for a, b in itertools.combinations(label_boxes(shapes), 2):
        assert not _overlap(a, b)


@pytest.mark.parametrize("chain", ATLAS, ids=lambda c: c.name.replace(" ", "-"))
def test_schematic_gears_in_mesh_touch_in_their_column(chain):
    """Each gear pair's two bars share a column and meet at one point (the pitch point:
    the axes' distance is the sum of the pitch radii); each axis is a centre line."""
    bars = {}
    for s in schematic_shapes(chain):
        if s.cls == "gear":
            (x0, y0), (x1, y1) = s.points
            assert x0 == x1
            bars.setdefault(x0, []).append((min(y0, y1), max(y0, y1)))
    assert len(bars) == len(chain.gears)
    for column in bars.values():
        (lo1, hi1), (lo2, hi2) = sorted(column)
        assert math.isclose(hi1, lo2, abs_tol=1e-9)
    axes = {s.points[0][1] for s in schematic_shapes(chain) if s.cls == "axis"}
    assert axes == {j.at[1] for j in chain.joints if j.kind == "R"}


@pytest.mark.parametrize("links, dof", [(4, 1), (5, 1), (6, 1), (6, 2)])
def test_graph_labels_do_not_overlap(links, dof):
    for e in gear_atlas(links, dof):
        shapes = train_graph_shapes([str(i + 1) for i in range(links)], e.turning, e.gears)
        boxes = label_boxes(shapes)
        assert len([s for s in shapes if s.cls == "carrier"]) == len(e.gears)
        for a, b in itertools.combinations(boxes, 2):
            assert not _overlap(a, b), e.key
