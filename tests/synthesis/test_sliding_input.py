"""Type synthesis through inversions driven by a sliding input (a P pair on the fixed
link): the space's families, tasks taken from known slider-driven mechanisms (sampled by
the solver at known slides) found again exactly, with and without a timing in slides,
each answer re-solved from its written file; a closed task leaves those families out,
counted by inversion.

The searches run one family each (``families``), from Python: a few seconds."""

import math

import numpy as np
import pytest

import chaingraph
from chaingraph.files import loads
from chaingraph.model.chainfile import toml_text
from chaingraph.synthesis import PointTargets, certify, motion, path
from chaingraph.synthesis.family import AtlasFamily, LoopFamily
from chaingraph.synthesis.optimiser import timed_guides
from chaingraph.synthesis.type_synthesis import NOT_CHOSEN, SLIDING_CLOSED, atlas_space

#: slides of the engine's piston (mm) at which its point is sampled: 680 mm in all, more
#: than 360, so that a slide read as a turn would wrap round
SLIDES = [0.0, -140.0, -300.0, -480.0, -680.0]


def _engine():
    """A reciprocating engine driven by its piston (crank 800, rod 2400, the point P on
    the rod), its piston's slide the input, swept over SLIDES: a chain file."""
    j4 = (800 * math.cos(math.radians(60)), 800 * math.sin(math.radians(60)))
    x3 = j4[0] + math.sqrt(2400 ** 2 - j4[1] ** 2)
    p = (0.5 * (j4[0] + x3), j4[1] + 600)
    return loads(f"""
name = "Engine driven by its piston"
units = "mm"
joints = [{{id = "S", kind = "P", links = ["frame", "piston"], at = [{x3 - 600}, 0], axis = 0}},
          {{id = "A", kind = "R", links = ["frame", "crank"], at = [0, 0]}},
          {{id = "B", kind = "R", links = ["piston", "rod"], at = [{x3}, 0]}},
          {{id = "C", kind = "R", links = ["crank", "rod"], at = [{j4[0]}, {j4[1]}]}}]
points = [{{id = "P", link = "rod", at = [{p[0]}, {p[1]}]}}]
[mechanism]
fixed = "frame"
inputs = [{{joint = "S", from = 0.0, to = {SLIDES[-1]}}}]
output = "P"
""")


def _sampled(chain, slides, point="P"):
    """The point's places solved by the kernel at the input's values."""
    out = []
    for v in slides:
        m = chaingraph.solve(chain, start=v, stop=v, steps=1, summary=False)
        out.append((float(m[f"x:{point}"][0]), float(m[f"y:{point}"][0])))
    return out


def _size(points):
    return max(math.dist(p, q) for p in points for q in points)


def _reproduced(solution, points):
    """The solution, written and read back, passes the points at its reached_at."""
    chain = loads(toml_text(solution.to_dict()["mechanism"]))
    fixed = chain.mechanism.fixed
    pair = chain.joint(chain.mechanism.inputs[0].joint)
    assert chain.mechanism.driver is None and pair.kind == "P" and fixed in pair.links
    for (x, y), (gx, gy) in zip(points, _sampled(chain, solution.reached_at)):
        assert math.hypot(gx - x, gy - y) <= 1e-8 * _size(points)
    again = certify(chain, PointTargets(tuple(points), "P"))
    assert again.input == "slides"
    assert again.error_max == pytest.approx(solution.error.max, abs=1e-9 * _size(points))
    return chain


def test_the_space_adds_a_family_per_sliding_input():
    """Six links, one sliding pair: the 116 turning families first (their numbers, so
    their random streams, as before), then 23 driven by a slide on the fixed link (15
    solved dyad by dyad, 8 leaving a triad: by Newton), in 9 of the 25 inversions."""
    space = atlas_space(6, 1)
    turning = [c for c in space.choices if not c.slides]      # (cylinders: slides too)
    sliding = [c for c in space.choices if c.sliding]
    assert (len(turning), len(sliding)) == (116, 23)
    assert space.choices[:116] == tuple(turning)
    assert [c.method for c in sliding].count("dyads") == 15
    assert [c.method for c in sliding].count("newton") == 8
    assert len({(c.chain_id, c.inversion) for c in sliding}) == 9
    for c in sliding:
        pair = [j for j in c.chain.joints if set(j.links) == {c.fixed, c.driver}]
        assert [j.kind for j in pair] == ["P"]
    # two sliding pairs: 3 inversions have no turning pair on their fixed link (before:
    # no input, so not searched), driven by a slide now
    two = atlas_space(6, 2)
    turning = {(c.chain_id, c.inversion) for c in two.choices if not c.slides}
    only = {(c.chain_id, c.inversion) for c in two.choices if c.sliding} - turning
    assert len(only) == 3 and two.undriven == 0
    assert len(turning | only) == two.inversions == 71


