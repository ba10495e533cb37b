"""Outlines to cut (issue 40): each link's part at one pose, read back from the DXF with
ezdxf (a layer per link, a hole at every pin where the pose puts it, closed outlines,
the units recorded) and from the SVG (the same parts, true size)."""

import io
import itertools
import math
import re
import sys
import xml.etree.ElementTree as ET

import ezdxf
import pytest
from ezdxf import path as dxf_path

import chaingraph
from chaingraph.drawing.outlines import layer_name, link_outlines, outlines_dxf, outlines_svg
from chaingraph.errors import MechanismError
from chaingraph.geometry import segment_distance
from chaingraph.kinematics import pose_motion
from chaingraph.naming.catalog import catalog_path

# a four-bar, a slider crank, a Watt six-bar, a slotted lever (a slot in a moving link)
CASES = [("four-bar-chain", None), ("beam-engine", 100.0), ("reciprocating-engine", 130.0),
         ("watt-i-mechanism", 75.0), ("crank-and-slotted-lever-mechanism", 200.0)]


def _read(text):
    return ezdxf.read(io.StringIO(text))


def _polygon(entity):
    """A closed LWPOLYLINE as points along its lines and arcs (chords of 1e-4)."""
    return [(v.x, v.y) for v in dxf_path.make_path(entity).flattening(1e-4)]


def _inside(p, poly):
    inside = False
    for (x1, y1), (x2, y2) in zip(poly, poly[1:] + poly[:1]):
        if (y1 > p[1]) != (y2 > p[1]) and p[0] < x1 + (p[1] - y1) * (x2 - x1) / (y2 - y1):
            inside = not inside
    return inside


@pytest.mark.parametrize("name, at", CASES)
def test_the_dxf_has_a_layer_per_link_and_a_hole_at_every_pin(name, at):
    chain = chaingraph.load(catalog_path(name))
    where = chain.positions() if at is None else pose_motion(chain, at=at).positions
    parts = link_outlines(chain, at=at, width=6.0, hole=2.5)
    doc = _read(outlines_dxf(parts))
    assert doc.header["$INSUNITS"] == 4                      # the file's mm
    layers = {layer.dxf.name for layer in doc.layers} - {"0", "Defpoints"}
    assert layers == {layer_name(link) for link in chain.links}
    msp = doc.modelspace()
    for link in chain.links:
        circles = msp.query(f'CIRCLE[layer=="{layer_name(link)}"]')
        pins = [j for j in chain.joints_of(link) if j.kind == "R"]
        assert len(circles) == len(pins)
        for j in pins:
            assert min(math.dist((c.dxf.center.x, c.dxf.center.y), where[j.id])
                       for c in circles) <= 1e-9
        assert all(c.dxf.radius == 1.25 for c in circles)
        outlines = msp.query(f'LWPOLYLINE[layer=="{layer_name(link)}"]')
        assert outlines and all(e.closed for e in outlines)
        boundary = max(outlines, key=lambda e: len(_polygon(e)))
        for j in pins:                       # every pin in its part, clear of the edge
            poly = _polygon(boundary)
            assert _inside(where[j.id], poly)
            assert min(segment_distance(where[j.id], p, q) for p, q in
                       zip(poly, poly[1:] + poly[:1])) >= 3.0 - 1e-3 - 1e-9


def test_a_binary_link_is_a_bar_with_round_ends_of_half_the_width():
    """Every point of a bar's outline is half the width from the segment of its pins."""
    chain = chaingraph.load(catalog_path("four-bar-chain"))
    parts = link_outlines(chain, width=8.0)
    for part in parts.links:
        a, b = (h.centre for h in part.holes)
        assert all(abs(segment_distance(p, a, b) - 4.0) <= 1e-9
                   for p in part.boundary.points(degrees=3.0))


def test_a_ternary_link_is_a_plate_round_its_three_joints():
    chain = chaingraph.load(catalog_path("watt-i-mechanism"))
    parts = link_outlines(chain, width=10.0)
    doc = _read(outlines_dxf(parts))
    for link in ("coupler", "rocker"):
        pins = [j.id for j in chain.joints_of(link)]
        assert len(pins) == 3
        boundary, = doc.modelspace().query(f'LWPOLYLINE[layer=="{link}"]')
        poly = _polygon(boundary)
        assert all(_inside(chain.joint(j).at, poly) for j in pins)
        assert parts.link(link).boundary.contains(chain.joint(pins[0]).at)


