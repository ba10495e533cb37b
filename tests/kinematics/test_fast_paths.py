"""The solve's shortcuts give what the long way gives: a dyad's joints as the rates'
solve found them, a whole turn's last row as its first, the summary's few cubics in
floats, a plan's hash worked out once."""

import pickle
from dataclasses import replace

import numpy as np
import pytest

import chaingraph
from chaingraph.kinematics import summary
from chaingraph.kinematics.columns import LinkStates, point_of_states
from chaingraph.naming.catalog import catalog_path

from .inversions import pinned_pairs

#: catalog mechanisms with an RRR dyad: a crank-rocker, a parallelogram (dead centres:
#: its rates are NaN there), a six-bar
DYADS = ["beam-engine", "coupling-rod-of-a-locomotive", "watt-i-mechanism"]


@pytest.mark.parametrize("name", DYADS)
def test_a_dyad_s_joints_are_what_their_links_motion_gives(name):
    m = chaingraph.solve(chaingraph.load(catalog_path(name)), steps=720, summary=False)
    plan, states = m.plan, m.states
    assert states.points, "the rates' solve went through the dyad's joints"
    long_way = LinkStates(states.tau, states.pose, states.velocity, states.acceleration)
    size = plan.size
    for joint in m.joints:
        got, want = point_of_states(plan, states, joint), point_of_states(plan, long_way, joint)
        for field in ("x", "y", "vx", "vy", "ax", "ay"):
            a, b = getattr(got, field), getattr(want, field)
            assert np.array_equal(np.isnan(a), np.isnan(b)), (joint, field)
            scale = max(size, np.nanmax(np.abs(b), initial=0.0))
            assert np.nanmax(np.abs(a - b), initial=0.0) <= 1e-12 * scale, (joint, field)


def test_no_joint_shares_an_array_with_another_or_with_a_link_s_rates():
    m = chaingraph.solve(chaingraph.load(catalog_path("beam-engine")), steps=90, summary=False)
    joints = [getattr(p, f) for p in m.joints.values() for f in ("vx", "vy", "ax", "ay")]
    rates = {id(v) for table in (m.states.velocity, m.states.acceleration)
             for entry in table.values() for v in entry}
    assert len({id(v) for v in joints}) == len(joints)
    assert not rates & {id(v) for v in joints}


@pytest.mark.parametrize("name", ["beam-engine", "reciprocating-engine"])
def test_a_whole_turn_s_last_row_is_its_first(name):
    m = chaingraph.solve(chaingraph.load(catalog_path(name)), steps=3600)
    for column, values in m.columns.items():
        if column == "theta":
            continue
        first, last = values[0], values[-1]
        if column.startswith("angle:"):       # continuous over the turn: a turn on
            assert abs(np.remainder(last - first + 180.0, 360.0) - 180.0) < 1e-9, column
        else:
            assert last == first or np.isnan(last) and np.isnan(first), column


def test_the_few_cubics_solved_in_floats_are_the_arrays_ones():
    rng = np.random.default_rng(7)
    t0 = rng.uniform(0.0, 300.0, 6)
    t1 = t0 + rng.uniform(0.01, 2.0, 6)
    f0 = rng.uniform(0.1, 2.0, 6)
    f1 = -rng.uniform(0.1, 2.0, 6)
    g0, g1 = rng.normal(size=6), rng.normal(size=6)
    few = summary._cubic_roots(t0, t1, f0, f1, g0, g1)
    many = summary._cubic_roots(*(np.tile(v, 2) for v in (t0, t1, f0, f1, g0, g1)))[:6]
    assert np.array_equal(few, many)
    assert np.all((few >= t0) & (few <= t1))


def test_a_plan_s_hash_is_the_fields_and_is_not_pickled():
    plan = chaingraph.build_plan(chaingraph.load(catalog_path("beam-engine")))
    h = hash(plan)
    again = pickle.loads(pickle.dumps(plan))
    assert "_hash" not in again.__dict__ and again == plan and hash(again) == h
    moved = replace(plan, theta0=(plan.theta0 or 0.0) + 1.0)
    assert moved != plan and "_hash" not in moved.__dict__


def test_the_pairs_a_step_meets_by_construction_are_met_in_every_inversion():
    """The sweep checks the closure of only the pairs its closed-form steps do not meet
    by construction (closure_checks): every other pair is met to rounding, in every
    inversion of every catalog chain of up to 8 links that solves (a pair wrongly taken
    as met would show here as a residual of the size of a step's error)."""
    from chaingraph.errors import AssemblyError, MechanismError
    from chaingraph.kinematics.closed_form import closure_checks
    from chaingraph.kinematics.equations import constraint_residuals
    from chaingraph.kinematics.gears import is_gear_train
    from chaingraph.kinematics.inputs import plan_of
    from chaingraph.naming.catalog import catalog_files
    seen = 0
    for path in catalog_files():
        chain = chaingraph.load(path)
        if not chain.has_pose or len(chain.links) > 8 or is_gear_train(chain):
            continue
        for fixed, driver in pinned_pairs(chain):
            try:
                plan = plan_of(chain, fixed, driver)
                if any(s.kind == "group" for s in plan.steps):
                    continue            # (Newton's method meets no pair by construction)
                v0 = plan.inputs[plan.lead].value0      # a few degrees about the drawing
                m = chaingraph.solve(chain, fixed=fixed, driver=driver, start=v0 - 3.0,
                                     stop=v0 + 3.0, steps=6, summary=False)
            except (MechanismError, AssemblyError):   # (a rocker drawn near its limit)
                continue
            plan, pose = m.plan, m.states.pose
            checked = closure_checks(plan)
            for c in plan.constraints:
                if c in checked:
                    continue
                seen += 1
                worst = max(float(np.nanmax(np.abs(np.broadcast_to(e, m.theta.shape))))
                            for e in constraint_residuals(c, pose))
                assert worst <= 1e-12 * plan.size, (path.name, fixed, driver, c.joint, worst)
    assert seen > 1000


def test_a_pose_off_at_a_checked_pair_is_refused():
    from chaingraph.errors import AssemblyError
    from chaingraph.kinematics.closed_form import closure_checks
    from chaingraph.kinematics.equations import check_poses
    m = chaingraph.solve(chaingraph.load(catalog_path("log10-function-generator")),
                         steps=12, summary=False)
    plan, pose = m.plan, dict(m.states.pose)
    assert [c.joint for c in closure_checks(plan)] == ["C"]
    check_poses(plan, pose, np.ones(13, dtype=bool), constraints=closure_checks(plan))
    x, y, *rest = pose["rocker"]
    x = np.array(x, dtype=float)
    x[5] += 1e-7 * plan.size                  # the rocker off its pin C at one step
    pose["rocker"] = (x, y, *rest)
    with pytest.raises(AssemblyError, match="loop closure fails at step 5"):
        check_poses(plan, pose, np.ones(13, dtype=bool), constraints=closure_checks(plan))