def test_the_certification_reads_a_slide_not_a_turn():
    """The engine driven by its piston, certified against its own points: reached at
    the slides it was sampled at (680 mm of slide, not wrapped round as a turn)."""
    engine = _engine()
    points = _sampled(engine, SLIDES)
    c = certify(engine, PointTargets(tuple(points), "P"))
    assert c.input == "slides"
    assert np.allclose(c.reached_at, SLIDES, atol=1e-6)
    assert c.error_max <= 1e-9 * _size(points)


def test_a_task_of_the_engine_driven_by_its_piston_is_passed_by_a_slider_driven_chain():
    """--links 4 --prismatic 1, the family driven by the slider: five points of the
    engine's coupler curve passed exactly by reciprocating engines driven by their
    pistons, each re-solved from its file."""
    points = _sampled(_engine(), SLIDES)
    found = path(points=points, links=4, prismatic=1, seed=1, solutions=2,
                 families=lambda c: c.sliding)
    assert found.rejected[NOT_CHOSEN] == 4        # 3 turning, 1 by its cylinder
    assert found.solutions
    for s in found.solutions:
        assert s.error.max <= 1e-9 * _size(points)
        assert s.input == "slides" and s.names[-1] == "Reciprocating engine"
        assert s.atlas == {"links": 4, "prismatic": 1, "chain": 1, "inversion": 1}
        chain = _reproduced(s, points)
        assert "driven by its sliding pair" in chain.name
        # the file sweeps its input from the first target to the last
        i = chain.mechanism.inputs[0]
        assert (i.start, i.stop) == pytest.approx((0.0, s.reached_at[-1]), abs=1e-6)


def test_a_timing_in_slides_is_kept():
    """Four points with the piston's slides as the timing (file units): the solutions
    reach them at those slides (up to the first's), exactly."""
    points = _sampled(_engine(), SLIDES[:4])
    found = path(points=points, timing=SLIDES[:4], links=4, prismatic=1, seed=1,
                 solutions=1, families=lambda c: c.sliding)
    assert found.solutions
    for s in found.solutions:
        assert s.error.max <= 1e-9 * _size(points)
        assert np.allclose(np.diff(s.reached_at), np.diff(SLIDES[:4]), atol=1e-6)
        _reproduced(s, points)


def test_five_points_timed_in_slides_find_the_engine():
    """Five points with the piston's slides as the timing: ten equations on the engine
    driven by its piston's nine dimensions (a slide has no start of its own), so its
    solutions are isolated and random seeds missed them; seeded as the textbooks
    reduce timed path generation to motion generation (the guide and the rod's pin
    where the targets less the slides are concyclic, the crank a Burmester point of
    the rod's five poses), the engine is found at those slides, exactly, whatever the
    seed."""
    points = _sampled(_engine(), SLIDES)
    for seed in (1, 2):
        found = path(points=points, timing=SLIDES, links=4, prismatic=1, seed=seed,
                     solutions=1, families=lambda c: c.sliding)
        s, = found.solutions
        assert s.error.max <= 1e-9 * _size(points)
        assert np.allclose(np.diff(s.reached_at), np.diff(SLIDES), atol=1e-6)
        chain = _reproduced(s, points)
        crank = sorted(math.dist(a.at, b.at) for a in chain.joints for b in chain.joints
                       if a.kind == b.kind == "R" and len(set(a.links) & set(b.links)) == 1)
        assert min(crank) == pytest.approx(800.0, rel=1e-6)   # the engine's crank


def test_the_guide_of_timed_slides_is_where_the_targets_are_concyclic():
    """The engine's points less its piston's slides along its guide (the x axis) lie
    on a circle about the rod's pin (radius the pin to P): the guide's direction, the
    pin and the radius found first among the candidates, to the rounding of a fit of
    squares."""
    points = np.array(_sampled(_engine(), SLIDES))
    (phi, cx, cy, r), *_ = timed_guides(points, np.array(SLIDES))
    j4 = (800 * math.cos(math.radians(60)), 800 * math.sin(math.radians(60)))
    pin = (j4[0] + math.sqrt(2400 ** 2 - j4[1] ** 2), 0.0)
    assert math.remainder(phi, 2 * math.pi) == pytest.approx(0.0, abs=1e-7)
    assert (cx, cy) == pytest.approx(pin, abs=1e-8 * 2400)     # a fit of squares
    assert r == pytest.approx(math.dist(pin, points[0]), rel=1e-8)


