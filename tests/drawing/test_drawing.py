"""The mechanism drawings, read back: blocks on guides in every frame, frames that move."""

import math

import xml.etree.ElementTree as ET

import pytest

import chaingraph
from chaingraph.drawing.mechanism import mechanism_svg

from ..conftest import CATALOG, catalog_path, run_cli

NS = {"s": "http://www.w3.org/2000/svg"}
MECHANISMS = [p for p in CATALOG if (c := chaingraph.load(p)).mechanism is not None
              and c.has_pose and all(j.kind in "RP" for j in c.joints)]


def points(element):
    return [tuple(map(float, xy.split(","))) for xy in element.get("points").split()]


@pytest.fixture(scope="module")
def drawings():
    out = {}
    for path in MECHANISMS:
        motion = chaingraph.solve(chaingraph.load(path), steps=72)
        out[path.stem] = (motion, ET.fromstring(mechanism_svg(motion, frames=12)))
    return out


@pytest.mark.parametrize("name", [p.stem for p in MECHANISMS])
def test_every_sliding_pair_is_a_block_on_its_guide_in_every_frame(drawings, name):
    motion, svg = drawings[name]
    slides = [j for j in motion.plan.chain.joints if j.kind == "P"]
    frames = svg.findall("s:g[@class='frame']", NS)
    assert len(frames) >= 12
    width = float(svg.get("viewBox").split()[2])
    for frame in frames:
        for j in slides:
            (block,) = frame.findall(f"s:polygon[@class='block'][@data-joint='{j.id}']", NS)
            (guide,) = frame.findall(f"s:line[@class='guide'][@data-joint='{j.id}']", NS)
            corners = points(block)
            assert len(corners) == 4
            cx = sum(p[0] for p in corners) / 4
            cy = sum(p[1] for p in corners) / 4
            x1, y1, x2, y2 = (float(guide.get(k)) for k in ("x1", "y1", "x2", "y2"))
            length = math.hypot(x2 - x1, y2 - y1)
            # on the guide's line, and between its ends
            off = abs((x2 - x1) * (cy - y1) - (y2 - y1) * (cx - x1)) / length
            along = ((cx - x1) * (x2 - x1) + (cy - y1) * (y2 - y1)) / length
            assert off <= 1e-3 * width, (j.id, off)
            assert 0 < along < length, (j.id, along, length)
            assert guide.get("data-link") in j.links


@pytest.mark.parametrize("name", [p.stem for p in MECHANISMS])
def test_every_animation_moves(drawings, name):
    _, svg = drawings[name]
    frames = svg.findall("s:g[@class='frame']", NS)
    shapes = {ET.tostring(f).decode().split(">", 1)[1].split("</animate>", 1)[-1] for f in frames}
    assert len(shapes) > 1, "every frame is the same"


def test_the_slot_is_drawn_on_the_link_that_reaches_past_the_block(drawings):
    """The textbook numbers the crank and slotted lever so that its small block carries
    the pair's guide; the slot is drawn on the lever."""
    _, svg = drawings["crank-and-slotted-lever-mechanism"]
    guide = svg.find("s:g[@class='frame']/s:line[@class='guide']", NS)
    assert guide.get("data-link") == "slotted lever"
    assert svg.findall("s:g[@class='frame']/s:line[@class='slot']", NS)


@pytest.mark.parametrize("name, cylinder, rod", [
    ("oscillating-cylinder-engine", "cylinder", "piston rod"),
    ("pendulum-pump", None, None),
])
def test_an_oscillating_cylinder_is_a_barrel_with_the_rod_and_piston_in_it(drawings, name,
                                                                           cylinder, rod):
    """A block on a pin to the frame is a trunnion: the barrel swings on it, closed at
    the end away from the rod, and the piston (the block) stays inside it in every frame,
    joined to the rod's pin by the rod. (The pendulum pump's cylinder is the frame: a
    way.)"""
    motion, svg = drawings[name]
    (slide,) = [j for j in motion.plan.chain.joints if j.kind == "P"]
    barrels = svg.findall(".//s:polyline[@class='barrel']", NS)
    if cylinder is None:
        assert not barrels and svg.findall(".//s:line[@class='hatch']", NS)
        return
    assert len(barrels) == len(svg.findall("s:g[@class='frame']", NS))
    for frame in svg.findall("s:g[@class='frame']", NS):
        (barrel,) = frame.findall(f"s:polyline[@class='barrel'][@data-joint='{slide.id}']", NS)
        assert barrel.get("data-link") == cylinder
        (p0, p1, p2, p3) = points(barrel)            # open end, closed end, closed end, open
        (block,) = frame.findall(f"s:polygon[@class='block'][@data-joint='{slide.id}']", NS)
        cx = sum(p[0] for p in points(block)) / 4
        cy = sum(p[1] for p in points(block)) / 4
        # the piston's centre lies inside the barrel's rectangle
        ax, ay = p1[0] - p0[0], p1[1] - p0[1]
        bx, by = p3[0] - p0[0], p3[1] - p0[1]
        t = ((cx - p0[0]) * ax + (cy - p0[1]) * ay) / (ax * ax + ay * ay)
        n = ((cx - p0[0]) * bx + (cy - p0[1]) * by) / (bx * bx + by * by)
        assert 0 < t < 1 and 0 < n < 1, (t, n)
        (bar,) = frame.findall(f"s:polyline[@class='bar'][@data-link='{rod}']", NS)
        ends = points(bar)
        assert min(math.hypot(x - cx, y - cy) for x, y in ends) < 1e-2 * math.hypot(ax, ay)


