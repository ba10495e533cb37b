"""Type synthesis through inversions driven by a cylinder: a sliding pair between two
moving links as the input (the inverted slider crank driven by its cylinder's
extension, a boom lifted by a cylinder). The space's families, the family's screen
against the kernel's solver (points and transmission angles), and a task taken from a
known cylinder-driven boom found again exactly, re-solved from its written file."""

import math

import numpy as np
import pytest

import chaingraph
from chaingraph.files import loads
from chaingraph.model.chainfile import toml_text
from chaingraph.structure.atlas import atlas
from chaingraph.synthesis import PointTargets, certify, path
from chaingraph.synthesis.certification import transmission_angles
from chaingraph.synthesis.family import CylinderDyads, CylinderFamily, cylinder_joints
from chaingraph.synthesis.type_synthesis import NOT_CHOSEN, atlas_space

from .conftest import automorphisms

#: the cylinder's extensions (mm, from the drawn pose) at which the boom is sampled
SLIDES = [0.0, 60.0, 130.0, 210.0]


def _boom():
    """A boom (L4) pivoted on the frame (L3) at J4, lifted by a cylinder: its barrel
    (L1) pivoted on the frame at J2, its rod (L2) pinned to the boom at J3, the rod
    sliding in the barrel (J1, along the line J2-J3); the point P on the rod. The
    slider-crank chain of the atlas, its link L3 fixed: an inverted slider crank driven
    by its cylinder's extension."""
    axis = math.degrees(math.atan2(500.0, 200.0))
    return loads(f"""
name = "Boom lifted by a cylinder"
units = "mm"
joints = [{{id = "J1", kind = "P", links = ["L1", "L2"], at = [500, -50], axis = {axis}}},
          {{id = "J2", kind = "R", links = ["L1", "L3"], at = [400, -300]}},
          {{id = "J3", kind = "R", links = ["L2", "L4"], at = [600, 200]}},
          {{id = "J4", kind = "R", links = ["L3", "L4"], at = [0, 0]}}]
points = [{{id = "P", link = "L2", at = [700, 500]}}]
[mechanism]
fixed = "L3"
inputs = [{{joint = "J1", from = 0.0, to = 210.0}}]
output = "P"
""")


def _sampled(chain, slides, point="P"):
    """The point's places solved by the kernel at the input's values, and the motions."""
    rows = [chaingraph.solve(chain, start=v, stop=v, steps=1, summary=False) for v in slides]
    return [(float(m[f"x:{point}"][0]), float(m[f"y:{point}"][0])) for m in rows], rows


def _params(chain, point="P"):
    """A chain's drawn pose as an atlas family's parameters (joints, each sliding
    pair's second point along its axis, the point)."""
    p = [v for j in chain.joints for v in j.at]
    for j in chain.joints:
        if j.kind == "P":
            p += [j.at[0] + math.cos(math.radians(j.axis)), j.at[1] + math.sin(math.radians(j.axis))]
    return np.array([p + list(chain.point(point).at)])


def test_the_space_adds_every_cylinder_between_moving_links():
    """The slider-crank chain: one cylinder family (L3 fixed, the pair J1 of L1 and L2
    driving, the point on L2); six links, one sliding pair: 43 families driven by a
    cylinder in 16 of the 25 inversions, after the 139 driven on the fixed link (their
    numbers, so their random streams, as before), each's input a sliding pair of two
    moving links; 15 solved dyad by dyad (the cylinder's links as one leave RRR dyads),
    28 by Newton's method."""
    chain, = atlas(links=4, prismatic=1)
    assert cylinder_joints(chain, "L3") == ["J1"] and cylinder_joints(chain, "L1") == []
    cyl = [c for c in atlas_space(4, 1).choices if c.cylinder]
    assert [(c.fixed, c.cylinder, c.driver, c.carrier, c.method) for c in cyl] == [
        ("L3", "J1", "L2", "L2", "dyads")]
    space = atlas_space(6, 1)
    cyl = [c for c in space.choices if c.cylinder]
    assert len(space.choices) == 139 + 43 and len(cyl) == 43
    assert all(not c.cylinder for c in space.choices[:139])
    assert len({(c.chain_id, c.inversion) for c in cyl}) == 16
    for c in cyl:
        pair = c.chain.joint(c.cylinder)
        assert pair.kind == "P" and c.fixed not in pair.links and c.slides and not c.sliding
    assert [c.method for c in cyl].count("dyads") == 15
    assert [c.method for c in cyl].count("newton") == 28


@pytest.mark.parametrize("kind", [CylinderDyads, CylinderFamily])
def test_the_family_traces_and_measures_what_the_solver_does(kind):
    """The boom's family, in closed form and by Newton's method: its point and its
    transmission angle (the cylinder's axis against the boom) at extensions either way
    of the drawn pose, and the limits of its sweep, as the kernel solves them from the
    file."""
    boom = _boom()
    family = kind(boom, "L3", "J1", "L2")
    params = _params(boom)
    slides = [-300.0, -120.0, 0.0, 75.0, 210.0, 400.0]
    points, rows = _sampled(boom, slides)
    x, y = family.positions(params, np.array([slides]))
    assert np.allclose(np.stack([x[0], y[0]], axis=1), points, atol=1e-7)
    mu = family.transmission(params, np.array([slides]))[0]
    assert np.allclose(mu, [transmission_angles(boom, [m])[0] for m in rows], atol=1e-7)
    # the sweep's ends: the rod's pin J3 at |J4 J2| +- |J4 J3| from the barrel's pivot
    # (the cylinder's line passes through both pins), less the drawn distance; a screen's
    # limits, found to a fraction of a percent (Newton's steps near a fold)
    sweep = family.sweep(params, 5)[0]
    d0, base, arm = math.dist((400, -300), (600, 200)), math.dist((0, 0), (400, -300)), \
        math.dist((0, 0), (600, 200))
    assert sweep[0] == pytest.approx(abs(base - arm) - d0, abs=5e-3 * d0)
    assert sweep[-1] == pytest.approx(base + arm - d0, abs=5e-3 * d0)


