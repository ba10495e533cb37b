"""The free bodies as a textbook prints them: every link in its panel with its arrows
inside it, no label over another, the arrows to one scale with a force scale."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

import chaingraph
from chaingraph import LinkMass
from chaingraph.drawing.forces import forces_on, free_body_shapes, free_body_svg
from chaingraph.drawing.scene import label_box
from chaingraph.naming.catalog import catalog_files, catalog_path

WITH_MASSES = [p for p in catalog_files() if (c := chaingraph.load(p)).masses
               and c.mechanism is not None]


def test_there_are_catalog_mechanisms_with_masses():
    assert len(WITH_MASSES) >= 4


def boxes_overlap(a, b):
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


@pytest.mark.parametrize("path", WITH_MASSES, ids=lambda p: p.stem)
@pytest.mark.parametrize("at", [None, 137.0])
def test_no_label_over_another_and_every_arrow_in_its_panel(path, at):
    chain = chaingraph.load(path)
    if at is not None:
        # a pose well inside the range of an input that rocks (137 degrees for a crank)
        rng = chaingraph.solve(chain, steps=4).summary.input_range
        if not rng[0] <= at <= rng[1]:
            at = rng[0] + 0.37 * (rng[1] - rng[0])
    f = (chaingraph.forces(chain, steps=4, omega=30.0).pose(0) if at is None
         else chaingraph.forces(chain, at=at, omega=30.0))
    shapes, view = free_body_shapes(f)
    texts = [s for s in shapes if s.kind == "text"]
    boxes = [label_box(*s.points[0], s.text, s.size) for s in texts]
    for i, a in enumerate(boxes):
        for b, s in zip(boxes[i + 1:], texts[i + 1:]):
            assert not boxes_overlap(a, b), (texts[i].text, s.text)
    panels = {dict(s.data)["link"]: s.points for s in shapes if s.cls == "panel"}
    assert sorted(panels) == sorted(x for x in chain.links if x != f.fixed)
    arrows = [s for s in shapes if s.cls in ("force", "arrowhead")]
    assert arrows
    for s in arrows:
        (x0, y0), _, (x1, y1), _ = panels[dict(s.data)["link"]]
        for x, y in s.points:
            assert x0 <= x <= x1 and y0 <= y <= y1, (dict(s.data), (x, y))
    # the labels inside the picture, and each force's label in its own panel
    for s, box in zip(texts, boxes):
        assert view.lo[0] - view.pad <= box[0] and box[2] <= view.hi[0] + view.pad
        if s.cls == "force-label":
            (x0, y0), _, (x1, y1), _ = panels[dict(s.data)["link"]]
            assert x0 <= box[0] and box[2] <= x1 and y0 <= box[1] and box[3] <= y1


def test_the_force_scale_is_the_arrows_scale_and_the_bodies_have_their_shapes():
    f = chaingraph.forces(chaingraph.load(catalog_path("shaper-crank-and-slotted-lever")),
                          at=100.0, omega=5.0)
    shapes, _ = free_body_shapes(f)
    bar = next(s for s in shapes if s.cls == "scale")
    label = next(s for s in shapes if s.cls == "scale-label")
    value = float(label.text.split(": ")[1].split()[0])
    value *= 1000 if label.text.endswith("kN") else 1
    per_newton = math.dist(*bar.points) / value
    for s, head in zip(shapes, shapes[1:]):
        if s.cls == "force":
            link = dict(s.data)["link"]
            what = dict(s.data)["force"]
            force = next(x[3] for x in forces_on(f, link) if x[0] == what)
            # from the shaft's start to the head's point, the way of the force
            tail, tip = s.points[0], head.points[0]
            assert math.dist(tail, tip) / math.hypot(*force) == pytest.approx(per_newton,
                                                                              rel=1e-9)
            assert (tip[0] - tail[0]) * force[0] + (tip[1] - tail[1]) * force[1] > 0
    # the block a slider, the ram a block too, the crank a bar, slots on the lever
    kinds = {(s.cls, dict(s.data).get("link")) for s in shapes}
    assert {("block", "block"), ("block", "ram"), ("bar", "crank"),
            ("slot", "slotted lever")} <= kinds
    assert "force scale" in free_body_svg(f)


def test_a_ternary_link_is_a_plate():
    chain = chaingraph.load(catalog_path("stephenson-iii-mechanism"))
    chain = replace(chain, masses=tuple(LinkMass(x, 1.0) for x in chain.links
                                        if x != chain.mechanism.fixed),
                    units=chain.units or "mm")
    f = chaingraph.forces(chain, at=30.0, omega=3.0)
    shapes, _ = free_body_shapes(f)
    ternary = [x for x in chain.links if x != f.fixed
               and sum(x in j.links for j in chain.joints) >= 3]
    assert ternary
    plates = {dict(s.data)["link"] for s in shapes if s.cls == "plate"}
    assert set(ternary) <= plates


@pytest.mark.parametrize("path", WITH_MASSES, ids=lambda p: p.stem)
def test_every_arrow_lies_off_its_body_as_a_textbook_draws_it(path):
    """A reaction or a load at a pin is drawn from outside the body: a push ends at its
    pin, a pull starts there and goes out (a connecting rod's arrows lie beyond its
    pins, not along it); a weight or an inertia force starts at the centre of mass.
    Checked from the drawing: each arrow's far end (its tail, or its head for a pull)
    is farther from the middle of its body's pins than the end at its point."""
    chain = chaingraph.load(path)
    f = chaingraph.forces(chain, steps=4, omega=30.0).pose(1)
    shapes, _ = free_body_shapes(f)
    pins: dict[str, list] = {}
    for s in shapes:
        if s.cls == "pin":
            pins.setdefault(dict(s.data)["link"], []).append(s.points[0])
    checked = 0
    for s, head in zip(shapes, shapes[1:]):
        if s.cls != "force":
            continue
        link, what = dict(s.data)["link"], dict(s.data)["force"]
        key = next(k for w, k, _, _ in forces_on(f, link) if w == what)
        tail, tip = s.points[0], head.points[0]
        if key in ("weight", "inertia force"):
            continue
        xs, ys = [p[0] for p in pins[link]], [p[1] for p in pins[link]]
        middle = (0.5 * (max(xs) + min(xs)), 0.5 * (max(ys) + min(ys)))
        at_point = min((tail, tip), key=lambda p: min(math.dist(p, q) for q in pins[link])) \
            if len(pins[link]) > 1 else None
        if at_point is None or min(math.dist(at_point, q) for q in pins[link]) > 1e-9:
            continue                        # not at a pin (a block's, a load's point)
        far = tip if at_point is tail else tail
        assert math.dist(far, middle) >= math.dist(at_point, middle) - 1e-9, (link, what)
        checked += 1
    assert checked