def test_a_link_without_pins_is_drawn_between_its_guides(drawings):
    """The Scotch yoke's yoke has no R joint: its body joins the block in the frame's
    way to the middle of its slot, and it moves with them."""
    motion, svg = drawings["scotch-yoke"]
    frames = svg.findall("s:g[@class='frame']", NS)
    bars = [f.find("s:polyline[@class='bar'][@data-link='yoke']", NS) for f in frames]
    assert all(b is not None for b in bars)
    assert len({b.get("points") for b in bars}) > 1
    way = frames[0].find("s:line[@class='guide'][@data-joint='G1']", NS)
    assert way.get("data-link") == "frame"          # the yoke slides in the frame's way


def test_fixed_pivots_stand_on_hatched_ground_and_names_are_text(tmp_path):
    chain = chaingraph.load(catalog_path("reciprocating-engine"))
    odd = chain.relabelled(links={"crank": "$\\alert$ <crank> & co"})
    svg = mechanism_svg(chaingraph.solve(odd, steps=36))
    root = ET.fromstring(svg)                       # well formed, names escaped
    assert len(root.findall(".//s:polygon[@class='ground']", NS)) == 1
    assert root.find(".//s:polyline[@class='bar']", NS).get("data-link") == "$\\alert$ <crank> & co"
    assert "mm" in root.find(".//s:g[@class='scale']/s:text", NS).text


def test_solve_draw_writes_the_drawing(tmp_path):
    out = tmp_path / "shaper.svg"
    code, _, err = run_cli("solve", catalog_path("shaper-crank-and-slotted-lever"), "--draw", out)
    assert code == 0, err
    root = ET.fromstring(out.read_text())
    assert len(root.findall(".//s:polygon[@class='block']", NS)) == 2


@pytest.mark.parametrize("path", CATALOG, ids=[p.stem for p in CATALOG])
def test_every_chain_has_a_skeleton(path):
    """The skeleton is the animation's scene at the drawn pose: every joint a pin, a
    block (on its guide) or a higher pair; every moving link of two joints or more a
    body; the fixed link the ground."""
    from chaingraph.drawing.mechanism import skeleton_svg
    chain = chaingraph.load(path)
    root = ET.fromstring(skeleton_svg(chain))
    marks = (root.findall(".//s:circle[@class='pin']", NS)
             + root.findall(".//s:polygon[@class='block']", NS)
             + root.findall(".//s:circle[@class='higher']", NS))
    assert len(marks) == len(chain.joints)
    # (a cam's body is its profile, a gear's its pitch circle)
    bodies = root.findall(".//s:polygon[@class='plate']", NS) + \
        root.findall(".//s:polyline[@class='bar']", NS) + \
        root.findall(".//s:polygon[@class='cam']", NS) + \
        root.findall(".//s:circle[@class='pitch']", NS)
    fixed = chain.mechanism.fixed if chain.mechanism else None
    # the fixed link is the ground (hatched pivots and ways), never a moving body; a
    # block on the link's one pin is the link's body
    assert {e.get("data-link") for e in bodies} == {
        x for x in chain.links if x != fixed and len(
            {(round(j.at[0], 6), round(j.at[1], 6)) for j in chain.joints_of(x)}) >= 2}
    grounds = root.findall(".//s:polygon[@class='ground']", NS)
    assert len(grounds) == sum(1 for j in chain.joints if j.kind == "R" and fixed in j.links)
    guides = root.findall(".//s:line[@class='guide']", NS)
    assert len(guides) == sum(j.kind == "P" for j in chain.joints)
    # every pin after every block: a pin at a block's place stays in sight
    order = [e.get("class") for e in root.iter() if e.get("class") in ("pin", "block")]
    assert "block" not in order[order.index("pin"):] if "pin" in order else True


