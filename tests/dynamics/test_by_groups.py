"""The equilibrium solved group by group (the textbook's order: the last dyad placed,
back to the input) against the whole system solved at once: the same reactions and
efforts to 1e-12 of their size, the same dead centres, over every catalog mechanism,
in statics and kinetostatics, with friction at the sliding pairs."""

from __future__ import annotations

import random
from dataclasses import replace

import numpy as np
import pytest

import chaingraph
from chaingraph import LinkMass
from chaingraph.dynamics.cycle import kinematic_state
from chaingraph.dynamics.equilibrium import solve_block_triangular, solve_equilibrium
from chaingraph.dynamics.reactions import length_metres
from chaingraph.naming.catalog import catalog_files, catalog_path

MECHANISMS = [p.stem for p in catalog_files()
              if (c := chaingraph.load(p)).mechanism is not None and c.has_pose]


def loaded(name, *, friction):
    """The catalog's mechanism with its own masses and loads, else a mass (and an
    inertia) on every moving link and gravity; ``friction`` at every sliding pair."""
    chain = chaingraph.load(catalog_path(name))
    rng = random.Random(name)
    if not chain.masses:
        fixed = chain.mechanism.fixed
        chain = replace(chain, masses=tuple(LinkMass(x, rng.uniform(0.5, 3.0), None,
                                                     rng.uniform(1e-3, 5e-2))
                                            for x in chain.links if x != fixed),
                        gravity=(0.0, -9.81), units=chain.units or "mm")
    if friction:
        chain = replace(chain, joints=tuple(replace(j, friction=0.15) if j.kind == "P" else j
                                            for j in chain.joints))
    return chain


def swept(chain, steps):
    """(plan, state, metres) at ``steps`` poses of a sweep as :func:`chaingraph.forces`
    takes them (the motion's own rates and dead centres)."""
    motion = chaingraph.solve(chain, steps=steps)
    plan = motion.plan
    lead = plan.inputs[plan.lead]
    metres = length_metres(chain)
    kin = kinematic_state(chain, plan, motion.states, motion.omega, metres, rates_known=True,
                          angle=np.radians(motion.theta) if lead.kind == "R" else None)
    return plan, kin, metres


def both(chain, steps, static, sweep=None):
    """The solution by groups and the whole system's (at ``sweep``, else at ``steps``
    poses of a sweep)."""
    plan, kin, metres = sweep or swept(chain, steps)
    return [solve_equilibrium(chain, plan, kin, static=static, metres=metres, by_groups=g)
            for g in (True, False)]


def size(series):
    """The largest determined value of all the ``series``."""
    values = [np.abs(np.asarray(v, dtype=float)) for v in series]
    return max([float(np.nanmax(v)) for v in values if np.isfinite(v).any()] + [0.0])


def same(u, v, scale):
    """Equal to 1e-12 of ``scale`` where determined, NaN at the same steps."""
    u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
    assert (np.isnan(u) == np.isnan(v)).all()
    fine = np.isfinite(v)
    if fine.any():
        assert np.abs(u[fine] - v[fine]).max() <= 1e-12 * scale


def agree(grouped, whole, sweep):
    """Every reaction, normal force, couple and effort the same, to 1e-12 of the
    largest of its kind (a reaction that is nil but for rounding is compared with the
    others' size, not its own; a couple with the largest force times the mechanism's
    size too)."""
    assert grouped.forces.keys() == whole.forces.keys()
    forces = size(c for f in whole.forces.values() for c in f)
    for key in whole.forces:
        for u, v in zip(grouped.forces[key], whole.forces[key]):
            same(u, v, forces)
    for key in whole.normal:
        same(grouped.normal[key], whole.normal[key], forces)
    plan, _, metres = sweep
    couples = max(size(whole.couple.values()), forces * plan.size * metres)
    for key in whole.couple:
        same(grouped.couple[key], whole.couple[key], couples)
    for key in whole.efforts:
        same(grouped.efforts[key], whole.efforts[key], size([whole.efforts[key]]))