def test_six_link_cylinder_families_trace_what_the_solver_traces():
    """A mechanism drawn from a six-link family driven by a cylinder, the first of the
    chains 1 (solved dyad by dyad) and 4 (by Newton's method), traced
    over the extensions the solver sweeps from its written file (its whole range, the
    limits left out) as the solver traces it."""
    rng = np.random.default_rng(7)
    seen = set()
    for c in atlas_space(6, 1).choices:
        if not c.cylinder or c.chain_id not in (1, 4) or c.chain_id in {i for i, _ in seen}:
            continue
        seen.add((c.chain_id, c.method))
        kind = CylinderDyads if c.method == "dyads" else CylinderFamily
        family = kind(c.chain, c.fixed, c.cylinder, c.carrier)
        p = family.sample(rng, 1)[0] * 50.0
        chain = family.chain(p, name="sampled", units="mm", notes="")
        m = chaingraph.solve(chain, steps=14, summary=False)    # its whole range
        slides = m[f"input:{c.cylinder}"]
        x, y = family.positions(p[None, :], np.asarray(slides)[None, :])
        x, y, slides = x[:, 1:-1], y[:, 1:-1], slides[1:-1]      # the limits left out
        m = {k: m[k][1:-1] for k in ("x:P", "y:P")}
        # a screen: Newton's method may miss a pose a hair from a fold (the kernel
        # certifies every answer); everywhere else, the solver's points
        ok = np.isfinite(x[0])
        assert ok.sum() >= len(ok) - 1, c
        assert np.allclose(x[0][ok], m["x:P"][ok], atol=1e-9 * 50), c
        assert np.allclose(y[0][ok], m["y:P"][ok], atol=1e-9 * 50), c
    assert seen == {(1, "dyads"), (4, "newton")}


@pytest.mark.slow
def test_a_task_of_the_boom_is_passed_by_a_cylinder_driven_chain():
    """--links 4 --prismatic 1, the family driven by the cylinder alone (solved dyad by
    dyad): four points of the boom's rod passed exactly by an inverted slider crank
    driven by its cylinder, re-solved from its file at its reported extensions, its
    input the cylinder's pair swept from the first target to the last."""
    points, _ = _sampled(_boom(), SLIDES)
    size = max(math.dist(p, q) for p in points for q in points)
    found = path(points=points, links=4, prismatic=1, seed=1, solutions=1,
                 families=lambda c: bool(c.cylinder))
    assert found.rejected[NOT_CHOSEN] == 4
    s, = found.solutions
    assert s.error.max <= 1e-9 * size and s.input == "slides"
    assert s.atlas == {"links": 4, "prismatic": 1, "chain": 1, "inversion": 2}
    chain = loads(toml_text(s.to_dict()["mechanism"]))
    i, = chain.mechanism.inputs
    pair = chain.joint(i.joint)
    assert pair.kind == "P" and chain.mechanism.fixed not in pair.links
    assert "driven by its cylinder" in chain.name
    assert (i.start, i.stop) == pytest.approx((0.0, s.reached_at[-1]), abs=1e-6)
    got, _ = _sampled(chain, s.reached_at)
    assert max(math.dist(p, q) for p, q in zip(points, got)) <= 1e-8 * size
    again = certify(chain, PointTargets(tuple(points), "P"))
    assert again.input == "slides"
    assert again.error_max == pytest.approx(s.error.max, abs=1e-9 * size)


def test_one_cylinder_family_per_orbit_under_the_whole_group():
    """Six links, two sliding pairs: the cylinder families of each inversion are one per
    orbit of its cylinders under every automorphism that keeps the fixed link, found by
    brute force over the links' permutations (chain 3 with L5 or L6 fixed has two
    cylinders in one orbit: the generators that keep the fixed link alone made them two
    families)."""
    space = atlas_space(6, 2)
    kept: dict = {}
    for c in space.choices:
        if c.cylinder:
            kept.setdefault((c.chain_id, c.fixed), set()).add(c.cylinder)
    assert kept
    for (chain_id, fixed), mine in kept.items():
        chain = next(c.chain for c in space.choices if c.chain_id == chain_id)
        autos = [jm for lm, jm in automorphisms(chain) if lm[fixed] == fixed]
        every = set(cylinder_joints(chain, fixed))
        orbits = {frozenset(g[j] for g in autos) for j in every}
        assert len(mine) == len(orbits), (chain_id, fixed, mine, orbits)
        assert all(len(mine & o) == 1 for o in orbits), (chain_id, fixed)