def test_draw_mechanism_takes_a_chain_in_its_drawn_pose():
    """A chain with a mechanism is drawn in its drawn pose (it raised AttributeError:
    'Chain' object has no attribute 'plan'); anything else is one line saying what it
    takes."""
    from chaingraph.drawing.plots import draw_mechanism
    chain = chaingraph.load(catalog_path("non-grashof-four-bar"))
    fig = draw_mechanism(chain)
    from matplotlib.patches import Circle
    pins = [p.center for p in fig.axes[0].patches if isinstance(p, Circle)]
    assert len(pins) == len(chain.joints)
    for j in chain.joints:
        assert min(math.dist(j.at, p) for p in pins) <= 1e-9 * 100, j.id
    with pytest.raises(TypeError, match="takes a solved motion"):
        draw_mechanism("beam-engine.toml")


# -- one scene, two emitters ----------------------------------------------------------------
@pytest.mark.parametrize("name", ["whitworth-quick-return-with-ram", "oscillating-cylinder-engine",
                                  "stephenson-iii-mechanism", "elliptical-trammels"])
def test_the_svg_and_the_matplotlib_picture_are_one_scene(name):
    """The same shapes reach both formats: as many plates, bars, blocks, pins and labels
    in the SVG as matplotlib draws, each pin where the solver puts its joint."""
    from matplotlib.patches import Circle, Polygon

    from chaingraph.drawing.mechanism import mechanism_svg
    from chaingraph.drawing.plots import draw_mechanism
    from chaingraph.drawing.scene import Scene, frame_shapes

    motion = chaingraph.solve(chaingraph.load(catalog_path(name)), steps=24)
    shapes = frame_shapes(Scene.of_motion(motion), 0)
    svg = mechanism_svg(motion)
    kinds = {}
    for s in shapes:
        kinds[s.cls] = kinds.get(s.cls, 0) + 1
    for cls, count in kinds.items():
        assert svg.count(f'class="{cls}"') == count, cls
    fig = draw_mechanism(motion)
    ax = fig.axes[0]
    circles = [p for p in ax.patches if isinstance(p, Circle)]
    polygons = [p for p in ax.patches if isinstance(p, Polygon)]
    assert len(circles) == kinds.get("pin", 0) + kinds.get("point", 0)
    assert len(polygons) == sum(kinds.get(c, 0) for c in ("plate", "block", "ground"))
    assert len(ax.texts) == kinds["label"]
    pins = [s for s in shapes if s.cls == "pin"]
    for s in pins:
        joint = dict(s.data)["joint"]
        at = (motion[f"x:{joint}"][0], motion[f"y:{joint}"][0])
        assert math.dist(s.points[0], at) <= 1e-9 * motion.plan.size
        assert any(math.dist(c.center, at) <= 1e-9 * motion.plan.size for c in circles)


def test_the_scene_of_a_sweep_is_the_scene_of_each_of_its_poses():
    """The scene reads the motion's typed fields (positions, the guides' angles in
    radians, the slides): at every step it is the scene of that one pose, solved alone."""
    import numpy as np

    from chaingraph.drawing.scene import Scene
    from chaingraph.kinematics.pose import pose_motion
    chain = chaingraph.load(catalog_path("shaper-crank-and-slotted-lever"))
    motion = chaingraph.solve(chain, steps=8)
    sweep = Scene.of_motion(motion)
    for k in (0, 3, 8):
        one = Scene.of_pose(pose_motion(chain, at=motion.input_values(k)))
        for name, (x, y) in one.xy.items():
            assert (sweep.xy[name][0][k], sweep.xy[name][1][k]) == pytest.approx(
                (x[0], y[0]), abs=1e-9)
        for j in ("S", "G"):
            turn = np.remainder(sweep.angle[j][k] - one.angle[j][0] + math.pi, 2 * math.pi)
            assert turn - math.pi == pytest.approx(0.0, abs=1e-12)
            assert sweep.slide[j][k] == pytest.approx(one.slide[j][0], abs=1e-9)