def test_the_triads_driven_by_a_slide_trace_what_the_solver_traces():
    """The eight six-link families whose sliding driver leaves a triad (Newton's method,
    continued both ways from the drawn slide): a mechanism drawn from each, traced over
    its slides (within its limits) as the solver traces it from its written file."""
    rng = np.random.default_rng(7)
    triads = [c for c in atlas_space(6, 1).choices if c.sliding and c.method == "newton"]
    assert len(triads) == 8
    for c in triads:
        family = LoopFamily(c.chain, c.fixed, c.driver, c.carrier)
        p = family.sample(rng, 1)[0] * 50.0
        drawn = float(family.first_input(p[None, :])[0])
        ends = family.sweep(p[None, :], 2)[0] - drawn
        chain = family.chain(p, name="sampled", units="mm", notes="",
                             span=(0.95 * ends[0], 0.95 * ends[1]))
        m = chaingraph.solve(chain, steps=24, summary=False)
        x, y = family.positions(p[None, :], drawn + m["theta"][None, :])
        assert np.allclose(x[0], m["x:P"], atol=1e-9 * 50)
        assert np.allclose(y[0], m["y:P"], atol=1e-9 * 50)


def test_a_six_link_chain_driven_by_a_slide_passes_points_of_its_own_family():
    """A six-link chain with one sliding pair, driven by the slide on its fixed link:
    a mechanism drawn from the family, sampled by the solver at four slides, is passed
    exactly by the search of that family (the 138 others not chosen)."""
    space = atlas_space(6, 1)
    choice = next(c for c in space.choices if c.sliding and c.method == "dyads")
    family = AtlasFamily(choice.chain, choice.fixed, choice.driver, choice.carrier)
    params = family.sample(np.random.default_rng(3), 1)[0] * 100.0
    ends = family.sweep(params[None, :], 2)[0] - family.first_input(params[None, :])[0]
    slides = list(np.linspace(0.0, 0.6 * ends[1], 4))
    chain = family.chain(params, name="drawn", units="mm", notes="",
                         span=(0.0, slides[-1]))
    points = _sampled(chain, slides)
    found = path(points=points, links=6, prismatic=1, seed=1, solutions=1,
                 families=lambda c: c == choice)
    assert found.searched.chains == 6 and found.searched.inversions == 25
    assert found.rejected[NOT_CHOSEN] == len(space.choices) - 1
    best = found.solutions[0]
    assert best.error.max <= 1e-9 * _size(points) and best.input == "slides"
    assert best.atlas["chain"] == choice.chain_id
    assert best.atlas["inversion"] == choice.inversion
    _reproduced(best, points)


@pytest.mark.parametrize("links, prismatic, inversions, others", [(4, 1, 2, 3), (6, 1, 25, 116)])
def test_a_closed_curve_leaves_the_sliding_inputs_out(links, prismatic, inversions, others):
    """A closed curve needs a turning input: the families driven by a slide (on the
    fixed link, or by a cylinder between two moving links: every six-link inversion
    with a sliding pair has one) are not searched, the inversions that have them
    counted under their reason (the turning families, here none chosen, under
    theirs)."""
    curve = [(math.cos(t), math.sin(t)) for t in np.linspace(0, 2 * math.pi, 8,
                                                             endpoint=False)]
    found = path(points=curve, closed=True, links=links, prismatic=prismatic, seed=1,
                 families=lambda c: False)
    assert found.rejected == {NOT_CHOSEN: others, SLIDING_CLOSED: inversions}
    assert not found.solutions


def test_four_poses_of_the_engine_rod_give_the_engine_back():
    """Motion generation over the family driven by the slider: four poses of the
    engine's rod (at the piston's slides) are passed exactly, and the engine's own
    slider dyad is among the solutions (the rod's pin B on the guide y = 0, reached at
    the same slides, up to the guide's sense); its crank is a free choice (four poses
    leave a curve of centre points: Burmester's)."""
    engine = _engine()
    ref = engine.reference_direction("rod")
    poses = []
    for v in SLIDES[:4]:
        m = chaingraph.solve(engine, start=v, stop=v, steps=1, summary=False)
        poses.append((float(m["x:P"][0]), float(m["y:P"][0]),
                      float(m["angle:rod"][0]) - ref))
    found = motion(poses=poses, links=4, prismatic=1, seed=1, solutions=2,
                   families=lambda c: c.sliding)
    size = _size([p[:2] for p in poses])
    pin = engine.joint("B").at
    assert found.solutions
    engines = 0
    for s in found.solutions:
        assert s.input == "slides"
        assert s.error.max <= 1e-9 * size and s.error.angle <= 1e-9
        chain = loads(toml_text(s.to_dict()["mechanism"]))
        guide = chain.joint(chain.mechanism.inputs[0].joint)
        block = next(x for x in guide.links if x != chain.mechanism.fixed)
        on_block = next(j for j in chain.joints if block in j.links and j.kind == "R")
        engines += (math.dist(on_block.at, pin) <= 1e-6 * size
                    and abs(math.sin(math.radians(guide.axis))) <= 1e-9
                    and np.allclose(np.abs(s.reached_at), np.abs(SLIDES[:4]), atol=1e-6))
    assert engines >= 1