@pytest.mark.parametrize("name", MECHANISMS)
def test_by_groups_equals_the_whole_system(name):
    chain = loaded(name, friction=False)
    for static in (True, False):
        sweep = swept(chain, 7)
        grouped, whole = both(chain, 7, static, sweep)
        assert (grouped.singular == whole.singular).all()
        assert (grouped.jammed == whole.jammed).all()
        agree(grouped, whole, sweep)


@pytest.mark.parametrize("name", ["whitworth-quick-return-with-ram", "reciprocating-engine",
                                  "oldhams-coupling", "elliptical-trammels"])
def test_by_groups_with_friction_at_every_sliding_pair(name):
    """Friction's signs iterated per step (the matrix changes with them): the same
    signs, the same answers."""
    chain = loaded(name, friction=True)
    sweep = swept(chain, 48)
    grouped, whole = both(chain, 48, False, sweep)
    assert (grouped.jammed == whole.jammed).all()
    for key in whole.at_rest:
        assert (grouped.at_rest[key] == whole.at_rest[key]).all()
    agree(grouped, whole, sweep)


@pytest.mark.parametrize("name, sizes", [
    # the rod and ram's RRP dyad, the block and lever's RPR dyad in closed form, the
    # crank by Cramer's rule: no LU, but the whole system's (for the comparison)
    ("whitworth-quick-return-with-ram", [15]),
    # the triad's group of four links by LU, then the crank
    ("stephenson-iii-mechanism", [12, 15])])
def test_the_systems_solved_by_groups(monkeypatch, name, sizes):
    """The batched LU solves of a sweep by groups, then of the whole system: a dyad's
    and a single link's equations are solved in closed form, a larger group's by LU."""
    found = []
    solve = np.linalg.solve

    def spy(a, b):
        found.append(a.shape[-1])
        return solve(a, b)
    chain = loaded(name, friction=False)
    sweep = swept(chain, 12)
    monkeypatch.setattr(np.linalg, "solve", spy)
    both(chain, 12, False, sweep)
    assert found == sizes


def test_a_singular_block_raises_as_the_whole_solve():
    """Block triangular matrices at random: the forward solve equals numpy's; where a
    block is singular it refuses, as numpy does (and the whole system is solved)."""
    rng = np.random.default_rng(3)
    ends = (6, 12, 15)
    a = rng.normal(size=(20, 15, 15))
    for lo, hi in zip((0, 6, 12), ends):
        a[:, lo:hi, hi:] = 0.0
    b = rng.normal(size=(20, 15, 1))
    assert np.allclose(solve_block_triangular(a, b, ends), np.linalg.solve(a, b), rtol=1e-10,
                       atol=1e-10)
    single = a.copy()
    a[4, 6:12, 8] = 0.0                           # a column of the second block
    with pytest.raises(np.linalg.LinAlgError):
        solve_block_triangular(a, b, ends)
    single[7, 12:, 13] = 0.0                      # of the last (solved by Cramer's rule)
    with pytest.raises(np.linalg.LinAlgError):
        solve_block_triangular(single, b, ends)


def test_a_dyad_in_closed_form_equals_the_lu():
    """Dyads [[E1, 0, I1], [0, E2, I2]] at random (3 x 2 blocks): the closed form equals
    numpy's LU; one whose first link's own unknowns act along the same line (E1 of rank
    one: the dyad is singular) is refused (the solve then takes the whole system, as
    without groups)."""
    rng = np.random.default_rng(5)
    n = 50
    a = rng.normal(size=(n, 9, 9))
    a[:, :6, 6:] = 0.0                            # blocks (6, 9): a dyad, then a single
    a[:, 0:3, 2:4] = 0.0
    a[:, 3:6, 0:2] = 0.0
    b = rng.normal(size=(n, 9, 1))
    x = solve_block_triangular(a, b, (6, 9), dyads=(True, False))
    assert np.allclose(x, np.linalg.solve(a, b), rtol=1e-9, atol=1e-9)
    a[3, 0:3, 1] = 2.0 * a[3, 0:3, 0]
    with pytest.raises(np.linalg.LinAlgError):
        solve_block_triangular(a, b, (6, 9), dyads=(True, False))