def test_a_slot_lets_its_block_travel_the_whole_cycle():
    """The engine's guide is a slot in the frame: the crosshead's pin stays in it over a
    turn of the crank, and the block (a width across, two along) sits on the pin."""
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    parts = link_outlines(chain, width=10.0)
    slot, = parts.link("frame").slots
    motion = chaingraph.solve(chain, steps=72)
    for x, y in zip(motion.joint("B").x, motion.joint("B").y):
        assert slot.contains((float(x), float(y)))
        assert parts.link("frame").boundary.contains((float(x), float(y)))
    block = parts.link("crosshead").boundary.points(degrees=1.0)
    xs, ys = [p[0] for p in block], [p[1] for p in block]
    assert max(xs) - min(xs) == pytest.approx(20.0) and max(ys) - min(ys) == pytest.approx(10.0)


def test_the_svg_has_the_same_parts_at_true_size():
    chain = chaingraph.load(catalog_path("watt-i-mechanism"))
    parts = link_outlines(chain, width=10.0, hole=4.0)
    root = ET.fromstring(outlines_svg(parts))
    ns = {"s": "http://www.w3.org/2000/svg"}
    assert root.get("width").endswith("mm")
    groups = root.findall("s:g", ns)
    assert [g.get("data-link") for g in groups] == list(chain.links)
    for g in groups:
        part = parts.link(g.get("data-link"))
        path, = g.findall("s:path[@class='outline']", ns)
        # the path's vertices are the contour's, y flipped, shifted as one (SVG's
        # coordinates keep 1e-5 of the picture's size: 1e-3 mm here)
        ends = [tuple(map(float, p.split(","))) for p in
                re.findall(r"(-?[\d.]+,-?[\d.]+)(?= [LAZ]|$)", path.get("d"))]
        model = part.boundary.vertices
        assert len(ends) == len(model)
        shift = (ends[0][0] - model[0][0], ends[0][1] + model[0][1])
        assert all(math.dist((x - shift[0], shift[1] - y), v) <= 1.5e-3
                   for (x, y), v in zip(ends, model))
        holes = g.findall("s:circle", ns)
        assert [h.get("data-joint") for h in holes] == [h.joint for h in part.holes]
        assert all(float(h.get("r")) == 2.0 for h in holes)
        # distances between the holes as in the mechanism (SVG's y is flipped)
        for (h1, p1), (h2, p2) in itertools.combinations(zip(holes, part.holes), 2):
            d = math.dist((float(h1.get("cx")), float(h1.get("cy"))),
                          (float(h2.get("cx")), float(h2.get("cy"))))
            assert d == pytest.approx(math.dist(p1.centre, p2.centre), abs=1.5e-3)


def test_bad_sizes_are_refused_by_parameter():
    chain = chaingraph.load(catalog_path("four-bar-chain"))
    with pytest.raises(MechanismError) as e:
        link_outlines(chain, width=5.0, hole=5.0)
    assert e.value.parameter == "hole"
    with pytest.raises(MechanismError) as e:
        link_outlines(chain, width=-1.0)
    assert e.value.parameter == "width"


def test_dxf_without_ezdxf_says_which_extra(monkeypatch):
    parts = link_outlines(chaingraph.load(catalog_path("four-bar-chain")))
    monkeypatch.setitem(sys.modules, "ezdxf", None)
    with pytest.raises(ImportError, match=r"DXF needs the cad extra: pip install "
                                          r"chaingraph\[cad\]"):
        outlines_dxf(parts)


@pytest.mark.parametrize("name", ["crank-and-slotted-lever-mechanism",
                                  "whitworth-quick-return-mechanism",
                                  "oscillating-cylinder-engine",
                                  "shaper-crank-and-slotted-lever"])
def test_every_block_is_in_its_slot_at_every_pose(name):
    """A sliding pair's point, where the solver puts it at the pose, lies in a slot cut
    in one of the pair's two links."""
    chain = chaingraph.load(catalog_path(name))
    for at in (0.0, 77.0, 150.0, 230.0, 300.0):
        slides = pose_motion(chain, at=at).slides
        parts = link_outlines(chain, at=at)
        for j in chain.joints:
            if j.kind == "P":
                assert any(slot.contains(slides[j.id].at) for link in j.links
                           for slot in parts.link(link).slots), (at, j.id)
